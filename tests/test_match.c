/* Matching with segments as probes (paper §6) on the synthetic humanoid: all poses share one vertex
 * order, so the ground-truth map is the identity. */
#include "specseg/fmap.h"
#include "specseg/match.h"
#include "specseg/mesh.h"
#include "specseg/synth.h"
#include "testlib.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* head, left hand, right hand, left foot, right foot of the rest pose (y up, left side on +x) */
static void humanoid_landmarks(const ss_mesh *m, int lm[5]) {
  double best[5] = {-INFINITY, -INFINITY, -INFINITY, -INFINITY, -INFINITY};
  for (int i = 0; i < m->nv; i++) {
    const double *p = m->V + 3 * (size_t)i;
    double score[5] = {p[1], p[0], -p[0], p[0] > 0.05 ? -p[1] + 0.1 * p[2] : -INFINITY,
                       p[0] < -0.05 ? -p[1] + 0.1 * p[2] : -INFINITY};
    for (int l = 0; l < 5; l++)
      if (score[l] > best[l]) best[l] = score[l], lm[l] = i;
  }
}

static void test_pair_critical_points(void) {
  /* X has 3 points, Y 2: X chooses. x0 and x1 both nearest to y0; x1 is closer, keeps it. */
  double dX[3 * 2] = {0.10, 0.12, 0.90, /* landmark 0 */ 0.50, 0.50, 0.20};
  double dY[2 * 2] = {0.12, 0.88, /* landmark 0 */ 0.50, 0.21};
  ss_segment_pairs p;
  ss_error e;
  CHECK(ss_pair_critical_points(3, 2, 2, dX, dY, &p, &e) == SS_OK);
  CHECK(p.n == 2 && p.nx == 3 && p.ny == 2);
  if (p.n == 2) {
    CHECK(p.sx[0] == 1 && p.sy[0] == 0); /* sorted by X segment */
    CHECK(p.sx[1] == 2 && p.sy[1] == 1);
    CHECK_NEAR(p.energy[0], 0.0, 1e-12);
    CHECK_NEAR(p.energy[1], sqrt(0.02 * 0.02 + 0.01 * 0.01), 1e-12);
  }
  ss_segment_pairs_free(&p);
  /* swapped roles: Y (fewer) chooses, output still as (X segment, Y segment) sorted by X */
  CHECK(ss_pair_critical_points(2, 3, 2, dY, dX, &p, &e) == SS_OK);
  CHECK(p.n == 2);
  if (p.n == 2) {
    CHECK(p.sx[0] == 0 && p.sy[0] == 1);
    CHECK(p.sx[1] == 1 && p.sy[1] == 2);
  }
  ss_segment_pairs_free(&p);
  CHECK(ss_pair_critical_points(2, 3, 0, dY, dX, &p, &e) == SS_ERR_INVALID);
}

/* confidence rules on a constructed case (one landmark; X's 3 points choose among Y's 4):
 *   a0 = 0.0 -> b0 (0.3; second b1 at 0.5: ratio 1.67), but a1 is nearer b0 (0.2): not mutual,
 *             and its energy is large next to its distance to the landmark (0);
 *   a1 = 0.5 -> b1 (exact);
 *   a2 = 1.0 -> b2 (0.1; second b3 at 0.12: ratio 1.2, ambiguous). */
