/* The hypothesis energy of a landmark-free map (ss_match_prepared_auto): how far a point map X -> Y
 * is from an orientation-preserving isometry, from the map alone (no ground truth). */
#include "match/hypotheses.h"
#include "match/autopair_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void ssi_hyp_ctx_free(ssi_hyp_ctx *c) {
  if (!c) return;
  ss_graph_free(&c->gX), ss_graph_free(&c->gY);
  free(c->src), free(c->dX), free(c->dY), free(c->dB);
  memset(c, 0, sizeof *c);
}

ss_status ssi_hyp_ctx_new(const ss_mesh *X, const ss_mesh *Y, int nsrc, int fit_scale, ssi_hyp_ctx *c,
                          ss_error *err) {
  memset(c, 0, sizeof *c);
  const int nX = X->nv;
  if (nsrc > nX) nsrc = nX;
  c->X = X, c->Y = Y, c->nsrc = nsrc, c->fit_scale = fit_scale, c->scale = 1;
  c->sX = sqrt(ss_mesh_area(X)), c->sY = sqrt(ss_mesh_area(Y));
  if (!(c->sX > 0) || !(c->sY > 0)) return ss_fail(err, SS_ERR_INVALID, "match: a mesh of zero area");
  ss_status st;
  if ((st = ss_graph_edges(X, &c->gX, err)) || (st = ss_graph_edges(Y, &c->gY, err))) goto fail;
  c->src = malloc(sizeof(int) * (size_t)nsrc);
  c->dX = malloc(sizeof(double) * (size_t)nX * nsrc);
  c->dY = malloc(sizeof(double) * (size_t)Y->nv);
  c->dB = malloc(sizeof(double) * (size_t)nX * nsrc);
  double *near = malloc(sizeof(double) * (size_t)nX);
  if (!c->src || !c->dX || !c->dY || !c->dB || !near) {
    free(near);
    st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
    goto fail;
  }
  /* farthest-point sources from vertex 0's farthest vertex (deterministic, spread over X) */
  int s = 0;
  if ((st = ss_graph_dijkstra(&c->gX, &s, 1, 0, c->dX, NULL, err))) { free(near); goto fail; }
  for (int v = 0; v < nX; v++)
    if (isfinite(c->dX[v]) && c->dX[v] > c->dX[s]) s = v;
  for (int v = 0; v < nX; v++) near[v] = INFINITY;
  for (int i = 0; i < nsrc; i++) {
    c->src[i] = s;
    double *d = c->dX + (size_t)nX * i;
    if ((st = ss_graph_dijkstra(&c->gX, &s, 1, 0, d, NULL, err))) { free(near); goto fail; }
    int far = s;
    for (int v = 0; v < nX; v++) {
      if (d[v] < near[v]) near[v] = d[v];
      if (isfinite(near[v]) && near[v] > near[far]) far = v;
    }
    s = far;
  }
  free(near);
  return SS_OK;
fail:
  ssi_hyp_ctx_free(c);
  return st;
}

ss_status ssi_hyp_distortion(ssi_hyp_ctx *c, const int *map, double *out, ss_error *err) {
  const int nX = c->X->nv;
  /* the images' distances first (b, one row per source), so that the scale is known before the sum */
  double sab = 0, sbb = 0;
  for (int i = 0; i < c->nsrc; i++) {
    int t = map[c->src[i]];
    ss_status st = ss_graph_dijkstra(&c->gY, &t, 1, 0, c->dY, NULL, err);
    if (st) return st;
    const double *a = c->dX + (size_t)nX * i;
    double *b = c->dB + (size_t)nX * i;
    for (int v = 0; v < nX; v++) {
      b[v] = c->dY[map[v]] / c->sY;
      if (isfinite(a[v]) && isfinite(b[v])) sab += a[v] / c->sX * b[v], sbb += b[v] * b[v];
    }
  }
  double s = 1;
  if (c->fit_scale && sbb > 0) s = fmin(fmax(sab / sbb, 0.5), 2.0);
  double sum = 0;
  long cnt = 0;
  for (size_t j = 0; j < (size_t)nX * c->nsrc; j++) {
    const double a = c->dX[j] / c->sX, b = s * c->dB[j];
    if (isfinite(a) && isfinite(b)) sum += fabs(a - b), cnt++;
  }
  c->scale = s;
  *out = cnt ? sum / (double)cnt : INFINITY;
  return SS_OK;
}
