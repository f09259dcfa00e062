/* specseg — the k smallest eigenpairs of W φ = λ M φ (shift-invert on CHOLMOD: ARPACK, or block
 * Lanczos on large meshes). */
#ifndef SPECSEG_SPECTRUM_H
#define SPECSEG_SPECTRUM_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Where the time of one ss_eigs call went (wall seconds). */
typedef struct ss_eigs_stats {
  int null_pairs;          /* exact λ = 0 pairs (components) */
  double factor_nnz;       /* non-zeros of the Cholesky factor */
  double t_factor, t_arpack; /* t_arpack: the Lanczos iteration (whichever method ran) */
  int operator_applications;
  double t_solves;         /* inside t_arpack */
  double t_completeness;   /* inertia check and recovery of missed pairs */
  int recovered;
  double t_orthonormalize, t_rayleigh;
  int method;   /* the solver that ran: SS_EIGS_ARPACK, SS_EIGS_BLOCK or SS_EIGS_PRO (0 when only null pairs) */
  int block;    /* SS_EIGS_BLOCK: block size and thick restarts taken (SS_EIGS_PRO: restarts = reorthogonalisations) */
  int restarts;
} ss_eigs_stats;

/* Which Lanczos process computes the pairs (all give the same eigenvalues to ~1e-12 relative and
 * eigenpairs within ss_eigs_check's usual bounds; eigenvectors agree up to sign, and within an
 * eigenspace of a multiple eigenvalue up to a rotation):
 *  - SS_EIGS_ARPACK: implicitly restarted Lanczos one vector at a time (ARPACK) on a simplicial
 *    LDLᵀ factor, reorthogonalising every vector against the whole basis; any shift.
 *  - SS_EIGS_PRO: Lanczos one vector at a time with partial reorthogonalisation (Simon 1984) and no
 *    restarts, on the same factor (eigs_pro.c): orthogonality loss is estimated by a recurrence and
 *    repaired only where and when it nears working precision. 1.5-2.4x ARPACK's speed at FAUST size
 *    (k = 50-110), relative residuals as small (ss_eigs_check: 5e-11 at k = 100). Only for σ <= 0;
 *    when its basis of k + min(4k, 2k + 200) vectors does not suffice, ARPACK runs instead.
 *  - SS_EIGS_BLOCK: thick-restart block Lanczos on a supernodal LLᵀ factor, solving blocks of right-
 *    hand sides at once and reorthogonalising with matrix-matrix products, both shared over the
 *    OpenMP threads (eigs_block.c). Only for σ <= 0 (positive definite shifted matrix); otherwise,
 *    or when the shifted matrix is not positive definite or the mesh too small for the block basis,
 *    ARPACK runs instead.
 *  - SS_EIGS_AUTO (default): SS_EIGS_BLOCK from SS_EIGS_BLOCK_MIN_N vertices and 32 pairs on,
 *    SS_EIGS_PRO below (up to SS_EIGS_PRO_MAX_K pairs and without ncv; every FAUST and TOSCA
 *    matching and segmentation computation runs there), ARPACK otherwise. */
typedef enum ss_eigs_method { SS_EIGS_AUTO = 0, SS_EIGS_ARPACK = 1, SS_EIGS_BLOCK = 2, SS_EIGS_PRO = 3 } ss_eigs_method;
#define SS_EIGS_BLOCK_MIN_N 15000
#define SS_EIGS_PRO_MAX_K 500

/* Options of ss_eigs (start from ss_eigs_default_options). */
typedef struct ss_eigs_options {
  double sigma; /* shift; default -1e-8 (just below 0 so W - σM is positive definite). A negative
                   shift means "just below the spectrum": its size relative to the shape,
                   |σ|·Σ M, is kept within [1e-10, 1e-3] (σ is used as given inside that band,
                   e.g. the default on any shape of area 1e-2 ... 1e5; the nearer end of the
                   band outside it), so results scale exactly with the shape */
  double tol;   /* convergence tolerance (ARPACK's test, every method); default 1e-10 */
  int ncv;      /* Krylov dimension (block: most basis vectors kept, at least k + 4·block); 0 = automatic */
  int maxiter;  /* restarts; 0 = automatic */
  ss_eigs_stats *stats; /* NULL (default), or receives the timing breakdown of the call */
  int method;   /* ss_eigs_method; default SS_EIGS_AUTO */
  int block;    /* block size of SS_EIGS_BLOCK; 0 = automatic */
} ss_eigs_options;

