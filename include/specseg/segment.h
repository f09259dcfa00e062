/* specseg — coherent segmentation (paper §4): critical points of the Fiedler function, the intrinsic
 * Voronoi diagram (iVd) of those points on the NPP22 geodesic graph, and the whole pipeline
 * (CMCF smoothing → isotropic remeshing → Fiedler → critical points → iVd → labels on the input). */
#ifndef SPECSEG_SEGMENT_H
#define SPECSEG_SEGMENT_H

#include "specseg/core.h"
#include "specseg/geodesic.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Critical points of a vertex function (§4.2) ------------------------------------------------ */

typedef enum ss_crit_type {
  SS_CRIT_REGULAR = 0,
  SS_CRIT_MIN = 1,    /* φ(x) < φ(y) for every y of the 1-ring */
  SS_CRIT_MAX = 2,    /* φ(x) > φ(y) for every y of the 1-ring */
  SS_CRIT_SADDLE = 3  /* ≥ 4 triangles t_xyz of the star with min(φy,φz) < φx < max(φy,φz) */
} ss_crit_type;

/* Critical points (minima, maxima, saddles) of a vertex function on a mesh (§4.2), with the authors'
 * optional clean-up. Every comparison is on (φ, vertex index) lexicographically (symbolic
 * perturbation), so ties never make a vertex both or neither. Clean-up (cleanup_rings > 0): a critical
 * point is dropped when another critical point within its cleanup_rings-ring (mesh edges) has a
 * per-vertex gradient magnitude of φ not larger than its own (ties between equal magnitudes resolved
 * by vertex index, so one of them survives); the test is made against the raw set (simultaneously),
 * as the rule reads. Vertices in no face are regular.
 *
 * Inputs:
 *   m        triangle mesh, nv vertices
 *   phi      nv finite values (e.g. the Fiedler vector)
 *   cleanup_rings  clean-up radius in rings (>= 0; 0: no clean-up)
 * Outputs:
 *   type     (may be NULL) nv entries: the ss_crit_type of each vertex AFTER clean-up (dropped: REGULAR)
 *   points   *points: malloc'd list of the critical vertices after clean-up, ascending (free())
 *   npoints  their count
 *   nraw     (may be NULL) the number of critical points before clean-up
 * Errors: SS_ERR_INVALID on NULL outputs, an invalid mesh, a face index out of range, a NULL or
 *   non-finite phi, a negative cleanup_rings; SS_ERR_NOMEM.
 */
SS_API ss_status ss_fiedler_critical_points(const ss_mesh *m, const double *phi, int cleanup_rings,
                                            signed char *type, int **points, int *npoints, int *nraw,
                                            ss_error *err);

/* Per-vertex gradient magnitude of a piecewise-linear function: |area-weighted mean of the incident
 * faces' gradients| (the clean-up's measure in ss_fiedler_critical_points).
 *
 * Inputs:
 *   m        triangle mesh, nv vertices
 *   phi      nv values
 * Outputs:
 *   grad_norm  nv values (caller-allocated; 0 for isolated vertices)
 * Errors: SS_ERR_INVALID on an invalid mesh or phi (as ss_fiedler_critical_points); SS_ERR_NOMEM.
 */
SS_API ss_status ss_vertex_gradient_norm(const ss_mesh *m, const double *phi, double *grad_norm, ss_error *err);

/* ---- Intrinsic Voronoi diagram (§4.3) ----------------------------------------------------------- */

/* Intrinsic Voronoi diagram (iVd, §4.3) of `centers` on a graph, computed as the paper does:
 * Dijkstra from centers[0] gives s and ρ = max s; each further centre runs a Dijkstra bounded by ρ
 * that overwrites s and the tag of every node it strictly improves; then ρ = max s again.
 *
 * Inputs:
 *   g        the graph (e.g. ss_graph_npp22 of the work mesh), n nodes, non-negative finite weights
 *   centers  ncenters distinct nodes in [0, n)
 * Outputs:
 *   s        n entries: distance to the nearest centre (INFINITY for nodes no centre reaches)
 *   tag      n entries: index into `centers` of that centre, ties to the earlier centre (-1: unreached)
 * Errors: SS_ERR_INVALID on a malformed graph, a centre out of range or a repeated centre; SS_ERR_NOMEM.
 */
SS_API ss_status ss_ivd(const ss_graph *g, const int *centers, int ncenters, double *s, int *tag, ss_error *err);

/* ---- The whole pipeline ------------------------------------------------------------------------- */

/* Options of ss_segment (start from ss_segment_default_options). */
typedef struct ss_segment_options {
  int target_faces;    /* remeshing target triangle count; default 15000, at most SS_REMESH_MAX_FACES */
  int no_streamline;   /* 1: Fiedler + critical points + iVd straight on the input (no CMCF/remesh) */
  int cleanup_rings;   /* critical-point clean-up radius in rings (0 = off); default 5 (the authors') */
  int n_eigs;          /* eigenpairs computed (the Fiedler vector is the 2nd); default 2, min 2 */
  int cmcf_steps;      /* 0 = streamline module default */
  double cmcf_dt;      /* 0 = streamline module default */
  int sanitize;        /* 1: ss_mesh_sanitize the input first (pinched vertices, degenerate faces) */
} ss_segment_options;

/* Fills o with the defaults: 15000 target faces, streamlining on, clean-up radius 5, 2 eigenpairs,
 * the streamline module's CMCF defaults, sanitize on.
 *
 * Outputs:
 *   o        every field written
 */
SS_API void ss_segment_default_options(ss_segment_options *o);

/* A segmentation (ss_segment's output): labels and centres on the input, and what was computed on
 * the work mesh to get them. Free with ss_segmentation_free.
 */
