/* Internal to the spectrum module: the shift-invert operator both eigensolvers iterate with, and the
 * block Lanczos solver (eigs_block.c) next to ARPACK (eigs.c). Not part of the public API. */
#ifndef SS_SPECTRUM_EIGS_INTERNAL_H
#define SS_SPECTRUM_EIGS_INTERNAL_H

#include <stdint.h>

#include "linalg/cholmod_wrap.h"
#include "specseg/core.h"

/* What the Lanczos operator needs: OP = P M^{1/2} (W − σM)^{-1} M^{1/2} P, where P projects out the
 * exact null pairs and (when recovering missed eigenvalues) already found eigenvectors. */
typedef struct ssi_lanczos_ctx {
  ssi_chol *chol;
  const double *sqm, *mass;
  const int *label;
  double *acc;
  int n, nnull;
  const double *defl; /* n x ndefl orthonormal (scaled space), may be NULL */
  int ndefl;
  double *coef;       /* ndefl */
  double sigma, tol;
  double opscale; /* OP is applied times this power of two (1 at everyday scales, see ss_eigs) */
  int maxiter, ncv_opt;
  int nops;
  double tsolve;
  int block, restarts, verified; /* block Lanczos: block size used, restarts taken, residual checks */
  const ss_sparse *W; /* block Lanczos: the pairs' residuals are checked on W φ = λ M φ when given */
  const double *M;
  int k; /* the caller's k (messages) */
} ssi_lanczos_ctx;

/* y = OP x (y must not alias x), counted in nops and timed in tsolve. */
ss_status ssi_eigs_apply_op(ssi_lanczos_ctx *c, const double *x, double *y, ss_error *err);

/* x ← P x (uses the context's scratch arrays: one caller at a time). */
void ssi_eigs_project(ssi_lanczos_ctx *c, double *x);

/* Deterministic start vector: a fixed-seed xorshift sequence, uniform in [-1, 1). */
void ssi_eigs_start_vector(double *r, int n, uint64_t seed);

/* The nev eigenpairs of OP of largest ν (OP positive semi-definite: σ <= 0) by thick-restart block
 * Lanczos with full reorthogonalisation: Y (n x nev, scaled space, orthonormal) and lam
 * (λ = σ + 1/ν), both ordered by ascending λ. block: block size; mmax: most basis columns kept
 * (mmax + block <= dimension of the space OP acts on). The chol factor may be simplicial or
 * supernodal. Same convergence test as ARPACK's: ‖OP y − ν y‖ <= tol·ν for each wanted pair. */
ss_status ssi_eigs_block_lanczos(ssi_lanczos_ctx *c, int nev, int block, int mmax, uint64_t seed, double *Y,
                                 double *lam, ss_error *err);

/* The same nev pairs by single-vector Lanczos with partial reorthogonalisation and no restarts
 * (eigs_pro.c): at most mmax basis columns; *converged = 0 (and SS_OK) when they did not suffice or
 * the process broke down, for the caller to run ARPACK instead. Same convergence test. */
ss_status ssi_eigs_pro_lanczos(ssi_lanczos_ctx *c, int nev, int mmax, uint64_t seed, double *Y, double *lam,
                               int *converged, ss_error *err);

#endif
