/* specseg — the discrete Laplace–Beltrami operator: cotangent stiffness W and lumped mass M,
 * so that the generalized eigenproblem W φ = λ M φ approximates Δφ = λφ (λ ≥ 0). */
#ifndef SPECSEG_LAPLACIAN_H
#define SPECSEG_LAPLACIAN_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Cotangent stiffness matrix W of the mesh: W_ij = -(cot α_ij + cot β_ij)/2 for each edge ij (one
 * term on a boundary edge), W_ii = -Σ_j W_ij. Symmetric, positive semi-definite (for meshes with
 * obtuse triangles too: it is the P1 FEM stiffness matrix), rows sum to zero. Degenerate (zero-area)
 * faces contribute nothing.
 *
 * Inputs:
 *   m        triangle mesh, nv vertices, nf faces
 * Outputs:
 *   W        nv x nv sparse matrix, both triangles stored (free with ss_sparse_free)
 * Errors: SS_ERR_INVALID on a face index out of range or a used vertex with a non-finite or
 *   too-large coordinate (or a bounding box too small to compute with); SS_ERR_NOMEM.
 */
SS_API ss_status ss_cotan_stiffness(const ss_mesh *m, ss_sparse *W, ss_error *err);

typedef enum ss_mass_kind {
  SS_MASS_BARYCENTRIC = 0, /* a third of each incident triangle's area (the default) */
  SS_MASS_VORONOI = 1      /* mixed Voronoi areas of Meyer et al. 2003 */
} ss_mass_kind;

/* Lumped (diagonal) mass matrix: one area per vertex; Σ M = area for both kinds.
 *
 * Inputs:
 *   m        triangle mesh, nv vertices
 *   kind     SS_MASS_BARYCENTRIC (a third of each incident triangle's area) or SS_MASS_VORONOI
 * Outputs:
 *   M        nv values, caller-allocated (0 for a vertex in no face)
 * Errors: SS_ERR_INVALID on a face index out of range or a used vertex with a non-finite or
 *   too-large coordinate.
 */
SS_API ss_status ss_mass_lumped(const ss_mesh *m, ss_mass_kind kind, double *M, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
