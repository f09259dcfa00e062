/* The one place where the evaluation calls the matching pipeline (issue 5's ss_match_prepared,
 * decomposed so that what depends on one shape is computed once per shape and what depends on one
 * pair once per pair): landmark fields at the critical points (per shape, cached), base probes
 * (per shape and landmark set), pairing and the assembled normal equations (per pair and landmark
 * set, shared by STD / ASA / DIFF), then one solve and point map per method. The library calls are
 * the ones ss_match_prepared makes, so the maps are the same (tests/test_eval.c checks it). */
#include "eval_internal.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

const int *ev_landmarks(const ev_context *ctx, const ev_shape *s, int lmset) {
  if (s->own_lm && (lmset == SS_LM_BEST || lmset == SS_LM_GT)) return lmset == SS_LM_BEST ? s->best : s->gt;
  return lmset == SS_LM_BEST ? ctx->best : lmset == SS_LM_GT ? ctx->gt : lmset == SS_LM_FPS ? s->fps : NULL;
}

static ss_fmap_shape fmap_shape(const ev_shape *s) {
  ss_fmap_shape f = {&s->mesh, s->prep.M, s->prep.evals, s->prep.evecs, s->prep.kev, NULL, 0, NULL, 0};
  return f;
}

static ss_fmap_match_options fmap_options(const ev_context *ctx) {
  ss_fmap_match_options fo = ctx->mopt.fmap;
  return fo;
}

ss_status ev_shape_probes(ev_shape *s, const ev_context *ctx, int lm_mask, ss_error *err) {
  ss_fmap_shape f = fmap_shape(s);
  ss_fmap_match_options fo = fmap_options(ctx);
  int todo = 0;
  for (int set = 0; set < 3; set++) todo += (lm_mask >> set & 1) && s->base[set].p == 0;
  /* the landmark sets share the shape-only parts (the same numbers as computed per set) */
  ss_fmap_probe_cache c = {0};
  ss_status st = SS_OK;
  if (todo > 1 && !fo.no_wks && !(st = ss_fmap_probe_cache_compute(&f, &fo, 1, 0, &c, err))) f.cache = &c, f.ncache = 1;
  for (int set = 0; set < 3 && !st; set++) {
    if (!(lm_mask >> set & 1) || s->base[set].p > 0) continue;
    st = ss_fmap_base_probes(&f, EV_NL, ev_landmarks(ctx, s, set), &fo, fo.w_dcomm > 0, &s->base[set], err);
  }
  ss_fmap_probe_cache_free(&c);
  return st;
}