static void test_pairing_confidence(void) {
  const double dX[3] = {0.0, 0.5, 1.0}, dY[4] = {0.3, 0.5, 0.9, 1.12};
  ss_pairing_options po;
  ss_segment_pairs p;
  ss_error e;
  ss_pairing_paper_options(&po);
  CHECK(ss_pair_critical_points_conf(3, 4, 1, dX, dY, &po, &p, &e) == SS_OK);
  CHECK(p.n == 3 && p.sy[0] == 0 && p.sy[1] == 1 && p.sy[2] == 2);
  ss_segment_pairs_free(&p);
  CHECK(ss_pair_critical_points_conf(3, 4, 1, dX, dY, NULL, &p, &e) == SS_OK); /* NULL = the paper */
  CHECK(p.n == 3);
  ss_segment_pairs_free(&p);
  po.min_ratio = 1.5; /* the ambiguous a2 is left unpaired */
  CHECK(ss_pair_critical_points_conf(3, 4, 1, dX, dY, &po, &p, &e) == SS_OK);
  CHECK(p.n == 2 && p.sx[0] == 0 && p.sx[1] == 1);
  ss_segment_pairs_free(&p);
  ss_pairing_paper_options(&po);
  po.mutual = 1; /* a0 is not b0's nearest */
  CHECK(ss_pair_critical_points_conf(3, 4, 1, dX, dY, &po, &p, &e) == SS_OK);
  CHECK(p.n == 2 && p.sx[0] == 1 && p.sx[1] == 2 && p.sy[0] == 1 && p.sy[1] == 2);
  ss_segment_pairs_free(&p);
  ss_pairing_paper_options(&po);
  po.max_rel_energy = 0.5; /* a0: energy 0.3 at distance 0 from the landmark */
  CHECK(ss_pair_critical_points_conf(3, 4, 1, dX, dY, &po, &p, &e) == SS_OK);
  CHECK(p.n == 2 && p.sx[0] == 1 && p.sx[1] == 2);
  ss_segment_pairs_free(&p);
  /* the same rules when Y chooses (roles swapped, output still (X segment, Y segment)) */
  po.max_rel_energy = 0, po.min_ratio = 1.5;
  CHECK(ss_pair_critical_points_conf(4, 3, 1, dY, dX, &po, &p, &e) == SS_OK);
  CHECK(p.n == 2 && p.sx[0] == 0 && p.sy[0] == 0 && p.sx[1] == 1 && p.sy[1] == 1);
  ss_segment_pairs_free(&p);
}

/* the map check (min_map_share) on hand-made labels: X has segments 0 (vertices 0-3) and 1 (4-5), Y
 * segments 0 (0-2) and 1 (3-5); the map sends X's 0 to Y's 0 but for vertex 3 (share 3/4 by count,
 * 0.5 by mass below) and X's 1 into Y's 0 (share 0 for the pair 1-1, 1 for a pair 1-0). */
static void test_pairs_check_map(void) {
  int lx[6] = {0, 0, 0, 0, 1, 1}, ly[6] = {0, 0, 0, 1, 1, 1}, map[6] = {0, 1, 2, 4, 0, 1};
  ss_segmentation X, Y;
  memset(&X, 0, sizeof X), memset(&Y, 0, sizeof Y);
  X.nv = Y.nv = 6, X.m = Y.m = 2, X.labels = lx, Y.labels = ly;
  int sx[3] = {0, 1, 1}, sy[3] = {0, 1, 0};
  double en[3] = {0.1, 0.2, 0.3}, sh[3], M[6] = {1, 1, 1, 3, 1, 1};
  ss_segment_pairs p = {3, sx, sy, en, 2, 2};
  ss_error e;
  int dropped = -1;
  CHECK(ss_segment_pairs_check_map(&X, &Y, NULL, map, 0.7, &p, sh, &dropped, &e) == SS_OK);
  CHECK(fabs(sh[0] - 0.75) < 1e-15 && sh[1] == 0 && sh[2] == 1);
  CHECK(dropped == 1 && p.n == 2 && sx[0] == 0 && sy[0] == 0 && sx[1] == 1 && sy[1] == 0 && en[1] == 0.3);
  p.n = 2; /* by mass: vertex 3 weighs 3 of 6 */
  CHECK(ss_segment_pairs_check_map(&X, &Y, M, map, 0.7, &p, sh, &dropped, &e) == SS_OK);
  CHECK(fabs(sh[0] - 0.5) < 1e-15 && dropped == 1 && p.n == 1 && sx[0] == 1 && sy[0] == 0);
  map[0] = 6; /* out of range: counts as outside */
  sx[0] = 0, sy[0] = 0, p.n = 1;
  CHECK(ss_segment_pairs_check_map(&X, &Y, NULL, map, 0, &p, sh, &dropped, &e) == SS_OK);
  CHECK(fabs(sh[0] - 0.5) < 1e-15 && dropped == 0 && p.n == 1);
  sy[0] = 2; /* segment out of range */
  CHECK(ss_segment_pairs_check_map(&X, &Y, NULL, map, 0, &p, sh, &dropped, &e) == SS_ERR_INVALID);
  ss_pairing_options po;
  ss_pairing_paper_options(&po);
  CHECK(po.min_map_share == 0); /* the paper's rule: no check */
  ss_pairing_default_options(&po);
  CHECK(po.min_map_share > 0 && po.min_map_share < 1);
}