typedef struct ss_segmentation {
  int nv;              /* input vertices */
  int m;               /* number of segments (= critical points after clean-up) */
  int *labels;         /* nv: segment 0..m-1 of each input vertex */
  int *centers;        /* m: input vertex at the centre of each segment */
  int empty_segments;  /* segments no input vertex fell in (their cell on `work` missed Ψ's image) */
  /* the shape the Fiedler function lives on (the remeshed smoothed shape, or a copy of the input
   * under no_streamline) and what was computed on it */
  ss_mesh work;
  int *psi;            /* nv: input vertex → closest vertex of `work` to its smoothed twin (Ψ);
                          -1 for an input vertex no face uses (dropped by the sanitizer) */
  double *phi;         /* work.nv: the Fiedler vector (M-normalised; sign chosen so that its entry of
                          largest magnitude is positive) */
  double lambda2;      /* its eigenvalue */
  int *crit;           /* m: work vertex of the critical point at the centre of segment s */
  signed char *crit_type; /* m: ss_crit_type of crit[s] */
  int ncrit_raw;       /* critical points before clean-up */
  int *work_labels;    /* work.nv: iVd tag of each work vertex (segment index) */
  double *work_dist;   /* work.nv: geodesic (graph) distance to the nearest centre */
  /* wall seconds per stage (0 when skipped); t_total is the whole ss_segment call (sanitizing and
   * mapping back included, reading the file not) */
  double t_read;       /* filled by callers that read the mesh (CLI, bench); ss_segment leaves it */
  double t_smooth, t_remesh, t_psi, t_spectrum, t_critical, t_ivd, t_total;
} ss_segmentation;

/* Coherent segmentation of a shape (§4): CMCF smoothing, isotropic remeshing (the work mesh), the
 * Fiedler vector there, its critical points after clean-up, their iVd on the NPP22 graph, labels
 * lifted to the input through Ψ. Boundary loops (e.g. TOSCA's small holes) are closed with a centroid
 * fan before smoothing, since the remesher takes closed surfaces; the added vertices are not part of
 * the output. Critical points are ordered by vertex index of `work`, and segment s is the iVd cell of
 * crit[s]. Meshes of several components: see ss_segment_warn.
 *
 * Inputs:
 *   input    triangle mesh, one or more components
 *   opts     options (NULL: defaults from ss_segment_default_options)
 * Outputs:
 *   out      the segmentation (free with ss_segmentation_free); zeroed on failure
 * Errors: SS_ERR_INVALID on a NULL output, an empty mesh, options out of range, a mesh the sanitizer
 *   cannot repair; those of the stages (SS_ERR_UNSUPPORTED from the remesher, SS_ERR_NUMERIC from the
 *   flow or the eigensolver); SS_ERR_NOMEM.
 */
SS_API ss_status ss_segment(const ss_mesh *input, const ss_segment_options *opts, ss_segmentation *out,
                            ss_error *err);
/* ss_segment that also reports what was done to the input beyond the paper's pipeline: the
 * sanitizer's repairs (ss_mesh_sanitize), the holes (boundary loops) closed for smoothing and
 * remeshing, and the treatment of several components. Components (after sanitizing; faces joined
 * through shared vertices): with several, each component of at least 1% of the total area (and the
 * largest one, when none reaches 1%) is segmented on its own, as if it were the only shape (own CMCF,
 * remeshing to the full target_faces, Fiedler vector, critical points and iVd), its segment indices
 * following those of the components before it (ordered by lowest vertex), so labels are unique
 * across components. Smaller components (crumbs of a scan) get no segment of their own: their
 * vertices take the segment of the nearest (Euclidean) vertex of a significant component, psi is -1
 * on them, and the warning names them by their first input vertex. `work`, phi, crit, work_labels and
 * work_dist are then the concatenation of the components' (in that order), lambda2 is that of the
 * largest component and the timings are sums.
 *
 * Inputs:
 *   input, opts  as ss_segment
 *   warnings_size  bytes at warnings
 * Outputs:
 *   out      as ss_segment
 *   warnings (may be NULL) a human-readable summary ("" when nothing)
 * Errors: as ss_segment.
 */
SS_API ss_status ss_segment_warn(const ss_mesh *input, const ss_segment_options *opts, ss_segmentation *out,
                                 char *warnings, size_t warnings_size, ss_error *err);
/* Frees every array of s (and its work mesh) and zeroes it; safe on a zeroed struct.
 *
 * Inputs:
 *   s        from ss_segment / ss_segment_warn
 */
SS_API void ss_segmentation_free(ss_segmentation *s);

/* ---- Coherency (§5) ----------------------------------------------------------------------------- */

/* Coherency of a segmentation of Y with the segmentation of a reference shape X0 (§5): for every
 * vertex y of Y, with u the centre of y's segment, the check passes when GT(y) and GT(u) lie in the
 * same segment of X0. O(nv).
 *
 * Inputs:
 *   labels0  nv0 labels of X0 (any integers; only equality matters)
 *   labels   nv labels of Y, each in [0, m)
 *   centers  m vertices of Y (the centre of each segment)
 *   gt       nv vertices of X0 (GT(y)); NULL = identity (then nv must equal nv0)
 * Outputs:
 *   coherency  the fraction of Y's vertices that pass
 * Errors: SS_ERR_INVALID on a NULL output, empty input, unequal counts without gt, or out-of-range
 *   labels, centres or map entries.
 */
SS_API ss_status ss_coherency(const int *labels0, int nv0, const int *labels, const int *centers, int m, int nv,
                              const int *gt, double *coherency, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
