/* The k eigenpairs of W φ = λ M φ nearest a shift σ (the k smallest for σ just below 0).
 *
 * Formulation: with M diagonal we solve the equivalent *standard* symmetric problem
 *   A y = λ y,  A = M^{-1/2} W M^{-1/2},  y = M^{1/2} φ,
 * in ARPACK's regular mode on OP = (A − σI)^{-1} = M^{1/2} (W − σM)^{-1} M^{1/2}. Compared with
 * mode 3 (bmat='G'), this needs no B-products or B-inner products in the reverse-communication loop,
 * and the Lanczos basis is Euclidean-orthonormal, so φ = M^{-1/2} y is M-orthonormal for free.
 * (W − σM) is factored once with CHOLMOD (simplicial LDLᵀ).
 *
 * On large meshes (SS_EIGS_AUTO: from SS_EIGS_BLOCK_MIN_N vertices and 32 pairs) the same operator
 * is iterated by thick-restart block Lanczos instead (eigs_block.c) on a supernodal LLᵀ factor, and
 * below that by Lanczos with partial reorthogonalisation (eigs_pro.c), ARPACK being the fallback of
 * both: everything below (null pairs, completeness, Ritz post-processing) is shared.
 *
 * Ritz vectors: instead of dseupd (which applies Householder reflectors column by column), we take
 * the final ncv x ncv Lanczos tridiagonal T from ARPACK's workspace, diagonalise it with LAPACK and
 * form Y = V S with one dgemm. Eigenvalues are then Rayleigh quotients φᵀWφ/φᵀMφ (error ~ residual²).
 * M-orthonormality is checked and restored by a Cholesky step if the basis lost orthogonality. */
#include "specseg/spectrum.h"

#include <arpack/arpack.h>
#include <cblas.h>
#include <lapacke.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ARPACK is not reentrant (Fortran SAVE variables): one dsaupd/dseupd run at a time per process. */
static pthread_mutex_t arpack_lock = PTHREAD_MUTEX_INITIALIZER;

#include "specseg/laplacian.h"
#include "spectrum/eigs_internal.h"

void ss_eigs_default_options(ss_eigs_options *o) {
  o->sigma = -1e-8;
  o->tol = 1e-10;
  o->ncv = 0;
  o->maxiter = 0;
  o->stats = NULL;
  o->method = SS_EIGS_AUTO;
  o->block = 0;
}

static const char *arpack_info_msg(int info) {
  switch (info) {
    case 1: return "maximum number of restarts reached before convergence (increase maxiter)";
    case 3: return "no shifts could be applied during a restart (increase ncv)";
    case -1: return "N must be positive";
    case -2: return "NEV must be positive";
    case -3: return "NCV must satisfy NEV < NCV <= N";
    case -4: return "maximum number of iterations must be positive";
    case -5: return "WHICH is invalid";
    case -6: return "BMAT is invalid";
    case -7: return "workspace too small";
    case -8: return "error in the tridiagonal eigenvalue computation";
    case -9: return "starting vector is zero";
    case -10: return "invalid mode";
    case -11: return "mode and BMAT are incompatible";
    case -12: return "ISHIFT is invalid";
    case -13: return "NEV and WHICH are incompatible";
    case -9999: return "could not build an Arnoldi/Lanczos factorisation";
    default: return "unknown error";
  }
}

/* Deterministic start vector: a fixed-seed xorshift sequence, uniform in [-1, 1). Not a constant:
 * a symmetric start vector would miss parts of degenerate eigenspaces. */
void ssi_eigs_start_vector(double *r, int n, uint64_t seed) {
  uint64_t s = 0x9E3779B97F4A7C15ull ^ (seed * 0xD1B54A32D192ED03ull);
  for (int i = 0; i < n; i++) {
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    r[i] = (double)(s >> 11) * (2.0 / 9007199254740992.0) - 1.0;
  }
}

static ss_status validate(const ss_sparse *W, const double *M, int k, ss_error *err) {
  if (!W || !M) return ss_fail(err, SS_ERR_INVALID, "eigs: W and M must be given");
  if (W->nrows != W->ncols) return ss_fail(err, SS_ERR_INVALID, "eigs: W is %d x %d, not square", W->nrows, W->ncols);
  int n = W->ncols;
  if (n < 2) return ss_fail(err, SS_ERR_INVALID, "eigs: need at least 2 vertices, got %d", n);
  if (k < 1 || k >= n)
    return ss_fail(err, SS_ERR_INVALID, "eigs: k = %d must satisfy 1 <= k < n = %d", k, n);
  for (int i = 0; i < n; i++)
    if (!(M[i] > 0) || !isfinite(M[i]))
      return ss_fail(err, SS_ERR_INVALID,
                     "eigs: mass of vertex %d is %g; all masses must be positive and finite: a vertex no face uses "
                     "(unreferenced) or only zero-area faces use has none; drop such vertices first "
                     "(ss_mesh_sanitize does)",
                     i, M[i]);
  return SS_OK;
}

