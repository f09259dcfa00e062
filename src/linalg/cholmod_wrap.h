/* Internal: sparse symmetric factorisation of A + alpha*diag(d) with CHOLMOD (simplicial LDL^T, or
 * supernodal LL^T for positive definite matrices), and repeated solves with preallocated workspace.
 * Not part of the public API. */
#ifndef SS_LINALG_CHOLMOD_WRAP_H
#define SS_LINALG_CHOLMOD_WRAP_H

#include "specseg/core.h"

typedef struct ssi_chol ssi_chol;

/* A: symmetric n x n CSC with both triangles stored (only the upper one is read). d may be NULL
 * (then alpha is ignored). Fails with SS_ERR_NUMERIC when the matrix is numerically singular or
 * the factorisation breaks down, SS_ERR_NOMEM on allocation failure. */
ss_status ssi_chol_factor(const ss_sparse *A, double alpha, const double *d, ssi_chol **out, ss_error *err);

/* The same as a supernodal LL^T factor: only for positive definite matrices (anything else fails with
 * SS_ERR_NUMERIC). Its solves run dense kernels per supernode, so a block of many right-hand sides
 * costs much less per column than with the simplicial factor (n = 110k: 3.5 vs 6.8 ms per column at
 * 48 columns, 15 ms for one column alone). */
ss_status ssi_chol_factor_super(const ss_sparse *A, double alpha, const double *d, ssi_chol **out, ss_error *err);

/* X = (A + alpha D)^{-1} B for nrhs column-major right-hand sides of length n. X may alias B. */
ss_status ssi_chol_solve(ssi_chol *c, const double *B, double *X, int nrhs, ss_error *err);

/* The same through solve workspace `slot` (0 .. SSI_CHOL_SLOTS-1; slot 0 is ssi_chol_solve's own):
 * calls on distinct slots may run at the same time from different threads (the factor is only
 * read). Each column's result does not depend on the slot or on how columns are grouped. */
#define SSI_CHOL_SLOTS 16
ss_status ssi_chol_solve_slot(ssi_chol *c, int slot, const double *B, double *X, int nrhs, ss_error *err);

/* Factors A + alpha*diag(d) again into c, for an A of the pattern c was made from (a new diagonal, new
 * values): no new analysis, the same ordering. On failure c is not to be solved with. */
ss_status ssi_chol_refactor(ssi_chol *c, const ss_sparse *A, double alpha, const double *d, ss_error *err);

/* Number of negative pivots of the LDLᵀ factorisation of A + alpha*diag(d) (same pattern and
 * ordering as the factored matrix: refactored without a new analysis, or, for a supernodal factor,
 * a simplicial LDLᵀ in the factor's ordering). By Sylvester's law of inertia, with A = W and
 * d = M (positive), alpha = -τ, that is the number of eigenvalues of W φ = λ M φ below τ. */
ss_status ssi_chol_inertia(ssi_chol *c, const ss_sparse *A, double alpha, const double *d, int *negative,
                          ss_error *err);

int ssi_chol_size(const ssi_chol *c);
/* Number of nonzeros in the factor (for diagnostics). */
double ssi_chol_nnz(const ssi_chol *c);
void ssi_chol_free(ssi_chol *c);

#endif
