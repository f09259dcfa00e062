/* The matching pipeline of paper §6 on two shapes: pairing of the segments, their probe functions as
 * extra probes of the functional map (STD / ASA / DIFF), point map, ZoomOut. */
#include "specseg/match.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Defaults of what the paper leaves open (docs/tuning.md). */
#define SS_DEFAULT_DESCR_K 100
#define SS_DEFAULT_REFINE_KMAX 120
#define SS_DEFAULT_REFINE_W_DESCR 1.0

void ss_match_default_options(ss_match_options *o) {
  memset(o, 0, sizeof *o);
  o->probes = SS_PROBES_DIFF;
  ss_fmap_match_default_options(&o->fmap);
  o->fmap.descr_k = SS_DEFAULT_DESCR_K;
  o->fmap.zoomout_kmax = SS_DEFAULT_REFINE_KMAX;
  ss_segment_default_options(&o->seg);
  o->segment_profile = SS_PROFILE_TENT;
  ss_pairing_default_options(&o->pairing);
  o->refine = SS_REFINE_BEST;
  o->refine_w_lap = 0.0;
  o->refine_w_descr = SS_DEFAULT_REFINE_W_DESCR;
  ss_autopair_default_options(&o->autopair);
}

void ss_match_paper_options(ss_match_options *o) {
  ss_match_default_options(o);
  o->fmap.descr_k = 0;
  o->seg_descr_k = 0;
  o->fmap.zoomout_kmax = 0;
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

/* eigenpairs the options need on each shape */
static int match_kev(const ss_match_options *o) {
  int kev = o->fmap.k;
  if (o->refine != SS_REFINE_NONE && o->fmap.zoomout_kmax > kev) kev = o->fmap.zoomout_kmax;
  if (o->fmap.descr_k > kev) kev = o->fmap.descr_k;
  if (o->probes != SS_PROBES_STD && o->seg_descr_k > kev) kev = o->seg_descr_k;
  return kev;
}

/* the selection energy of SS_REFINE_BEST for the point map X -> Y (see match.h) */
static ss_status select_energy(const ss_shape_prep *X, const ss_shape_prep *Y, const ss_match_options *o, int k, int kz,
                               const ss_fmap_probes *bX, const ss_fmap_probes *bY, const int *map, double *E, ss_error *err) {
  ss_status st = ss_p2p_energy(Y->mesh->nv, X->mesh->nv, Y->evals, X->evals, Y->evecs, X->evecs, X->M, map, k, kz, 1,
                               o->refine_w_lap, E, NULL, NULL, err);
  if (st || !(o->refine_w_descr > 0)) return st;
  double r;
  if ((st = ss_p2p_descr_residual(Y->mesh->nv, X->mesh->nv, Y->evecs, X->evecs, X->M, bY, bX, map, &r, err))) return st;
  *E += o->refine_w_descr * r;
  return SS_OK;
}

static void add_note(ss_match_result *r, const char *msg) {
  size_t n = strlen(r->notes);
  snprintf(r->notes + n, sizeof r->notes - n, "%s%s", n ? "; " : "", msg);
}

static ss_status copy_pairs(const ss_segment_pairs *in, ss_segment_pairs *out, ss_error *err) {
  memset(out, 0, sizeof *out);
  const int n = in->n;
  out->sx = malloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
  out->sy = malloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
  out->energy = malloc(sizeof(double) * (size_t)(n > 0 ? n : 1));
  if (!out->sx || !out->sy || !out->energy) {
    ss_segment_pairs_free(out);
    return ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
  }
  if (n > 0) {
    memcpy(out->sx, in->sx, sizeof(int) * (size_t)n);
    memcpy(out->sy, in->sy, sizeof(int) * (size_t)n);
    memcpy(out->energy, in->energy, sizeof(double) * (size_t)n);
  }
  out->n = n, out->nx = in->nx, out->ny = in->ny;
  return SS_OK;
}

/* The pipeline; given (may be NULL): a pairing of the segments to use instead of the landmark one
 * (the landmark-free path, whose landmarks are the paired centres). */
static ss_status match_core(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX, const int *lmY,
                            const ss_segment_pairs *given, const ss_match_options *opts_in, ss_match_result *out,
                            ss_error *err) {
  double t_start = ss_time();
  out->refine_choice = -1;
  for (int i = 0; i < 4; i++) out->refine_energy[i] = NAN;
  ss_match_options o;
  if (opts_in) o = *opts_in;
  else ss_match_default_options(&o);
  if (!X || !Y || !X->mesh || !Y->mesh || !X->evecs || !Y->evecs)
    return ss_fail(err, SS_ERR_INVALID, "match: shapes not prepared");
  if ((int)o.segment_profile < SS_PROFILE_INDICATOR || o.segment_profile > SS_PROFILE_SOFT)
    return ss_fail(err, SS_ERR_INVALID, "match: unknown segment profile %d", (int)o.segment_profile);
  if (o.probes < SS_PROBES_STD || o.probes > SS_PROBES_DIFF)
    return ss_fail(err, SS_ERR_INVALID, "match: unknown probe set %d", (int)o.probes);
  if (o.seg_descr_k != 0 && o.seg_descr_k < o.fmap.k)
    return ss_fail(err, SS_ERR_INVALID, "match: seg_descr_k %d below k = %d", o.seg_descr_k, o.fmap.k);
  if (o.refine < SS_REFINE_NONE || o.refine > SS_REFINE_BEST)
    return ss_fail(err, SS_ERR_INVALID, "match: unknown refinement %d", (int)o.refine);
  if (!(o.refine_w_lap >= 0) || !isfinite(o.refine_w_lap) || !(o.refine_w_descr >= 0) || !isfinite(o.refine_w_descr))
    return ss_fail(err, SS_ERR_INVALID, "match: refine weights %g, %g must be finite and non-negative", o.refine_w_lap,
                   o.refine_w_descr);
  if (nl < 1 || !lmX || !lmY) return ss_fail(err, SS_ERR_INVALID, "match: needs at least one landmark");
  const int nX = X->mesh->nv, nY = Y->mesh->nv, k = o.fmap.k;
  for (int i = 0; i < nl; i++) {
    if (lmX[i] < 0 || lmX[i] >= nX)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on X [0,%d)", i, lmX[i], nX);
    if (lmY[i] < 0 || lmY[i] >= nY)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on Y [0,%d)", i, lmY[i], nY);
  }
  if (k < 3 || (o.fmap.zoomout_kmax != 0 && o.fmap.zoomout_kmax < k))
    return ss_fail(err, SS_ERR_INVALID, "match: bad basis sizes (k %d, ZoomOut %d)", k, o.fmap.zoomout_kmax);
  /* ZoomOut size: only with refinement */
  const int kz = o.refine != SS_REFINE_NONE && o.fmap.zoomout_kmax > k ? o.fmap.zoomout_kmax : k;
  int need = match_kev(&o);
  if (X->kev < need || Y->kev < need)
    return ss_fail(err, SS_ERR_INVALID, "match: %d eigenpairs needed, shapes have %d and %d", need, X->kev, Y->kev);

  ss_status st = SS_OK;
  double *EX = NULL, *EY = NULL, *Ck[2] = {NULL, NULL}, *Cz = NULL, *Cbest = NULL;
  int *cand = NULL, *zmap = NULL;
  ss_fmap_probes bX = {0}, bY = {0}, xX = {0}, xY = {0}, sbX = {0}, sbY = {0}; /* sb: STD's base, no operators */
  ss_fmap_system *sys = NULL;
  out->nX = nX;
  out->t_segment = X->t_segment + Y->t_segment;
  out->t_eigs = X->t_eigs + Y->t_eigs;

  /* 1. pairing of the segments (reported for every probe set) */
  double t0 = ss_time();
  if (given) {
    if ((st = copy_pairs(given, &out->pairs, err))) goto fail;
  } else if ((st = ss_pair_segments_conf(&X->seg, &Y->seg, nl, lmX, lmY, &o.pairing, &out->pairs, err))) goto fail;
  int np = out->pairs.n;
  out->centerX = malloc(sizeof(int) * (size_t)(np > 0 ? np : 1));
  out->centerY = malloc(sizeof(int) * (size_t)(np > 0 ? np : 1));
  if (!out->centerX || !out->centerY) goto nomem;
  for (int p = 0; p < np; p++) {
    out->centerX[p] = X->seg.centers[out->pairs.sx[p]];
    out->centerY[p] = Y->seg.centers[out->pairs.sy[p]];
  }
  double t1 = ss_time();
  out->t_pair = t1 - t0;

  /* 2. functional maps at size k: STD (base probes alone) and the segment-aided one (with the
   * chosen extra probes), against one assembled system per descriptor basis */
  int use_seg = o.probes != SS_PROBES_STD;
  if (use_seg && nl < o.pairing.min_landmarks) {
    char msg[160];
    snprintf(msg, sizeof msg, "%d landmarks (fewer than %d): no segment probes, STD map", nl, o.pairing.min_landmarks);
    add_note(out, msg);
    use_seg = 0;
  } else if (use_seg && np == 0) {
    add_note(out, "no segment paired: STD map");
    use_seg = 0;
  }
  /* candidate starts: 0 STD, 1 segment-aided */
  const int want_std = !use_seg || o.refine == SS_REFINE_BEST, want_seg = use_seg;
  ss_fmap_shape sX = {X->mesh, X->M, X->evals, X->evecs, X->kev}, sY = {Y->mesh, Y->M, Y->evals, Y->evecs, Y->kev};
  /* fo[0]: the STD map's options, fo[1]: the segment-aided one's (its own descriptor basis); one
   * assembled system per distinct descriptor basis */
  ss_fmap_match_options fo[2] = {o.fmap, o.fmap};
  fo[0].zoomout_kmax = fo[1].zoomout_kmax = 0; /* ZoomOut is run (and timed) below */
  fo[1].descr_k = o.seg_descr_k;
  const int ops = o.fmap.w_dcomm > 0, xops = ops && o.fmap.extra_dcomm;
  const int kd0 = fo[0].descr_k > k ? fo[0].descr_k : k, kd1 = fo[1].descr_k > k ? fo[1].descr_k : k;
  const int own1 = want_seg && (!want_std || kd1 != kd0); /* the segment-aided map needs its own base */
  ss_fmap_weights w;
  if ((st = ss_fmap_pair_weights(&sX, &sY, &fo[0], &w, err))) goto fail;
  for (int c = 0; c < 2; c++) {
    if (!(c ? want_seg : want_std)) continue;
    if (c == 0 || own1) {
      ss_fmap_probes_free(&bX), ss_fmap_probes_free(&bY);
      ss_fmap_system_free(sys);
      sys = NULL;
      if ((st = ss_fmap_base_probes(&sX, nl, lmX, &fo[c], ops, &bX, err))) goto fail;
      if ((st = ss_fmap_base_probes(&sY, nl, lmY, &fo[c], ops, &bY, err))) goto fail;
      /* source S = Y, target T = X: C maps functions on Y to functions on X, so its point map is X -> Y */
      if ((st = ss_fmap_system_new(k, k, Y->evals, X->evals, &bY, &bX, &w, &sys, err))) goto fail;
      if (c == 0 && o.refine == SS_REFINE_BEST && o.refine_w_descr > 0) { /* for the selection energy */
        if ((st = ss_fmap_base_probes(&sX, nl, lmX, &fo[0], 0, &sbX, err))) goto fail;
        if ((st = ss_fmap_base_probes(&sY, nl, lmY, &fo[0], 0, &sbY, err))) goto fail;
      }
    }
    if (c == 1) {
      ss_probe_filter filt = o.probes == SS_PROBES_DIFF ? SS_PROBE_WAVE : SS_PROBE_RAW;
      if ((st = ss_segment_probes(&X->seg, np, out->pairs.sx, o.segment_profile, &EX, err))) goto fail;
      if ((st = ss_segment_probes(&Y->seg, np, out->pairs.sy, o.segment_profile, &EY, err))) goto fail;
      if ((st = ss_fmap_extra_probes(&sX, nl, np, EX, filt, &fo[1], xops, &xX, err))) goto fail;
      if ((st = ss_fmap_extra_probes(&sY, nl, np, EY, filt, &fo[1], xops, &xY, err))) goto fail;
    }
    if (!(Ck[c] = malloc(sizeof(double) * (size_t)k * k))) goto nomem;
    if ((st = ss_fmap_system_solve(sys, c ? &xY : NULL, c ? &xX : NULL, o.fmap.w_extra, o.fmap.extra_dcomm, Ck[c], err)))
      goto fail;
  }
  out->map = malloc(sizeof(int) * (size_t)nX);
  if (!out->map) goto nomem;
  double t2 = ss_time();
  out->t_fmap = t2 - t1;

  /* 3. point map: unrefined, ZoomOut of the chosen probes' map, or the best of the candidates */
  const int main_c = use_seg ? 1 : 0;
  if (o.refine != SS_REFINE_BEST) {
    if (kz > k) {
      out->kc = kz;
      if (!(out->C = malloc(sizeof(double) * (size_t)kz * kz))) goto nomem;
      int step = o.fmap.zoomout_step > 0 ? o.fmap.zoomout_step : 1;
      if ((st = ss_zoomout(nY, nX, Y->evecs, X->evecs, X->M, k, Ck[main_c], kz, step, out->map, out->C, err))) goto fail;
      out->t_zoomout = ss_time() - t2;
    } else {
      if ((st = ss_fmap_p2p(nY, nX, k, k, Y->evecs, X->evecs, Ck[main_c], out->map, err))) goto fail;
      out->kc = k;
      out->C = Ck[main_c];
      Ck[main_c] = NULL;
    }
  } else {
    /* candidates 2c (start c at size k) and 2c+1 (its ZoomOut to kz), selection energy at size kz */
    cand = malloc(sizeof(int) * (size_t)nX);
    zmap = malloc(sizeof(int) * (size_t)nX);
    Cz = malloc(sizeof(double) * (size_t)kz * kz);
    Cbest = malloc(sizeof(double) * (size_t)kz * kz);
    if (!cand || !zmap || !Cz || !Cbest) goto nomem;
    const int step = o.fmap.zoomout_step > 0 ? o.fmap.zoomout_step : 1;
    double best = INFINITY;
    int kbest = k;
    for (int c = 0; c < 2; c++) {
      if (!Ck[c]) continue;
      if ((st = ss_fmap_p2p(nY, nX, k, k, Y->evecs, X->evecs, Ck[c], cand, err))) goto fail;
      double e0, e1 = INFINITY;
      if ((st = select_energy(X, Y, &o, k, kz, &sbX, &sbY, cand, &e0, err))) goto fail;
      out->refine_energy[2 * c] = e0;
      if (kz > k) {
        double tz = ss_time();
        if ((st = ss_zoomout(nY, nX, Y->evecs, X->evecs, X->M, k, Ck[c], kz, step, zmap, Cz, err))) goto fail;
        out->t_zoomout += ss_time() - tz;
        if ((st = select_energy(X, Y, &o, k, kz, &sbX, &sbY, zmap, &e1, err))) goto fail;
        out->refine_energy[2 * c + 1] = e1;
      }
      /* the start, then its refinement only when it lowers the energy (ties keep the earlier one) */
      if (e0 < best) {
        best = e0, out->refine_choice = 2 * c, kbest = k;
        memcpy(out->map, cand, sizeof(int) * (size_t)nX);
        memcpy(Cbest, Ck[c], sizeof(double) * (size_t)k * k);
      }
      if (e1 < best && e1 <= e0) {
        best = e1, out->refine_choice = 2 * c + 1, kbest = kz;
        memcpy(out->map, zmap, sizeof(int) * (size_t)nX);
        memcpy(Cbest, Cz, sizeof(double) * (size_t)kz * kz);
      }
    }
    out->kc = kbest;
    out->C = Cbest;
    Cbest = NULL;
  }
  out->t_total = out->t_segment + out->t_eigs + (ss_time() - t_start);
  goto cleanup;
nomem:
  st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
fail:
  ss_match_result_free(out);
cleanup:
  ss_fmap_system_free(sys);
  ss_fmap_probes_free(&bX), ss_fmap_probes_free(&bY), ss_fmap_probes_free(&xX), ss_fmap_probes_free(&xY);
  ss_fmap_probes_free(&sbX), ss_fmap_probes_free(&sbY);
  free(EX), free(EY), free(Ck[0]), free(Ck[1]), free(Cz), free(Cbest), free(cand), free(zmap);
  return st;
}

ss_status ss_match_prepared(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX, const int *lmY,
                            const ss_match_options *opts, ss_match_result *out, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  if (nl == 0) return ss_match_prepared_auto(X, Y, NULL, NULL, opts, out, err);
  memset(out, 0, sizeof *out);
  return match_core(X, Y, nl, lmX, lmY, NULL, opts, out, err);
}

ss_status ss_match_prepared_auto(const ss_shape_prep *X, const ss_shape_prep *Y, const ss_centre_signature *sigX,
                                 const ss_centre_signature *sigY, const ss_match_options *opts_in, ss_match_result *out,
                                 ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  memset(out, 0, sizeof *out);
  ss_match_options o;
  if (opts_in) o = *opts_in;
  else ss_match_default_options(&o);
  if (!X || !Y || !X->mesh || !Y->mesh || !X->evecs || !Y->evecs)
    return ss_fail(err, SS_ERR_INVALID, "match: shapes not prepared");
  ss_centre_signature own[2];
  memset(own, 0, sizeof own);
  ss_segment_pairs pr = {0};
  ss_autopair_info info;
  int *lx = NULL, *ly = NULL;
  ss_status st = SS_OK;
  double t0 = ss_time();
  if (!sigX && (st = ss_centre_signature_compute(X, &o.autopair, &own[0], err))) goto done;
  if (!sigY && (st = ss_centre_signature_compute(Y, &o.autopair, &own[1], err))) goto done;
  if ((st = ss_pair_centres_auto(sigX ? sigX : &own[0], sigY ? sigY : &own[1], &o.autopair, &pr, &info, err))) goto done;
  double t_pair = ss_time() - t0;
  lx = malloc(sizeof(int) * (size_t)(pr.n > 0 ? pr.n : 1));
  ly = malloc(sizeof(int) * (size_t)(pr.n > 0 ? pr.n : 1));
  if (!lx || !ly) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
  for (int p = 0; p < pr.n; p++) lx[p] = X->seg.centers[pr.sx[p]], ly[p] = Y->seg.centers[pr.sy[p]];
  /* the paired centres are the landmarks; the pairing is the segments' */
  o.pairing.min_landmarks = 1;
  if ((st = match_core(X, Y, pr.n, lx, ly, &pr, &o, out, err))) goto done;
  out->t_pair += t_pair;
  out->autopair = info;
  if (!info.confident) {
    char msg[200];
    snprintf(msg, sizeof msg, "landmark-free pairing NOT confident (gap %.3g, min %.3g; orientation %.2f, min %.2f): the "
             "map may be wrong (give landmarks)", info.gap, o.autopair.min_gap, info.mirror, o.autopair.min_mirror);
    add_note(out, msg);
  }
done:
  ss_centre_signature_free(&own[0]);
  ss_centre_signature_free(&own[1]);
  ss_segment_pairs_free(&pr);
  free(lx), free(ly);
  return st;
}

ss_status ss_match(const ss_mesh *X, const ss_mesh *Y, int nl, const int *lmX, const int *lmY,
                   const ss_match_options *opts_in, ss_match_result *out, ss_error *err) {
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
  int kev = match_kev(&o);
  ss_shape_prep pX, pY;
  ss_status st = ss_shape_prep_compute(X, &o.seg, kev, &pX, err);
  if (st) return st;
  if ((st = ss_shape_prep_compute(Y, &o.seg, kev, &pY, err))) {
    ss_shape_prep_free(&pX);
    return st;
  }
  st = ss_match_prepared(&pX, &pY, nl, lmX, lmY, &o, out, err);
  ss_shape_prep_free(&pX);
  ss_shape_prep_free(&pY);
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
