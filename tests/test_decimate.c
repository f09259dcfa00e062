/* Decimation before the flow (src/streamline/decimate.c) and the segmentation of large inputs through
 * it: topology kept (Euler characteristic, closed, manifold, oriented), face count at the target,
 * every input vertex mapped to a coarse vertex; ss_segment on a mesh above SSI_COARSEN_ABOVE_NV maps
 * every input vertex to a valid work vertex; FAUST tr_reg_000 (below the threshold) segments exactly as
 * before the coarsening existed (SKIP without the data). */
#include "testlib.h"
#include "specseg/io.h"
#include "specseg/mesh.h"
#include "specseg/match.h"
#include "specseg/segment.h"
#include "streamline/decimate.h"
#include "streamline/remesh_mesh.h"
#include "mesh/mesh_topology.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

/* Closed, manifold and oriented, as the remesher's own check says; χ = V − E + F with E = 3F/2. */
static int closed_manifold(const ss_mesh *m) {
  rm_mesh r;
  ss_error e = {0};
  if (rm_init(&r, m, &e)) {
    fprintf(stderr, "  not closed/manifold/oriented: %s\n", e.msg);
    return 0;
  }
  rm_free(&r);
  return 1;
}

static int euler(const ss_mesh *m) { return m->nv - 3 * m->nf / 2 + m->nf; }

/* Torus (genus 1) of nu × nv quads split into triangles, outward normals. */
static ss_status torus(int nu, int nv, ss_mesh *m) {
  ss_status st = ss_mesh_alloc(m, nu * nv, 2 * nu * nv, NULL);
  if (st) return st;
  for (int i = 0; i < nu; i++)
    for (int j = 0; j < nv; j++) {
      double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv, R = 1.0, r = 0.35 + 0.05 * sin(3 * u);
      double *p = m->V + 3 * (i * nv + j);
      p[0] = (R + r * cos(v)) * cos(u), p[1] = (R + r * cos(v)) * sin(u), p[2] = r * sin(v);
    }
  int f = 0;
  for (int i = 0; i < nu; i++)
    for (int j = 0; j < nv; j++) {
      int a = i * nv + j, b = ((i + 1) % nu) * nv + j, c = ((i + 1) % nu) * nv + (j + 1) % nv, d = i * nv + (j + 1) % nv;
      int *t = m->F + 3 * f;
      t[0] = a, t[1] = b, t[2] = c, t[3] = a, t[4] = c, t[5] = d;
      f += 2;
    }
  return SS_OK;
}

static void check_decimation(const char *name, const ss_mesh *in, int target) {
  ss_mesh out = {0};
  ss_error e = {0};
  int *to_coarse = malloc(sizeof(int) * (size_t)in->nv), *src = NULL;
  ss_status st = ssi_decimate(in, target, &out, to_coarse, &src, &e);
  CHECK_MSG(st == SS_OK, "%s: %s", name, e.msg);
  if (st) {
    free(to_coarse);
    return;
  }
  printf("%s: %d v / %d f -> %d v / %d f (target %d)\n", name, in->nv, in->nf, out.nv, out.nf, target);
  CHECK_MSG(euler(&out) == euler(in), "%s: Euler characteristic %d, input %d", name, euler(&out), euler(in));
  CHECK_MSG(closed_manifold(&out), "%s", name);
  CHECK_MSG(out.nf <= target && out.nf >= target - 2, "%s: %d faces for a target of %d", name, out.nf, target);
  int *comp_in = malloc(sizeof(int) * (size_t)in->nv), *comp_out = malloc(sizeof(int) * (size_t)out.nv);
  CHECK(ssi_mesh_components(in, comp_in) == ssi_mesh_components(&out, comp_out));
  int bad = 0, badsrc = 0, samecomp = 1;
  for (int i = 0; i < in->nv; i++) {
    if (to_coarse[i] < 0 || to_coarse[i] >= out.nv) bad++;
    else if (comp_in[i] != comp_in[src[to_coarse[i]]]) samecomp = 0; /* same component */
  }
  for (int c = 0; c < out.nv; c++) badsrc += src[c] < 0 || src[c] >= in->nv || (c > 0 && src[c] <= src[c - 1]);
  CHECK_MSG(bad == 0, "%s: %d input vertices without a coarse vertex", name, bad);
  CHECK_MSG(badsrc == 0, "%s: %d bad source indices", name, badsrc);
  CHECK(samecomp);
  /* a coarse vertex maps to itself through its source vertex */
  int self = 0;
  for (int c = 0; c < out.nv; c++) self += to_coarse[src[c]] == c;
  CHECK_MSG(self > out.nv / 2, "%s: %d of %d coarse vertices are their source's image", name, self, out.nv);
  free(comp_in), free(comp_out), free(to_coarse), free(src);
  ss_mesh_free(&out);
}

static uint64_t fnv(const int *a, int n) {
  uint64_t h = 1469598103934665603ull;
  for (int i = 0; i < n; i++) {
    uint32_t x = (uint32_t)a[i];
    for (int b = 0; b < 4; b++) h = (h ^ ((x >> (8 * b)) & 255u)) * 1099511628211ull;
  }
  return h;
}

