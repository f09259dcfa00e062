/* specseg — functional maps (paper §6): WKS and wave-kernel probe functions, the functional map of
 * Eq. (1) (Nogneng & Ovsjanikov 2017), point-to-point conversion and ZoomOut refinement.
 *
 * Conventions of this module:
 *  - a spectral basis is (evals[k], evecs n x k column-major, M-orthonormal, ascending eigenvalues,
 *    evals[0] ≈ 0 the constant function), as produced by ss_mesh_eigs;
 *  - a functional map C from a source shape S to a target shape T is k_T x k_S, column-major, and
 *    maps spectral coefficients of functions on S to those on T: b = C a;
 *  - the point map that goes with C is the pull-back one and goes the OTHER way, T -> S
 *    (f ∘ π for π : T -> S), so ss_fmap_p2p returns, for each TARGET vertex, a SOURCE vertex.
 *    ss_fmap_match therefore solves for the map from functions on Y to functions on X (source Y,
 *    target X) to return Π : X -> Y. */
#ifndef SPECSEG_FMAP_H
#define SPECSEG_FMAP_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- wave kernel (wks.c) */

/* The WKS energy filters of Aubry et al. 2011 (as in their code and pyFM): with e_min, e_max the logs
 * of the first non-zero and the last eigenvalue, δ = (e_max − e_min)/ne, σ = sigma_factor·δ (7 in the
 * paper), energies e_j evenly spaced in [e_min + 2σ, e_max − 2σ] (log scale); G[j,i] =
 * exp(−(e_j − log λ_i)² / 2σ²), 0 for the (numerically) zero eigenvalues (|λ| ≤ 1e-8·λ_max), so
 * constants are filtered out.
 *
 * Inputs:
 *   evals    k eigenvalues, ascending, k >= 3, at least two distinct non-zero ones
 *   ne       number of energies (>= 1)
 *   sigma_factor  σ in energy spacings (> 0)
 * Outputs:
 *   G        ne x k, column-major (caller-allocated)
 * Errors: SS_ERR_INVALID on k < 3, ne < 1, sigma_factor <= 0 or fewer than two distinct non-zero
 *   eigenvalues; SS_ERR_NOMEM.
 */
SS_API ss_status ss_wks_filters(const double *evals, int k, int ne, double sigma_factor, double *G, ss_error *err);

/* WKS descriptors: out[x,j] = Σ_i G[j,i] φ_i(x)² (G: ss_wks_filters), each column then normalised to
 * unit L²(M) norm.
 *
 * Inputs:
 *   n, k     vertices and eigenpairs (n >= 1, k >= 3)
 *   evals    k eigenvalues; evecs n x k, column-major
 *   M        n lumped masses
 *   ne, sigma_factor  as ss_wks_filters
 * Outputs:
 *   out      n x ne, column-major (caller-allocated)
 * Errors: SS_ERR_INVALID on bad sizes or NULL arrays and as ss_wks_filters; SS_ERR_NOMEM.
 */
SS_API ss_status ss_wks(int n, int k, const double *evals, const double *evecs, const double *M, int ne,
                        double sigma_factor, double *out, ss_error *err);

/* Wave-kernel filtering of nf functions: for each function f and energy j, the function
 * Σ_i G[j,i] <f, φ_i>_M φ_i, normalised in L²(M) (a column whose filtered version is numerically zero is
 * left zero).
 *
 * Inputs:
 *   n, k, evals, evecs, M, ne, sigma_factor  as ss_wks
 *   nf       number of functions (>= 0)
 *   F        n x nf, column-major
 * Outputs:
 *   out      n x (nf·ne), column-major, column f·ne + j (caller-allocated)
 * Errors: SS_ERR_INVALID on bad sizes and as ss_wks; SS_ERR_NOMEM.
 */
SS_API ss_status ss_wks_filter(int n, int k, const double *evals, const double *evecs, const double *M, int ne,
                               double sigma_factor, int nf, const double *F, double *out, ss_error *err);

/* Wave-kernel maps of landmarks (NO17): the filtered delta at each landmark,
 * out[x, l·ne + j] = Σ_i G[j,i] φ_i(lm[l]) φ_i(x), normalised in L²(M).
 *
 * Inputs:
 *   n, k, evals, evecs, M, ne, sigma_factor  as ss_wks
 *   nl       number of landmarks
 *   lm       nl vertices in [0, n)
 * Outputs:
 *   out      n x (nl·ne), column-major (caller-allocated)
 * Errors: SS_ERR_INVALID on a landmark out of range and as ss_wks; SS_ERR_NOMEM.
 */
SS_API ss_status ss_wks_landmarks(int n, int k, const double *evals, const double *evecs, const double *M, int ne,
                                  double sigma_factor, int nl, const int *lm, double *out, ss_error *err);

/* ------------------------------------------------------------------ heat kernel (hks.c) */

/* The HKS time filters (Sun, Ovsjanikov, Guibas 2009), in the WKS's style: nt times t_j log-spaced
 * from 4 ln 10 / λ_max to 4 ln 10 / λ_min (λ_min, λ_max: the first non-zero and the largest of the k
 * eigenvalues; e^{−λ t} then spans 1e-4 at either end, as in the reference code and pyFM), ascending
 * (nt = 1: their geometric mean); G[j,i] = exp(−λ_i t_j), 0 for the (numerically) zero eigenvalues
 * (|λ| ≤ 1e-8·λ_max) as the WKS filters, so the constant function does not enter.
 *
 * Inputs:
 *   evals    k eigenvalues, ascending, k >= 2, at least one non-zero
 *   nt       number of times (>= 1)
 * Outputs:
 *   G        nt x k, column-major (caller-allocated)
 *   times    (may be NULL) the nt times t_j
 * Errors: SS_ERR_INVALID on k < 2, nt < 1, NULL arrays or no non-zero eigenvalue; SS_ERR_NOMEM.
 */
