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
SS_API ss_status ss_graph_edges(const ss_mesh *m, ss_graph *g, ss_error *err);
/* NPP22 geodesic graph: 1-ring arcs plus, across each interior edge, the arc between the two
 * opposite vertices, weighted by the straight length in the unfolded pair of triangles, kept only
 * where that segment crosses the shared edge. */
SS_API ss_status ss_graph_npp22(const ss_mesh *m, ss_graph *g, ss_error *err);
SS_API void ss_graph_free(ss_graph *g);

/* Multi-source Dijkstra: dist[n] = distance to the nearest source (INFINITY when unreached or
 * farther than max_dist; max_dist <= 0 or INFINITY means no limit). nearest (may be NULL) receives
 * the index into `sources` of the nearest source, -1 when unreached. */
SS_API ss_status ss_graph_dijkstra(const ss_graph *g, const int *sources, int nsources, double max_dist,
                                   double *dist, int *nearest, ss_error *err);


/* ---- Exact polyhedral geodesics (window propagation with VTP-style vertex pruning) ----------
 * Distances are lengths of shortest paths on the piecewise-flat surface. Faces of an orientable
 * mesh that are not consistently oriented are re-oriented internally (each component as the
 * majority of its faces; the distances equal those of the clean mesh); a non-orientable mesh is
 * refused (SS_ERR_INVALID). Edges shared by more than two faces and zero-area faces are treated
 * as cuts (their vertices become boundary vertices), so distances there are exact on the cut
 * surface. */
typedef struct ss_geodesic_mesh ss_geodesic_mesh;

/* Build the propagation structure (twins, edge frames, vertex classes). Read-only afterwards (no
 * call modifies it), so one structure may be shared by any number of threads. */
SS_API ss_status ss_geodesic_mesh_build(const ss_mesh *m, ss_geodesic_mesh **out, ss_error *err);
SS_API void ss_geodesic_mesh_free(ss_geodesic_mesh *gm);
SS_API int ss_geodesic_mesh_nv(const ss_geodesic_mesh *gm);

/* Exact distance to the nearest of `sources` for every vertex (dist has nv entries). max_dist <= 0
 * or INFINITY: no limit; otherwise propagation stops past max_dist and farther vertices get INFINITY
 * (vertices within max_dist get the same values as without a limit). Unreachable: INFINITY. */
SS_API ss_status ss_vtp_distances(const ss_geodesic_mesh *gm, const int *sources, int nsources, double max_dist,
                                  double *dist, ss_error *err);
/* Same, stopping as soon as every vertex of `targets` is settled. dist (nv entries) is exact at the
 * targets and at every vertex not farther than the largest target distance; other entries are
 * upper bounds or INFINITY. */
SS_API ss_status ss_vtp_distances_targets(const ss_geodesic_mesh *gm, const int *sources, int nsources,
                                          const int *targets, int ntargets, double *dist, ss_error *err);

/* Many single-source fields in parallel (OpenMP over sources): column j of dist (nv x nsources,
 * column-major) is the field of sources[j]. max_dist as in ss_vtp_distances. */
SS_API ss_status ss_geodesic_fields(const ss_geodesic_mesh *gm, const int *sources, int nsources, double max_dist,
                                    double *dist, ss_error *err);
/* The same, each field stopping as soon as every vertex of `targets` is settled (as
 * ss_vtp_distances_targets): column j is exact at the targets (the values of the full field) and at
 * every vertex not farther than its largest target distance; other entries are upper bounds or
 * INFINITY. For distances from a few sources to a few targets. */
SS_API ss_status ss_geodesic_fields_targets(const ss_geodesic_mesh *gm, const int *sources, int nsources,
                                            const int *targets, int ntargets, double *dist, ss_error *err);
/* ---- Landmark accelerator for target queries --------------------------------------------------
 * Exact distance fields from `nlandmarks` farthest-spread landmarks of gm. Target queries given one
 * also use the lower bound |d_L(p) - d_L(t)|, which makes a far query explore a corridor instead of
 * a disc (FAUST, mirrored pairs: ~4x fewer windows than Euclidean A*). Cost: nlandmarks full fields
 * (OpenMP; ~0.15 s CPU for 8 on FAUST), nv x nlandmarks doubles. Read-only once built: one
 * accelerator may serve any number of threads. Distances do not depend on it beyond round-off.
 * Valid only with the gm it was built on (used with another mesh, it is ignored). */
typedef struct ss_geodesic_landmarks ss_geodesic_landmarks;
#define SS_GEODESIC_MAX_LANDMARKS 16
/* nlandmarks in [1, SS_GEODESIC_MAX_LANDMARKS]. */
SS_API ss_status ss_geodesic_landmarks_new(const ss_geodesic_mesh *gm, int nlandmarks, ss_geodesic_landmarks **out,
                                           ss_error *err);
SS_API void ss_geodesic_landmarks_free(ss_geodesic_landmarks *acc);