/* the calling thread's CPU seconds (the evaluation runs pairs in parallel) */
static double thread_cpu(void) {
  struct timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static ss_status match_paper(const ev_context *ctx, const ev_shape *X, const ev_shape *Y, int lmset, int methods_mask,
                             int *const maps[SS_EVAL_NMETHODS], double cpu[SS_EVAL_NMETHODS], int *paired,
                             ss_segment_pairs *pairs_out, ss_error *err);

/* the landmark-free pairing (SS_LM_NONE) of two shapes from their signatures, and the paired centres
 * as landmarks (lmX, lmY: malloc'd pr->n vertices) */
static ss_status auto_landmarks(const ev_context *ctx, const ev_shape *X, const ev_shape *Y, ss_segment_pairs *pr,
                                int **lmX, int **lmY, ss_error *err) {
  *lmX = *lmY = NULL;
  if (X->sig.m < 1 || Y->sig.m < 1) return ss_fail(err, SS_ERR_INVALID, "eval: landmark-free rows need signatures");
  ss_status st = ss_pair_centres_auto(&X->sig, &Y->sig, &ctx->mopt.autopair, pr, NULL, err);
  if (st) return st;
  *lmX = malloc(sizeof(int) * (size_t)(pr->n > 0 ? pr->n : 1));
  *lmY = malloc(sizeof(int) * (size_t)(pr->n > 0 ? pr->n : 1));
  if (!*lmX || !*lmY) {
    free(*lmX), free(*lmY), *lmX = *lmY = NULL, ss_segment_pairs_free(pr);
    return ss_fail(err, SS_ERR_NOMEM, "eval: out of memory");
  }
  for (int q = 0; q < pr->n; q++) (*lmX)[q] = X->prep.seg.centers[pr->sx[q]], (*lmY)[q] = Y->prep.seg.centers[pr->sy[q]];
  return SS_OK;
}

/* the refined default (SS_METHOD_REFINED): the confident pairing from the cached landmark fields,
 * then ss_match_prepared_pairs on the shapes' refined eigenpairs */
static ss_status match_refined(const ev_context *ctx, const ev_shape *X, const ev_shape *Y, int lmset, int *map, int *paired,
                               ss_error *err) {
  if (ctx->kref <= 0 || !X->rprep.evecs || !Y->rprep.evecs)
    return ss_fail(err, SS_ERR_INVALID, "eval: the refined method needs the shapes' refined eigenpairs");
  ss_segment_pairs pr;
  int *aX = NULL, *aY = NULL, nl = EV_NL;
  const int *lmX = ev_landmarks(ctx, X, lmset), *lmY = ev_landmarks(ctx, Y, lmset);
  ss_status st = lmset == SS_LM_NONE ? auto_landmarks(ctx, X, Y, &pr, &aX, &aY, err)
                                     : ss_pair_critical_points_conf(X->prep.seg.m, Y->prep.seg.m, EV_NL, X->lmd[lmset],
                                                                    Y->lmd[lmset], &ctx->ropt.pairing, &pr, err);
  if (st) return st;
  if (lmset == SS_LM_NONE) lmX = aX, lmY = aY, nl = pr.n;
  ss_match_result res;
  st = ss_match_prepared_pairs(&X->rprep, &Y->rprep, nl, lmX, lmY, &pr, &ctx->ropt, &res, err);
  ss_segment_pairs_free(&pr);
  free(aX), free(aY);
  if (st) return st;
  memcpy(map, res.map, sizeof(int) * (size_t)X->mesh.nv);
  *paired = res.pairs.n;
  ss_match_result_free(&res);
  return SS_OK;
}

ss_status ev_match_methods(const ev_context *ctx, const ev_shape *X, const ev_shape *Y, int lmset, int methods_mask,
                           int *const maps[SS_EVAL_NMETHODS], double cpu[SS_EVAL_NMETHODS], int paired_out[SS_EVAL_NMETHODS],
                           ss_error *err) {
  return ev_match_methods_pairs(ctx, X, Y, lmset, methods_mask, maps, cpu, paired_out, NULL, err);
}

ss_status ev_match_methods_pairs(const ev_context *ctx, const ev_shape *X, const ev_shape *Y, int lmset, int methods_mask,
                                 int *const maps[SS_EVAL_NMETHODS], double cpu[SS_EVAL_NMETHODS],
                                 int paired_out[SS_EVAL_NMETHODS], ss_segment_pairs *pairs_out, ss_error *err) {
  int paired_ref = 0;
  double c_ref = 0;
  if (methods_mask >> SS_METHOD_REFINED & 1) {
    double c0 = thread_cpu();
    ss_status st = match_refined(ctx, X, Y, lmset, maps[SS_METHOD_REFINED], &paired_ref, err);
    if (st) return st;
    c_ref = thread_cpu() - c0;
  }
  int paired_paper = 0;
  ss_status st = SS_OK;
  if (methods_mask & 7) st = match_paper(ctx, X, Y, lmset, methods_mask & 7, maps, cpu, &paired_paper, pairs_out, err);
  if (st) return st;
  if (cpu) cpu[SS_METHOD_REFINED] = c_ref;
  if (paired_out)
    for (int m = 0; m < SS_EVAL_NMETHODS; m++) paired_out[m] = m == SS_METHOD_REFINED ? paired_ref : paired_paper;
  return SS_OK;
}

/* the paper's methods of one pair and landmark set (mask within 7); pairs_out (may be NULL): the
 * segment pairing used */
static ss_status match_paper(const ev_context *ctx, const ev_shape *X, const ev_shape *Y, int lmset, int methods_mask,
                             int *const maps[SS_EVAL_NMETHODS], double cpu[SS_EVAL_NMETHODS], int *paired,
                             ss_segment_pairs *pairs_out, ss_error *err) {
  const ss_shape_prep *pX = &X->prep, *pY = &Y->prep;
  const double c_start = thread_cpu();
  ss_fmap_shape sX = fmap_shape(X), sY = fmap_shape(Y);
  ss_fmap_match_options fo = fmap_options(ctx);
  const int k = fo.k, ops = fo.w_dcomm > 0, xops = ops && fo.extra_dcomm;
  const int *lmX = ev_landmarks(ctx, X, lmset), *lmY = ev_landmarks(ctx, Y, lmset);
  int nl = EV_NL, *autoX = NULL, *autoY = NULL;
  ss_segment_pairs pr;
  ss_status st;
  if (lmset == SS_LM_NONE) { /* landmark-free: the automatic pairing, its centres as the landmarks */
    if ((st = auto_landmarks(ctx, X, Y, &pr, &autoX, &autoY, err))) return st;
    lmX = autoX, lmY = autoY, nl = pr.n;
  } else if ((st = ss_pair_critical_points_conf(pX->seg.m, pY->seg.m, EV_NL, X->lmd[lmset], Y->lmd[lmset], &ctx->mopt.pairing,
                                                &pr, err))) { /* the paper's rule unless the run asks for the safeguards */
    return st;
  }
  if (nl < ctx->mopt.pairing.min_landmarks) ss_segment_pairs_free(&pr); /* too few landmarks: no segment probes */
  *paired = pr.n;
  ss_fmap_probes ownX = {0}, ownY = {0}, xX = {0}, xY = {0};
  ss_fmap_system *sys = NULL;
  double *EX = NULL, *EY = NULL, *Ck = malloc(sizeof(double) * (size_t)k * k), c_method[3] = {0};
  if (!Ck) { st = ss_fail(err, SS_ERR_NOMEM, "eval: out of memory"); goto done; }
  /* base probes: the shapes' own (ev_shape_probes), else built here */
  static const ss_fmap_probes none = {0};
  const ss_fmap_probes *bX = lmset < 3 ? &X->base[lmset] : &none, *bY = lmset < 3 ? &Y->base[lmset] : &none;
  if (bX->p == 0) {
    if ((st = ss_fmap_base_probes(&sX, nl, lmX, &fo, ops, &ownX, err))) goto done;
    bX = &ownX;
  }
  if (bY->p == 0) {
    if ((st = ss_fmap_base_probes(&sY, nl, lmY, &fo, ops, &ownY, err))) goto done;
    bY = &ownY;
  }
  /* source S = Y, target T = X (see ss_fmap_match) */
  ss_fmap_weights w;
  if ((st = ss_fmap_pair_weights(&sX, &sY, &fo, &w, err))) goto done;
  if ((st = ss_fmap_system_new(k, k, pY->evals, pX->evals, bY, bX, &w, &sys, err))) goto done;
  if ((methods_mask & ~1) && pr.n > 0 && ctx->mopt.pairing.min_map_share > 0) {
    /* the pairing's map check (the confident rule), against the STD map, as ss_match_prepared does */
    int *m0 = malloc(sizeof(int) * (size_t)X->mesh.nv);
    if (!m0) { st = ss_fail(err, SS_ERR_NOMEM, "eval: out of memory"); goto done; }
    fo.zoomout_kmax = 0;
    st = ss_fmap_system_solve(sys, NULL, NULL, fo.w_extra, fo.extra_dcomm, Ck, err);
    if (!st) st = ss_fmap_match_finish(&sX, &sY, &fo, Ck, m0, NULL, err);
    if (!st) st = ss_segment_pairs_check_map(&pX->seg, &pY->seg, pX->M, m0, ctx->mopt.pairing.min_map_share, &pr, NULL,
                                             NULL, err);
    free(m0);
    if (st) goto done;
    *paired = pr.n;
  }
  if ((methods_mask & ~1) && pr.n > 0) {
    /* the same probe columns (indicator or tent profile) as ss_match_prepared builds */
    if ((st = ss_segment_probes(&pX->seg, pr.n, pr.sx, ctx->mopt.segment_profile, &EX, err))) goto done;
    if ((st = ss_segment_probes(&pY->seg, pr.n, pr.sy, ctx->mopt.segment_profile, &EY, err))) goto done;
  }
  const double c_shared = thread_cpu() - c_start;
  int nm = 0;
  for (int mth = 0; mth < 3; mth++) {
    if (!(methods_mask >> mth & 1)) continue;
    nm++;
    double c0 = thread_cpu();
    int nextra = mth == SS_METHOD_STD ? 0 : pr.n;
    if (nextra > 0) {
      ss_probe_filter f = mth == SS_METHOD_DIFF ? SS_PROBE_WAVE : SS_PROBE_RAW;
      if ((st = ss_fmap_extra_probes(&sX, nl, nextra, EX, f, &fo, xops, &xX, err))) goto done;
      if ((st = ss_fmap_extra_probes(&sY, nl, nextra, EY, f, &fo, xops, &xY, err))) goto done;
    }
    st = ss_fmap_system_solve(sys, nextra > 0 ? &xY : NULL, nextra > 0 ? &xX : NULL, fo.w_extra, fo.extra_dcomm, Ck, err);
    ss_fmap_probes_free(&xX), ss_fmap_probes_free(&xY);
    if (st) goto done;
    fo.zoomout_kmax = 0;
    if ((st = ss_fmap_match_finish(&sX, &sY, &fo, Ck, maps[mth], NULL, err))) goto done;
    c_method[mth] = thread_cpu() - c0;
  }
  if (cpu)
    for (int mth = 0; mth < 3; mth++) cpu[mth] = (methods_mask >> mth & 1) ? c_method[mth] + c_shared / nm : 0.0;
done:
  ss_fmap_system_free(sys);
  ss_fmap_probes_free(&ownX), ss_fmap_probes_free(&ownY), ss_fmap_probes_free(&xX), ss_fmap_probes_free(&xY);
  free(EX), free(EY), free(Ck), free(autoX), free(autoY);
  if (pairs_out && !st) *pairs_out = pr;
  else ss_segment_pairs_free(&pr);
  return st;
}

ss_status ev_match(const ev_context *ctx, const ev_shape *X, const ev_shape *Y, int lmset, int method, int *map,
                   int *paired, ss_error *err) {
  if (method < 0 || method >= SS_EVAL_NMETHODS) return ss_fail(err, SS_ERR_INVALID, "eval: unknown method %d", method);
  int *maps[SS_EVAL_NMETHODS] = {NULL, NULL, NULL, NULL}, pm[SS_EVAL_NMETHODS] = {0};
  maps[method] = map;
  ss_status st = ev_match_methods(ctx, X, Y, lmset, 1 << method, maps, NULL, pm, err);
  if (!st && paired) *paired = pm[method];
  return st;
}
