/* Landmark fields that sharpen the lower bounds of target queries (ALT: for a landmark L and
 * exact distances d_L, d(p,t) >= |d_L(p) - d_L(t)|). Landmarks are spread by farthest-point
 * sampling on the edge graph (cheap; any spread works), their fields are exact. */
#include "geodesic/vtp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void ss_geodesic_landmarks_free(ss_geodesic_landmarks *acc) {
  if (!acc) return;
  free(acc->lm);
  free(acc);
}

ss_status ss_geodesic_landmarks_new(const ss_geodesic_mesh *gm, int nlandmarks, ss_geodesic_landmarks **out,
                                    ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "null output");
  *out = NULL;
  if (!gm) return ss_fail(err, SS_ERR_INVALID, "null geodesic mesh");
  if (nlandmarks < 1 || nlandmarks > SS_GEODESIC_MAX_LANDMARKS)
    return ss_fail(err, SS_ERR_INVALID, "landmark count %d outside [1,%d]", nlandmarks, SS_GEODESIC_MAX_LANDMARKS);
  int nv = gm->nv, K = nlandmarks < nv ? nlandmarks : nv;
  ss_geodesic_landmarks *acc = calloc(1, sizeof *acc);
  if (!acc) return ss_fail(err, SS_ERR_NOMEM, "out of memory");
  ss_mesh view = {gm->nv, gm->nf, gm->V, gm->F};
  ss_graph g;
  ss_status st = ss_graph_edges(&view, &g, err);
  if (st) {
    free(acc);
    return st;
  }
  int lmk[SS_GEODESIC_MAX_LANDMARKS];
  double *dg = malloc(sizeof(double) * (size_t)nv), *mind = malloc(sizeof(double) * (size_t)nv);
  double *F = malloc(sizeof(double) * (size_t)nv * (size_t)K), *lm = malloc(sizeof(double) * (size_t)nv * (size_t)K);
  if (!dg || !mind || !F || !lm) {
    st = ss_fail(err, SS_ERR_NOMEM, "out of memory");
    goto done;
  }
  /* first landmark: the vertex farthest from vertex 0 (an extremity), then farthest-point */
  int s = 0;
  if ((st = ss_graph_dijkstra(&g, &s, 1, 0, dg, NULL, err))) goto done;
  for (int i = 0; i < nv; i++) mind[i] = INFINITY;
  for (int k = 0; k < K; k++) {
    const double *ref = k == 0 ? dg : mind;
    int best = 0;
    double bv = -1;
    for (int i = 0; i < nv; i++)
      if (isfinite(ref[i]) && ref[i] > bv) { bv = ref[i]; best = i; }
    lmk[k] = best;
    if ((st = ss_graph_dijkstra(&g, &best, 1, 0, dg, NULL, err))) goto done;
    for (int i = 0; i < nv; i++) if (dg[i] < mind[i]) mind[i] = dg[i];
  }
  if ((st = ss_geodesic_fields(gm, lmk, K, 0, F, err))) goto done;
  for (int v = 0; v < nv; v++)
    for (int k = 0; k < K; k++) lm[(size_t)v * K + k] = F[(size_t)k * nv + v];
  acc->nv = nv;
  acc->nlm = K;
  acc->lm = lm;
  lm = NULL;
  *out = acc;
  acc = NULL;
done:
  ss_graph_free(&g);
  free(dg); free(mind); free(F); free(lm);
  ss_geodesic_landmarks_free(acc);
  return st;
}

double ss_geodesic_lower_bound(const ss_geodesic_mesh *gm, const ss_geodesic_landmarks *acc, int a, int b) {
  if (!gm || a < 0 || b < 0 || a >= gm->nv || b >= gm->nv) return 0.0;
  const double *pa = gm->V + 3 * (size_t)a, *pb = gm->V + 3 * (size_t)b;
  double dx = pa[0] - pb[0], dy = pa[1] - pb[1], dz = pa[2] - pb[2], lb = sqrt(dx * dx + dy * dy + dz * dz);
  if (acc && acc->nv == gm->nv) {
    const double *lm = acc->lm;
    const int K = acc->nlm;
    const double *la = lm + (size_t)a * K, *lb2 = lm + (size_t)b * K;
    for (int k = 0; k < K; k++) {
      double t = fabs(la[k] - lb2[k]);
      if (t > lb) lb = t;
    }
  }
  return lb;
}