/* Columns of WΦ (n x k, column-major). */
static void sparse_times_dense(const ss_sparse *W, const double *X, double *Y, int k) {
  size_t n = (size_t)W->nrows;
#pragma omp parallel for schedule(static)
  for (int j = 0; j < k; j++) ss_sparse_matvec(W, X + n * (size_t)j, Y + n * (size_t)j);
}

ss_status ss_eigs_check(const ss_sparse *W, const double *M, int k, const double *evals, const double *evecs,
                        double *max_rel_residual, double *max_orth_error, ss_error *err) {
  ss_status st = validate(W, M, k, err);
  if (st) return st;
  size_t n = (size_t)W->nrows;
  double *WX = malloc(sizeof(double) * n * (size_t)k);
  double *Y = malloc(sizeof(double) * n * (size_t)k);
  double *G = malloc(sizeof(double) * (size_t)k * (size_t)k);
  if (!WX || !Y || !G) {
    free(WX); free(Y); free(G);
    return ss_fail(err, SS_ERR_NOMEM, "eigs: out of memory");
  }
  sparse_times_dense(W, evecs, WX, k);
  double worst = 0;
  for (int j = 0; j < k; j++) {
    const double *x = evecs + n * (size_t)j, *wx = WX + n * (size_t)j;
    double r2 = 0, m2 = 0;
    for (size_t i = 0; i < n; i++) {
      double mx = M[i] * x[i], r = wx[i] - evals[j] * mx;
      r2 += r * r;
      m2 += mx * mx;
    }
    double rel = sqrt(r2) / ((fabs(evals[j]) + 1) * sqrt(m2));
    if (!(rel <= worst)) worst = rel; /* NaN propagates */
  }
  for (size_t j = 0; j < (size_t)k; j++)
    for (size_t i = 0; i < n; i++) Y[i + n * j] = sqrt(M[i]) * evecs[i + n * j];
  cblas_dsyrk(CblasColMajor, CblasUpper, CblasTrans, k, (int)n, 1.0, Y, (int)n, 0.0, G, k);
  double orth = 0;
  for (int j = 0; j < k; j++)
    for (int i = 0; i <= j; i++) {
      double e = fabs(G[i + (size_t)k * j] - (i == j ? 1.0 : 0.0));
      if (!(e <= orth)) orth = e;
    }
  if (max_rel_residual) *max_rel_residual = worst;
  if (max_orth_error) *max_orth_error = orth;
  free(WX); free(Y); free(G);
  return SS_OK;
}

typedef struct {
  double nu;
  int idx;
} ritz_pair;

static int by_magnitude_desc(const void *a, const void *b) {
  double x = fabs(((const ritz_pair *)a)->nu), y = fabs(((const ritz_pair *)b)->nu);
  return (x < y) - (x > y);
}

typedef struct {
  double lambda;
  int col;
} eig_pair;

static int by_lambda_asc(const void *a, const void *b) {
  double x = ((const eig_pair *)a)->lambda, y = ((const eig_pair *)b)->lambda;
  if (x < y) return -1;
  if (x > y) return 1;
  return ((const eig_pair *)a)->col - ((const eig_pair *)b)->col;
}

/* Connected components of W's graph (nonzero off-diagonal entries) on which W annihilates the
 * constant vector (all row sums ~0, as for any Laplacian): each gives an exact eigenpair λ = 0.
 * label[i] = component index (0.., numbered by smallest vertex) or -1 when not such a component.
 * Returns the number of such components, or -1 on allocation failure. */
static int null_components(const ss_sparse *W, int *label) {
  int n = W->ncols;
  int *parent = malloc(sizeof(int) * (size_t)n);
  int *id = malloc(sizeof(int) * (size_t)n);
  char *ok = malloc((size_t)n);
  if (!parent || !id || !ok) { free(parent); free(id); free(ok); return -1; }
  for (int i = 0; i < n; i++) parent[i] = i;
  for (int j = 0; j < n; j++)
    for (int p = W->colptr[j]; p < W->colptr[j + 1]; p++) {
      int i = W->rowind[p];
      if (i == j || W->val[p] == 0) continue;
      int a = i, b = j;
      while (parent[a] != a) a = parent[a] = parent[parent[a]];
      while (parent[b] != b) b = parent[b] = parent[parent[b]];
      if (a != b) { if (a < b) parent[b] = a; else parent[a] = b; }
    }
  int nc = 0;
  for (int i = 0; i < n; i++) {
    int r = i;
    while (parent[r] != r) r = parent[r];
    parent[i] = r;
    if (r == i) { id[i] = nc; ok[nc] = 1; nc++; }
    label[i] = id[r];
  }
  /* W symmetric: column sums are row sums */
  for (int j = 0; j < n; j++) {
    double sum = 0, mag = 0;
    for (int p = W->colptr[j]; p < W->colptr[j + 1]; p++) { sum += W->val[p]; mag += fabs(W->val[p]); }
    if (!(fabs(sum) <= 1e-12 * mag)) ok[label[j]] = 0;
  }
  int nk = 0;
  for (int c = 0; c < nc; c++) id[c] = ok[c] ? nk++ : -1;
  for (int i = 0; i < n; i++) label[i] = id[label[i]];
  free(parent); free(id); free(ok);
  return nk;
}

