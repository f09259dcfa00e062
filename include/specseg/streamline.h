/* specseg — streamlining the geometry (paper §4.1): conformalized mean curvature flow (CMCF),
 * isotropic remeshing to a target triangle count, and Ψ, the closest-vertex map from the smoothed
 * mesh to its remeshed version. */
#ifndef SPECSEG_STREAMLINE_H
#define SPECSEG_STREAMLINE_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------------------------------------
 * CMCF (Kazhdan, Solomon, Ben-Chen 2012). Each step solves
 *     (M_t + δ·W₀) X_{t+1} = M_t X_t
 * with W₀ the cotangent stiffness of the input (fixed) and M_t the lumped (barycentric) mass of the
 * current embedding. Before every step the current shape is centred (area-weighted centroid at the
 * origin) and uniformly rescaled to a canonical size, so δ is a dimensionless time step:
 *
 *  - SS_CMCF_UNIT_AREA (default): total area 1. This is the "δ relative to a unit-area shape" of
 *    issue 3; the shape neither drifts nor shrinks across steps.
 *  - SS_CMCF_UNIT_BBOX: bounding-box diagonal 1 — what the authors' code does (δ = 1e-5, 12 steps).
 *
 * How δ maps between the two: M scales with length², W₀ is scale-invariant, so a step of δ_bbox on
 * a shape with bbox diagonal 1 and area a equals a step of δ_area = δ_bbox / a at unit area.
 * a = area/diag² is 0.37–0.45 on FAUST (it depends on the pose through the bbox; 0.448 for
 * tr_reg_000), hence the default δ_area = 2.2e-5 ≈ 1e-5 / 0.45: on tr_reg_000 the two runs differ
 * by 0.2% of the bbox diagonal on average (0.7% at most). Unit area makes δ pose-independent.
 * Normalising before each step and once more at the end is the "re-centre and re-scale to
 * the input's area after each step" with δ measured at unit area.
 * With the defaults, on FAUST fingers, toes and ears collapse while arms and legs stay (Figure 2).
 *
 * The output keeps the input's connectivity and vertex order, and is returned at the input's scale
 * and position: total area equal to the input's, area-weighted centroid at the input's. Vertices in
 * no face keep their input position. */
typedef enum ss_cmcf_normalization {
  SS_CMCF_UNIT_AREA = 0,
  SS_CMCF_UNIT_BBOX = 1
} ss_cmcf_normalization;

/* Options of ss_cmcf_smooth (start from ss_cmcf_default_options). */
typedef struct ss_cmcf_options {
  int steps;                           /* default 12 */
  double dt;                           /* δ, default 2.2e-5 (unit area) */
  ss_cmcf_normalization normalization; /* default SS_CMCF_UNIT_AREA */
  int refactor_symbolic;               /* 0 (default): one cholmod_analyze for all steps; 1: analyse
                                          afresh every step (only for testing the reuse) */
} ss_cmcf_options;

/* Fills opt with the defaults: 12 steps, δ = 2.2e-5 at unit area, SS_CMCF_UNIT_AREA, one symbolic
 * analysis for all steps.
 *
 * Outputs:
 *   opt      every field written
 */
SS_API void ss_cmcf_default_options(ss_cmcf_options *opt);

/* Conformalized mean curvature flow (§4.1; the scheme above): smooths the shape's protrusions away
 * in a few implicit steps, keeping its connectivity.
 *
 * Inputs:
 *   in       triangle mesh, nv vertices, nf faces, non-zero area
 *   opt      options (NULL: defaults from ss_cmcf_default_options)
 * Outputs:
 *   out      a new mesh, in's connectivity and vertex order, at in's area and centroid (free with
 *            ss_mesh_free; may not alias in)
 * Errors: SS_ERR_INVALID on an empty / zero-area mesh, bad indices or coordinates, bad options;
 *   SS_ERR_NUMERIC when the factorisation or a solve fails or the flow degenerates; SS_ERR_NOMEM.
 */
SS_API ss_status ss_cmcf_smooth(const ss_mesh *in, const ss_cmcf_options *opt, ss_mesh *out, ss_error *err);

/* ---------------------------------------------------------------------------------------------
 * Isotropic remeshing (Botsch & Kobbelt 2004): split edges longer than 4/3·L, collapse edges shorter
 * than 4/5·L (never creating an edge longer than 4/3·L, a flipped normal or a non-manifold
 * configuration), flip edges towards valence 6, area-weighted tangential relaxation, projection onto
 * the input surface (exact closest point, BVH). L starts from the equilateral-triangle length for the
 * target count and is corrected from the face count measured after each round; after the last
 * topological round the count is brought to the target (±2) by splitting the longest or collapsing
 * the shortest edges, and the final rounds only flip and relax. Input: closed (no boundary edges), edge-manifold triangle mesh;
 * open meshes are refused with SS_ERR_UNSUPPORTED. The output has the same components and genus and
 * all its vertices lie on the input surface. */
