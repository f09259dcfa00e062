/* The matching pipeline's entry points (match.h): its options and result; ss_match / ss_match_warn
 * from two meshes (landmarks checked, the kept components and proxies of match_submesh.c, both shapes
 * prepared side by side, the map lifted back); ss_match_prepared and ss_match_prepared_pairs on
 * prepared shapes; ss_pair_auto. The stages they run: match_core.c (one match from landmarks),
 * match_hypotheses.c (the hypotheses' maps), match_probe_cache.c; pairing.c and autopair.c pair the
 * segments, segment_probes.c gives their probe functions. */
#include "specseg/match.h"
#include "match/match_internal.h"
#include "match/match_submesh.h"
#include "match/hypotheses.h"
#include "match/landmark_check.h"
#include "util/side_by_side.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Defaults of what the paper leaves open (docs/tuning.md). */
#define SS_DEFAULT_DESCR_K 100
#define SS_DEFAULT_REFINE_KMAX 110
#define SS_DEFAULT_REFINE_W_DESCR 1.0
#define SS_DEFAULT_REFINE_STEP 5
#define SS_DEFAULT_REFINE_SAMPLES 1000
#define SS_DEFAULT_REFINE_SINGLE 1
#define SS_DEFAULT_W_ORIENT 1e-3

void ss_match_default_options(ss_match_options *o) {
  memset(o, 0, sizeof *o);
  o->probes = SS_PROBES_DIFF;
  ss_fmap_match_default_options(&o->fmap);
  o->fmap.descr_k = SS_DEFAULT_DESCR_K;
  o->fmap.zoomout_kmax = SS_DEFAULT_REFINE_KMAX;
  o->fmap.zoomout_step = SS_DEFAULT_REFINE_STEP;
  o->fmap.zoomout_samples = SS_DEFAULT_REFINE_SAMPLES;
  o->fmap.w_orient = SS_DEFAULT_W_ORIENT;
  ss_segment_default_options(&o->seg);
  o->segment_profile = SS_PROFILE_TENT;
  ss_pairing_default_options(&o->pairing);
  o->refine = SS_REFINE_BEST;
  o->refine_w_lap = 0.0;
  o->refine_w_descr = SS_DEFAULT_REFINE_W_DESCR;
  o->refine_single = SS_DEFAULT_REFINE_SINGLE;
  ss_autopair_default_options(&o->autopair);
}

void ss_match_paper_options(ss_match_options *o) {
  ss_match_default_options(o);
  o->fmap.descr_k = 0;
  o->seg_descr_k = 0;
  o->fmap.zoomout_kmax = 0;
  o->fmap.w_orient = 0.0;
  ss_pairing_paper_options(&o->pairing);
  o->refine = SS_REFINE_NONE;
}

void ss_match_result_free(ss_match_result *r) {
  if (!r) return;
  free(r->map);
  free(r->C);
  free(r->centerX);
  free(r->centerY);
  ss_segment_pairs_free(&r->pairs);
  memset(r, 0, sizeof *r);
}

/* "match: what" -> "match: SHAPE: what" (every message of a shape's preparation is about one mesh) */
static void name_shape(ss_error *err, const char *shape) {
  if (!err) return;
  char tmp[sizeof err->msg];
  const char *m = err->msg;
  if (!strncmp(m, "match: ", 7)) m += 7;
  snprintf(tmp, sizeof tmp, "match: %s: %.900s", shape, m);
  memcpy(err->msg, tmp, sizeof tmp);
}

/* One shape's preparation for ss_match: segmented (ASA, DIFF, landmark-free) or spectral only. */
typedef struct prep_task {
  const ss_mesh *m;
  int segment, kev;
  const ss_segment_options *so;
  ss_shape_prep *p;
  int done;
} prep_task;
static ss_status prep_task_run(void *arg, ss_error *err) {
  prep_task *t = arg;
  ss_status st = t->segment ? ss_shape_prep_compute(t->m, t->so, t->kev, t->p, err)
                            : ss_shape_prep_compute_spectral(t->m, t->kev, t->p, err);
  t->done = !st;
  return st;
}

/* Both shapes' preparations, side by side (ssi_run_both). Errors name the shape, X's first;
 * *have_x / *have_y: which preparation succeeded (to be freed). */
static ss_status prepare_both(const ss_mesh *PX, const ss_mesh *PY, int segment, const ss_segment_options *so, int kev,
                              ss_shape_prep *pX, ss_shape_prep *pY, int *have_x, int *have_y, ss_error *err) {
  prep_task tx = {PX, segment, kev, so, pX, 0}, ty = {PY, segment, kev, so, pY, 0};
  ss_status st = ssi_run_both(prep_task_run, &tx, prep_task_run, &ty, 1, err);
  *have_x = tx.done, *have_y = ty.done;
  if (st) name_shape(err, !tx.done ? "X (the first mesh)" : "Y (the second mesh)");
  return st;
}