/* x ← P x, P = I − Σ_c y_c y_cᵀ with y_c = M^{1/2} 1_c / ‖M^{1/2} 1_c‖ (mass[c] = Σ_{i∈c} M_i). */
static void project_out(double *x, int n, const int *label, const double *sqm, const double *mass, double *acc,
                        int nc) {
  if (nc == 1) { /* one component (the usual case): the same sums without the scatter */
    double a = 0;
    for (int i = 0; i < n; i++)
      if (label[i] >= 0) a += sqm[i] * x[i];
    a /= mass[0];
    for (int i = 0; i < n; i++)
      if (label[i] >= 0) x[i] -= sqm[i] * a;
    return;
  }
  memset(acc, 0, sizeof(double) * (size_t)nc);
  for (int i = 0; i < n; i++)
    if (label[i] >= 0) acc[label[i]] += sqm[i] * x[i];
  for (int c = 0; c < nc; c++) acc[c] /= mass[c];
  for (int i = 0; i < n; i++)
    if (label[i] >= 0) x[i] -= sqm[i] * acc[label[i]];
}

void ssi_eigs_project(ssi_lanczos_ctx *c, double *x) {
  if (c->nnull) project_out(x, c->n, c->label, c->sqm, c->mass, c->acc, c->nnull);
  for (int pass = 0; pass < (c->ndefl ? 2 : 0); pass++) {
    cblas_dgemv(CblasColMajor, CblasTrans, c->n, c->ndefl, 1.0, c->defl, c->n, x, 1, 0.0, c->coef, 1);
    cblas_dgemv(CblasColMajor, CblasNoTrans, c->n, c->ndefl, -1.0, c->defl, c->n, c->coef, 1, 1.0, x, 1);
  }
}

ss_status ssi_eigs_apply_op(ssi_lanczos_ctx *c, const double *x, double *y, ss_error *err) {
  const int n = c->n;
  memcpy(y, x, sizeof(double) * (size_t)n);
  ssi_eigs_project(c, y);
  for (int i = 0; i < n; i++) y[i] *= c->sqm[i];
  double ts = ss_time();
  ss_status st = ssi_chol_solve(c->chol, y, y, 1, err);
  c->tsolve += ss_time() - ts;
  c->nops++;
  if (st) return st;
  const double s = c->opscale; /* a power of two: sqm·s is exact */
  for (int i = 0; i < n; i++) y[i] *= c->sqm[i] * s;
  ssi_eigs_project(c, y);
  return SS_OK;
}

/* The reverse-communication loop of dsaupd: OP y = M^-1/2 (W - σM)^-1 M^-1/2 x on the projected space. */
static ss_status arpack_iterate(ssi_lanczos_ctx *c, int nev, int ncv, double *resid, double *V, a_int *iparam,
                                a_int *ipntr, double *workd, double *workl, int lworkl, a_int *info,
                                ss_error *err) {
  const int n = c->n;
  a_int ido = 0;
  for (;;) {
    dsaupd_c(&ido, "I", n, "LM", nev, c->tol, resid, ncv, V, n, iparam, ipntr, workd, workl, lworkl, info);
    if (ido != -1 && ido != 1) return SS_OK;
    ss_status st = ssi_eigs_apply_op(c, workd + ipntr[0] - 1, workd + ipntr[1] - 1, err);
    if (st) return st;
  }
}

/* The nev eigenpairs of OP of largest |ν| with ARPACK: Y (n x nev, scaled space, orthonormal) and
 * lam (λ = σ + 1/ν), both ordered by ascending λ. */
