/* specseg — geodesic distances: graph (NPP22, mesh edges) Dijkstra and exact VTP. */
#ifndef SPECSEG_GEODESIC_H
#define SPECSEG_GEODESIC_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Weighted undirected graph on the mesh vertices, CSR: neighbours of i are adj[ptr[i]..ptr[i+1])
 * with weights w[ptr[i]..ptr[i+1]); n = nv.
 */
typedef struct ss_graph {
  int n;
  int *ptr;
  int *adj;
  double *w;
} ss_graph;

/* The mesh-edge graph: each edge weighted by its length.
 *
 * Inputs:
 *   m        triangle mesh, nv vertices
 * Outputs:
 *   g        n = nv nodes, arrays malloc'd (free with ss_graph_free)
 * Errors: SS_ERR_INVALID on a face index out of range or a non-finite coordinate; SS_ERR_NOMEM.
 */
SS_API ss_status ss_graph_edges(const ss_mesh *m, ss_graph *g, ss_error *err);
/* NPP22 geodesic graph (used for the iVd, §4.3): the 1-ring arcs plus, across each interior edge,
 * the arc between the two opposite vertices, weighted by the straight length in the unfolded pair of
 * triangles, kept only where that segment crosses the shared edge.
 *
 * Inputs:
 *   m        triangle mesh, nv vertices
 * Outputs:
 *   g        n = nv nodes, arrays malloc'd (free with ss_graph_free)
 * Errors: SS_ERR_INVALID on a face index out of range or a non-finite coordinate; SS_ERR_NOMEM.
 */
SS_API ss_status ss_graph_npp22(const ss_mesh *m, ss_graph *g, ss_error *err);
/* Frees the arrays of g and zeroes it; safe on a zeroed struct.
 *
 * Inputs:
 *   g        a graph from ss_graph_edges / ss_graph_npp22
 */
SS_API void ss_graph_free(ss_graph *g);

/* Multi-source Dijkstra on a graph: the distance of every node to the nearest source.
 *
 * Inputs:
 *   g        the graph, n nodes
 *   sources  nsources node indices in [0, n)
 *   max_dist stop beyond this distance (<= 0 or INFINITY: no limit)
 * Outputs:
 *   dist     n distances (caller-allocated; INFINITY when unreached or farther than max_dist)
 *   nearest  (may be NULL) n entries: the index into `sources` of the nearest source, -1 when unreached
 * Errors: SS_ERR_INVALID on a source out of range or bad sizes; SS_ERR_NOMEM.
 */
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

/* Builds the exact-geodesic propagation structure of a mesh (twins, edge frames, vertex classes).
 * Read-only afterwards (no call modifies it), so one structure may be shared by any number of threads.
 *
 * Inputs:
 *   m        triangle mesh, nv >= 1 (its arrays are copied: m may be freed afterwards)
 * Outputs:
 *   out      *out: the structure (free with ss_geodesic_mesh_free)
 * Errors: SS_ERR_INVALID on a NULL output, an empty mesh, bad indices or a non-orientable surface;
 *   SS_ERR_NOMEM.
 */
SS_API ss_status ss_geodesic_mesh_build(const ss_mesh *m, ss_geodesic_mesh **out, ss_error *err);
/* Frees a structure from ss_geodesic_mesh_build (NULL allowed).
 *
 * Inputs:
 *   gm       the structure
 */
SS_API void ss_geodesic_mesh_free(ss_geodesic_mesh *gm);
/* Number of vertices of the mesh the structure was built on.
 *
 * Inputs:
 *   gm       the structure
 * Returns: nv.
 */
SS_API int ss_geodesic_mesh_nv(const ss_geodesic_mesh *gm);

