/* The one place where the evaluation calls the matching pipeline (issue 5's ss_match_prepared,
 * decomposed so that the per-shape landmark fields are computed once per shape instead of once per
 * pair and method: pairing from cached fields, segment indicators, ss_fmap_match). */
#include "eval_internal.h"

#include <stdlib.h>
#include <string.h>

const int *ev_landmarks(const ev_context *ctx, const ev_shape *s, int lmset) {
  return lmset == SS_LM_BEST ? ctx->best : lmset == SS_LM_GT ? ctx->gt : s->fps;
}

/* indicator of each paired segment on one shape: E (n x np), column p = 1 on segment seg[p] */
static double *indicators(int n, const int *labels, int m, int np, const int *seg) {
  double *E = calloc((size_t)n * (np > 0 ? np : 1), sizeof(double));
  int *col = malloc(sizeof(int) * (size_t)(m > 0 ? m : 1));
  if (!E || !col) { free(E); free(col); return NULL; }
  for (int s = 0; s < m; s++) col[s] = -1;
  for (int p = 0; p < np; p++) col[seg[p]] = p;
  for (int i = 0; i < n; i++)
    if (labels[i] >= 0 && labels[i] < m && col[labels[i]] >= 0) E[i + (size_t)n * col[labels[i]]] = 1.0;
  free(col);
  return E;
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
    EX = indicators(X->mesh.nv, pX->seg.labels, pX->seg.m, pr.n, pr.sx);
    EY = indicators(Y->mesh.nv, pY->seg.labels, pY->seg.m, pr.n, pr.sy);
    if (!EX || !EY) st = ss_fail(err, SS_ERR_NOMEM, "eval: out of memory for probes");
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