SS_API ss_status ss_hks_filters(const double *evals, int k, int nt, double *G, double *times, ss_error *err);

/* HKS descriptors: out[x,j] = Σ_i G[j,i] φ_i(x)² (G: ss_hks_filters), each column then normalised to
 * unit L²(M) norm as ss_wks does (instead of pyFM's division by the heat trace: the scale of each
 * column is lost either way).
 *
 * Inputs:
 *   n, k     vertices and eigenpairs (n >= 1, k >= 2)
 *   evals    k eigenvalues; evecs n x k, column-major
 *   M        n lumped masses
 *   nt       number of times (>= 1)
 * Outputs:
 *   out      n x nt, column-major (caller-allocated)
 * Errors: SS_ERR_INVALID on bad sizes or NULL arrays and as ss_hks_filters; SS_ERR_NOMEM.
 */
SS_API ss_status ss_hks(int n, int k, const double *evals, const double *evecs, const double *M, int nt, double *out,
                        ss_error *err);

/* ------------------------------------------------------- functional map (fmap_solve.c) */

/* Spectral coefficients A = Φᵀ M F of p functions, Φ the first k columns of evecs.
 *
 * Inputs:
 *   n, k     vertices and basis size (>= 1)
 *   evecs    n x (>= k), column-major, leading dimension n
 *   M        n lumped masses
 *   p        number of functions (>= 0)
 *   F        n x p, column-major
 * Outputs:
 *   A        k x p, column-major (caller-allocated)
 * Errors: SS_ERR_INVALID on bad sizes; SS_ERR_NOMEM.
 */
SS_API ss_status ss_fmap_project(int n, int k, const double *evecs, const double *M, int p, const double *F,
                                 double *A, ss_error *err);

/* Multiplication operators in the reduced basis: D_i = Φᵀ M diag(f_i) Φ (k x k, symmetric) for p
 * functions.
 *
 * Inputs:
 *   n, k, evecs, M  as ss_fmap_project
 *   p        number of functions (>= 0)
 *   F        n x p, column-major
 * Outputs:
 *   D        p consecutive k x k column-major blocks, p·k·k doubles (caller-allocated)
 * Errors: SS_ERR_INVALID on bad sizes; SS_ERR_NOMEM.
 */
SS_API ss_status ss_fmap_mult_operators(int n, int k, const double *evecs, const double *M, int p,
                                        const double *F, double *D, ss_error *err);

/* ss_fmap_mult_operators, packed: column i of P holds the upper triangle of D_i, entry (a, b) with
 * a <= b at index b(b+1)/2 + a. This is what the solver consumes.
 *
 * Inputs:
 *   n, k, evecs, M, p, F  as ss_fmap_mult_operators
 * Outputs:
 *   P        k(k+1)/2 x p, column-major (caller-allocated)
 * Errors: SS_ERR_INVALID on bad sizes; SS_ERR_NOMEM.
 */
SS_API ss_status ss_fmap_mult_operators_packed(int n, int k, const double *evecs, const double *M, int p, const double *F,
                                               double *P, ss_error *err);

/* Weights of Eq. (1):
 *   E(C) = w_descr ‖C A − B‖² + w_lap ‖Λ_T C − C Λ_S‖² + w_dcomm Σ_i ‖C D_i^S − D_i^T C‖².
 * fix_constant: keep the first column at C[:,0] = s·sqrt(area_T/area_S)·e_0 (the constant function
 * maps to the constant; s = sign making evecs' first columns agree, given by const_sign) and
 * minimise over the other columns, as pyFM does.
 */
typedef struct ss_fmap_weights {
  double w_descr, w_lap, w_dcomm;
  int fix_constant;
  double const_value; /* value of C[0,0] when fix_constant (s·sqrt(area_T/area_S)) */
  /* orientation term w_orient Σ_i ‖C O_i^S − O_i^T C‖² over the probes' orientation operators
   * (ss_fmap_probes.O; Ren et al. 2018); used by ss_fmap_system, 0 in ss_fmap_solve */
  double w_orient;
} ss_fmap_weights;

/* Global minimiser of E(C) of Eq. (1) (weights above): the k_T·k_S normal equations, assembled
 * densely through their Kronecker structure, solved by Cholesky (ss_fmap_system below); the
 * orientation term is not used here.
 *
 * Inputs:
 *   k_S, k_T basis sizes of source and target (>= 1; k_S·k_T <= 40,000)
 *   p        number of descriptors (>= 0)
 *   A, B     k_S x p and k_T x p coefficients of the corresponding descriptors (NULL when p = 0)
 *   evals_S, evals_T  k_S and k_T eigenvalues
 *   nd       number of operator pairs (>= 0)
 *   D_S, D_T nd blocks k_S x k_S and nd blocks k_T x k_T (ss_fmap_mult_operators; NULL when nd = 0)
 *   w        the weights (non-negative)
 * Outputs:
 *   C        k_T x k_S, column-major (caller-allocated)
 * Errors: SS_ERR_INVALID on bad sizes, missing arrays or negative weights; SS_ERR_NUMERIC when the
 *   system is singular (e.g. all weights zero); SS_ERR_NOMEM.
 */
SS_API ss_status ss_fmap_solve(int k_S, int k_T, int p, const double *A, const double *B, const double *evals_S,
                               const double *evals_T, int nd, const double *D_S, const double *D_T,
                               const ss_fmap_weights *w, double *C, ss_error *err);

/* Probe functions of one shape in its reduced basis — all Eq. (1) needs from that side: the spectral
 * coefficients A (k x p) and the packed multiplication operators (ss_fmap_mult_operators_packed) of
 * the first nd probes, P (k(k+1)/2 x nd; NULL when nd = 0). Both sides of a pair must have the same
 * p and nd, column i of one corresponding to column i of the other. */