int main(void) {
  ss_error e = {0};
  /* genus 1, two components */
  {
    ss_mesh t = {0}, t2 = {0};
    CHECK(torus(300, 120, &t) == SS_OK);
    check_decimation("torus", &t, 4000);
    /* two tori side by side: components stay apart */
    CHECK(ss_mesh_alloc(&t2, 2 * t.nv, 2 * t.nf, NULL) == SS_OK);
    memcpy(t2.V, t.V, sizeof(double) * 3 * (size_t)t.nv);
    for (int i = 0; i < t.nv; i++) {
      memcpy(t2.V + 3 * (size_t)(t.nv + i), t.V + 3 * (size_t)i, 3 * sizeof(double));
      t2.V[3 * (size_t)(t.nv + i)] += 2.9;
    }
    memcpy(t2.F, t.F, sizeof(int) * 3 * (size_t)t.nf);
    for (int i = 0; i < 3 * t.nf; i++) t2.F[3 * t.nf + i] = t.F[i] + t.nv;
    check_decimation("two tori", &t2, 3000);
    ss_mesh_free(&t), ss_mesh_free(&t2);
  }
  /* a target above the face count leaves the mesh as it is */
  {
    ss_mesh t = {0}, out = {0};
    CHECK(torus(20, 10, &t) == SS_OK);
    int *tc = malloc(sizeof(int) * (size_t)t.nv);
    CHECK(ssi_decimate(&t, 1000, &out, tc, NULL, &e) == SS_OK);
    CHECK(out.nv == t.nv && out.nf == t.nf);
    int id = 1;
    for (int i = 0; i < t.nv; i++) id &= tc[i] == i;
    CHECK(id);
    free(tc);
    ss_mesh_free(&t), ss_mesh_free(&out);
  }
  /* an open mesh is refused (the pipeline closes holes first) */
  {
    ss_mesh t = {0}, out = {0};
    CHECK(torus(20, 10, &t) == SS_OK);
    t.nf -= 2;
    int *tc = malloc(sizeof(int) * (size_t)t.nv);
    CHECK(ssi_decimate(&t, 100, &out, tc, NULL, &e) == SS_ERR_UNSUPPORTED);
    free(tc);
    ss_mesh_free(&t);
  }

  const char *data = tl_data_dir();
  if (!data) {
    SKIP("FAUST data not found (SS_DATA_DIR)");
    TEST_MAIN_END();
  }
  char path[4096];
  snprintf(path, sizeof path, "%s/faust/tr_reg_000.off", data);
  ss_mesh faust = {0};
  CHECK(ss_read_mesh(path, &faust, &e) == SS_OK);
  /* FAUST (6,890 vertices, below the threshold): the segmentation is bit for bit the one from before
   * the coarsening (labels hashed; 8 segments) */
  {
    ss_segmentation s = {0};
    CHECK(ss_segment(&faust, NULL, &s, &e) == SS_OK);
    CHECK(s.m == 8);
    uint64_t h = fnv(s.labels, s.nv);
    CHECK_MSG(h == 0x34e55fd060647ab4ull, "FAUST tr_reg_000 labels hash %016llx", (unsigned long long)h);
    ss_segmentation_free(&s);
  }
  /* subdivided twice (110k vertices, above the threshold): decimation keeps the topology; the
   * segmentation goes through the coarse mesh and Ψ maps every input vertex to a work vertex */
  {
    ss_mesh s1 = {0}, s2 = {0};
    CHECK(ss_mesh_subdivide(&faust, &s1, &e) == SS_OK);
    CHECK(ss_mesh_subdivide(&s1, &s2, &e) == SS_OK);
    CHECK(s2.nv > SSI_COARSEN_ABOVE_NV);
    check_decimation("FAUST x2 subdivided", &s2, SSI_COARSE_FACES);
    ss_segmentation s = {0};
    CHECK_MSG(ss_segment(&s2, NULL, &s, &e) == SS_OK, "%s", e.msg);
    if (s.labels) {
      int bad = 0, badl = 0;
      for (int i = 0; i < s2.nv; i++) {
        bad += s.psi[i] < 0 || s.psi[i] >= s.work.nv;
        badl += s.labels[i] < 0 || s.labels[i] >= s.m;
      }
      CHECK_MSG(bad == 0, "%d input vertices with no work vertex", bad);
      CHECK(badl == 0);
      CHECK_MSG(s.m == 8, "%d segments on FAUST x2 (8 on FAUST)", s.m);
      for (int c = 0; c < s.m; c++) CHECK(s.centers[c] >= 0 && s.centers[c] < s2.nv && s.labels[s.centers[c]] == c);
      printf("FAUST x2: %d segments, work mesh %d v / %d f\n", s.m, s.work.nv, s.work.nf);
    }
    /* prepared (small spectrum, for speed): matched through its proxy, as ss_match_warn matches the
     * mesh; the input's own segmentation kept for `segment`; the file round trip keeps both */
    {
      ss_match_options o;
      ss_match_default_options(&o);
      o.fmap.k = 20, o.fmap.zoomout_kmax = 30, o.fmap.descr_k = 30, o.seg_descr_k = 0;
      /* the further refinement of the map kept and the pairing's descriptors at 40 (one spectrum
       * serves the match with landmarks and the landmark-free one) */
      o.autopair.hyp_final_kmax = o.autopair.descr_k = o.autopair.orient_descr_k = 40;
      const int lm[5] = {412, 5891, 6593, 3323, 2119}, kev = ss_match_eigenpairs(&o, 5);
      CHECK_MSG(kev == 40 && ss_match_eigenpairs(&o, 0) == 40, "eigenpairs %d / %d, want 40", kev,
                ss_match_eigenpairs(&o, 0));
      ss_prepared_shape P = {0}, R = {0};
      CHECK_MSG(ss_prepared_shape_compute(&s2, NULL, kev, &o.autopair, &P, &e) == SS_OK, "%s", e.msg);
      CHECK(P.has_proxy && P.proxy.nv < s2.nv / 2 && P.prep.kev == 0 && !P.prep.evecs && P.proxy_prep.kev == kev &&
            ss_prepared_shape_matched(&P) == &P.proxy_prep && P.proxy_prep.crit_fields);
      CHECK(s.labels && P.prep.seg.nv == s2.nv && !memcmp(P.prep.seg.labels, s.labels, sizeof(int) * (size_t)s2.nv));
      int bad = 0;
      for (int i = 0; i < s2.nv; i++) bad += P.to_proxy[i] < 0 || P.to_proxy[i] >= P.proxy.nv;
      for (int i = 0; i < P.proxy.nv; i++) bad += P.proxy_src[i] < 0 || P.proxy_src[i] >= s2.nv;
      CHECK(bad == 0);
      char path[] = "/tmp/test_decimate_XXXXXX";
      int fd = mkstemp(path);
      CHECK(fd >= 0);
      if (fd >= 0) close(fd);
      CHECK(ss_prepared_shape_write(path, &P, &e) == SS_OK);
      CHECK_MSG(ss_prepared_shape_read(path, &R, &e) == SS_OK, "%s", e.msg);
      remove(path);
      CHECK(R.has_proxy && R.proxy.nv == P.proxy.nv && R.proxy_prep.kev == kev &&
            !memcmp(R.to_proxy, P.to_proxy, sizeof(int) * (size_t)s2.nv) &&
            !memcmp(R.proxy_prep.evecs, P.proxy_prep.evecs, sizeof(double) * (size_t)kev * P.proxy.nv) &&
            !memcmp(R.prep.seg.labels, P.prep.seg.labels, sizeof(int) * (size_t)s2.nv));
      ss_match_result a = {0}, b = {0};
      CHECK_MSG(ss_match_warn(&s2, &s2, 5, lm, lm, &o, &a, NULL, 0, &e) == SS_OK, "%s", e.msg);
      CHECK_MSG(ss_match_prepared_shapes(&R, &R, 5, lm, lm, &o, &b, NULL, 0, &e) == SS_OK, "%s", e.msg);
      CHECK(a.map && b.map && a.nX == s2.nv && b.nX == s2.nv &&
            !memcmp(a.map, b.map, sizeof(int) * (size_t)s2.nv) && a.pairs.n == b.pairs.n);
      for (int q = 0; q < a.pairs.n && q < b.pairs.n; q++)
        CHECK(a.centerX[q] == b.centerX[q] && a.centerY[q] == b.centerY[q] && b.centerX[q] < s2.nv);
      /* the map kept beside the landmarks was refined further on the proxies' eigenpairs */
      CHECK_MSG(b.autopair.hyp_final_k == 40 && b.kc == 40, "with landmarks: refined further to %d (kc %d), want 40",
                b.autopair.hyp_final_k, b.kc);
      ss_match_result_free(&a), ss_match_result_free(&b);
      /* landmark-free through the proxy: the hypotheses on the proxies, the map kept refined further
       * there, then lifted to every input vertex */
      CHECK(R.has_signature);
      CHECK_MSG(ss_match_prepared_shapes(&R, &R, 0, NULL, NULL, &o, &a, NULL, 0, &e) == SS_OK, "%s", e.msg);
      CHECK_MSG(a.autopair.hyp_final_k == 40 && a.kc == 40, "landmark-free: refined further to %d (kc %d), want 40",
                a.autopair.hyp_final_k, a.kc);
      int out_of_range = 0, fixed = 0;
      for (int i = 0; a.map && i < s2.nv; i++) {
        out_of_range += a.map[i] < 0 || a.map[i] >= s2.nv;
        fixed += a.map[i] == i;
      }
      CHECK(a.map && a.nX == s2.nv && out_of_range == 0);
      printf("FAUST x2 onto itself, landmark-free through the proxy: %d of %d vertices fixed\n", fixed, s2.nv);
      ss_match_result_free(&a);
      ss_prepared_shape_free(&P), ss_prepared_shape_free(&R);
    }
    ss_segmentation_free(&s);
    ss_mesh_free(&s1), ss_mesh_free(&s2);
  }
  ss_mesh_free(&faust);
  TEST_MAIN_END();
}
