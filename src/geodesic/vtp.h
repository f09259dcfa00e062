/* Internal: the exact propagation engine and its reusable per-thread workspace. */
#ifndef SS_GEODESIC_VTP_H
#define SS_GEODESIC_VTP_H

#include "geodesic/geodesic_mesh.h"

typedef struct ssi_vtp_ws ssi_vtp_ws;

/* Target queries with at most this many targets use A* keys (Euclidean lower bound). */
#define SS_VTP_MAX_HEUR 8

ssi_vtp_ws *ssi_vtp_ws_new(int nv, int nf);
void ssi_vtp_ws_free(ssi_vtp_ws *ws);

/* One propagation. dist (nv) receives the distances. max_dist <= 0 / INFINITY: no limit. targets
 * may be NULL; when given, propagation stops once all are settled. Returns SS_ERR_NOMEM or
 * SS_ERR_INVALID (bad source / target index); `settled_radius` (may be NULL) receives the queue key
 * at stop: every vertex with dist <= that value is exact. */
ss_status ssi_vtp_run(const ss_geodesic_mesh *gm, ssi_vtp_ws *ws, const int *sources, int nsources,
                     double max_dist, const int *targets, int ntargets, double *dist,
                     double *settled_radius, ss_error *err);

/* Exact d(source, targets[i]) -> out[i], stopping once every target is final; the cost follows the
 * region settled (no O(nv) work per call). astar != 0 (and ntargets <= SS_VTP_MAX_HEUR): keys add
 * a lower bound on the way to the nearest remaining target (Euclidean, and landmarks when lm is
 * given), which steers the front towards the targets. first != 0: stop at the first target that is
 * final and write only out[0] = the distance to the nearest target (INFINITY: none reachable). */
ss_status ssi_vtp_query(const ss_geodesic_mesh *gm, const ss_geodesic_landmarks *lm, ssi_vtp_ws *ws, int source,
                        const int *targets, int ntargets, int astar, int first, double *out, ss_error *err);

/* Counters of the last run (for benchmarks). */
typedef struct ssi_vtp_stats {
  long long windows_created, windows_propagated, events;
  size_t peak_heap, peak_windows;
  int touched; /* vertices whose estimate was set */
} ssi_vtp_stats;
void ssi_vtp_ws_stats(const ssi_vtp_ws *ws, ssi_vtp_stats *st);

#endif