typedef struct ss_fmap_probes {
  int k, p, nd;
  double *A;
  double *P;
  /* no orientation operators (ss_fmap_orientation_operators), k x k each, column-major, one after
   * the other (NULL when no = 0); both sides of a pair must have the same no */
  int no;
  double *O;
} ss_fmap_probes;

/* Frees A, P and O of pr and zeroes it; safe on a zeroed struct.
 *
 * Inputs:
 *   pr       probes from ss_fmap_base_probes / ss_fmap_extra_probes
 */
SS_API void ss_fmap_probes_free(ss_fmap_probes *pr); /* frees A, P and O, zeroes the struct */

/* Orientation operators in the reduced basis (Ren, Poulenard, Wonka, Ovsjanikov 2018): for each of
 * p functions f, the k x k matrix of g ↦ ⟨n × ∇f, ∇g⟩ (the signed Jacobian of f and g on the surface),
 * O[i, j] = ∫ φ_i ⟨n × ∇f, ∇φ_j⟩ with piecewise-linear gradients per face, averaged to the vertices by
 * area and integrated with the lumped masses. The face areas cancel: per face t = (a, b, c),
 * ⟨n × ∇f, ∇g⟩·area = ±(f_a(g_b − g_c) + f_b(g_c − g_a) + f_c(g_a − g_b))/2, so O depends on the values
 * and on each face's winding only, and an orientation-preserving isometry C satisfies
 * C O^Y_f = O^X_{Cf} C, an orientation-reversing one C O^Y = −O^X C. Cost: 2·nf·k²·p flops.
 *
 * Inputs:
 *   m        consistently oriented triangle mesh, n = m->nv vertices
 *   k        basis size (>= 1)
 *   evecs    n x (>= k), column-major, leading dimension n
 *   p        number of functions (>= 0)
 *   F        n x p, column-major
 * Outputs:
 *   O        p consecutive k x k column-major blocks (caller-allocated)
 * Errors: SS_ERR_INVALID on bad arguments or a face index out of range; SS_ERR_NOMEM.
 */
SS_API ss_status ss_fmap_orientation_operators(const ss_mesh *m, int k, const double *evecs, int p, const double *F,
                                               double *O, ss_error *err);

/* The normal equations of Eq. (1) for a pair's base probes (source S, target T), assembled once so
 * that several extra-probe blocks can be solved against them (STD / ASA / DIFF differ only in the
 * segments). Opaque; read-only after ss_fmap_system_new, so solves may run concurrently. About
 * 8·(k_S·k_T)² bytes (50 MB at k = 50); k_S·k_T is limited to 40,000 unknowns. */
typedef struct ss_fmap_system ss_fmap_system;

/* Assembles the normal equations of Eq. (1) for a pair's base probes (source S, target T) once, so
 * that several extra-probe blocks can be solved against them (STD / ASA / DIFF differ only in the
 * segments). The system is read-only afterwards: solves may run concurrently. About 8·(k_S·k_T)²
 * bytes (50 MB at k = 50).
 *
 * Inputs:
 *   k_S, k_T basis sizes (>= 1; k_S·k_T <= 40,000 unknowns)
 *   evals_S, evals_T  k_S and k_T eigenvalues
 *   S, T     the two shapes' base probes (same p, nd and no; S->k = k_S, T->k = k_T)
 *   w        the weights (non-negative; w_orient used with the probes' orientation operators)
 * Outputs:
 *   out      *out: the system (free with ss_fmap_system_free)
 * Errors: SS_ERR_INVALID on a NULL output, bad sizes, probes that do not match, negative weights or
 *   too many unknowns; SS_ERR_NUMERIC; SS_ERR_NOMEM.
 */
SS_API ss_status ss_fmap_system_new(int k_S, int k_T, const double *evals_S, const double *evals_T, const ss_fmap_probes *S,
                                    const ss_fmap_probes *T, const ss_fmap_weights *w, ss_fmap_system **out, ss_error *err);

/* Global minimiser C of E(C) plus an extra probe block's terms: its data term weighted by
 * w_extra·w_descr and, when extra_dcomm, its operators in the commutativity term. Cholesky in single
 * precision with iterative refinement in double (LAPACK dsposv): double-accurate.
 *
 * Inputs:
 *   sys      from ss_fmap_system_new
 *   S_extra, T_extra  the extra probes of both shapes (same counts), or both NULL (the base problem alone)
 *   w_extra  weight of the extra data term relative to w_descr (>= 0)
 *   extra_dcomm  1: the extra probes' operators enter the commutativity term
 * Outputs:
 *   C        k_T x k_S, column-major (caller-allocated)
 * Errors: SS_ERR_INVALID on a NULL system or output, probes that do not match, a negative w_extra;
 *   SS_ERR_NUMERIC when the normal equations are not positive definite or the solution is not
 *   finite or all zero (a weight near DBL_MAX overflows the system); SS_ERR_NOMEM.
 */
SS_API ss_status ss_fmap_system_solve(const ss_fmap_system *sys, const ss_fmap_probes *S_extra, const ss_fmap_probes *T_extra,
                                      double w_extra, int extra_dcomm, double *C, ss_error *err);

/* Frees a system from ss_fmap_system_new (NULL allowed).
 *
 * Inputs:
 *   sys      the system
 */
SS_API void ss_fmap_system_free(ss_fmap_system *sys);

/* E(C) of Eq. (1) and its gradient, e.g. to check optimality of ss_fmap_solve's C.
 *
 * Inputs:
 *   k_S, k_T, p, A, B, evals_S, evals_T, nd, D_S, D_T, w  as ss_fmap_solve
 *   C        k_T x k_S, column-major
 * Outputs:
 *   E        the energy
 *   grad     (may be NULL) dE/dC, k_T x k_S, column-major
 * Errors: SS_ERR_INVALID on bad sizes, missing arrays or negative weights; SS_ERR_NOMEM.
 */
