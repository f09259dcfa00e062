/* specseg — the discrete Laplace–Beltrami operator: cotangent stiffness W and lumped mass M,
 * so that the generalized eigenproblem W φ = λ M φ approximates Δφ = λφ (λ ≥ 0). */
#ifndef SPECSEG_LAPLACIAN_H
#define SPECSEG_LAPLACIAN_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Cotangent stiffness: W_ij = -(cot α_ij + cot β_ij)/2 for each edge ij (one term on a boundary
 * edge), W_ii = -Σ_j W_ij. Symmetric, positive semi-definite (for non-obtuse-free meshes too: it is
 * the P1 FEM stiffness matrix), rows sum to zero. Degenerate (zero-area) faces contribute nothing. */
SS_API ss_status ss_cotan_stiffness(const ss_mesh *m, ss_sparse *W, ss_error *err);

typedef enum ss_mass_kind {
  SS_MASS_BARYCENTRIC = 0, /* a third of each incident triangle's area (the default) */
  SS_MASS_VORONOI = 1      /* mixed Voronoi areas of Meyer et al. 2003 */
} ss_mass_kind;

/* Lumped (diagonal) mass: M[i] for each vertex; Σ M = area for both kinds. */
SS_API ss_status ss_mass_lumped(const ss_mesh *m, ss_mass_kind kind, double *M, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