ss_status ss_match_prepared(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX, const int *lmY,
                            const ss_match_options *opts, ss_match_result *out, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  return ssi_match_prepared_signed(X, Y, NULL, NULL, nl, lmX, lmY, opts, out, err);
}


ss_status ss_match_prepared_pairs(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX, const int *lmY,
                                  const ss_segment_pairs *pairs, const ss_match_options *opts, ss_match_result *out,
                                  ss_error *err) {
  if (!pairs) {
    if (out) memset(out, 0, sizeof *out);
    return ss_fail(err, SS_ERR_INVALID, "match: NULL segment pairs");
  }
  return ssi_match_core(X, Y, nl, lmX, lmY, pairs, opts, out, err);
}

ss_status ss_match(const ss_mesh *X, const ss_mesh *Y, int nl, const int *lmX, const int *lmY,
                   const ss_match_options *opts_in, ss_match_result *out, ss_error *err) {
  return ss_match_warn(X, Y, nl, lmX, lmY, opts_in, out, NULL, 0, err);
}

ss_status ss_match_warn(const ss_mesh *X, const ss_mesh *Y, int nl, const int *lmX, const int *lmY,
                        const ss_match_options *opts_in, ss_match_result *out, char *warnings, size_t warnings_size,
                        ss_error *err) {
  if (warnings && warnings_size) warnings[0] = '\0';
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  memset(out, 0, sizeof *out);
  ss_match_options o;
  if (opts_in) o = *opts_in;
  else ss_match_default_options(&o);
  if (!X || !Y) return ss_fail(err, SS_ERR_INVALID, "match: NULL mesh");
  /* check the landmarks before the expensive part */
  if (nl < 0 || (nl > 0 && (!lmX || !lmY))) return ss_fail(err, SS_ERR_INVALID, "match: bad landmarks");
  for (int i = 0; i < nl; i++) {
    if (lmX[i] < 0 || lmX[i] >= X->nv)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on X [0,%d)", i, lmX[i], X->nv);
    if (lmY[i] < 0 || lmY[i] >= Y->nv)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on Y [0,%d)", i, lmY[i], Y->nv);
  }
  if (ss_landmarks_check(nl, lmX, lmY, NULL, NULL, err)) return SS_ERR_INVALID; /* too many, two partners */
  ssi_kept kx, ky;
  ss_status st = ssi_keep_landmark_components(X, "X (the first mesh)", nl, lmX, &kx, err);
  if (st) return st;
  if ((st = ssi_keep_landmark_components(Y, "Y (the second mesh)", nl, lmY, &ky, err))) {
    ssi_kept_free(&kx);
    return st;
  }
  const ss_mesh *PX = kx.sub.active ? &kx.sub.mesh : X, *PY = ky.sub.active ? &ky.sub.mesh : Y;
  int *lx = malloc(sizeof(int) * (size_t)(nl > 0 ? nl : 1)), *ly = malloc(sizeof(int) * (size_t)(nl > 0 ? nl : 1));
  double *dX = NULL, *dY = NULL; /* the caller's descriptors on the kept vertices */
  ss_shape_prep pX = {0}, pY = {0};
  ssi_submesh cx = {0}, cy = {0};
  int have_x = 0, have_y = 0;
  if (!lx || !ly) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
  if (o.ndescr > 0 && o.descrX && o.descrY) {
    for (int s = 0; s < 2; s++) {
      const ssi_submesh *kk = s ? &ky.sub : &kx.sub;
      if (!kk->active) continue;
      double *d = malloc(sizeof(double) * (size_t)kk->mesh.nv * (size_t)o.ndescr);
      if (!d) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
      ssi_submesh_restrict(kk, s ? Y->nv : X->nv, o.ndescr, s ? o.descrY : o.descrX, d);
      if (s) dY = d, o.descrY = d;
      else dX = d, o.descrX = d;
    }
  }
  for (int i = 0; i < nl; i++) lx[i] = ssi_submesh_sub_vertex(&kx.sub, lmX[i]), ly[i] = ssi_submesh_sub_vertex(&ky.sub, lmY[i]);
  int kev = ss_match_eigenpairs(&o, nl);
  /* very large meshes are matched through coarse proxies (topology kept), the map lifted back */
  const ss_mesh *FX = PX;
  /* (not with the caller's descriptors: their rows are the mesh's vertices, not the proxy's) */
  if (!(o.ndescr > 0 && o.descrX && o.descrY) &&
      ((st = ssi_proxy_make(PX, nl, lx, &cx, err)) || (st = ssi_proxy_make(PY, nl, ly, &cy, err))))
    goto done;
  if (cx.active) PX = &cx.mesh;
  if (cy.active) PY = &cy.mesh;
  /* STD with landmarks uses no segments: only the spectra, unless the pairing is asked for */
  const int segment = ss_match_segments(&o, nl);
  double t_prep = ss_time();
  if ((st = prepare_both(PX, PY, segment, &o.seg, kev, &pX, &pY, &have_x, &have_y, err))) goto done;
  t_prep = ss_time() - t_prep;
  if ((st = ssi_check_landmarks_segmented(&pX, &pY, nl, lx, ly, lmX, lmY, err))) goto done;
  if ((st = ss_match_prepared(&pX, &pY, nl, lx, ly, &o, out, err))) goto done;
  /* the stage times add up both shapes' work; the total is the time this call took */
  out->t_total += t_prep - (pX.t_segment + pY.t_segment + pX.t_eigs + pY.t_eigs);
  /* back to the input meshes' vertices: from the proxies, then from the kept components */
  if ((st = ssi_match_lift(&cx, &cy, FX, out, err))) goto done;
  if ((st = ssi_match_lift(&kx.sub, &ky.sub, X, out, err))) goto done;
  ssi_kept_warning(&kx, X, "X (the first mesh)", 1, warnings, warnings_size);
  ssi_kept_warning(&ky, Y, "Y (the second mesh)", 0, warnings, warnings_size);
done:
  if (st) ss_match_result_free(out);
  if (have_x) ss_shape_prep_free(&pX);
  if (have_y) ss_shape_prep_free(&pY);
  free(lx);
  free(ly);
  free(dX);
  free(dY);
  ssi_kept_free(&kx);
  ssi_kept_free(&ky);
  ssi_submesh_free(&cx);
  ssi_submesh_free(&cy);
  return st;
}

