/* One prepared FAUST shape for the Table 1 runner: segmentation + eigenpairs (ss_shape_prep), its
 * own FPS landmarks and the landmark distance fields at its critical points for the three landmark
 * sets — all of it depends on the shape only, so it is computed once and optionally cached on disk. */
#include "eval_internal.h"
#include "specseg/io.h"
#include "specseg/streamline.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

void ev_shape_free(ev_shape *s) {
  if (!s) return;
  ss_shape_prep_free(&s->prep);
  ss_mesh_free(&s->mesh);
  for (int i = 0; i < 3; i++) free(s->lmd[i]), ss_fmap_probes_free(&s->base[i]);
  ss_centre_signature_free(&s->sig);
  memset(s, 0, sizeof *s);
}

ss_status ev_shape_signature(ev_shape *s, const ev_context *ctx, ss_error *err) {
  if (s->sig.m > 0) return SS_OK;
  return ss_centre_signature_compute(&s->prep, &ctx->mopt.autopair, &s->sig, err);
}

ss_status ev_fps_landmarks(const ss_mesh *m, const ss_segmentation *seg, const ss_segment_options *so, int seed_vertex,
                           int *lm, ss_error *err) {
  if (!seg->psi || seg->work.nv <= 0) return ss_fail(err, SS_ERR_INVALID, "fps landmarks: segmentation has no work mesh");
  if (seed_vertex < 0 || seed_vertex >= m->nv) return ss_fail(err, SS_ERR_INVALID, "fps landmarks: bad seed vertex");
  ss_geodesic_mesh *gm = NULL;
  ss_mesh smooth = {0};
  int pts[EV_NL];
  double P[3 * EV_NL];
  ss_status st = ss_geodesic_mesh_build(&seg->work, &gm, err);
  if (!st) st = ss_fps(gm, seg->psi[seed_vertex], EV_NL, pts, NULL, err);
  ss_geodesic_mesh_free(gm);
  if (st) return st;
  /* back to the input: the input vertex whose smoothed position is nearest (the smoothed mesh has
   * the input's connectivity; the CMCF settings are the segmentation's) */
  ss_cmcf_options co;
  ss_cmcf_default_options(&co);
  if (so && so->cmcf_steps > 0) co.steps = so->cmcf_steps;
  if (so && so->cmcf_dt > 0) co.dt = so->cmcf_dt;
  if ((st = ss_cmcf_smooth(m, &co, &smooth, err))) return st;
  for (int i = 0; i < EV_NL; i++) memcpy(P + 3 * i, seg->work.V + 3 * (size_t)pts[i], sizeof(double) * 3);
  st = ss_closest_vertices(P, EV_NL, &smooth, lm, err);
  ss_mesh_free(&smooth);
  if (st) return st;
  lm[0] = seed_vertex; /* the seed is the given input vertex itself (the only landmark known to match) */
  return SS_OK;
}

/* scaled exact distances from the landmarks of each set (Ψ-mapped to the work mesh) to the
 * critical points, as ss_pair_segments computes them */
static ss_status landmark_fields(ev_shape *s, const ev_context *ctx, ss_error *err) {
  const ss_segmentation *seg = &s->prep.seg;
  const ss_mesh *w = &seg->work;
  int src[3 * EV_NL];
  for (int set = 0; set < 3; set++)
    for (int i = 0; i < EV_NL; i++) src[set * EV_NL + i] = seg->psi[ev_landmarks(ctx, s, set)[i]];
  double *F = malloc(sizeof(double) * (size_t)w->nv * 3 * EV_NL);
  ss_geodesic_mesh *gm = NULL;
  ss_status st = F ? SS_OK : ss_fail(err, SS_ERR_NOMEM, "eval: out of memory");
  if (!st) st = ss_geodesic_mesh_build(w, &gm, err);
  if (!st) st = ss_geodesic_fields(gm, src, 3 * EV_NL, 0, F, err);
  if (!st) {
    double scale = 1.0 / sqrt(ss_mesh_area(w));
    for (int set = 0; set < 3 && !st; set++) {
      s->lmd[set] = malloc(sizeof(double) * (size_t)seg->m * EV_NL);
      if (!s->lmd[set]) { st = ss_fail(err, SS_ERR_NOMEM, "eval: out of memory"); break; }
      for (int i = 0; i < EV_NL; i++)
        for (int c = 0; c < seg->m; c++)
          s->lmd[set][c + (size_t)seg->m * i] = F[seg->crit[c] + (size_t)w->nv * (set * EV_NL + i)] * scale;
    }
  }
  ss_geodesic_mesh_free(gm);
  free(F);
  return st;
}