static ss_status arpack_run(ssi_lanczos_ctx *c, int nev, uint64_t seed, double *Y, double *lam, ss_error *err) {
  const int n = c->n;
  const size_t nn = (size_t)n;
  int room = n - c->nnull - c->ndefl; /* dimension of the space OP acts on */
  if (nev < 1) return ss_fail(err, SS_ERR_NUMERIC, "eigs: asked for %d eigenpairs", nev);
  if (nev >= room) /* every vertex but one is an eigenpair already: only ever reached for k ~ n */
    return ss_fail(err, SS_ERR_NUMERIC,
                   "eigs: k = %d is too close to the number of vertices (%d): %d eigenpair%s still to be found in a "
                   "space of dimension %d; use k <= %d, which leaves the Lanczos solver the room it needs",
                   c->k, n, nev, nev == 1 ? " is" : "s are", room, c->nnull + (n - c->nnull - 1) / 2);
  int ncv = c->ncv_opt ? c->ncv_opt : (2 * nev + 1 > 20 ? 2 * nev + 1 : 20);
  if (ncv > room) ncv = room;
  if (ncv <= nev) ncv = nev + 1;
  int lworkl = ncv * (ncv + 8);
  double *resid = malloc(sizeof(double) * nn);
  double *V = malloc(sizeof(double) * nn * (size_t)ncv);
  double *workd = malloc(sizeof(double) * 3 * nn);
  double *workl = malloc(sizeof(double) * (size_t)lworkl);
  double *T = malloc(sizeof(double) * ((size_t)ncv * ncv + 3 * (size_t)ncv));
  double *S = malloc(sizeof(double) * (size_t)ncv * (size_t)nev);
  ritz_pair *rp = malloc(sizeof(ritz_pair) * (size_t)ncv);
  eig_pair *ep = malloc(sizeof(eig_pair) * (size_t)nev);
  int *isupp = malloc(sizeof(int) * 2 * (size_t)ncv);
  ss_status st = SS_OK;
  if (!resid || !V || !workd || !workl || !T || !S || !rp || !ep || !isupp) {
    st = ss_fail(err, SS_ERR_NOMEM, "eigs: out of memory (n = %d, ncv = %d)", n, ncv);
    goto out;
  }
  /* ARPACK reverse communication: regular mode, standard problem, wanted = largest |ν| of OP */
  a_int iparam[11] = {0}, ipntr[14] = {0};
  iparam[0] = 1; /* exact shifts */
  iparam[2] = c->maxiter;
  iparam[6] = 1; /* mode 1: OP applied by us */
  a_int info = 1;
  ssi_eigs_start_vector(resid, n, seed);
  ssi_eigs_project(c, resid);
  /* ARPACK's Fortran core keeps SAVEd state between reverse-communication calls, so one run must not
   * interleave with another: serialise whole runs across OpenMP threads (the factorisation, the
   * Ritz vectors and everything else stay parallel). */
  pthread_mutex_lock(&arpack_lock);
  st = arpack_iterate(c, nev, ncv, resid, V, iparam, ipntr, workd, workl, lworkl, &info, err);
  pthread_mutex_unlock(&arpack_lock);
  if (st) goto out;
  if (info < 0) {
    st = ss_fail(err, SS_ERR_NUMERIC, "eigs: ARPACK dsaupd failed (info %d: %s)", (int)info, arpack_info_msg((int)info));
    goto out;
  }
  if (iparam[4] < nev) {
    /* the usual cause: k so close to n that the Krylov space could not get its ~2k vectors */
    int k = c->k, kmax = c->nnull + (n - c->nnull - 1) / 2;
    if (!c->ncv_opt && 2 * nev + 1 > room)
      st = ss_fail(err, SS_ERR_NUMERIC,
                   "eigs: k = %d is too close to the number of vertices (%d): the Lanczos solver (ARPACK) needs room "
                   "for about 2k basis vectors and converged only %d of the %d pairs asked (ARPACK info %d); use k "
                   "<= %d, which leaves it that room",
                   k, n, (int)iparam[4], nev, (int)info, kmax);
    else
      st = ss_fail(err, SS_ERR_NUMERIC, "eigs: ARPACK converged %d of %d eigenpairs (info %d: %s)", (int)iparam[4], nev,
                   (int)info, info ? arpack_info_msg((int)info) : "no convergence");
    goto out;
  }
  /* Final Lanczos factorisation OP V = V T + f e_ncvᵀ: T's diagonal and subdiagonal sit in workl at
   * ipntr[4] (column 2 and column 1 of an ncv x 2 array, see dseupd). */
  const double *H = workl + ipntr[4] - 1;
  double *Z = T, *d = T + (size_t)ncv * ncv, *e = d + ncv, *w = e + ncv;
  for (int i = 0; i < ncv; i++) d[i] = H[ncv + i];
  for (int i = 0; i + 1 < ncv; i++) e[i] = H[1 + i];
  /* σ <= 0: OP is positive semi-definite, the wanted are the nev largest and MRRR computes just
   * those; otherwise both ends may be wanted and we take the whole spectrum of T. */
  lapack_int nfound = 0;
  int all = c->sigma > 0;
  lapack_int linfo = LAPACKE_dstevr(LAPACK_COL_MAJOR, 'V', all ? 'A' : 'I', ncv, d, e, 0.0, 0.0,
                                    all ? 0 : ncv - nev + 1, ncv, 0.0, &nfound, w, Z, ncv, isupp);
  if (linfo != 0 || nfound < nev) {
    st = ss_fail(err, SS_ERR_NUMERIC, "eigs: tridiagonal eigensolver failed (info %d)", (int)linfo);
    goto out;
  }
  for (int i = 0; i < nfound; i++) { rp[i].nu = w[i]; rp[i].idx = i; }
  qsort(rp, (size_t)nfound, sizeof *rp, by_magnitude_desc);
  for (int j = 0; j < nev; j++) {
    if (rp[j].nu == 0) {
      st = ss_fail(err, SS_ERR_NUMERIC, "eigs: zero Ritz value of the shifted inverse");
      goto out;
    }
    ep[j].lambda = c->sigma + 1.0 / (rp[j].nu / c->opscale);
    ep[j].col = rp[j].idx;
  }
  qsort(ep, (size_t)nev, sizeof *ep, by_lambda_asc);
  for (int j = 0; j < nev; j++) {
    memcpy(S + (size_t)ncv * j, Z + (size_t)ncv * ep[j].col, sizeof(double) * (size_t)ncv);
    lam[j] = ep[j].lambda;
  }
  /* Ritz vectors Y = V S with one dgemm */
  cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n, nev, ncv, 1.0, V, n, S, ncv, 0.0, Y, n);