/* out[i] = exact d(src[i], dst[i]) for npairs pairs (agrees with the full fields to round-off,
 * 1e-12 relative). Pairs are grouped by source; each group propagates only until its targets are
 * final, A*-steered when it has at most 8 distinct targets (Euclidean and landmark lower bounds);
 * groups run in parallel (OpenMP) and each writes only its own outputs, so results do not depend on
 * the number of threads. src[i] == dst[i] gives 0.
 * lm: NULL (Euclidean bounds only), or the caller's accelerator slot: a non-NULL *lm is used; an
 * empty slot (*lm == NULL) receives an 8-landmark accelerator when the batch has >= 32 far pairs
 * (straight distance > 0.1 x the bounding-box diagonal: the decision depends on the input only),
 * which the caller frees with ss_geodesic_landmarks_free and may pass to later calls. A slot may not
 * be shared by concurrent calls while it is empty. Cost for a map error on FAUST (6,890 pairs
 * d(Pi(x), x)): ~0.01 s CPU for 1-ring errors, ~0.3 s CPU when 5% of the vertices go to the far side. */
SS_API ss_status ss_geodesic_pairs(const ss_geodesic_mesh *gm, ss_geodesic_landmarks **lm, const int *src,
                                   const int *dst, int npairs, double *out, ss_error *err);

/* Exact d(source, targets[i]) -> out[i] (ntargets entries), stopping as soon as every target is
 * final; a query costs in proportion to the region it settles (nothing O(nv) per call). Up to 8
 * targets steer the front A*-style with lower bounds on the remaining length (Euclidean, and the
 * landmark bound when lm is given; lm may be NULL); values agree with the full field to round-off
 * (1e-12 relative; identical in all our tests). */
SS_API ss_status ss_geodesic_one_to_many(const ss_geodesic_mesh *gm, const ss_geodesic_landmarks *lm, int source,
                                         const int *targets, int ntargets, double *out, ss_error *err);
/* The same with a reusable workspace, for callers that run many queries (e.g. inside their own
 * OpenMP loop: one query object per thread; the mesh structure and lm are shared). lm may be NULL
 * and must outlive the query object. */
typedef struct ss_geodesic_query ss_geodesic_query;
SS_API ss_status ss_geodesic_query_new(const ss_geodesic_mesh *gm, const ss_geodesic_landmarks *lm,
                                       ss_geodesic_query **out, ss_error *err);
SS_API void ss_geodesic_query_free(ss_geodesic_query *q);
SS_API ss_status ss_geodesic_query_run(ss_geodesic_query *q, int source, const int *targets, int ntargets,
                                       double *out, ss_error *err);
/* out[i] = min over j < k of exact d(src[i], dst[i*k + j]) for n sources (k >= 1 targets each):
 * one query per source that stops at the first target to become final, so the cost follows the
 * NEAREST target. This is the symmetric map error min(d(Pi(x), x), d(Pi(x), x')) with x' the mirror
 * of x (k = 2) at the price of the smaller distance; through ss_geodesic_pairs on both pairs the
 * mirrored one costs a far query for every vertex (FAUST: 0.09 s vs ~5 s CPU per map). A*-steered
 * for k <= 8; OpenMP over sources, results independent of the thread count; lm as in
 * ss_geodesic_pairs (a source counts as far when all its targets are). */
SS_API ss_status ss_geodesic_nearest_of(const ss_geodesic_mesh *gm, ss_geodesic_landmarks **lm, const int *src,
                                        const int *dst, int k, int n, double *out, ss_error *err);

/* A lower bound on the exact geodesic distance d(a, b): the straight distance, and with an
 * accelerator (lm may be NULL) also max over landmarks L of |d_L(a) − d_L(b)| (exact fields, so the
 * bound may exceed d(a, b) by round-off only: compare with a relative margin). 0 for invalid input. */
SS_API double ss_geodesic_lower_bound(const ss_geodesic_mesh *gm, const ss_geodesic_landmarks *lm, int a, int b);

/* ---- Farthest point sampling (Appendix A) ----------------------------------------------------- */

/* p_0 = seed, p_{j+1} = argmax_x min_{i ≤ j} d(p_i, x) with exact (VTP) geodesics; ties go to the
 * lower vertex index. points: m vertices. mindist (may be NULL): nv entries, min distance to
 * p_0..p_{m-1} on return. Vertices unreachable from the seed are never chosen; fails with
 * SS_ERR_INVALID when fewer than m vertices are reachable. Cost: m full fields. */
SS_API ss_status ss_fps(const ss_geodesic_mesh *gm, int seed, int m, int *points, double *mindist, ss_error *err);

/* Method switch used by the CLI: exact (VTP), NPP22 graph or edge graph, multi-source, max_dist as
 * above. */
typedef enum ss_geodesic_method { SS_GEODESIC_EXACT = 0, SS_GEODESIC_GRAPH = 1, SS_GEODESIC_EDGE = 2 } ss_geodesic_method;
SS_API ss_status ss_geodesic_distances(const ss_mesh *m, ss_geodesic_method method, const int *sources, int nsources,
                                       double max_dist, double *dist, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