/* Exact geodesic distance to the nearest of `sources` for every vertex. With a limit, propagation
 * stops past max_dist and farther vertices get INFINITY (vertices within max_dist get the same values
 * as without a limit). Unreachable vertices: INFINITY.
 *
 * Inputs:
 *   gm       the structure (ss_geodesic_mesh_build), nv vertices
 *   sources  nsources vertices in [0, nv)
 *   max_dist <= 0 or INFINITY: no limit
 * Outputs:
 *   dist     nv distances (caller-allocated)
 * Errors: SS_ERR_INVALID on a NULL structure or a source out of range; SS_ERR_NOMEM.
 */
SS_API ss_status ss_vtp_distances(const ss_geodesic_mesh *gm, const int *sources, int nsources, double max_dist,
                                  double *dist, ss_error *err);
/* ss_vtp_distances stopping as soon as every vertex of `targets` is settled.
 *
 * Inputs:
 *   gm, sources, nsources  as ss_vtp_distances
 *   targets  ntargets vertices in [0, nv)
 * Outputs:
 *   dist     nv entries: exact at the targets and at every vertex not farther than the largest target
 *            distance; other entries are upper bounds or INFINITY
 * Errors: SS_ERR_INVALID on a NULL structure, an invalid target list or a vertex out of range;
 *   SS_ERR_NOMEM.
 */
SS_API ss_status ss_vtp_distances_targets(const ss_geodesic_mesh *gm, const int *sources, int nsources,
                                          const int *targets, int ntargets, double *dist, ss_error *err);

/* Many single-source exact fields in parallel (OpenMP over sources).
 *
 * Inputs:
 *   gm       the structure, nv vertices
 *   sources  nsources vertices in [0, nv)
 *   max_dist as in ss_vtp_distances
 * Outputs:
 *   dist     nv x nsources, column-major (caller-allocated): column j is the field of sources[j]
 * Errors: SS_ERR_INVALID on bad arguments or a source out of range; SS_ERR_NOMEM.
 */
SS_API ss_status ss_geodesic_fields(const ss_geodesic_mesh *gm, const int *sources, int nsources, double max_dist,
                                    double *dist, ss_error *err);
/* ss_geodesic_fields with each field stopping as soon as every vertex of `targets` is settled (as
 * ss_vtp_distances_targets). For distances from a few sources to a few targets.
 *
 * Inputs:
 *   gm, sources, nsources  as ss_geodesic_fields
 *   targets  ntargets vertices in [0, nv)
 * Outputs:
 *   dist     nv x nsources, column-major: column j exact at the targets (the values of the full field)
 *            and at every vertex not farther than its largest target distance; other entries are
 *            upper bounds or INFINITY
 * Errors: SS_ERR_INVALID on bad arguments or a vertex out of range; SS_ERR_NOMEM.
 */
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
/* Builds a landmark accelerator (above): exact fields from nlandmarks farthest-spread vertices of
 * gm, for the lower bound |d_L(p) - d_L(t)| in target queries.
 *
 * Inputs:
 *   gm       the structure (the accelerator is valid only with it)
 *   nlandmarks  in [1, SS_GEODESIC_MAX_LANDMARKS]
 * Outputs:
 *   out      *out: the accelerator (free with ss_geodesic_landmarks_free)
 * Errors: SS_ERR_INVALID on nlandmarks out of range or bad arguments; SS_ERR_NOMEM.
 */
SS_API ss_status ss_geodesic_landmarks_new(const ss_geodesic_mesh *gm, int nlandmarks, ss_geodesic_landmarks **out,
                                           ss_error *err);
/* Frees an accelerator (NULL allowed).
 *
 * Inputs:
 *   acc      from ss_geodesic_landmarks_new or ss_geodesic_pairs
 */
SS_API void ss_geodesic_landmarks_free(ss_geodesic_landmarks *acc);

