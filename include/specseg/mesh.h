/* specseg — mesh checks, repair and subdivision. */
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
  /* orientation, over edges shared by exactly two faces (faces with a repeated index left out) */
  int misoriented_edges;     /* edges both of whose faces run it in the same direction */
  int oriented;              /* 1 when no edge is misoriented (faces consistently oriented) */
  int orientable;            /* 1 when every component can be oriented consistently (no Moebius-like
                                band); the pipeline re-orients such meshes itself, with a warning */
  int reorient_faces;        /* faces the pipeline would reverse (each component keeps the orientation
                                of the majority of its faces); 0 when oriented or not orientable */
} ss_mesh_report;

/* Everything `specseg info` reports about a mesh: counts, area, components, boundary, manifoldness,
 * degenerate / duplicate / unreferenced vertices and faces, Euler characteristic, orientation. O(n log n).
 * Faces with a repeated vertex index count as degenerate and are left out of the topology (edges,
 * fans, loops, Euler characteristic); zero-area faces (height < 1e-14 x longest edge) with distinct
 * vertices are counted as degenerate but kept, and so are duplicates (whose edges then show as
 * non-manifold). Boundary loops are traced per vertex fan, so loops touching at a pinched vertex
 * count separately.
 *
 * Inputs:
 *   m        the mesh (any content; non-finite coordinates are counted, not refused)
 * Outputs:
 *   r        the report (every field written)
 * Errors: SS_ERR_INVALID on a face index out of range or bad sizes; SS_ERR_NOMEM.
 */
SS_API ss_status ss_mesh_check(const ss_mesh *m, ss_mesh_report *r, ss_error *err);

/* Makes a mesh the pipeline can process: drops degenerate / duplicate faces and unreferenced
 * vertices, splits pinched (non-manifold) vertices into one copy per fan, and orients every component
 * consistently (a component's faces of the minority orientation are reversed). Output vertices keep
 * the input order (copies of a split vertex are adjacent) and faces keep their order (and orientation,
 * unless inconsistent), so a mesh that needs no repair comes back identical with to_input = identity.
 *
 * Inputs:
 *   in       the mesh
 *   warnings_size  bytes at warnings
 * Outputs:
 *   out      the repaired mesh (free with ss_mesh_free)
 *   to_input malloc'd out->nv entries (free()): the input vertex of each output vertex
 *   warnings (may be NULL) a human-readable summary of what was changed ("" when nothing)
 * Errors: SS_ERR_INVALID on NULL outputs, non-finite coordinates on a vertex that a kept face uses,
 *   non-manifold edges that splitting vertices cannot repair, a non-orientable surface (named by one of
 *   its faces), or an empty result; SS_ERR_NOMEM.
 */
SS_API ss_status ss_mesh_sanitize(const ss_mesh *in, ss_mesh *out, int **to_input, char *warnings,
                                  size_t warnings_size, ss_error *err);

/* 1->4 midpoint subdivision: each edge split at its midpoint, no smoothing.
 *
 * Inputs:
 *   in       triangle mesh, nv vertices, nf faces
 * Outputs:
 *   out      nv + #edges vertices (input vertices keep their indices), 4·nf faces (free with
 *            ss_mesh_free)
 * Errors: SS_ERR_INVALID on bad sizes, a face index out of range or a result too large for int
 *   counts; SS_ERR_NOMEM.
 */
SS_API ss_status ss_mesh_subdivide(const ss_mesh *in, ss_mesh *out, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
