/* Public entry points of the exact geodesic engine: single run, target early stop, batch of fields
 * (target queries and pairs: geodesic_query.c). */
#include "geodesic/vtp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

ss_status ss_vtp_distances(const ss_geodesic_mesh *gm, const int *sources, int nsources, double max_dist,
                           double *dist, ss_error *err) {
  if (!gm) return ss_fail(err, SS_ERR_INVALID, "null geodesic mesh");
  ssi_vtp_ws *ws = ssi_vtp_ws_new(gm->nv, gm->nf);
  if (!ws) return ss_fail(err, SS_ERR_NOMEM, "out of memory");
  ss_status st = ssi_vtp_run(gm, ws, sources, nsources, max_dist, NULL, 0, dist, NULL, err);
  ssi_vtp_ws_free(ws);
  return st;
}

ss_status ss_vtp_distances_targets(const ss_geodesic_mesh *gm, const int *sources, int nsources,
                                   const int *targets, int ntargets, double *dist, ss_error *err) {
  if (!gm) return ss_fail(err, SS_ERR_INVALID, "null geodesic mesh");
  if (ntargets < 0 || (ntargets > 0 && !targets)) return ss_fail(err, SS_ERR_INVALID, "invalid target list");
  ssi_vtp_ws *ws = ssi_vtp_ws_new(gm->nv, gm->nf);
  if (!ws) return ss_fail(err, SS_ERR_NOMEM, "out of memory");
  ss_status st = ssi_vtp_run(gm, ws, sources, nsources, 0, targets, ntargets, dist, NULL, err);
  ssi_vtp_ws_free(ws);
  return st;
}

static ss_status fields(const ss_geodesic_mesh *gm, const int *sources, int nsources, double max_dist,
                        const int *targets, int ntargets, double *dist, ss_error *err) {
  if (!gm || nsources < 0 || (nsources > 0 && (!sources || !dist)) || ntargets < 0 || (ntargets > 0 && !targets))
    return ss_fail(err, SS_ERR_INVALID, "invalid arguments to ss_geodesic_fields");
  for (int i = 0; i < nsources; i++)
    if (sources[i] < 0 || sources[i] >= gm->nv)
      return ss_fail(err, SS_ERR_INVALID, "source vertex %d outside [0,%d)", sources[i], gm->nv);
  for (int i = 0; i < ntargets; i++)
    if (targets[i] < 0 || targets[i] >= gm->nv)
      return ss_fail(err, SS_ERR_INVALID, "target vertex %d outside [0,%d)", targets[i], gm->nv);
  int failed = 0;
#pragma omp parallel
  {
    ssi_vtp_ws *ws = ssi_vtp_ws_new(gm->nv, gm->nf);
    if (!ws) {
#pragma omp atomic write
      failed = 1;
    }
#pragma omp for schedule(dynamic, 1)
    for (int j = 0; j < nsources; j++) {
      if (!ws) continue;
      if (ssi_vtp_run(gm, ws, sources + j, 1, max_dist, targets, ntargets, dist + (size_t)j * gm->nv, NULL, NULL)) {
#pragma omp atomic write
        failed = 1;
      }
    }
    ssi_vtp_ws_free(ws);
  }
  if (failed) return ss_fail(err, SS_ERR_NOMEM, "out of memory computing geodesic fields");
  return SS_OK;
}

ss_status ss_geodesic_fields(const ss_geodesic_mesh *gm, const int *sources, int nsources, double max_dist,
                             double *dist, ss_error *err) {
  return fields(gm, sources, nsources, max_dist, NULL, 0, dist, err);
}

ss_status ss_geodesic_fields_targets(const ss_geodesic_mesh *gm, const int *sources, int nsources, const int *targets,
                                     int ntargets, double *dist, ss_error *err) {
  return fields(gm, sources, nsources, 0, targets, ntargets, dist, err);
}

ss_status ss_geodesic_distances(const ss_mesh *m, ss_geodesic_method method, const int *sources, int nsources,
                                double max_dist, double *dist, ss_error *err) {
  ss_status st;
  if (method == SS_GEODESIC_EXACT) {
    ss_geodesic_mesh *gm;
    if ((st = ss_geodesic_mesh_build(m, &gm, err))) return st;
    st = ss_vtp_distances(gm, sources, nsources, max_dist, dist, err);
    ss_geodesic_mesh_free(gm);
    return st;
  }
  if (method != SS_GEODESIC_GRAPH && method != SS_GEODESIC_EDGE)
    return ss_fail(err, SS_ERR_INVALID, "unknown geodesic method %d", (int)method);
  ss_graph g;
  st = method == SS_GEODESIC_GRAPH ? ss_graph_npp22(m, &g, err) : ss_graph_edges(m, &g, err);
  if (st) return st;
  st = ss_graph_dijkstra(&g, sources, nsources, max_dist, dist, NULL, err);
  ss_graph_free(&g);
  return st;
}