out:
  free(resid); free(V); free(workd); free(workl); free(T); free(S); free(rp); free(ep); free(isupp);
  return st;
}

ss_status ss_eigs(const ss_sparse *W, const double *M, int k, const ss_eigs_options *opts, double *evals,
                  double *evecs, ss_error *err) {
  ss_status st = validate(W, M, k, err);
  if (st) return st;
  if (!evals) return ss_fail(err, SS_ERR_INVALID, "eigs: evals must not be NULL");
  ss_eigs_options o;
  ss_eigs_default_options(&o);
  if (opts) o = *opts;
  const int n = W->ncols;
  const size_t nn = (size_t)n;
  if (!isfinite(o.sigma)) return ss_fail(err, SS_ERR_INVALID, "eigs: sigma must be finite");
  if (!(o.tol >= 0) || !isfinite(o.tol) || o.tol >= 1)
    return ss_fail(err, SS_ERR_INVALID, "eigs: tol = %g must be in [0, 1)", o.tol);
  if (o.ncv != 0 && (o.ncv <= k || o.ncv > n))
    return ss_fail(err, SS_ERR_INVALID, "eigs: ncv = %d must satisfy k = %d < ncv <= n = %d", o.ncv, k, n);
  if (o.maxiter < 0) return ss_fail(err, SS_ERR_INVALID, "eigs: maxiter must be >= 0");
  if (o.method != SS_EIGS_AUTO && o.method != SS_EIGS_ARPACK && o.method != SS_EIGS_BLOCK && o.method != SS_EIGS_PRO)
    return ss_fail(err, SS_ERR_INVALID, "eigs: unknown method %d", o.method);
  if (o.block < 0 || o.block >= n) return ss_fail(err, SS_ERR_INVALID, "eigs: block = %d must be in [0, n)", o.block);
  /* Scale. W is invariant under a uniform scaling of the shape by s and M scales with s², so the
   * eigenvalues scale with 1/s² while an absolute shift does not: at s = 1e8 a shift of −1e-8 lies
   * 1e8 times farther below 0 than λ₂ is above it, OP = (W − σM)⁻¹ is ~ −M⁻¹/σ up to 1e-8 and the
   * low eigenvalues drown (wrong values, split multiplets). A negative shift only says "below the
   * spectrum", so its dimensionless size |σ|·area is kept in [1e-10, 1e-3]: inside that band (every
   * FAUST and TOSCA shape: 1.6e-8 ... 7.1e-4 with the default) σ is used as given, bit for bit;
   * outside it the nearer end of the band is used, which makes the computation covariant under
   * scaling (the same dimensionless problem at every scale). */
  double sigma = o.sigma;
  if (sigma < 0) {
    double area = 0;
    for (int i = 0; i < n; i++) area += M[i];
    const double lo = 1e-10, hi = 1e-3;
    if (isfinite(area) && area > 0) {
      if (-sigma * area > hi) sigma = -hi / area;
      else if (-sigma * area < lo) sigma = -lo / area;
    }
  }
  /* The operator's eigenvalues 1/(λ − σ) have the dimension of an area. ARPACK's convergence test
   * is relative only above eps^(2/3) ~ 4e-11 (dsconv: tol · max(eps23, |ritz|)), so on a shape of
   * area 1e-20 every Ritz value looks converged at once. Outside the everyday range of areas the
   * operator is applied times a power of two near 1/area (exact: no rounding is added), which
   * makes the Lanczos process the same at every scale; inside it (FAUST, TOSCA) nothing changes. */
  double opscale = 1;
  {
    double area = 0;
    for (int i = 0; i < n; i++) area += M[i];
    if (isfinite(area) && area > 0 && (area < 1e-3 || area > 1e6)) {
      int e2;
      frexp(area, &e2);
      opscale = ldexp(1.0, -e2);
    }
  }
  /* passed by value to ARPACK's C binding, where 0 does not mean machine precision: be explicit */
  double tol = o.tol > 0 ? o.tol : DBL_EPSILON;
  int maxiter = o.maxiter > 0 ? o.maxiter : 1000;

  double *sqm = malloc(sizeof(double) * nn);
  int *label = malloc(sizeof(int) * nn);
  double *X = evecs ? evecs : malloc(sizeof(double) * nn * (size_t)k);
  double *mass = NULL, *acc = NULL, *lam = NULL;
  double *WX = NULL, *G = NULL;
  ssi_chol *chol = NULL;
  if (!sqm || !label || !X) { st = ss_fail(err, SS_ERR_NOMEM, "eigs: out of memory (n = %d)", n); goto done; }
  for (size_t i = 0; i < nn; i++) sqm[i] = sqrt(M[i]);

  /* Deflation. With σ just below 0, OP's largest eigenvalue is 1/|σ| ~ 1e8 and every Lanczos step
   * carries errors of eps·‖OP‖ into the other pairs (residuals ~1e-9 on unit spheres). The λ = 0
   * pairs are known exactly (constants per component), so for σ <= 0 we project them out of OP and
   * ask ARPACK only for the remaining k − c pairs. */
  int nnull = 0;
  if (sigma <= 0) {
    nnull = null_components(W, label);
    if (nnull < 0) { st = ss_fail(err, SS_ERR_NOMEM, "eigs: out of memory"); goto done; }
  }
  int c0 = nnull < k ? nnull : k; /* null pairs reported */
  int kk = k - c0;                /* pairs asked from ARPACK */
  mass = calloc((size_t)(nnull > 0 ? nnull : 1), sizeof(double));
  acc = malloc(sizeof(double) * (size_t)(nnull > 0 ? nnull : 1));
  if (!mass || !acc) { st = ss_fail(err, SS_ERR_NOMEM, "eigs: out of memory"); goto done; }
  if (nnull > 0)
    for (int i = 0; i < n; i++)
      if (label[i] >= 0) mass[label[i]] += M[i];
  for (int c = 0; c < c0; c++) {
    double *y = X + nn * (size_t)c, s = 1.0 / sqrt(mass[c]);
    for (int i = 0; i < n; i++) y[i] = label[i] == c ? sqm[i] * s : 0.0;
  }

  double tt0 = ss_time(), tt1 = tt0, tt2 = tt0;
  ssi_lanczos_ctx lc = {NULL, sqm, mass, label, acc, n, nnull, NULL, 0, NULL, sigma, tol, opscale, maxiter, o.ncv,
                        0, 0.0, 0, 0, 0, W, M, k};
  int recovered = 0, method = 0;
  if (kk > 0) {
    lam = malloc(sizeof(double) * (size_t)k);
    if (!lam) { st = ss_fail(err, SS_ERR_NOMEM, "eigs: out of memory"); goto done; }
    /* block Lanczos: where chosen, for σ <= 0 and room for its basis; mmax basis columns of blocks
     * of b (defaults measured at 110k vertices, k = 100: bench_eigs) */
    int b = o.block ? o.block : 8;
    if (b > kk) b = kk;
    int mmax = o.ncv ? o.ncv : 2 * kk + 6 * b;
    /* a restart keeps about kk + (mmax − kk)/2 columns: below kk + 4b it adds one block or none and
     * the method crawls (ncv = k + 20 at k = 100: 1,000 restarts, 10 s, no convergence) */
    if (mmax < kk + 4 * b) mmax = kk + 4 * b;
    int room = n - nnull;
    int use_block = o.method == SS_EIGS_BLOCK || (o.method == SS_EIGS_AUTO && n >= SS_EIGS_BLOCK_MIN_N && kk >= 32);
    if (sigma > 0 || mmax + b > room) use_block = 0;
    if (use_block) {
      ss_error ferr;
      if (ssi_chol_factor_super(W, -sigma, M, &chol, &ferr) != SS_OK) use_block = 0; /* not definite: LDLᵀ */
    }
    if (!use_block) st = ssi_chol_factor(W, -sigma, M, &chol, err);
    tt1 = ss_time();
    if (st) goto done;
    lc.chol = chol;
    int pro_done = 0;
    if (use_block) st = ssi_eigs_block_lanczos(&lc, kk, b, mmax, 0, X + nn * (size_t)c0, lam, err);
    else {
      /* partial reorthogonalisation first where it applies; ARPACK when its basis did not suffice */
      /* (ncv is ARPACK's Krylov size: given, AUTO runs ARPACK) */
      const int pro = sigma <= 0 && (o.method == SS_EIGS_PRO || (o.method == SS_EIGS_AUTO && kk <= SS_EIGS_PRO_MAX_K && !o.ncv));
      /* no restarts: room for the ~2.5k steps FAUST took at k = 50-110, and more (spheres: 3.8k) */
      int pmax = kk + (4 * kk < 2 * kk + 200 ? 4 * kk : 2 * kk + 200);
      if (pmax < kk + 100) pmax = kk + 100;
      if (pmax > room - 1) pmax = room - 1;
      if (pro) st = ssi_eigs_pro_lanczos(&lc, kk, pmax, 0, X + nn * (size_t)c0, lam, &pro_done, err);
      if (!st && !pro_done) st = arpack_run(&lc, kk, 0, X + nn * (size_t)c0, lam, err);
    }
    if (st) goto done;
    method = use_block ? SS_EIGS_BLOCK : pro_done ? SS_EIGS_PRO : SS_EIGS_ARPACK;
    tt2 = ss_time();
    /* Completeness. Lanczos from one start vector sees a single direction of each exactly degenerate
     * eigenspace (symmetric shapes: spheres, tori) and can converge to a later eigenvalue instead of
     * a second copy. Sylvester's inertia of W − τM, τ just below the largest computed λ, counts the
     * eigenvalues below τ; if we hold fewer, the missing ones are computed with everything found so
     * far deflated, and the k smallest of the union kept. */
    for (int attempt = 0; sigma <= 0 && attempt < 8; attempt++) {
      double top = lam[kk - 1];
      if (!(top > 0)) break;
      double tau = top * (1 - 1e-6);
      int below = 0, have = c0;
      ss_error ierr;
      if (ssi_chol_inertia(chol, W, -tau, M, &below, &ierr) != SS_OK) break; /* cannot check: keep ARPACK's */
      for (int j = 0; j < kk; j++) have += lam[j] < tau;
      if (below <= have) break;
      int miss = below - have;
      double *Xn = malloc(sizeof(double) * nn * (size_t)miss), *ln = malloc(sizeof(double) * (size_t)miss);
      double *all = malloc(sizeof(double) * nn * (size_t)(kk + miss)), *la = malloc(sizeof(double) * (size_t)(kk + miss));
      double *coef = malloc(sizeof(double) * (size_t)kk);
      eig_pair *mp = malloc(sizeof(eig_pair) * (size_t)(kk + miss));
      if (!Xn || !ln || !all || !la || !coef || !mp) {
        free(Xn); free(ln); free(all); free(la); free(coef); free(mp);
        st = ss_fail(err, SS_ERR_NOMEM, "eigs: out of memory");
        goto done;
      }
      lc.defl = X + nn * (size_t)c0;
      lc.ndefl = kk;
      lc.coef = coef;
      st = arpack_run(&lc, miss, (uint64_t)attempt + 1, Xn, ln, err);
      lc.defl = NULL;
      lc.ndefl = 0;
      if (!st) {
        memcpy(all, X + nn * (size_t)c0, sizeof(double) * nn * (size_t)kk);
        memcpy(all + nn * (size_t)kk, Xn, sizeof(double) * nn * (size_t)miss);
        memcpy(la, lam, sizeof(double) * (size_t)kk);
        memcpy(la + kk, ln, sizeof(double) * (size_t)miss);
        for (int j = 0; j < kk + miss; j++) { mp[j].lambda = la[j]; mp[j].col = j; }
        qsort(mp, (size_t)(kk + miss), sizeof *mp, by_lambda_asc);
        for (int j = 0; j < kk; j++) {
          memcpy(X + nn * (size_t)(c0 + j), all + nn * (size_t)mp[j].col, sizeof(double) * nn);
          lam[j] = mp[j].lambda;
        }
        recovered += miss;
      }
      free(Xn); free(ln); free(all); free(la); free(coef); free(mp);
      if (st) goto done;
    }
  }
  double tp0 = ss_time();
  /* M-orthonormality of Φ is Euclidean orthonormality of Y: check it (G = YᵀY) and restore it with
   * a Cholesky factor if the basis drifted. */
  G = malloc(sizeof(double) * (size_t)k * (size_t)k);
  if (!G) { st = ss_fail(err, SS_ERR_NOMEM, "eigs: out of memory"); goto done; }
  cblas_dsyrk(CblasColMajor, CblasUpper, CblasTrans, k, n, 1.0, X, n, 0.0, G, k);
  double worst = 0;
  for (int j = 0; j < k; j++)
    for (int i = 0; i <= j; i++) {
      double e = fabs(G[i + (size_t)k * j] - (i == j ? 1.0 : 0.0));
      if (!(e <= worst)) worst = e;
    }
  if (!isfinite(worst)) { st = ss_fail(err, SS_ERR_NUMERIC, "eigs: non-finite eigenvectors"); goto done; }
  if (worst > 1e-12) {
    lapack_int linfo = LAPACKE_dpotrf(LAPACK_COL_MAJOR, 'U', k, G, k);
    if (linfo != 0) {
      st = ss_fail(err, SS_ERR_NUMERIC, "eigs: computed eigenvectors are linearly dependent");
      goto done;
    }
    cblas_dtrsm(CblasColMajor, CblasRight, CblasUpper, CblasNoTrans, CblasNonUnit, n, k, 1.0, G, k, X, n);
  }
  for (size_t j = 0; j < (size_t)k; j++) {
    double *x = X + nn * j;
    for (size_t i = 0; i < nn; i++) x[i] /= sqm[i];
  }
  double tp1 = ss_time();
  /* Rayleigh quotients: errors ~ residual², better than σ + 1/ν */
  WX = malloc(sizeof(double) * nn * (size_t)k);
  if (!WX) { st = ss_fail(err, SS_ERR_NOMEM, "eigs: out of memory"); goto done; }
  sparse_times_dense(W, X, WX, k);
  for (int j = 0; j < k; j++) {
    const double *x = X + nn * (size_t)j, *wx = WX + nn * (size_t)j;
    double num = 0, den = 0;
    for (size_t i = 0; i < nn; i++) {
      num += x[i] * wx[i];
      den += M[i] * x[i] * x[i];
    }
    evals[j] = num / den;
  }
  /* Rayleigh quotients may swap nearly equal neighbours: keep the output ascending */
  for (int j = 1; j < k; j++)
    for (int i = j; i > 0 && evals[i] < evals[i - 1]; i--) {
      double t = evals[i]; evals[i] = evals[i - 1]; evals[i - 1] = t;
      for (size_t r = 0; r < nn; r++) {
        double u = X[r + nn * i]; X[r + nn * i] = X[r + nn * (i - 1)]; X[r + nn * (i - 1)] = u;
      }
    }
  st = SS_OK;
  if (o.stats) {
    ss_eigs_stats es = {c0, chol ? ssi_chol_nnz(chol) : 0.0, tt1 - tt0, tt2 - tt1, lc.nops, lc.tsolve,
                        tp0 - tt2, recovered, tp1 - tp0, ss_time() - tp1, method, lc.block, lc.restarts};
    *o.stats = es;
  }

done:
  ssi_chol_free(chol);
  free(sqm); free(label); free(mass); free(acc); free(lam); free(WX); free(G);
  if (X != evecs) free(X);
  return st;
}