SS_API ss_status ss_fmap_energy(int k_S, int k_T, int p, const double *A, const double *B, const double *evals_S,
                                const double *evals_T, int nd, const double *D_S, const double *D_T,
                                const ss_fmap_weights *w, const double *C, double *E, double *grad, ss_error *err);

/* ------------------------------- nearest neighbours and point maps (nearest_neighbor.c, p2p.c) */

/* Exact Euclidean nearest neighbours: for each query point the index of the closest database
 * point; ties go to the lower index. Clusters the database (farthest-point centres, radii, a 3-D local
 * frame per cluster) and skips clusters and points by the triangle inequality (spectral embeddings of
 * surfaces are intrinsically 2-D, so few survive); results identical to ss_nn_brute; OpenMP over
 * queries.
 *
 * Inputs:
 *   ndb, nq, d  database points, queries, dimension
 *   db       ndb x d, column-major, leading dimension lddb >= ndb
 *   q        nq x d, column-major, leading dimension ldq >= nq
 * Outputs:
 *   idx      nq database indices (caller-allocated)
 *   dist2    (may be NULL) nq squared distances, exact Σ (q_j − b_j)² in double
 * Errors: SS_ERR_INVALID on bad sizes or NULL arrays; SS_ERR_NOMEM.
 */
SS_API ss_status ss_nn_exact(int ndb, int nq, int d, const double *db, int lddb, const double *q, int ldq, int *idx,
                             double *dist2, ss_error *err);
/* Exact Euclidean nearest neighbours by blocked-BLAS brute force (‖q‖² − 2 q·b + ‖b‖² with an exact
 * recheck of near-ties); the same results as ss_nn_exact. OpenMP over queries.
 *
 * Inputs:
 *   ndb, nq, d  database points, queries, dimension
 *   db       ndb x d, column-major, leading dimension lddb >= ndb
 *   q        nq x d, column-major, leading dimension ldq >= nq
 * Outputs:
 *   idx      nq database indices (caller-allocated)
 *   dist2    (may be NULL) nq squared distances
 * Errors: SS_ERR_INVALID on bad sizes or NULL arrays; SS_ERR_NOMEM.
 */
SS_API ss_status ss_nn_brute(int ndb, int nq, int d, const double *db, int lddb, const double *q, int ldq, int *idx,
                             double *dist2, ss_error *err);

/* ss_nn_exact for repeated searches (ZoomOut), the same results: a given partition of the database
 * and a guess per query speed it up. Small databases (< 256 points) are searched by brute force.
 *
 * Inputs:
 *   ndb, nq, d  database points, queries, dimension
 *   db       ndb x d, column-major, leading dimension lddb >= ndb
 *   q        nq x d, column-major, leading dimension ldq >= nq
 *   part     (may be NULL: computed as ss_nn_exact does) ndb cluster labels in [0, ndb), any
 *            partition (any keeps the search exact, compact ones make it fast)
 *   guess    (may be NULL; may be the same array as idx) nq database indices, e.g. the previous match:
 *            its distance bounds the search from the start
 * Outputs:
 *   idx      nq database indices
 *   dist2    (may be NULL) nq squared distances
 * Errors: SS_ERR_INVALID on bad sizes, NULL arrays, a guess or label out of range; SS_ERR_NOMEM.
 */
SS_API ss_status ss_nn_exact_guided(int ndb, int nq, int d, const double *db, int lddb, const double *q, int ldq,
                                    const int *part, const int *guess, int *idx, double *dist2, ss_error *err);

/* The partition ss_nn_exact uses: nc clusters of the points around farthest-point seeds, each point
 * labelled with its nearest seed.
 *
 * Inputs:
 *   n, d     points and dimension (>= 1)
 *   X        n x d, column-major, leading dimension ldx >= n
 *   nc       number of clusters (<= 0: ~1.5 √n)
 * Outputs:
 *   part     n cluster labels (caller-allocated)
 * Errors: SS_ERR_INVALID on bad sizes or NULL arrays; SS_ERR_NOMEM.
 */
SS_API ss_status ss_nn_partition(int n, int d, const double *X, int ldx, int nc, int *part, ss_error *err);

/* Point map of a functional map C (functions S -> T): for each target vertex y, the source vertex x
 * minimising ‖Φ_S(x) Cᵀ − Φ_T(y)‖ (rows of the first k_S / k_T eigenvectors); nearest neighbours by
 * ss_nn_exact.
 *
 * Inputs:
 *   n_S, n_T vertices of source and target (>= 1)
 *   k_S, k_T basis sizes (>= 1)
 *   evecs_S  n_S x (>= k_S), column-major, leading dimension n_S; likewise evecs_T
 *   C        k_T x k_S, column-major
 * Outputs:
 *   map      n_T source vertices, one per target vertex (T -> S; caller-allocated)
 * Errors: SS_ERR_INVALID on bad sizes; SS_ERR_NOMEM.
 */
SS_API ss_status ss_fmap_p2p(int n_S, int n_T, int k_S, int k_T, const double *evecs_S, const double *evecs_T,
                             const double *C, int *map, ss_error *err);

/* Functional map of a point map π : T -> S: C = Φ_Tᵀ M_T Π Φ_S.
 *
 * Inputs:
 *   n_S, n_T, k_S, k_T, evecs_S, evecs_T  as ss_fmap_p2p
 *   M_T      n_T lumped masses of the target
 *   map      n_T source vertices in [0, n_S)
 * Outputs:
 *   C        k_T x k_S, column-major (caller-allocated)
 * Errors: SS_ERR_INVALID on bad sizes or a map entry out of range; SS_ERR_NOMEM.
 */
SS_API ss_status ss_fmap_from_p2p(int n_S, int n_T, int k_S, int k_T, const double *evecs_S, const double *evecs_T,
                                  const double *M_T, const int *map, double *C, ss_error *err);

