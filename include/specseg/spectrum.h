/* specseg — the k smallest eigenpairs of W φ = λ M φ (ARPACK shift-invert on CHOLMOD). */
#ifndef SPECSEG_SPECTRUM_H
#define SPECSEG_SPECTRUM_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ss_eigs_options {
  double sigma; /* shift; default -1e-8 (just below 0 so W - σM is positive definite) */
  double tol;   /* ARPACK tolerance; default 1e-10 */
  int ncv;      /* Krylov dimension; 0 = automatic */
  int maxiter;  /* 0 = automatic */
} ss_eigs_options;

void ss_eigs_default_options(ss_eigs_options *o);

/* W: symmetric n x n (both triangles stored); M: n positive lumped masses. Writes the k smallest
 * eigenvalues ascending into evals[k] and M-orthonormal eigenvectors, column-major n x k, into evecs.
 * opts may be NULL for defaults. */
ss_status ss_eigs(const ss_sparse *W, const double *M, int k, const ss_eigs_options *opts, double *evals,
                  double *evecs, ss_error *err);

/* Convenience: W, M (barycentric) of the mesh, then ss_eigs. */
ss_status ss_mesh_eigs(const ss_mesh *m, int k, double *evals, double *evecs, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