/* ---- disk cache: a text key line (everything the content depends on), then raw arrays ---------- */

static void cache_key(const ev_context *c, int id, char *key, size_t n) {
  const ss_segment_options *o = &c->mopt.seg;
  snprintf(key, n,
           "specseg-eval-v2 faust %03d kev %d faces %d nostream %d cleanup %d neigs %d cmcf %d %.17g best %d %d %d %d %d "
           "gt %d %d %d %d %d\n",
           id, c->kev, o->target_faces, o->no_streamline, o->cleanup_rings, o->n_eigs, o->cmcf_steps, o->cmcf_dt,
           c->best[0], c->best[1], c->best[2], c->best[3], c->best[4], c->gt[0], c->gt[1], c->gt[2], c->gt[3], c->gt[4]);
}

static void cache_path(const char *dir, const char *key, int id, char *path, size_t n) {
  uint64_t h = 1469598103934665603ull; /* FNV-1a */
  for (const char *p = key; *p; p++) h = (h ^ (unsigned char)*p) * 1099511628211ull;
  snprintf(path, n, "%s/faust_%03d_%016llx.bin", dir, id, (unsigned long long)h);
}

#define RD(ptr, cnt) (fread((ptr), sizeof *(ptr), (size_t)(cnt), f) == (size_t)(cnt))
#define WR(ptr, cnt) (fwrite((ptr), sizeof *(ptr), (size_t)(cnt), f) == (size_t)(cnt))

static int cache_load(const char *path, const char *key, ev_shape *s) {
  FILE *f = fopen(path, "rb");
  if (!f) return 0;
  char line[1024];
  int ok = fgets(line, sizeof line, f) && !strcmp(line, key);
  int nv = 0, kev = 0, m = 0, wn = 0;
  ss_shape_prep *p = &s->prep;
  ok = ok && RD(&nv, 1) && RD(&kev, 1) && RD(&m, 1) && RD(&wn, 1) && nv == s->mesh.nv && kev >= 3 && kev < nv &&
       m >= 1 && m <= nv && wn >= 1 && wn <= 16 * nv + 1000000;
  if (ok) {
    p->evals = malloc(sizeof(double) * (size_t)kev);
    p->evecs = malloc(sizeof(double) * (size_t)nv * kev);
    p->M = malloc(sizeof(double) * (size_t)nv);
    p->seg.labels = malloc(sizeof(int) * (size_t)nv);
    p->seg.centers = malloc(sizeof(int) * (size_t)m);
    /* Ψ and the distance to the segment centres: the tent-profile segment probes need them */
    p->seg.psi = malloc(sizeof(int) * (size_t)nv);
    p->seg.work_dist = malloc(sizeof(double) * (size_t)wn);
    for (int i = 0; i < 3; i++) s->lmd[i] = malloc(sizeof(double) * (size_t)m * EV_NL);
    ok = p->evals && p->evecs && p->M && p->seg.labels && p->seg.centers && p->seg.psi && p->seg.work_dist &&
         s->lmd[0] && s->lmd[1] && s->lmd[2];
    ok = ok && RD(p->evals, kev) && RD(p->evecs, (size_t)nv * kev) && RD(p->M, nv) && RD(p->seg.labels, nv) &&
         RD(p->seg.centers, m) && RD(p->seg.psi, nv) && RD(p->seg.work_dist, wn) && RD(s->fps, EV_NL) && RD(s->lmd[0], m * EV_NL) && RD(s->lmd[1], m * EV_NL) &&
         RD(s->lmd[2], m * EV_NL) && RD(&s->t_prep, 1) && RD(&p->t_segment, 1) && RD(&p->t_eigs, 1);
    for (int i = 0; ok && i < nv; i++) ok = p->seg.labels[i] >= 0 && p->seg.labels[i] < m && p->seg.psi[i] >= 0 &&
                                            p->seg.psi[i] < wn;
    for (int i = 0; ok && i < EV_NL; i++) ok = s->fps[i] >= 0 && s->fps[i] < nv;
  }
  fclose(f);
  if (!ok) {
    ss_shape_prep_free(p);
    for (int i = 0; i < 3; i++) free(s->lmd[i]), s->lmd[i] = NULL;
    return 0;
  }
  p->mesh = &s->mesh;
  p->kev = kev;
  p->seg.nv = nv;
  p->seg.m = m;
  p->area = 0;
  for (int i = 0; i < nv; i++) p->area += p->M[i];
  s->from_cache = 1;
  return 1;
}