/* ------------------------------------------------------------------ ZoomOut (zoomout.c) */

/* ZoomOut (Melzi et al. 2019): from C0 alternate the point map and the spectral up-sampling
 * C ← Φ_Tᵀ M_T Π Φ_S at sizes k0+step, k0+2·step, …, kmax, then a last point map.
 *
 * Inputs:
 *   n_S, n_T vertices of source and target
 *   evecs_S, evecs_T  n_S x (>= kmax) and n_T x (>= kmax), column-major
 *   M_T      n_T lumped masses of the target
 *   k0       size of C0, 1 <= k0 <= kmax
 *   C0       k0 x k0, column-major (functions S -> T)
 *   kmax, step  final size and step (>= 1)
 * Outputs:
 *   map      n_T source vertices (T -> S; caller-allocated)
 *   C_out    (may be NULL) the final kmax x kmax map
 * Errors: SS_ERR_INVALID on bad sizes; SS_ERR_NOMEM.
 */
SS_API ss_status ss_zoomout(int n_S, int n_T, const double *evecs_S, const double *evecs_T, const double *M_T, int k0,
                            const double *C0, int kmax, int step, int *map, double *C_out, ss_error *err);

/* The vertex samples of ss_zoomout_sampled (ss_zoomout_samples computes them) and how it uses them. */
typedef struct ss_zoomout_sample {
  int ns_S, ns_T;       /* samples on each shape (1 ≤ ns ≤ n; ns_S unused without sub_S) */
  const int *sub_S;     /* ns_S source vertices, or NULL: every source vertex */
  const int *sub_T;     /* ns_T target vertices */
  const double *w_T;    /* ns_T weights of the target samples (e.g. their Voronoi areas) */
  const int *near_T;    /* may be NULL: n_T entries, a sample (index into sub_T) near each target
                           vertex; its image is the final search's starting guess (speed only) */
  const int *part_S;    /* may be NULL: a partition of the source's full Φ_S (kmax columns) for the
                           final searches (ss_nn_exact_guided; speed only, e.g. shared by two calls) */
  int lstsq;            /* 0: weighted sum, 1: weighted least squares (see above) */
  int polish;           /* iterations at kmax on every vertex after the sampled ones (>= 0) */
  const double *M_T;    /* n_T lumped masses of the target (needed when polish > 0) */
} ss_zoomout_sample;

/* ZoomOut on vertex samples (as ZoomOut's authors run it): the iterations of ss_zoomout for the
 * sampled target rows of Φ_T only, their images among the sampled source rows of Φ_S or (sub_S =
 * NULL) among every source vertex, then one point map of every target vertex from the final C
 * (kmax x kmax) among all source vertices, then `polish` iterations at kmax on every vertex
 * (C ← Φ_Tᵀ M_T Π Φ_S, point map). Images among source samples are quantised to the samples' spacing,
 * which limits the accuracy (docs/tuning.md has the measurements). The spectral up-sampling on the
 * samples is the weighted sum B = Φ_T[sub_T]ᵀ diag(w_T) Π Φ_S[sub_S] (lstsq 0), or its weighted
 * least-squares version C = G⁻¹ B with G = Φ_T[sub_T]ᵀ diag(w_T) Φ_T[sub_T] (lstsq 1: the coefficients
 * on T that best fit the pulled-back functions at the samples; corrects the samples' quadrature error,
 * which the weighted sum leaves at high frequencies; G's Cholesky factor is made once at kmax and its
 * leading blocks serve every size; a G that is not positive definite falls back to the weighted sum).
 * Its cost per iteration scales with the samples, not the vertices. With every vertex its own sample
 * (sub = 0..n−1 in order, w_T = M_T), lstsq 0 and polish 0 it is ss_zoomout bit for bit
 * (tests/test_fmap.c).
 *
 * Inputs:
 *   n_S, n_T, evecs_S, evecs_T, k0, C0, kmax, step  as ss_zoomout
 *   smp      the samples and options (above)
 * Outputs:
 *   map      n_T source vertices (T -> S; caller-allocated)
 *   C_out    (may be NULL) the final kmax x kmax map
 * Errors: SS_ERR_INVALID on bad sizes, samples out of range, bad polish / lstsq or polish > 0 without
 *   M_T; SS_ERR_NOMEM.
 */
SS_API ss_status ss_zoomout_sampled(int n_S, int n_T, const double *evecs_S, const double *evecs_T, int k0,
                                    const double *C0, int kmax, int step, const ss_zoomout_sample *smp, int *map,
                                    double *C_out, ss_error *err);

/* Samples for ss_zoomout_sampled: ns vertices of m by Euclidean farthest-point sampling from
 * vertex 0 (sub[0] = 0), each vertex's nearest sample in R³ (ties to the earlier sample) and each
 * sample's weight w = Σ M over the vertices nearest to it (its Voronoi area).
 *
 * Inputs:
 *   m        the mesh, n = m->nv vertices
 *   M        (may be NULL, with w NULL) n lumped masses
 *   ns       number of samples, 1 <= ns <= n
 * Outputs:
 *   sub      ns sample vertices (caller-allocated)
 *   w        (may be NULL) ns weights
 *   near     n entries: each vertex's nearest sample (index into sub)
 * Errors: SS_ERR_INVALID on bad arguments; SS_ERR_NOMEM.
 */
SS_API ss_status ss_zoomout_samples(const ss_mesh *m, const double *M, int ns, int *sub, double *w, int *near,
                                    ss_error *err);

