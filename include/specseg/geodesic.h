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
/* out[i] = exact d(src[i], dst[i]) for npairs pairs (agrees with the full fields to round-off,
 * 1e-12 relative). Pairs are grouped by source; each group propagates only until its targets are
 * final, A*-steered when it has at most 8 distinct targets (Euclidean and landmark lower bounds; the
 * first call with >= 32 far pairs attaches 8 landmark fields to gm, see
 * ss_geodesic_mesh_prepare_queries); groups run in parallel (OpenMP) and each writes only its own
 * outputs, so results do not depend on the number of threads. src[i] == dst[i] gives 0. Cost for a
 * map error on FAUST (6,890 pairs d(Pi(x), x)): ~0.01 s CPU for 1-ring errors, ~0.3 s CPU when 5%
 * of the vertices go to the far side. */
ss_status ss_geodesic_pairs(const ss_geodesic_mesh *gm, const int *src, const int *dst, int npairs,
                            double *out, ss_error *err);

/* Exact d(source, targets[i]) -> out[i] (ntargets entries), stopping as soon as every target is
 * final; a query costs in proportion to the region it settles (nothing O(nv) per call). Up to 8
 * targets steer the front A*-style with lower bounds on the remaining length (Euclidean, and the
 * landmark bound when gm has landmarks); values agree with the full field to round-off (1e-12
 * relative; identical in all our tests). */
ss_status ss_geodesic_one_to_many(const ss_geodesic_mesh *gm, int source, const int *targets, int ntargets,
                                  double *out, ss_error *err);
/* The same with a reusable workspace, for callers that run many queries (e.g. inside their own
 * OpenMP loop: one query object per thread; the mesh structure is shared). */
typedef struct ss_geodesic_query ss_geodesic_query;
ss_status ss_geodesic_query_new(const ss_geodesic_mesh *gm, ss_geodesic_query **out, ss_error *err);
void ss_geodesic_query_free(ss_geodesic_query *q);
ss_status ss_geodesic_query_run(ss_geodesic_query *q, int source, const int *targets, int ntargets, double *out,
                                ss_error *err);
/* out[i] = min over j < k of exact d(src[i], dst[i*k + j]) for n sources (k >= 1 targets each):
 * one query per source that stops at the first target to become final, so the cost follows the
 * NEAREST target. This is the symmetric map error min(d(Pi(x), x), d(Pi(x), x')) with x' the mirror
 * of x (k = 2) at the price of the smaller distance; through ss_geodesic_pairs on both pairs the
 * mirrored one costs a far query for every vertex (FAUST: 0.09 s vs ~5 s CPU per map). A*-steered
 * for k <= 8; OpenMP over sources, results independent of the thread count; landmarks attached as
 * by ss_geodesic_pairs. */
ss_status ss_geodesic_nearest_of(const ss_geodesic_mesh *gm, const int *src, const int *dst, int k, int n,
                                 double *out, ss_error *err);
/* Attach exact distance fields from `nlandmarks` (0..16) farthest-spread landmarks to gm. Target
 * queries then also use the lower bound |d_L(p) - d_L(t)|, which makes a far query explore a
 * corridor instead of a disc (FAUST, mirrored pairs: ~4x fewer windows than Euclidean A*). Costs
 * nlandmarks full fields (OpenMP; ~0.15 s CPU for 8 on FAUST). ss_geodesic_pairs and
 * ss_geodesic_nearest_of do it themselves (8 landmarks, under a per-mesh lock) on their first call
 * with >= 32 far queries (straight distance > 0.1 x the bounding-box diagonal: the decision depends
 * on the input only); call this beforehand to choose the count, or with 0 to keep queries
 * landmark-free. Not thread-safe against concurrent queries on gm. Distances do not depend on the
 * landmarks beyond round-off; for bit-identical results across runs, make the same calls on the
 * mesh in the same order (as a deterministic program does). */
ss_status ss_geodesic_mesh_prepare_queries(ss_geodesic_mesh *gm, int nlandmarks, ss_error *err);

/* A lower bound on the exact geodesic distance d(a, b): the straight distance, and with prepared
 * landmark fields also max over landmarks L of |d_L(a) − d_L(b)| (exact fields, so the bound may
 * exceed d(a, b) by round-off only: compare with a relative margin). 0 for invalid input. */
double ss_geodesic_lower_bound(const ss_geodesic_mesh *gm, int a, int b);

/* Method switch used by the CLI: exact (VTP), NPP22 graph or edge graph, multi-source, max_dist as
 * above. */
typedef enum ss_geodesic_method { SS_GEODESIC_EXACT = 0, SS_GEODESIC_GRAPH = 1, SS_GEODESIC_EDGE = 2 } ss_geodesic_method;
ss_status ss_geodesic_distances(const ss_mesh *m, ss_geodesic_method method, const int *sources, int nsources,
                                double max_dist, double *dist, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