static void cache_store(const char *path, const char *key, const ev_shape *s) {
  char tmp[4300];
  snprintf(tmp, sizeof tmp, "%.4200s.tmp%ld", path, (long)getpid());
  FILE *f = fopen(tmp, "wb");
  if (!f) return; /* the cache is an optimisation: a read-only folder only costs time */
  const ss_shape_prep *p = &s->prep;
  int nv = s->mesh.nv, m = p->seg.m, wn = p->seg.work.nv;
  int ok = p->seg.psi && p->seg.work_dist && fputs(key, f) >= 0 && WR(&nv, 1) && WR(&p->kev, 1) && WR(&m, 1) &&
           WR(&wn, 1) && WR(p->evals, p->kev) && WR(p->evecs, (size_t)nv * p->kev) && WR(p->M, nv) &&
           WR(p->seg.labels, nv) && WR(p->seg.centers, m) && WR(p->seg.psi, nv) && WR(p->seg.work_dist, wn) &&
           WR(s->fps, EV_NL) && WR(s->lmd[0], m * EV_NL) && WR(s->lmd[1], m * EV_NL) && WR(s->lmd[2], m * EV_NL) &&
           WR(&s->t_prep, 1) && WR(&p->t_segment, 1) && WR(&p->t_eigs, 1);
  ok = !fclose(f) && ok;
  /* rename is atomic: concurrent shards never see a half-written file */
  if (!ok || rename(tmp, path)) remove(tmp);
}

ss_status ev_shape_load(const char *data_dir, const char *cache_dir, int id, const ev_context *ctx, ev_shape *s,
                        ss_error *err) {
  memset(s, 0, sizeof *s);
  s->id = id;
  char path[4096], key[1024], cpath[4200];
  snprintf(path, sizeof path, "%s/faust/tr_reg_%03d.off", data_dir, id);
  ss_status st = ss_read_mesh(path, &s->mesh, err);
  if (st) return st;
  if (cache_dir) {
    cache_key(ctx, id, key, sizeof key);
    cache_path(cache_dir, key, id, cpath, sizeof cpath);
    if (cache_load(cpath, key, s)) return SS_OK;
  }
  if ((st = ev_shape_prepare(s, ctx, err))) goto fail;
  if (cache_dir) cache_store(cpath, key, s);
  return SS_OK;
fail:
  ev_shape_free(s);
  return st;
}

ss_status ev_shape_prepare(ev_shape *s, const ev_context *ctx, ss_error *err) {
  ss_status st;
  double t0 = ss_time();
  st = ss_shape_prep_compute(&s->mesh, &ctx->mopt.seg, ctx->kev, &s->prep, err);
  if (st) goto fail;
  if ((st = ev_fps_landmarks(&s->mesh, &s->prep.seg, &ctx->mopt.seg, 0, s->fps, err))) goto fail;
  if ((st = landmark_fields(s, ctx, err))) goto fail;
  s->t_prep = ss_time() - t0;
  return SS_OK;
fail:
  ss_shape_prep_free(&s->prep);
  for (int i = 0; i < 3; i++) free(s->lmd[i]), s->lmd[i] = NULL;
  return st;
}
