/* The probe functions of paired segments on one shape (indicator, tent or soft iVd profile). */
#include "specseg/match.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Indicator functions of the paired segments: E (n x npairs), column p = 1 on segment seg[p]. */
static double *indicators(int n, const int *labels, int npairs, const int *seg) {
  double *E = calloc((size_t)n * (npairs > 0 ? npairs : 1), sizeof(double));
  if (!E) return NULL;
  int m = 0;
  for (int p = 0; p < npairs; p++) m = seg[p] + 1 > m ? seg[p] + 1 : m;
  int *col = malloc(sizeof(int) * (size_t)(m > 0 ? m : 1)); /* segment → column, -1 when unpaired */
  if (!col) {
    free(E);
    return NULL;
  }
  for (int s = 0; s < m; s++) col[s] = -1;
  for (int p = 0; p < npairs; p++) col[seg[p]] = p;
  for (int i = 0; i < n; i++) {
    int s = labels[i];
    if (s >= 0 && s < m && col[s] >= 0) E[i + (size_t)n * col[s]] = 1.0;
  }
  free(col);
  return E;
}

/* The tent profile (SS_PROFILE_TENT): each nonzero column of E becomes
 * 1 − d/R on its segment, d the segmentation's distance (work mesh, through Ψ) to the centre. */
static void tent_profile(const ss_segmentation *sg, int n, int npairs, double *E) {
  for (int p = 0; p < npairs; p++) {
    double *f = E + (size_t)n * p, R = 0;
    for (int i = 0; i < n; i++)
      if (f[i] > 0 && sg->psi[i] >= 0 && sg->work_dist[sg->psi[i]] > R) R = sg->work_dist[sg->psi[i]];
    if (!(R > 0)) continue;
    for (int i = 0; i < n; i++)
      if (f[i] > 0) f[i] = sg->psi[i] >= 0 ? 1.0 - sg->work_dist[sg->psi[i]] / R : 0.0;
  }
}

/* Temperature of the soft iVd profile, in units of sqrt(area) of the work mesh (docs/tuning.md). */
#define SOFT_IVD_TAU 0.2

/* The soft iVd profile (SS_PROFILE_SOFT): column p = exp(−d_s/τ) / Σ_j exp(−d_j/τ), s = seg[p],
 * d_j the NPP22-graph distance on the work mesh from the centre of segment j (the distances whose
 * arg-min is the iVd, i.e. the segments themselves as τ → 0), pulled back through Ψ. The columns of
 * all m segments would sum to 1: a partition of unity whose transitions are τ wide instead of a step
 * at a boundary that the other shape places elsewhere. */
static ss_status soft_ivd_profile(const ss_segmentation *sg, int npairs, const int *seg, double *E, ss_error *err) {
  const int n = sg->nv, nw = sg->work.nv, m = sg->m;
  ss_graph g = {0};
  double *D = malloc(sizeof(double) * (size_t)nw * (m > 0 ? m : 1));
  ss_status st = SS_OK;
  if (!D) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory for segment probes"); goto done; }
  if ((st = ss_graph_npp22(&sg->work, &g, err))) goto done;
  for (int j = 0; j < m; j++)
    if ((st = ss_graph_dijkstra(&g, sg->crit + j, 1, 0, D + (size_t)nw * j, NULL, err))) goto done;
  const double area = ss_mesh_area(&sg->work), tau = SOFT_IVD_TAU * sqrt(area > 0 ? area : 1.0);
  for (int x = 0; x < n; x++) {
    int w = sg->psi[x];
    double dmin = INFINITY, z = 0;
    if (w >= 0 && w < nw)
      for (int j = 0; j < m; j++) dmin = fmin(dmin, D[w + (size_t)nw * j]);
    if (!isfinite(dmin)) { /* no centre reaches it (or no work vertex): in no segment */
      for (int p = 0; p < npairs; p++) E[x + (size_t)n * p] = 0;
      continue;
    }
    for (int j = 0; j < m; j++) z += exp(-(D[w + (size_t)nw * j] - dmin) / tau);
    for (int p = 0; p < npairs; p++) E[x + (size_t)n * p] = exp(-(D[w + (size_t)nw * seg[p]] - dmin) / tau) / z;
  }
done:
  ss_graph_free(&g);
  free(D);
  return st;
}

ss_status ss_segment_probes(const ss_segmentation *sg, int npairs, const int *seg, ss_segment_profile profile,
                            double **E, ss_error *err) {
  *E = NULL;
  if ((int)profile < SS_PROFILE_INDICATOR || profile > SS_PROFILE_SOFT)
    return ss_fail(err, SS_ERR_INVALID, "match: unknown segment profile %d", (int)profile);
  for (int p = 0; p < npairs; p++)
    if (seg[p] < 0 || seg[p] >= sg->m)
      return ss_fail(err, SS_ERR_INVALID, "match: paired segment %d out of range [0,%d)", seg[p], sg->m);
  if (profile == SS_PROFILE_TENT && (!sg->work_dist || !sg->psi))
    return ss_fail(err, SS_ERR_INVALID, "match: the tent segment profile needs the segmentation's distances");
  if (profile == SS_PROFILE_SOFT && (!sg->psi || !sg->crit || sg->work.nv < 1 || !sg->work.V || !sg->work.F))
    return ss_fail(err, SS_ERR_INVALID, "match: the soft segment profile needs the segmentation's work mesh");
  *E = indicators(sg->nv, sg->labels, npairs, seg);
  if (!*E) return ss_fail(err, SS_ERR_NOMEM, "match: out of memory for segment probes");
  if (profile == SS_PROFILE_TENT) tent_profile(sg, sg->nv, npairs, *E);
  if (profile == SS_PROFILE_SOFT) {
    ss_status st = soft_ivd_profile(sg, npairs, seg, *E, err);
    if (st) {
      free(*E);
      *E = NULL;
      return st;
    }
  }
  return SS_OK;
}