/* d(Π(x), GT(x)) / √area as per-vertex errors; returns the mean */
static double map_error(const ss_mesh *Y, int n, const int *map, double *errors) {
  double mean = NAN;
  ss_error e;
  if (ss_map_geodesic_error(Y, n, map, NULL, NULL, errors, &mean, &e)) printf("map error: %s\n", e.msg);
  return mean;
}

int main(void) {
  test_pair_critical_points();
  test_pairing_confidence();
  test_pairs_check_map();

  ss_error e;
  ss_mesh X = {0}, Y = {0};
  const int poseY = 5;
  CHECK(ss_synth_humanoid(0, &X, &e) == SS_OK);
  CHECK(ss_synth_humanoid(poseY, &Y, &e) == SS_OK);
  int lm[5];
  humanoid_landmarks(&X, lm);
  ss_match_options o;
  ss_match_paper_options(&o); /* the paper's variants first; the refined default below */
  o.fmap.k = 40;
  ss_shape_prep pX, pY;
  if (ss_shape_prep_compute(&X, &o.seg, 50, &pX, &e) || ss_shape_prep_compute(&Y, &o.seg, 50, &pY, &e)) {
    printf("prep: %s\n", e.msg);
    CHECK(0);
    TEST_MAIN_END();
  }
  printf("segments: %d (pose 0), %d (pose %d)\n", pX.seg.m, pY.seg.m, poseY);
  CHECK(pX.seg.m >= 2 && pY.seg.m >= 2);

  /* pairing a shape with itself pairs every segment with itself, at zero energy */
  ss_segment_pairs sp;
  CHECK(ss_pair_segments(&pX.seg, &pX.seg, 5, lm, lm, &sp, &e) == SS_OK);
  CHECK(sp.n == pX.seg.m);
  int self_ok = 1;
  for (int p = 0; p < sp.n; p++) self_ok &= sp.sx[p] == p && sp.sy[p] == p && sp.energy[p] < 1e-12;
  CHECK(self_ok);
  ss_segment_pairs_free(&sp);
  /* out-of-range landmark */
  int badlm[5] = {lm[0], lm[1], X.nv, lm[3], lm[4]};
  CHECK(ss_pair_segments(&pX.seg, &pY.seg, 5, badlm, lm, &sp, &e) == SS_ERR_INVALID);

  /* segment probe profiles over all segments of X: indicators (0) and the soft iVd (2) are partitions
   * of unity; the soft iVd's largest member is the vertex's own segment; the tent (1) lies in [0,1] */
  {
    const int m = pX.seg.m, n = X.nv;
    int *all = malloc(sizeof(int) * m);
    for (int s = 0; s < m; s++) all[s] = s;
    for (int prof = 0; prof <= 2; prof++) {
      double *E = NULL;
      CHECK(ss_segment_probes(&pX.seg, m, all, prof, &E, &e) == SS_OK);
      if (!E) continue;
      int range_ok = 1, unity_ok = 1, own = 0;
      for (int x = 0; x < n; x++) {
        double sum = 0, best = -1;
        int arg = -1;
        for (int s = 0; s < m; s++) {
          double v = E[x + (size_t)n * s];
          range_ok &= v >= 0 && v <= 1 + 1e-12;
          sum += v;
          if (v > best) best = v, arg = s;
        }
        if (prof != 1) unity_ok &= fabs(sum - 1) < 1e-9;
        own += arg == pX.seg.labels[x];
      }
      CHECK(range_ok);
      CHECK(unity_ok);
      if (prof == 2) {
        printf("soft iVd profile: own segment largest on %.4f of the vertices\n", (double)own / n);
        CHECK(own >= 0.98 * n);
      }
      free(E);
    }
    double *E = NULL;
    CHECK(ss_segment_probes(&pX.seg, m, all, 3, &E, &e) == SS_ERR_INVALID && E == NULL);
    free(all);
  }

  /* the pairing across poses: most vertices lie in corresponding segments */
  ss_match_result r[3];
  const ss_probe_set sets[3] = {SS_PROBES_STD, SS_PROBES_ASA, SS_PROBES_DIFF};
  double err3[3];
  double *ev = malloc(sizeof(double) * X.nv);
  for (int v = 0; v < 3; v++) {
    o.probes = sets[v];
    CHECK(ss_match_prepared(&pX, &pY, 5, lm, lm, &o, &r[v], &e) == SS_OK);
    err3[v] = map_error(&Y, X.nv, r[v].map, NULL);
  }
  printf("pose 0 -> %d: %d pairs; mean geodesic error STD %.4f ASA %.4f DIFF %.4f\n", poseY, r[2].pairs.n, err3[0],
         err3[1], err3[2]);
  CHECK(r[2].pairs.n >= 2);
  {
    int *col = malloc(sizeof(int) * pX.seg.m), same = 0;
    for (int s = 0; s < pX.seg.m; s++) col[s] = -1;
    for (int p = 0; p < r[2].pairs.n; p++) col[r[2].pairs.sx[p]] = r[2].pairs.sy[p];
    for (int i = 0; i < X.nv; i++) same += col[pX.seg.labels[i]] == pY.seg.labels[i];
    printf("vertices in paired corresponding segments: %.3f\n", (double)same / X.nv);
    CHECK(same > 0.7 * X.nv);
    for (int p = 0; p < r[2].pairs.n; p++) /* centres are input vertices of their segments */
      CHECK(pX.seg.labels[r[2].centerX[p]] == r[2].pairs.sx[p] && pY.seg.labels[r[2].centerY[p]] == r[2].pairs.sy[p]);
    free(col);
  }
  CHECK(err3[2] < err3[0]);
  CHECK(err3[2] < 0.1);

  /* STD uses no segments: not paired by default, nor segmented from meshes; the map is the same as
   * with the pairing asked for (std_pairs), which pairs as DIFF does */
  {
    CHECK(r[0].pairs.n == 0 && r[0].t_pair < 1e-3);
    ss_match_options os = o;
    os.probes = SS_PROBES_STD, os.std_pairs = 0;
    CHECK(ss_match_segments(NULL, 5) && !ss_match_segments(&os, 5) && ss_match_segments(&os, 0));
    os.std_pairs = 1;
    CHECK(ss_match_segments(&os, 5));
    os.probes = SS_PROBES_STD, os.std_pairs = 1;
    ss_match_result rp, rm;
    CHECK(ss_match_prepared(&pX, &pY, 5, lm, lm, &os, &rp, &e) == SS_OK);
    CHECK(rp.pairs.n == r[2].pairs.n && rp.pairs.n >= 2);
    os.std_pairs = 0;
    CHECK_MSG(ss_match(&X, &Y, 5, lm, lm, &os, &rm, &e) == SS_OK, "%s", e.msg);
    CHECK(rm.pairs.n == 0 && rm.t_segment == 0 && rm.t_eigs > 0);
    int same = rp.map && rm.map && r[0].map;
    for (int x = 0; same && x < X.nv; x++) same = rp.map[x] == r[0].map[x] && rm.map[x] == r[0].map[x];
    CHECK(same);
    ss_match_result_free(&rp), ss_match_result_free(&rm);
    /* a spectral-only preparation carries no segments: DIFF refuses it, STD matches with it */
    ss_shape_prep qX;
    CHECK(ss_shape_prep_compute_spectral(&X, 50, &qX, &e) == SS_OK && qX.seg.centers == NULL && qX.seg.m == 0);
    os.probes = SS_PROBES_DIFF;
    CHECK(ss_match_prepared(&qX, &pY, 5, lm, lm, &os, &rm, &e) == SS_ERR_INVALID && strstr(e.msg, "not segmented"));
    os.probes = SS_PROBES_STD;
    CHECK(ss_match_prepared(&qX, &pY, 5, lm, lm, &os, &rm, &e) == SS_OK);
    same = rm.map != NULL;
    for (int x = 0; same && x < X.nv; x++) same = rm.map[x] == r[0].map[x];
    CHECK(same);
    ss_match_result_free(&rm);
    ss_shape_prep_free(&qX);
  }
  CHECK(r[2].kc == o.fmap.k && r[2].C != NULL);

  /* swapping X and Y: the composition Y -> X -> Y stays near the identity on most vertices */
  {
    ss_match_result rb;
    o.probes = SS_PROBES_DIFF;
    CHECK(ss_match_prepared(&pY, &pX, 5, lm, lm, &o, &rb, &e) == SS_OK);
    if (rb.map) {
      int *comp = malloc(sizeof(int) * X.nv);
      for (int x = 0; x < X.nv; x++) comp[x] = rb.map[r[2].map[x]]; /* X -> Y -> X */
      double mean = map_error(&X, X.nv, comp, ev);
      int close = 0;
      for (int x = 0; x < X.nv; x++) close += ev[x] < 0.05;
      printf("X -> Y -> X: mean %.4f, within 0.05 on %.3f of the vertices\n", mean, (double)close / X.nv);
      CHECK(close > 0.8 * X.nv);
      free(comp);
    }
    ss_match_result_free(&rb);
  }

  /* from meshes, the two shapes are prepared side by side when OpenMP gives two threads: the same
   * map, byte for byte, as one after the other; an error names the shape it comes from (X's first) */
  {
#ifdef _OPENMP
    const int threads0 = omp_get_max_threads();
#endif
    ss_match_options om = o;
    om.probes = SS_PROBES_DIFF;
    om.refine = SS_REFINE_NONE;
    ss_match_result r1 = {0}, r2 = {0};
#ifdef _OPENMP
    omp_set_num_threads(1);
#endif
    CHECK_MSG(ss_match(&X, &Y, 5, lm, lm, &om, &r1, &e) == SS_OK, "%s", e.msg);
#ifdef _OPENMP
    omp_set_num_threads(2);
#endif
    CHECK_MSG(ss_match(&X, &Y, 5, lm, lm, &om, &r2, &e) == SS_OK, "%s", e.msg);
    int same = r1.map && r2.map && r1.pairs.n == r2.pairs.n && r1.pairs.n >= 2;
    for (int x = 0; same && x < X.nv; x++) same = r1.map[x] == r2.map[x];
    CHECK(same);
    CHECK(r2.t_segment > 0 && r2.t_eigs > 0 && r2.t_total > 0);
    ss_match_result_free(&r1), ss_match_result_free(&r2);
    /* one shape's segmentation and eigenpairs side by side (two threads) = one after the other */
    {
      ss_shape_prep q1, q2;
#ifdef _OPENMP
      omp_set_num_threads(1);
#endif
      CHECK(ss_shape_prep_compute(&Y, &o.seg, 30, &q1, &e) == SS_OK);
#ifdef _OPENMP
      omp_set_num_threads(2);
#endif
      CHECK(ss_shape_prep_compute(&Y, &o.seg, 30, &q2, &e) == SS_OK);
      CHECK(q1.seg.m == q2.seg.m && q1.kev == q2.kev && q1.area == q2.area);
      CHECK(!memcmp(q1.seg.labels, q2.seg.labels, sizeof(int) * (size_t)Y.nv));
      CHECK(!memcmp(q1.evals, q2.evals, sizeof(double) * 30) && !memcmp(q1.evecs, q2.evecs, sizeof(double) * 30 * (size_t)Y.nv));
      CHECK(q2.t_segment > 0 && q2.t_eigs > 0);
      ss_shape_prep_free(&q1), ss_shape_prep_free(&q2);
    }
    /* a 4-vertex tetrahedron is too small to match: on Y, on X, on both (X's error) */
    const double tv[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const int tf[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    ss_mesh T = {4, 4, (double *)tv, (int *)tf};
    int lt[5] = {0, 1, 2, 3, 0}; /* four landmarks: a fifth would give vertex 0 of T two partners (refused first) */
    CHECK(ss_match(&X, &T, 4, lm, lt, &om, &r1, &e) == SS_ERR_INVALID && strstr(e.msg, "Y (the second mesh)"));
    CHECK(ss_match(&T, &Y, 4, lt, lm, &om, &r1, &e) == SS_ERR_INVALID && strstr(e.msg, "X (the first mesh)"));
    CHECK(ss_match(&T, &T, 5, lt, lt, &om, &r1, &e) == SS_ERR_INVALID && strstr(e.msg, "X (the first mesh)"));
    /* a vertex with two partners, too many landmarks: refused, naming them (issue 32, item 6) */
    int la = 0, lb = 0;
    CHECK(ss_match(&X, &T, 5, lm, lt, &om, &r1, &e) == SS_ERR_INVALID && strstr(e.msg, "landmarks 0 and 4: vertex 0 of Y has two partners on X"));
    CHECK(ss_landmarks_check(5, lt, lt, &la, &lb, &e) == SS_OK && la == 0 && lb == 4); /* an exact repeat */
    {
      int many[SS_MAX_LANDMARKS + 1];
      for (int i = 0; i <= SS_MAX_LANDMARKS; i++) many[i] = i;
      CHECK(ss_landmarks_check(SS_MAX_LANDMARKS, many, many, &la, &lb, &e) == SS_OK && la == -1);
      CHECK(ss_match(&X, &X, SS_MAX_LANDMARKS + 1, many, many, &om, &r1, &e) == SS_ERR_INVALID && strstr(e.msg, "at most 200"));
    }
#ifdef _OPENMP
    omp_set_num_threads(threads0);
#endif
  }

  /* a shape matched to itself: the identity */
  {
    ss_match_result rs;
    CHECK(ss_match_prepared(&pX, &pX, 5, lm, lm, &o, &rs, &e) == SS_OK);
    int id = 0;
    for (int x = 0; rs.map && x < X.nv; x++) id += rs.map[x] == x;
    printf("self-match: identity on %.4f of the vertices\n", (double)id / X.nv);
    CHECK(id >= 0.95 * X.nv);
    ss_match_result_free(&rs);
  }

  /* ZoomOut from the DIFF map does not make it worse */
  {
    ss_match_result rz;
    o.refine = SS_REFINE_ZOOMOUT;
    o.fmap.zoomout_kmax = 50;
    CHECK(ss_match_prepared(&pX, &pY, 5, lm, lm, &o, &rz, &e) == SS_OK);
    if (rz.map) {
      double ez = map_error(&Y, X.nv, rz.map, NULL);
      printf("DIFF + ZoomOut 40 -> 50: %.4f\n", ez);
      CHECK(ez <= err3[2] * 1.05);
      CHECK(rz.kc == 50);
    }
    ss_match_result_free(&rz);
    o.fmap.zoomout_kmax = 100; /* more than computed */
    CHECK(ss_match_prepared(&pX, &pY, 5, lm, lm, &o, &rz, &e) == SS_ERR_INVALID);
    o.fmap.zoomout_kmax = 0;
    o.refine = SS_REFINE_NONE;
  }
  /* the refined default (descriptors and refinement at 50: what the shapes carry): the returned map is
   * the candidate of lowest selection energy, never above its own start, and the energy is that of
   * the returned map */
  {
    ss_match_options od;
    ss_match_default_options(&od);
    CHECK(od.autopair.hyp_landmarks == 2); /* the default: landmark-free hypotheses beside the landmarks */
    od.autopair.hyp_landmarks = 0;         /* these checks are of the landmarks' own map and its refinement */
    od.fmap.k = 40, od.fmap.descr_k = 50, od.fmap.zoomout_kmax = 50;
    od.refine_w_descr = 0; /* the energy recomputed below is ss_p2p_energy alone */
    od.refine_single = 0;  /* every start refined: the reference of the single refinement below */
    ss_match_result rd;
    CHECK(ss_match_prepared(&pX, &pY, 5, lm, lm, &od, &rd, &e) == SS_OK);
    int c = rd.refine_choice;
    CHECK(c >= 0 && c <= 3);
    if (c >= 0 && c <= 3 && rd.map) {
      for (int i = 0; i < 4; i++) CHECK(isnan(rd.refine_energy[i]) || rd.refine_energy[c] <= rd.refine_energy[i]);
      CHECK(!isnan(rd.refine_energy[0]) && !isnan(rd.refine_energy[1]) && !isnan(rd.refine_energy[2]));
      CHECK(rd.refine_energy[c] <= rd.refine_energy[c & ~1]); /* never above its own start */
      CHECK(rd.kc == (c & 1 ? 50 : 40));
      double E;
      CHECK(ss_p2p_energy(pY.mesh->nv, X.nv, pY.evals, pX.evals, pY.evecs, pX.evecs, pX.M, rd.map, 40, 50, 1, 0.0, &E, NULL,
                          NULL, &e) == SS_OK);
      CHECK_NEAR(E, rd.refine_energy[c], 1e-12 * fabs(E));
      double ed = map_error(&Y, X.nv, rd.map, NULL);
      printf("refined default (40 -> 50): %.4f, candidate %d, energies %.4g %.4g %.4g %.4g\n", ed, c, rd.refine_energy[0],
             rd.refine_energy[1], rd.refine_energy[2], rd.refine_energy[3]);
      CHECK(ed < 0.1);
      CHECK(rd.notes[0] == 0);
      /* refine_single (the default): the starts' energies are the reference's, only the start of
       * lower energy is refined (to the reference's refinement), and whenever the reference's choice
       * is among the candidates computed it is the same choice and the same map */
      ss_match_result r1;
      od.refine_single = 1;
      CHECK(ss_match_prepared(&pX, &pY, 5, lm, lm, &od, &r1, &e) == SS_OK);
      if (r1.map) {
        CHECK(r1.refine_energy[0] == rd.refine_energy[0] && r1.refine_energy[2] == rd.refine_energy[2]);
        const int lo = rd.refine_energy[2] < rd.refine_energy[0] ? 2 : 0, hi = 2 - lo;
        CHECK(r1.refine_energy[lo + 1] == rd.refine_energy[lo + 1] && isnan(r1.refine_energy[hi + 1]));
        CHECK(r1.refine_choice >= 0 && r1.refine_choice != hi + 1);
        CHECK(r1.refine_energy[r1.refine_choice] <= r1.refine_energy[r1.refine_choice & ~1]);
        for (int i = 0; i < 4; i++) CHECK(isnan(r1.refine_energy[i]) || r1.refine_energy[r1.refine_choice] <= r1.refine_energy[i]);
        if (c != hi + 1) {
          CHECK(r1.refine_choice == c);
          int same = 1;
          for (int x = 0; same && x < X.nv; x++) same = r1.map[x] == rd.map[x];
          CHECK(same);
        }
      }
      ss_match_result_free(&r1);
    }
    ss_match_result_free(&rd);
    /* with the default selection energy (descriptor residual included): the same invariants */
    ss_match_default_options(&od);
    od.autopair.hyp_landmarks = 0;
    od.fmap.k = 40, od.fmap.descr_k = 50, od.fmap.zoomout_kmax = 50;
    CHECK(od.refine_w_descr > 0);
    CHECK(ss_match_prepared(&pX, &pY, 5, lm, lm, &od, &rd, &e) == SS_OK);
    c = rd.refine_choice;
    CHECK(c >= 0 && c <= 3);
    if (c >= 0 && c <= 3) {
      for (int i = 0; i < 4; i++) CHECK(isnan(rd.refine_energy[i]) || rd.refine_energy[c] <= rd.refine_energy[i]);
      CHECK(rd.refine_energy[c] <= rd.refine_energy[c & ~1]);
      printf("refined default, descriptor term: %.4f, candidate %d\n", map_error(&Y, X.nv, rd.map, NULL), c);
    }
    ss_match_result_free(&rd);
    /* 3 landmarks: no segment probes (a note says so), the map is STD's */
    ss_match_result r3, s3;
    od.refine = SS_REFINE_NONE;
    CHECK(ss_match_prepared(&pX, &pY, 3, lm, lm, &od, &r3, &e) == SS_OK);
    od.probes = SS_PROBES_STD;
    CHECK(ss_match_prepared(&pX, &pY, 3, lm, lm, &od, &s3, &e) == SS_OK);
    CHECK(strstr(r3.notes, "no segment probes") != NULL && s3.notes[0] == 0);
    int same = r3.map && s3.map;
    for (int x = 0; same && x < X.nv; x++) same = r3.map[x] == s3.map[x];
    CHECK(same);
    ss_match_result_free(&r3), ss_match_result_free(&s3);
    /* the same 3 landmarks with the paper's pairing rule use the segments */
    od.probes = SS_PROBES_DIFF;
    ss_pairing_paper_options(&od.pairing);
    CHECK(ss_match_prepared(&pX, &pY, 3, lm, lm, &od, &r3, &e) == SS_OK);
    CHECK(r3.notes[0] == 0 || r3.pairs.n == 0);
    ss_match_result_free(&r3);
  }
  /* the energy is zero for the identity of a shape with itself, positive for a constant map */
  {
    int *id = malloc(sizeof(int) * X.nv);
    double E0, E1, Eo, El;
    for (int x = 0; x < X.nv; x++) id[x] = x;
    CHECK(ss_p2p_energy(X.nv, X.nv, pX.evals, pX.evals, pX.evecs, pX.evecs, pX.M, id, 10, 50, 5, 1.0, &E0, &Eo, &El, &e) == SS_OK);
    CHECK(E0 < 1e-10 && El < 1e-10);
    for (int x = 0; x < X.nv; x++) id[x] = 0;
    CHECK(ss_p2p_energy(X.nv, X.nv, pX.evals, pX.evals, pX.evecs, pX.evecs, pX.M, id, 10, 50, 5, 1.0, &E1, &Eo, &El, &e) == SS_OK);
    CHECK(E1 > 0.5 && fabs(E1 - (Eo + El)) < 1e-12);
    id[0] = X.nv;
    CHECK(ss_p2p_energy(X.nv, X.nv, pX.evals, pX.evals, pX.evecs, pX.evecs, pX.M, id, 10, 50, 5, 1.0, &E1, NULL, NULL, &e) ==
          SS_ERR_INVALID);
    /* descriptor residual: 0 for the identity, large for a map onto one vertex, and it tells a
     * left-right flip of the humanoid (a near-isometry the orthonormality energy accepts) */
    ss_fmap_shape fx = {&X, pX.M, pX.evals, pX.evecs, pX.kev, NULL, 0, NULL, 0};
    ss_fmap_match_options fo;
    ss_fmap_match_default_options(&fo);
    fo.k = 40;
    ss_fmap_probes pb;
    CHECK(ss_fmap_base_probes(&fx, 5, lm, &fo, 0, &pb, &e) == SS_OK);
    double R0, R1;
    CHECK(ss_p2p_descr_residual(X.nv, X.nv, pX.evecs, pX.evecs, pX.M, &pb, &pb, id, &R1, &e) == SS_ERR_INVALID);
    id[0] = 0;
    CHECK(ss_p2p_descr_residual(X.nv, X.nv, pX.evecs, pX.evecs, pX.M, &pb, &pb, id, &R1, &e) == SS_OK);
    for (int x = 0; x < X.nv; x++) id[x] = x;
    CHECK(ss_p2p_descr_residual(X.nv, X.nv, pX.evecs, pX.evecs, pX.M, &pb, &pb, id, &R0, &e) == SS_OK);
    CHECK(R0 < 1e-20 && R1 > 0.3);
    /* the mirror x -> nearest vertex of (-x, y, z) */
    for (int x = 0; x < X.nv; x++) {
      double best = INFINITY;
      for (int z = 0; z < X.nv; z++) {
        double dx = X.V[3 * z] + X.V[3 * x], dy = X.V[3 * z + 1] - X.V[3 * x + 1], dz = X.V[3 * z + 2] - X.V[3 * x + 2];
        double d = dx * dx + dy * dy + dz * dz;
        if (d < best) best = d, id[x] = z;
      }
    }
    double Rf, Ef;
    CHECK(ss_p2p_descr_residual(X.nv, X.nv, pX.evecs, pX.evecs, pX.M, &pb, &pb, id, &Rf, &e) == SS_OK);
    CHECK(ss_p2p_energy(X.nv, X.nv, pX.evals, pX.evals, pX.evecs, pX.evecs, pX.M, id, 10, 50, 5, 0.0, &Ef, NULL, NULL, &e) == SS_OK);
    printf("left-right flip: descriptor residual %.3f, orthonormality energy %.4f\n", Rf, Ef);
    CHECK(Rf > 0.1 && Rf > 10 * Ef);
    ss_fmap_probes_free(&pb);
    free(id);
  }
  /* bad input */
  {
    ss_match_result rr;
    int bl[5] = {lm[0], -1, lm[2], lm[3], lm[4]};
    CHECK(ss_match_prepared(&pX, &pY, 5, bl, lm, &o, &rr, &e) == SS_ERR_INVALID);
    CHECK(ss_match(&X, &Y, 5, lm, bl, &o, &rr, &e) == SS_ERR_INVALID);
    CHECK(strstr(e.msg, "landmark") != NULL);
  }

  for (int v = 0; v < 3; v++) ss_match_result_free(&r[v]);
  free(ev);
  ss_shape_prep_free(&pX);
  ss_shape_prep_free(&pY);
  ss_mesh_free(&X);
  ss_mesh_free(&Y);
  TEST_MAIN_END();
}