/* An unsupervised energy of a point map π : T -> S, no ground truth: with C the functional map of π
 * at size K (ss_fmap_from_p2p) and C_k its leading k x k block,
 *   E_orth = mean over k = k0, k0+step, …, K of ‖C_kᵀ C_k − I_k‖²_F / k
 * (ZoomOut's energy: the pull-back of an area-preserving bijection is orthonormal at every size), and
 *   E_lap = Σ_ij C_ij² (λ_T,i − λ_S,j)² / Σ_ij C_ij² (λ_T,i² + λ_S,j²)
 * (scale-free Laplacian commutativity: an isometry maps eigenfunctions to eigenfunctions of the same
 * eigenvalue); E = E_orth + w_lap · E_lap.
 *
 * Inputs:
 *   n_S, n_T vertices of source and target
 *   evals_S, evals_T, evecs_S, evecs_T  >= K eigenpairs of each (evecs column-major, n x >= K)
 *   M_T      n_T lumped masses of the target
 *   map      n_T source vertices in [0, n_S)
 *   k0, K, step  the sizes (1 <= k0 <= K, step >= 1)
 *   w_lap    weight of E_lap
 * Outputs:
 *   E        the energy
 *   E_orth, E_lap  (may be NULL) the two terms
 * Errors: SS_ERR_INVALID on bad sizes or a map entry out of range; SS_ERR_NOMEM.
 */
SS_API ss_status ss_p2p_energy(int n_S, int n_T, const double *evals_S, const double *evals_T, const double *evecs_S,
                               const double *evecs_T, const double *M_T, const int *map, int k0, int K, int step,
                               double w_lap, double *E, double *E_orth, double *E_lap, ss_error *err);

/* Descriptor preservation of a point map π : T -> S, no ground truth: the probes of both shapes
 * synthesised in their bases, F = Φ A, and
 *   E = Σ_t M_T(t) ‖F_T(t) − F_S(π(t))‖² / Σ_t M_T(t) ‖F_T(t)‖².
 * Unlike the orthonormality energy it sees a left–right flip (the landmark probes break the symmetry).
 *
 * Inputs:
 *   n_S, n_T vertices of source and target
 *   evecs_S, evecs_T  column-major, n x (>= S->k / T->k)
 *   M_T      n_T lumped masses of the target
 *   S, T     probes of both shapes with the same columns (e.g. ss_fmap_base_probes')
 *   map      n_T source vertices in [0, n_S)
 * Outputs:
 *   E        the residual
 * Errors: SS_ERR_INVALID on bad arguments or a map entry out of range; SS_ERR_NOMEM.
 */
SS_API ss_status ss_p2p_descr_residual(int n_S, int n_T, const double *evecs_S, const double *evecs_T, const double *M_T,
                                       const ss_fmap_probes *S, const ss_fmap_probes *T, const int *map, double *E,
                                       ss_error *err);

/* ----------------------------------------------------------- pipeline (fmap_match.c) */

/* Shape-only parts of the base probes, computed once per shape (defined below). */
typedef struct ss_fmap_probe_cache ss_fmap_probe_cache;

/* One shape as the matcher sees it: its mesh (for the area), lumped masses (M; NULL = barycentric
 * masses of the mesh, as ss_mesh_eigs uses) and eigenpairs (kev of them, evecs nv x kev). descr (may be
 * NULL with ndescr = 0): the caller's own descriptors, nv x ndescr column-major (e.g. `specseg
 * descriptors`, or any per-vertex features), column j corresponding to column j of the other shape's;
 * they join the base probes (ss_fmap_base_probes) as they are, each normalised in L²(M). Everything
 * is borrowed.
 */
typedef struct ss_fmap_shape {
  const ss_mesh *mesh;
  const double *M;
  const double *evals;
  const double *evecs;
  int kev;
  const double *descr;
  int ndescr;
  /* Optional (NULL / 0): shape-only parts of the base probes computed once
   * (ss_fmap_probe_cache_compute, from this shape's M, evals and evecs); ss_fmap_base_probes reads an
   * entry whose options match instead of computing it, with the same result (the same bits with a
   * single-threaded BLAS, as the CLI runs it; a multithreaded OpenBLAS splits the products by
   * columns, and may round the last bit differently). */
  const ss_fmap_probe_cache *cache;
  int ncache;
} ss_fmap_shape;

/* What ss_fmap_base_probes computes from the shape alone, at one option set: the WKS columns
 * (normalised in L²(M)) with their coefficients A, packed multiplication operators P and, with the
 * orientation term, orientation operators O (all at unit area, as in the base probes); and the
 * triple products T[(a, b), l] = Σ_x M_x φ_a φ_b φ_l (a <= b < k packed as in
 * ss_fmap_mult_operators_packed, l < kt), the operator of every wave-filtered landmark probe being
 * the combination of T's columns by its spectral coefficients. Either part may be absent (nwks 0,
 * T NULL). Used when k, the descriptor basis kd (of A, P, O), n_energies, sigma_factor and
 * descr_step match and kt >= the call's kd; the orientation operators when present. */
struct ss_fmap_probe_cache {
  int k, kd, n_energies, descr_step;
  double sigma_factor;
  int nwks;
  double *A, *P, *O; /* k x nwks, k(k+1)/2 x nwks, k² x nwks (O NULL: none) */
  int kt;
  double *T;         /* k(k+1)/2 x kt (NULL: none) */
};


typedef enum ss_probe_filter {
  SS_PROBE_RAW = 0, /* extra probe functions used as they are (ASA) */
  SS_PROBE_WAVE = 1 /* extra probe functions filtered by the WKS energy filters (DIFF) */
} ss_probe_filter;