ss_status ss_pair_auto(const ss_mesh *X, const ss_mesh *Y, const ss_match_options *opts_in, ss_segment_pairs *pairs,
                       int **centerX, int **centerY, ss_autopair_info *info, ss_error *err) {
  if (!pairs) return ss_fail(err, SS_ERR_INVALID, "pair: NULL output");
  memset(pairs, 0, sizeof *pairs);
  if (centerX) *centerX = NULL;
  if (centerY) *centerY = NULL;
  if (!X || !Y) return ss_fail(err, SS_ERR_INVALID, "pair: NULL mesh");
  ss_match_options o;
  if (opts_in) o = *opts_in;
  else ss_match_default_options(&o);
  int kev = o.autopair.descr_k > o.autopair.orient_k ? o.autopair.descr_k : o.autopair.orient_k;
  const int nmin = X->nv < Y->nv ? X->nv : Y->nv;
  if (kev >= nmin) kev = nmin - 1;
  ss_shape_prep pX = {0}, pY = {0};
  ss_centre_signature sX = {0}, sY = {0};
  ss_status st = ss_shape_prep_compute(X, &o.seg, kev, &pX, err);
  if (!st) st = ss_shape_prep_compute(Y, &o.seg, kev, &pY, err);
  if (!st) st = ss_centre_signature_compute(&pX, &o.autopair, &sX, err);
  if (!st) st = ss_centre_signature_compute(&pY, &o.autopair, &sY, err);
  if (!st) st = ss_pair_centres_auto(&sX, &sY, &o.autopair, pairs, info, err);
  if (!st && (centerX || centerY)) {
    int *cx = malloc(sizeof(int) * (size_t)(pairs->n > 0 ? pairs->n : 1));
    int *cy = malloc(sizeof(int) * (size_t)(pairs->n > 0 ? pairs->n : 1));
    if (!cx || !cy) {
      free(cx), free(cy);
      ss_segment_pairs_free(pairs);
      st = ss_fail(err, SS_ERR_NOMEM, "pair: out of memory");
    } else {
      for (int p = 0; p < pairs->n; p++) cx[p] = pX.seg.centers[pairs->sx[p]], cy[p] = pY.seg.centers[pairs->sy[p]];
      if (centerX) *centerX = cx;
      else free(cx);
      if (centerY) *centerY = cy;
      else free(cy);
    }
  }
  ss_centre_signature_free(&sX);
  ss_centre_signature_free(&sY);
  ss_shape_prep_free(&pX);
  ss_shape_prep_free(&pY);
  return st;
}