/* Exact distances of npairs vertex pairs, out[i] = d(src[i], dst[i]) (agrees with the full fields to
 * round-off, 1e-12 relative; src[i] == dst[i] gives 0). Pairs are grouped by source; each group
 * propagates only until its targets are final, A*-steered when it has at most 8 distinct targets
 * (Euclidean and landmark lower bounds); groups run in parallel (OpenMP) and each writes only its
 * own outputs, so results do not depend on the number of threads. Cost for a map error on FAUST (6,890
 * pairs d(Pi(x), x)): ~0.01 s CPU for 1-ring errors, ~0.3 s CPU when 5% of the vertices go to the far side.
 *
 * Inputs:
 *   gm       the structure, nv vertices
 *   lm       NULL (Euclidean bounds only), or the caller's accelerator slot: a non-NULL *lm is used; an
 *            empty slot (*lm == NULL) receives an 8-landmark accelerator when the batch has >= 32 far
 *            pairs (straight distance > 0.1 x the bounding-box diagonal: the decision depends on the
 *            input only), which the caller frees with ss_geodesic_landmarks_free and may pass to later
 *            calls. A slot may not be shared by concurrent calls while it is empty.
 *   src, dst npairs vertices each, in [0, nv)
 * Outputs:
 *   out      npairs distances (caller-allocated)
 * Errors: SS_ERR_INVALID on bad arguments or a pair out of range; SS_ERR_NOMEM.
 */
SS_API ss_status ss_geodesic_pairs(const ss_geodesic_mesh *gm, ss_geodesic_landmarks **lm, const int *src,
                                   const int *dst, int npairs, double *out, ss_error *err);

/* Exact d(source, targets[i]) for ntargets targets, stopping as soon as every target is final; a
 * query costs in proportion to the region it settles (nothing O(nv) per call). Up to 8 targets steer
 * the front A*-style with lower bounds on the remaining length (Euclidean, and the landmark bound
 * when lm is given); values agree with the full field to round-off (1e-12 relative).
 *
 * Inputs:
 *   gm       the structure, nv vertices
 *   lm       (may be NULL) an accelerator built on gm
 *   source   a vertex in [0, nv)
 *   targets  ntargets vertices in [0, nv)
 * Outputs:
 *   out      ntargets distances (caller-allocated)
 * Errors: SS_ERR_INVALID on bad arguments or a vertex out of range; SS_ERR_NOMEM.
 */
SS_API ss_status ss_geodesic_one_to_many(const ss_geodesic_mesh *gm, const ss_geodesic_landmarks *lm, int source,
                                         const int *targets, int ntargets, double *out, ss_error *err);
/* The same with a reusable workspace, for callers that run many queries (e.g. inside their own
 * OpenMP loop: one query object per thread; the mesh structure and lm are shared). lm may be NULL
 * and must outlive the query object. */
typedef struct ss_geodesic_query ss_geodesic_query;
/* A reusable workspace for ss_geodesic_one_to_many-style queries, for callers that run many (e.g.
 * inside their own OpenMP loop: one query object per thread; the structure and lm are shared).
 *
 * Inputs:
 *   gm       the structure (must outlive the query object)
 *   lm       (may be NULL) an accelerator built on gm (must outlive the query object)
 * Outputs:
 *   out      *out: the query object (free with ss_geodesic_query_free)
 * Errors: SS_ERR_INVALID on a NULL structure or output; SS_ERR_NOMEM.
 */
SS_API ss_status ss_geodesic_query_new(const ss_geodesic_mesh *gm, const ss_geodesic_landmarks *lm,
                                       ss_geodesic_query **out, ss_error *err);
/* Frees a query object (NULL allowed).
 *
 * Inputs:
 *   q        from ss_geodesic_query_new
 */
SS_API void ss_geodesic_query_free(ss_geodesic_query *q);
/* One query on a query object: as ss_geodesic_one_to_many, same values.
 *
 * Inputs:
 *   q        the query object (not shared between concurrent calls)
 *   source   a vertex in [0, nv)
 *   targets  ntargets vertices in [0, nv)
 * Outputs:
 *   out      ntargets distances (caller-allocated)
 * Errors: SS_ERR_INVALID on a NULL query, an invalid target list or a vertex out of range; SS_ERR_NOMEM.
 */
SS_API ss_status ss_geodesic_query_run(ss_geodesic_query *q, int source, const int *targets, int ntargets,
                                       double *out, ss_error *err);