/* Options of the functional-map pipeline ss_fmap_match (start from ss_fmap_match_default_options). */
typedef struct ss_fmap_match_options {
  int k;               /* basis size on both shapes (default 50) */
  int n_energies;      /* WKS energies (default 100) */
  double sigma_factor; /* WKS σ in energy spacings (default 7) */
  int descr_step;      /* keep every descr_step-th descriptor column (default 5, as pyFM) */
  double w_descr;      /* weights of Eq. (1): data term (default 30; pyFM uses 0.1), */
  double w_lap;        /*   Laplacian commutativity (default 1e-3, divided by Σ (λ_T,i − λ_S,j)² so that it */
  double w_dcomm;      /*   is scale free, as pyFM), descriptor commutativity (default 1) */
  int fix_constant;    /* default 1 */
  int zoomout_kmax;    /* 0 = no ZoomOut (default); else refine up to this size (>= k) */
  int zoomout_step;    /* default 1 */
  /* The extra (segment) probe block: its data-term weight relative to w_descr (default 0.5), and
   * whether its multiplication operators also enter the commutativity term (default 0: the segments'
   * boundaries differ between shapes, so their products constrain C with the wrong supports). How
   * the defaults were chosen: docs/tuning.md. */
  double w_extra;
  int extra_dcomm;
  /* Eigenpairs the probe functions (WKS, landmark wave kernels, wave-filtered extras) are computed
   * from, independently of the basis size k in which Eq. (1) is solved: the probes are synthesised
   * from the first descr_k eigenpairs, then projected onto the first k. 0 = k (NO17 and the paper:
   * what specseg eval's Table 1 uses). Must be 0 or >= k; the shapes need that many eigenpairs. */
  int descr_k;
  /* ZoomOut on this many vertex samples of the target (X; ss_zoomout_samples), their images among
   * every vertex of the other shape (ss_zoomout_sampled with the least-squares up-sampling and one
   * iteration on every vertex at the end); 0 (default) or at least X's vertex count: on every vertex
   * (ss_zoomout). */
  int zoomout_samples;
  /* 1: no WKS columns among the base probes, so the shapes' own descriptors (ss_fmap_shape.descr)
   * replace them; default 0 (WKS, then the shapes' descriptors, if any) */
  int no_wks;
  /* Weight (0..1e6) of the orientation term (ss_fmap_weights.w_orient) over the orientation operators of the
   * WKS probes (with no_wks: of the first of the shape's own descriptors, as many as the WKS columns
   * they replace); 0 (default, the paper's Eq. (1)): none computed. Each mesh is taken wound
   * outward (consistently per component, positive signed volume). */
  double w_orient;
} ss_fmap_match_options;

/* The probe-cache entry (ss_fmap_probe_cache) of options opts on shape s: the WKS columns (with
 * orientation operators when opts->w_orient > 0) and, with_triple, the triple products T.
 *
 * Inputs:
 *   s        the shape (its own cache ignored)
 *   opts     options (NULL: defaults from ss_fmap_match_default_options)
 *   with_triple  1: compute T
 *   kt_max   T's kt (>= the descriptor basis; 0: that basis)
 * Outputs:
 *   out      zeroed first, then the entry (free with ss_fmap_probe_cache_free)
 * Errors: SS_ERR_INVALID on bad options or a shape without enough eigenpairs; SS_ERR_NOMEM.
 */
SS_API ss_status ss_fmap_probe_cache_compute(const ss_fmap_shape *s, const ss_fmap_match_options *opts, int with_triple,
                                             int kt_max, ss_fmap_probe_cache *out, ss_error *err);
/* Frees the arrays of a cache entry and zeroes it; safe on a zeroed struct.
 *
 * Inputs:
 *   c        from ss_fmap_probe_cache_compute
 */
SS_API void ss_fmap_probe_cache_free(ss_fmap_probe_cache *c);

/* Fills o with the library's defaults (k 50, 100 WKS energies, σ 7, descr_step 5, w_descr 30,
 * w_lap 1e-3, w_dcomm 1, fix_constant 1, no ZoomOut (zoomout_step 1), w_extra 0.5, the others 0).
 *
 * Outputs:
 *   o        every field written
 */
SS_API void ss_fmap_match_default_options(ss_fmap_match_options *o);

/* Base probes of one shape, as ss_fmap_match builds them: the virtual column list
 * [WKS | landmark 1 | … | landmark nl] (n_energies columns per item; without the WKS item when
 * opts->no_wks) sub-sampled by descr_step, then the shape's own s->ndescr descriptors (not
 * sub-sampled), each column normalised in L²(M); their coefficients in the first opts->k
 * eigenfunctions and, with with_operators, their packed multiplication operators scaled to unit area
 * (ss_fmap_mult_operators_packed times √area, area = Σ M: the coefficients of unit-L²(M) functions do
 * not depend on the shape's scale, the raw operators go as 1/scale, so without that factor the
 * commutativity term of Eq. (1) would weigh scale⁻² against the data term). They depend on the shape
 * and its landmarks only, so an evaluation can build them once per shape and landmark set.
 *
 * Inputs:
 *   s        the shape (kev >= max(k, descr_k) eigenpairs)
 *   nl       number of landmarks (>= 0)
 *   lm       nl vertices of s
 *   opts     options (NULL: defaults)
 *   with_operators  1: also the packed operators (and orientation operators with w_orient > 0)
 * Outputs:
 *   out      the probes (free with ss_fmap_probes_free)
 * Errors: SS_ERR_INVALID on bad options, too few eigenpairs, a landmark out of range, or no WKS, no
 *   landmark and no descriptor at all; SS_ERR_NOMEM.
 */
SS_API ss_status ss_fmap_base_probes(const ss_fmap_shape *s, int nl, const int *lm, const ss_fmap_match_options *opts,
                                     int with_operators, ss_fmap_probes *out, ss_error *err);

/* Extra probes as they follow the base probes of nl landmarks: SS_PROBE_WAVE continues the virtual
 * column list (every function filtered by the WKS energies, the same sub-sampling), SS_PROBE_RAW keeps
 * them as they are; normalised in L²(M); their operators at unit area as in ss_fmap_base_probes.
 *
 * Inputs:
 *   s        the shape
 *   nl       landmarks of the base probes they follow
 *   nextra   number of functions
 *   extra    nv x nextra, column-major
 *   filter   SS_PROBE_RAW or SS_PROBE_WAVE
 *   opts     options (NULL: defaults)
 *   with_operators  1: also the packed operators
 * Outputs:
 *   out      the probes (free with ss_fmap_probes_free)
 * Errors: SS_ERR_INVALID on bad arguments or options; SS_ERR_NOMEM.
 */