ss_status ss_mesh_eigs(const ss_mesh *m, int k, double *evals, double *evecs, ss_error *err) {
  if (!m || m->nv < 1) return ss_fail(err, SS_ERR_INVALID, "eigs: empty mesh");
  ss_sparse W = {0};
  double *M = malloc(sizeof(double) * (size_t)m->nv);
  if (!M) return ss_fail(err, SS_ERR_NOMEM, "eigs: out of memory");
  ss_status st = ss_cotan_stiffness(m, &W, err);
  if (!st) st = ss_mass_lumped(m, SS_MASS_BARYCENTRIC, M, err);
  /* a vertex without mass makes the problem singular: say why it has none */
  for (int i = 0; !st && i < m->nv; i++) {
    if (M[i] > 0) continue;
    int used = 0;
    for (size_t c = 0; c < 3 * (size_t)m->nf && !used; c++) used = m->F[c] == i;
    st = ss_fail(err, SS_ERR_INVALID,
                 used ? "eigs: vertex %d is only in zero-area faces, so it has no mass and the eigenproblem is "
                        "singular; drop degenerate faces and the vertices they leave unused first (ss_mesh_sanitize "
                        "does; `specseg info` counts them)"
                      : "eigs: vertex %d is used by no face (unreferenced), so it has no mass and the eigenproblem is "
                        "singular; drop unreferenced vertices first (ss_mesh_sanitize does; `specseg info` counts them)",
                 i);
  }
  if (!st) st = ss_eigs(&W, M, k, NULL, evals, evecs, err);
  ss_sparse_free(&W);
  free(M);
  return st;
}
