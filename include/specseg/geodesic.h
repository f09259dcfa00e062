/* specseg — geodesic distances: graph (NPP22, mesh edges) Dijkstra and exact VTP. */
#ifndef SPECSEG_GEODESIC_H
#define SPECSEG_GEODESIC_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Weighted undirected graph on the mesh vertices, CSR: neighbours of i are adj[ptr[i]..ptr[i+1]). */
typedef struct ss_graph {
  int n;
  int *ptr;
  int *adj;
  double *w;
} ss_graph;

/* Mesh edges weighted by their length. */
ss_status ss_graph_edges(const ss_mesh *m, ss_graph *g, ss_error *err);
/* NPP22 geodesic graph: 1-ring arcs plus, across each interior edge, the arc between the two
 * opposite vertices, weighted by the straight length in the unfolded pair of triangles, kept only
 * where that segment crosses the shared edge. */
ss_status ss_graph_npp22(const ss_mesh *m, ss_graph *g, ss_error *err);
void ss_graph_free(ss_graph *g);

/* Multi-source Dijkstra: dist[n] = distance to the nearest source (INFINITY when unreached or
 * farther than max_dist; max_dist <= 0 or INFINITY means no limit). nearest (may be NULL) receives
 * the index into `sources` of the nearest source, -1 when unreached. */
ss_status ss_graph_dijkstra(const ss_graph *g, const int *sources, int nsources, double max_dist,
                            double *dist, int *nearest, ss_error *err);


/* ---- Exact polyhedral geodesics (window propagation with VTP-style vertex pruning) ----------
 * Distances are lengths of shortest paths on the piecewise-flat surface. The mesh must be
 * consistently oriented; edges shared by more than two faces, or by two faces with opposite
 * orientations, and zero-area faces are treated as cuts (their vertices become boundary
 * vertices), so distances there are exact on the cut surface. */
typedef struct ss_geodesic_mesh ss_geodesic_mesh;

/* Build the propagation structure (twins, edge frames, vertex classes). Read-only afterwards, so one
 * structure may be shared by any number of threads. */
ss_status ss_geodesic_mesh_build(const ss_mesh *m, ss_geodesic_mesh **out, ss_error *err);
void ss_geodesic_mesh_free(ss_geodesic_mesh *gm);
int ss_geodesic_mesh_nv(const ss_geodesic_mesh *gm);

/* Exact distance to the nearest of `sources` for every vertex (dist has nv entries). max_dist <= 0
 * or INFINITY: no limit; otherwise propagation stops past max_dist and farther vertices get INFINITY
 * (vertices within max_dist get the same values as without a limit). Unreachable: INFINITY. */
ss_status ss_vtp_distances(const ss_geodesic_mesh *gm, const int *sources, int nsources, double max_dist,
                           double *dist, ss_error *err);
/* Same, stopping as soon as every vertex of `targets` is settled. dist (nv entries) is exact at the
 * targets and at every vertex not farther than the largest target distance; other entries are
 * upper bounds or INFINITY. */
ss_status ss_vtp_distances_targets(const ss_geodesic_mesh *gm, const int *sources, int nsources,
                                   const int *targets, int ntargets, double *dist, ss_error *err);

/* Many single-source fields in parallel (OpenMP over sources): column j of dist (nv x nsources,
 * column-major) is the field of sources[j]. max_dist as in ss_vtp_distances. */
ss_status ss_geodesic_fields(const ss_geodesic_mesh *gm, const int *sources, int nsources, double max_dist,
                             double *dist, ss_error *err);
/* out[i] = exact d(src[i], dst[i]) for npairs pairs. Pairs are grouped by source; each source
 * propagates only until its targets are settled (in parallel over sources). */
ss_status ss_geodesic_pairs(const ss_geodesic_mesh *gm, const int *src, const int *dst, int npairs,
                            double *out, ss_error *err);

/* Method switch used by the CLI: exact (VTP), NPP22 graph or edge graph, multi-source, max_dist as
 * above. */
typedef enum ss_geodesic_method { SS_GEODESIC_EXACT = 0, SS_GEODESIC_GRAPH = 1, SS_GEODESIC_EDGE = 2 } ss_geodesic_method;
ss_status ss_geodesic_distances(const ss_mesh *m, ss_geodesic_method method, const int *sources, int nsources,
                                double max_dist, double *dist, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