/* Fills o with the defaults: sigma -1e-8, tol 1e-10, ncv 0 and maxiter 0 (automatic), stats NULL,
 * method SS_EIGS_AUTO, block 0 (automatic).
 *
 * Outputs:
 *   o        every field written
 */
SS_API void ss_eigs_default_options(ss_eigs_options *o);

/* The k eigenpairs of the generalized problem W φ = λ M φ nearest sigma (as scipy's
 * eigsh(..., sigma=σ)), which for the default σ just below 0 are the k smallest: shift-invert
 * Lanczos on a Cholesky factor of W - σM (method: ss_eigs_method). Deterministic (fixed start
 * vector). For sigma <= 0 the λ = 0 pairs of components on which W annihilates constants (any
 * Laplacian) are returned exactly (φ = 1/sqrt(component area) on the component) and deflated from
 * the Lanczos operator.
 *
 * Inputs:
 *   W        symmetric n x n sparse matrix (both triangles stored), n >= 2
 *   M        n positive, finite lumped masses
 *   k        1 <= k < n; above (n + c − 1) / 2 (c: components) the solver may lack the ~2k vectors it
 *            needs and fail (SS_ERR_NUMERIC, the message says which k works)
 *   opts     options (NULL: defaults from ss_eigs_default_options); opts->stats, when set, receives
 *            the timing breakdown
 * Outputs:
 *   evals    k eigenvalues, ascending (caller-allocated)
 *   evecs    n x k, column-major, M-orthonormal eigenvectors (caller-allocated; NULL: not wanted)
 * Errors: SS_ERR_INVALID on a bad k, sizes, a non-positive or non-finite mass, bad options;
 *   SS_ERR_NUMERIC when the shifted matrix is singular, Lanczos does not converge or ARPACK fails;
 *   SS_ERR_NOMEM.
 */
SS_API ss_status ss_eigs(const ss_sparse *W, const double *M, int k, const ss_eigs_options *opts, double *evals,
                         double *evecs, ss_error *err);

/* Accuracy of computed eigenpairs: max over i of ||W φ_i − λ_i M φ_i|| / ((|λ_i|+1) ||M φ_i||)
 * and max |ΦᵀMΦ − I|.
 *
 * Inputs:
 *   W, M, k  as for ss_eigs
 *   evals    k eigenvalues
 *   evecs    n x k, column-major
 * Outputs:
 *   max_rel_residual  (may be NULL) the largest relative residual
 *   max_orth_error    (may be NULL) the largest entry of |ΦᵀMΦ − I|
 * Errors: SS_ERR_INVALID on W, M, k as ss_eigs refuses them; SS_ERR_NOMEM.
 */
SS_API ss_status ss_eigs_check(const ss_sparse *W, const double *M, int k, const double *evals, const double *evecs,
                               double *max_rel_residual, double *max_orth_error, ss_error *err);

/* Convenience: the cotangent stiffness and barycentric lumped masses of the mesh, then ss_eigs with
 * the default options.
 *
 * Inputs:
 *   m        triangle mesh, nv >= 2 vertices, every vertex in a face of non-zero area
 *   k        1 <= k < nv (see ss_eigs)
 * Outputs:
 *   evals    k eigenvalues, ascending (caller-allocated)
 *   evecs    nv x k, column-major, M-orthonormal (caller-allocated; NULL: not wanted)
 * Errors: SS_ERR_INVALID on an empty mesh, or a vertex without mass (unreferenced, or only in
 *   zero-area faces: the message says which); those of ss_cotan_stiffness and ss_eigs.
 */
SS_API ss_status ss_mesh_eigs(const ss_mesh *m, int k, double *evals, double *evecs, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
