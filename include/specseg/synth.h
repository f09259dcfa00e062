/* specseg — synthetic shapes (library specseg_synth): deterministic test and demo meshes that need
 * no data set. */
#ifndef SPECSEG_SYNTH_H
#define SPECSEG_SYNTH_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

SS_API ss_status ss_synth_icosphere(int subdivisions, ss_mesh *m, ss_error *err); /* unit sphere */
SS_API ss_status ss_synth_torus(double R, double r, int nu, int nv, ss_mesh *m, ss_error *err);
/* Closed manifold humanoid (torso, head, arms, legs, finger/toe stubs), ~5–10k vertices. All poses
 * share one connectivity and vertex order (ground truth = identity). pose 0 is the rest pose. */
SS_API ss_status ss_synth_humanoid(int pose, ss_mesh *m, ss_error *err);
SS_API int ss_synth_humanoid_pose_count(void);
/* One-line description of a pose ("?" when out of range). */
SS_API const char *ss_synth_humanoid_pose_name(int pose);

#ifdef __cplusplus
}
#endif
#endif