/* The largest target face count ss_remesh (and ss_segment's remeshing) accepts: the cost grows a little
 * faster than linearly (on two cores: 1e5 faces 0.7 s, 4e5 5 s, 1e6 24 s, so 2e6 about 1.5 min and
 * 0.6 GB); 5e6 took over 400 s. */
#define SS_REMESH_MAX_FACES 2000000

/* Options of ss_remesh (start from ss_remesh_default_options). */
typedef struct ss_remesh_options {
  int target_faces;   /* default 15000; 4 .. SS_REMESH_MAX_FACES */
  int iterations;     /* split/collapse/flip/relax rounds, default 5 */
  int smooth_only_iterations; /* extra flip + relax rounds at the end, default 2 */
  double tolerance;   /* face-count tolerance, default 0.05; the count is snapped to the target when
                         it is off by more than tolerance/5 after the topological rounds */
} ss_remesh_options;

/* Fills opt with the defaults: 15000 faces, 5 rounds, 2 smooth-only rounds, tolerance 0.05.
 *
 * Outputs:
 *   opt      every field written
 */
SS_API void ss_remesh_default_options(ss_remesh_options *opt);

/* Isotropic remeshing of a closed surface to about opt->target_faces triangles (the algorithm
 * above); the output has the same components and genus and all its vertices lie on the input surface.
 *
 * Inputs:
 *   in       closed (no boundary edges), edge-manifold, consistently oriented triangle mesh of
 *            non-zero area
 *   opt      options (NULL: defaults from ss_remesh_default_options)
 * Outputs:
 *   out      the new mesh, about target_faces faces (free with ss_mesh_free)
 * Errors: SS_ERR_INVALID on NULL meshes, options out of range, a zero-area mesh or bad indices;
 *   SS_ERR_UNSUPPORTED on a boundary edge, a non-manifold or inconsistently oriented edge or a
 *   pinched vertex; SS_ERR_NOMEM.
 */
SS_API ss_status ss_remesh(const ss_mesh *in, const ss_remesh_options *opt, ss_mesh *out, ss_error *err);

/* Quality figures used by the tests and `specseg remesh`. `ref` (may be NULL) is the surface the
 * deviation is measured against (max over vertices of the distance to the closest point of `ref`,
 * divided by ref's bbox diagonal); without it max_deviation is 0. */
typedef struct ss_remesh_quality {
  int faces, vertices;
  double frac_min_angle_30; /* fraction of triangles whose smallest angle is ≥ 30° */
  double frac_valence_6;    /* fraction of vertices of valence 6 */
  double min_angle_deg;     /* smallest angle over all triangles */
  double max_deviation;     /* relative to ref's bbox diagonal */
} ss_remesh_quality;

/* Quality figures of a triangle mesh (angles, valences) and, with ref, its deviation from a
 * reference surface; used by the tests and `specseg remesh`.
 *
 * Inputs:
 *   m        the mesh (nv, nf > 0)
 *   ref      (may be NULL) the surface the deviation is measured against
 * Outputs:
 *   q        every field written (max_deviation 0 without ref)
 * Errors: SS_ERR_INVALID on an empty mesh or a face index out of range; SS_ERR_NOMEM.
 */
SS_API ss_status ss_remesh_quality_measure(const ss_mesh *m, const ss_mesh *ref, ss_remesh_quality *q,
                                           ss_error *err);

/* ---------------------------------------------------------------------------------------------
 * Ψ: for each of the np query points P (3*np doubles) the index of the nearest vertex of `target`
 * (exact Euclidean nearest, ties → smallest index), via a uniform grid. */
/* Ψ: for each query point, the index of the nearest vertex of `target` (exact Euclidean nearest,
 * ties to the smallest index), via a uniform grid.
 *
 * Inputs:
 *   P        np query points, 3*np doubles (xyz-interleaved)
 *   np       number of points (>= 0)
 *   target   the mesh whose vertices are searched (nv >= 1, finite coordinates)
 * Outputs:
 *   out      np vertex indices of target (caller-allocated)
 * Errors: SS_ERR_INVALID on bad arguments, an empty target or a non-finite point or vertex;
 *   SS_ERR_NOMEM.
 */
SS_API ss_status ss_closest_vertices(const double *P, int np, const ss_mesh *target, int *out, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
