/* specseg — synthetic shapes (library specseg_synth): deterministic test and demo meshes that need
 * no data set. */
#ifndef SPECSEG_SYNTH_H
#define SPECSEG_SYNTH_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Unit sphere as a subdivided icosahedron (each subdivision splits every triangle into 4, new
 * vertices projected onto the sphere).
 *
 * Inputs:
 *   subdivisions  0..9 (20·4^s faces, 10·4^s + 2 vertices)
 * Outputs:
 *   m        the mesh (free with ss_mesh_free)
 * Errors: SS_ERR_INVALID when subdivisions is outside [0, 9]; SS_ERR_NOMEM.
 */
SS_API ss_status ss_synth_icosphere(int subdivisions, ss_mesh *m, ss_error *err); /* unit sphere */
/* Torus of major radius R and minor radius r, a regular nu x nv grid of vertices, two triangles per
 * cell (genus 1, closed).
 *
 * Inputs:
 *   R, r     radii, 0 < r < R, R finite
 *   nu, nv   grid resolution around the major / minor circle, each in [3, 100000], nu·nv <= 5e7
 * Outputs:
 *   m        nu·nv vertices, 2·nu·nv faces (free with ss_mesh_free)
 * Errors: SS_ERR_INVALID on radii or a resolution outside those ranges; SS_ERR_NOMEM.
 */
SS_API ss_status ss_synth_torus(double R, double r, int nu, int nv, ss_mesh *m, ss_error *err);
/* Closed manifold humanoid (torso, head, arms, legs, finger/toe stubs), ~5–10k vertices, in one
 * of ss_synth_humanoid_pose_count() poses. All poses share one connectivity and vertex order
 * (ground truth = identity), so pairs of poses are test data for matching.
 *
 * Inputs:
 *   pose     0 .. ss_synth_humanoid_pose_count() - 1 (0: the rest pose)
 * Outputs:
 *   m        the mesh (free with ss_mesh_free)
 * Errors: SS_ERR_INVALID when pose is out of range; SS_ERR_NOMEM.
 */
SS_API ss_status ss_synth_humanoid(int pose, ss_mesh *m, ss_error *err);
/* Number of poses ss_synth_humanoid knows.
 *
 * Returns: the count (poses are 0 .. count - 1).
 */
SS_API int ss_synth_humanoid_pose_count(void);
/* One-line description of a pose of ss_synth_humanoid.
 *
 * Inputs:
 *   pose     the pose index
 * Returns: a static string; "?" when pose is out of range.
 */
SS_API const char *ss_synth_humanoid_pose_name(int pose);

#ifdef __cplusplus
}
#endif
#endif