SS_API ss_status ss_fmap_extra_probes(const ss_fmap_shape *s, int nl, int nextra, const double *extra, ss_probe_filter filter,
                                      const ss_fmap_match_options *opts, int with_operators, ss_fmap_probes *out,
                                      ss_error *err);

/* The weights of Eq. (1) for the pair (source Y, target X) as ss_fmap_match uses them: opts' weights,
 * the Laplacian term made scale free (divided by Σ (λ_X,r − λ_Y,c)²), the constant column fixed to
 * ±sqrt(area_X / area_Y) with the sign that makes the first eigenvectors agree.
 *
 * Inputs:
 *   X, Y     the shapes
 *   opts     options (NULL: defaults)
 * Outputs:
 *   w        the weights
 * Errors: SS_ERR_INVALID on a shape of zero area or bad options; SS_ERR_NOMEM.
 */
SS_API ss_status ss_fmap_pair_weights(const ss_fmap_shape *X, const ss_fmap_shape *Y, const ss_fmap_match_options *opts,
                                      ss_fmap_weights *w, ss_error *err);

/* Point map (and functional map) from a solved C at size opts->k: the nearest-neighbour map, or
 * ZoomOut up to opts->zoomout_kmax (on opts->zoomout_samples samples when set).
 *
 * Inputs:
 *   X, Y     the shapes (X: the target of C's functions, the source of the point map)
 *   opts     options (NULL: defaults)
 *   Ck       k x k, column-major (functions on Y -> functions on X)
 * Outputs:
 *   map      X->mesh->nv vertices of Y
 *   C_out    (may be NULL) k x k, or zoomout_kmax² with ZoomOut
 * Errors: SS_ERR_INVALID on a NULL map or output, ZoomOut without X's masses, bad options; SS_ERR_NOMEM.
 */
SS_API ss_status ss_fmap_match_finish(const ss_fmap_shape *X, const ss_fmap_shape *Y, const ss_fmap_match_options *opts,
                                      const double *Ck, int *map, double *C_out, ss_error *err);

/* The STD / ASA / DIFF functional-map pipeline (§6): probes are the WKS descriptors of each shape
 * (unless opts->no_wks), the shapes' own descriptors, the wave-kernel maps of the landmarks, plus
 * nextra paired functions (e.g. segment indicators) used raw or wave-filtered. All descriptors are
 * normalised in L²(M) and sub-sampled by descr_step; the multiplication operators of the kept WKS and
 * landmark probes enter the commutativity term, those of the extras only with opts->extra_dcomm; the
 * extras' data term is weighted by opts->w_extra. Scale: both shapes scaled by one factor give the same
 * map (tests/test_scale.c). Shapes of different sizes are compared at their own sizes (C's constant
 * column √(area_X / area_Y), the eigenvalues of the Laplacian term as given), which suits shapes of
 * about equal area; give both at unit area (ss_shape_prep_unit_area, as ss_shape_prep holds them and
 * ss_match uses them) for a map that depends on neither size.
 *
 * Inputs:
 *   X, Y     the shapes (kev >= max(k, descr_k, zoomout_kmax); X->ndescr = Y->ndescr)
 *   nl       number of landmarks; lmX[i] on X corresponds to lmY[i] on Y
 *   nextra   number of paired extra functions; extraX nX x nextra, extraY nY x nextra (column-major)
 *   extra_filter  SS_PROBE_RAW or SS_PROBE_WAVE
 *   opts     options (NULL: defaults from ss_fmap_match_default_options)
 * Outputs:
 *   map      nX entries: map[i] = vertex of Y that is the image of vertex i of X
 *   C        (may be NULL) k x k, or zoomout_kmax² with ZoomOut: the functional map from functions on Y
 *            to functions on X (the pull-back of map)
 * Errors: SS_ERR_INVALID on missing landmarks or extras, unequal descriptor counts, a shape of zero
 *   area, bad options; SS_ERR_NUMERIC from the solve; SS_ERR_NOMEM.
 */
SS_API ss_status ss_fmap_match(const ss_fmap_shape *X, const ss_fmap_shape *Y, int nl, const int *lmX, const int *lmY,
                               int nextra, const double *extraX, const double *extraY, ss_probe_filter extra_filter,
                               const ss_fmap_match_options *opts, int *map, double *C, ss_error *err);

/* ------------------------------------------------------------- evaluation (map_error.c) */

/* Geodesic error of a point map Π : X -> Y (paper §6): e_x = d_Y(Π(x), Π_GT(x)) / √area(Y) with
 * exact geodesics (ss_geodesic_pairs: each source stops once its targets are settled, cheap for small
 * errors). With sym, the paper's "sym" variant e_x = min(d_Y(Π(x), Π_GT(x)), d_Y(Π(x), Π_GT(sym[x]))).
 *
 * Inputs:
 *   Y        the target mesh
 *   nX       vertices of X (>= 1)
 *   map      nX vertices of Y
 *   gt       (NULL: identity, needs nX <= nv(Y)) nX ground-truth images
 *   sym      (may be NULL) a left–right symmetry map of X, nX entries
 * Outputs:
 *   errors   (may be NULL) nX values e_x
 *   mean     their mean
 * Errors: SS_ERR_INVALID on an empty map, a map, ground-truth or symmetry entry out of range, a target
 *   of zero area; errors of ss_geodesic_mesh_build; SS_ERR_NOMEM.
 */
SS_API ss_status ss_map_geodesic_error(const ss_mesh *Y, int nX, const int *map, const int *gt, const int *sym,
                                       double *errors, double *mean, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
