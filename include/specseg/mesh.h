/* specseg — mesh topology, checks and repair, synthetic shapes. */
#ifndef SPECSEG_MESH_H
#define SPECSEG_MESH_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Everything `specseg info` reports. */
typedef struct ss_mesh_report {
  int vertices, faces;
  double area, bbox_diagonal;
  int components;            /* connected components of the face graph (through shared vertices) */
  int boundary_loops;
  int boundary_edges;
  int nonmanifold_edges;     /* edges with more than two incident faces */
  int nonmanifold_vertices;  /* vertices whose star is not a single fan (pinched) */
  int degenerate_faces;      /* zero area or repeated vertex */
  int duplicate_faces;       /* same vertex set as an earlier face */
  int unreferenced_vertices;
  int nonfinite_vertices;    /* NaN / Inf coordinates */
  int euler_characteristic;  /* V - E + F over referenced vertices */
  int manifold;              /* 1 when no non-manifold edge or vertex */
} ss_mesh_report;

ss_status ss_mesh_check(const ss_mesh *m, ss_mesh_report *r, ss_error *err);

/* Make a mesh the pipeline can process: drops degenerate/duplicate faces and unreferenced vertices,
 * splits pinched (non-manifold) vertices into one copy per fan. `to_input[i]` (malloc'd, out->nv
 * entries) gives the input vertex of each output vertex. Fails with SS_ERR_INVALID on NaN/Inf
 * coordinates, non-manifold edges that cannot be split, or an empty result. `warnings` (may be NULL)
 * receives a human-readable summary of what was changed ("" when nothing). */
ss_status ss_mesh_sanitize(const ss_mesh *in, ss_mesh *out, int **to_input, char *warnings,
                           size_t warnings_size, ss_error *err);

/* Synthetic shapes (deterministic). */
ss_status ss_synth_icosphere(int subdivisions, ss_mesh *m, ss_error *err); /* unit sphere */
ss_status ss_synth_torus(double R, double r, int nu, int nv, ss_mesh *m, ss_error *err);
/* Closed manifold humanoid (torso, head, arms, legs, finger/toe stubs), ~5–10k vertices. All poses
 * share one connectivity and vertex order (ground truth = identity). pose 0 is the rest pose. */
ss_status ss_synth_humanoid(int pose, ss_mesh *m, ss_error *err);
int ss_synth_humanoid_pose_count(void);

#ifdef __cplusplus
}
#endif
#endif