/* For n sources, the exact distance to the nearest of k targets each: one query per source that
 * stops at the first target to become final, so the cost follows the NEAREST target. This is the
 * symmetric map error min(d(Pi(x), x), d(Pi(x), x')) with x' the mirror of x (k = 2) at the price of
 * the smaller distance (through ss_geodesic_pairs on both pairs the mirrored one costs a far query
 * for every vertex). A*-steered for k <= 8; OpenMP over sources, results independent of the thread
 * count.
 *
 * Inputs:
 *   gm       the structure, nv vertices
 *   lm       as in ss_geodesic_pairs (a source counts as far when all its targets are)
 *   src      n vertices
 *   dst      n x k vertices, row-major: dst[i*k + j] is target j of source i
 *   k        targets per source (>= 1)
 * Outputs:
 *   out      n values: out[i] = min over j < k of d(src[i], dst[i*k + j]) (caller-allocated)
 * Errors: SS_ERR_INVALID on bad arguments or a vertex out of range; SS_ERR_NOMEM.
 */
SS_API ss_status ss_geodesic_nearest_of(const ss_geodesic_mesh *gm, ss_geodesic_landmarks **lm, const int *src,
                                        const int *dst, int k, int n, double *out, ss_error *err);

/* A lower bound on the exact geodesic distance d(a, b): the straight distance, and with an
 * accelerator also max over landmarks L of |d_L(a) − d_L(b)| (exact fields, so the bound may exceed
 * d(a, b) by round-off only: compare with a relative margin).
 *
 * Inputs:
 *   gm       the structure
 *   lm       (may be NULL) an accelerator built on gm
 *   a, b     two vertices
 * Returns: the bound; 0 for invalid input.
 */
SS_API double ss_geodesic_lower_bound(const ss_geodesic_mesh *gm, const ss_geodesic_landmarks *lm, int a, int b);

/* ---- Farthest point sampling (Appendix A) ----------------------------------------------------- */

/* Farthest point sampling with exact (VTP) geodesics (Appendix A): p_0 = seed,
 * p_{j+1} = argmax_x min_{i ≤ j} d(p_i, x); ties go to the lower vertex index. Vertices unreachable from
 * the seed are never chosen. Cost: m full fields.
 *
 * Inputs:
 *   gm       the structure, nv vertices
 *   seed     the first point, in [0, nv)
 *   m        number of points (>= 1)
 * Outputs:
 *   points   m vertices (caller-allocated)
 *   mindist  (may be NULL) nv entries: the distance to the nearest of p_0..p_{m-1} on return
 * Errors: SS_ERR_INVALID on bad arguments or when fewer than m vertices are reachable; SS_ERR_NOMEM.
 */
SS_API ss_status ss_fps(const ss_geodesic_mesh *gm, int seed, int m, int *points, double *mindist, ss_error *err);

/* Method switch used by the CLI: exact (VTP), NPP22 graph or edge graph, multi-source, max_dist as
 * above. */
typedef enum ss_geodesic_method { SS_GEODESIC_EXACT = 0, SS_GEODESIC_GRAPH = 1, SS_GEODESIC_EDGE = 2 } ss_geodesic_method;
/* Distance to the nearest source by the chosen method (the CLI's switch): exact (VTP), NPP22 graph
 * or mesh-edge graph Dijkstra; builds and frees the structure it needs.
 *
 * Inputs:
 *   m        triangle mesh, nv vertices
 *   method   SS_GEODESIC_EXACT, SS_GEODESIC_GRAPH or SS_GEODESIC_EDGE
 *   sources  nsources vertices in [0, nv)
 *   max_dist as in ss_vtp_distances
 * Outputs:
 *   dist     nv distances (caller-allocated)
 * Errors: SS_ERR_INVALID on an unknown method; those of the method's builder and solver.
 */
SS_API ss_status ss_geodesic_distances(const ss_mesh *m, ss_geodesic_method method, const int *sources, int nsources,
                                       double max_dist, double *dist, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
