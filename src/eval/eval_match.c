/* The one place where the evaluation calls the matching pipeline (issue 5's ss_match_prepared,
 * decomposed so that the per-shape landmark fields are computed once per shape instead of once per
 * pair and method: pairing from cached fields, segment indicators, ss_fmap_match). */
#include "eval_internal.h"

#include <stdlib.h>
#include <string.h>

const int *ev_landmarks(const ev_context *ctx, const ev_shape *s, int lmset) {
  return lmset == SS_LM_BEST ? ctx->best : lmset == SS_LM_GT ? ctx->gt : s->fps;
}

ss_status ev_match(const ev_context *ctx, const ev_shape *X, const ev_shape *Y, int lmset, int method, int *map,
                   int *paired, ss_error *err) {
  const ss_shape_prep *pX = &X->prep, *pY = &Y->prep;
  ss_segment_pairs pr;
  ss_status st = ss_pair_critical_points(pX->seg.m, pY->seg.m, EV_NL, X->lmd[lmset], Y->lmd[lmset], &pr, err);
  if (st) return st;
  *paired = pr.n;
  double *EX = NULL, *EY = NULL;
  int nextra = method == SS_METHOD_STD ? 0 : pr.n;
  if (nextra > 0) {
    /* the same probe columns (indicator or tent profile) as ss_match_prepared builds */
    st = ss_segment_probes(&pX->seg, pr.n, pr.sx, ctx->mopt.segment_profile, &EX, err);
    if (!st) st = ss_segment_probes(&pY->seg, pr.n, pr.sy, ctx->mopt.segment_profile, &EY, err);
  }
  if (!st) {
    ss_fmap_shape sX = {&X->mesh, pX->M, pX->evals, pX->evecs, pX->kev};
    ss_fmap_shape sY = {&Y->mesh, pY->M, pY->evals, pY->evecs, pY->kev};
    ss_fmap_match_options fo = ctx->mopt.fmap;
    fo.verbose = 0;
    st = ss_fmap_match(&sX, &sY, EV_NL, ev_landmarks(ctx, X, lmset), ev_landmarks(ctx, Y, lmset), nextra, EX, EY,
                       method == SS_METHOD_DIFF ? SS_PROBE_WAVE : SS_PROBE_RAW, &fo, map, NULL, err);
  }
  free(EX);
  free(EY);
  ss_segment_pairs_free(&pr);
  return st;
}
