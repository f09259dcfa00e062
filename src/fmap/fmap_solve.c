/* The functional map of Eq. (1) (Nogneng & Ovsjanikov 2017), solved exactly.
 *
 * With x = vec(C) (column-major, index r + k_T·c), E(C) = xᵀ N x − 2 bᵀ x + const where
 *   N = w_d (A Aᵀ ⊗ I) + w_l diag((λ_T,r − λ_S,c)²)
 *     + w_c Σ_i [ (D_i^S)² ⊗ I + I ⊗ (D_i^T)² − 2 D_i^S ⊗ D_i^T ],   b = w_d vec(B Aᵀ)
 * (the D's are symmetric). The only expensive block, Σ_i D_i^S ⊗ D_i^T, is one dgemm of the packed
 * upper triangles of the D's, so at k = 50 with ~100–200 probes the dense assembly plus a Cholesky
 * factorisation of the 2500 x 2500 system costs a few GFlop and no iteration count depends on the
 * conditioning. On FAUST (k = 50, 120 probes) N has a condition number of ~3e3 (LAPACK dpocon), so
 * CG to a 1e-8 relative residual needs a few hundred iterations; each costs either a pass over the
 * assembled 50 MB N (memory bound, ~5–10 ms) or 4·k³·p ≈ 0.1 GFlop in operator form — both slower
 * than the one 5 GFlop, compute-bound Cholesky (0.35–0.4 s single-threaded on this loaded machine,
 * assembly included). */
#include "specseg/fmap.h"

#include <cblas.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

ss_status ss_fmap_project(int n, int k, const double *evecs, const double *M, int p, const double *F,
                          double *A, ss_error *err) {
  if (n < 1 || k < 1 || p < 0) return ss_fail(err, SS_ERR_INVALID, "project: bad sizes");
  if (p == 0) return SS_OK;
  double *MF = malloc(sizeof(double) * (size_t)n * p);
  if (!MF) return ss_fail(err, SS_ERR_NOMEM, "project: out of memory");
  for (int c = 0; c < p; c++)
    for (int x = 0; x < n; x++) MF[x + (size_t)n * c] = M[x] * F[x + (size_t)n * c];
  cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, k, p, n, 1.0, evecs, n, MF, n, 0.0, A, k);
  free(MF);
  return SS_OK;
}

static inline size_t pk(int a, int b) { /* packed upper-triangle index, a <= b */
  return (size_t)b * (b + 1) / 2 + a;
}

/* Packed D's: P (kk x p), column i = upper triangle of D_i. Vertices in blocks so the product table
 * φ_a φ_b stays small; one dgemm per block. */
static ss_status packed_operators(int n, int k, const double *evecs, const double *M, int p, const double *F,
                                  double *P, ss_error *err) {
  const int kk = k * (k + 1) / 2, nb = 512;
  double *Q = malloc(sizeof(double) * (size_t)nb * kk), *W = malloc(sizeof(double) * (size_t)nb * p);
  if (!Q || !W) { free(Q); free(W); return ss_fail(err, SS_ERR_NOMEM, "operators: out of memory"); }
  memset(P, 0, sizeof(double) * (size_t)kk * p);
  for (int x0 = 0; x0 < n; x0 += nb) {
    int m = n - x0 < nb ? n - x0 : nb;
    for (int b = 0; b < k; b++)
      for (int a = 0; a <= b; a++) {
        double *q = Q + (size_t)m * pk(a, b);
        const double *fa = evecs + (size_t)n * a + x0, *fb = evecs + (size_t)n * b + x0;
        for (int x = 0; x < m; x++) q[x] = fa[x] * fb[x];
      }
    for (int c = 0; c < p; c++)
      for (int x = 0; x < m; x++) W[x + (size_t)m * c] = M[x0 + x] * F[x0 + x + (size_t)n * c];
    cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, kk, p, m, 1.0, Q, m, W, m, 1.0, P, kk);
  }
  free(Q);
  free(W);
  return SS_OK;
}

ss_status ss_fmap_mult_operators(int n, int k, const double *evecs, const double *M, int p,
                                 const double *F, double *D, ss_error *err) {
  if (n < 1 || k < 1 || p < 0) return ss_fail(err, SS_ERR_INVALID, "operators: bad sizes");
  if (p == 0) return SS_OK;
  const int kk = k * (k + 1) / 2;
  double *P = malloc(sizeof(double) * (size_t)kk * p);
  if (!P) return ss_fail(err, SS_ERR_NOMEM, "operators: out of memory");
  ss_status st = packed_operators(n, k, evecs, M, p, F, P, err);
  if (!st)
    for (int i = 0; i < p; i++) {
      double *Di = D + (size_t)k * k * i;
      for (int b = 0; b < k; b++)
        for (int a = 0; a <= b; a++) Di[a + (size_t)k * b] = Di[b + (size_t)k * a] = P[pk(a, b) + (size_t)kk * i];
    }
  free(P);
  return st;
}

/* Σ_i D_i² (k x k) */
static void sum_squares(int k, int nd, const double *D, double *S) {
  memset(S, 0, sizeof(double) * (size_t)k * k);
  for (int i = 0; i < nd; i++) {
    const double *Di = D + (size_t)k * k * i;
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, k, k, k, 1.0, Di, k, Di, k, 1.0, S, k);
  }
}

static ss_status check_args(int k_S, int k_T, int p, const double *A, const double *B, int nd, const double *D_S,
                            const double *D_T, const ss_fmap_weights *w, ss_error *err) {
  if (k_S < 1 || k_T < 1 || p < 0 || nd < 0 || !w) return ss_fail(err, SS_ERR_INVALID, "fmap: bad sizes");
  if (p > 0 && (!A || !B)) return ss_fail(err, SS_ERR_INVALID, "fmap: missing probe coefficients");
  if (nd > 0 && (!D_S || !D_T)) return ss_fail(err, SS_ERR_INVALID, "fmap: missing operators");
  if (!(w->w_descr >= 0 && w->w_lap >= 0 && w->w_dcomm >= 0))
    return ss_fail(err, SS_ERR_INVALID, "fmap: weights must be non-negative");
  return SS_OK;
}

ss_status ss_fmap_solve(int k_S, int k_T, int p, const double *A, const double *B, const double *evals_S,
                        const double *evals_T, int nd, const double *D_S, const double *D_T,
                        const ss_fmap_weights *w, double *C, ss_error *err) {
  ss_status st = check_args(k_S, k_T, p, A, B, nd, D_S, D_T, w, err);
  if (st) return st;
  const size_t m = (size_t)k_S * k_T;
  const int kkS = k_S * (k_S + 1) / 2, kkT = k_T * (k_T + 1) / 2;
  double *N = calloc(m * m, sizeof(double)), *rhs = calloc(m, sizeof(double));
  double *SS = calloc((size_t)k_S * k_S, sizeof(double)), *ST = calloc((size_t)k_T * k_T, sizeof(double));
  double *PS = NULL, *PT = NULL, *H = NULL;
  if (!N || !rhs || !SS || !ST) { st = ss_fail(err, SS_ERR_NOMEM, "fmap: out of memory (%zu unknowns)", m); goto done; }

  /* S-side blocks (act on columns of C): w_d A Aᵀ + w_c Σ (D^S)², same for every row r */
  if (p > 0 && w->w_descr > 0)
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, k_S, k_S, p, w->w_descr, A, k_S, A, k_S, 0.0, SS, k_S);
  if (nd > 0 && w->w_dcomm > 0) {
    double *tmp = malloc(sizeof(double) * (size_t)k_T * k_T > sizeof(double) * (size_t)k_S * k_S
                             ? sizeof(double) * (size_t)k_T * k_T
                             : sizeof(double) * (size_t)k_S * k_S);
    if (!tmp) { st = ss_fail(err, SS_ERR_NOMEM, "fmap: out of memory"); goto done; }
    sum_squares(k_S, nd, D_S, tmp);
    cblas_daxpy(k_S * k_S, w->w_dcomm, tmp, 1, SS, 1);
    sum_squares(k_T, nd, D_T, tmp);
    cblas_daxpy(k_T * k_T, w->w_dcomm, tmp, 1, ST, 1);
    free(tmp);
  }
  for (int c2 = 0; c2 < k_S; c2++)
    for (int c1 = 0; c1 < k_S; c1++) {
      double v = SS[c1 + (size_t)k_S * c2];
      if (v == 0) continue;
      for (int r = 0; r < k_T; r++) N[(r + (size_t)k_T * c1) + m * (r + (size_t)k_T * c2)] += v;
    }
  /* T-side blocks (act on rows): w_c Σ (D^T)², same for every column c */
  for (int c = 0; c < k_S; c++)
    for (int r2 = 0; r2 < k_T; r2++)
      for (int r1 = 0; r1 < k_T; r1++)
        N[(r1 + (size_t)k_T * c) + m * (r2 + (size_t)k_T * c)] += ST[r1 + (size_t)k_T * r2];
  /* Laplacian commutativity: diagonal */
  if (w->w_lap > 0)
    for (int c = 0; c < k_S; c++)
      for (int r = 0; r < k_T; r++) {
        double d = evals_T[r] - evals_S[c];
        size_t i = r + (size_t)k_T * c;
        N[i + m * i] += w->w_lap * d * d;
      }
  /* cross term −2 w_c Σ_i D_i^S ⊗ D_i^T: H = P_S P_Tᵀ on packed triangles */
  if (nd > 0 && w->w_dcomm > 0) {
    PS = malloc(sizeof(double) * (size_t)kkS * nd);
    PT = malloc(sizeof(double) * (size_t)kkT * nd);
    H = malloc(sizeof(double) * (size_t)kkS * kkT);
    if (!PS || !PT || !H) { st = ss_fail(err, SS_ERR_NOMEM, "fmap: out of memory"); goto done; }
    for (int i = 0; i < nd; i++) {
      const double *Ds = D_S + (size_t)k_S * k_S * i, *Dt = D_T + (size_t)k_T * k_T * i;
      for (int b = 0; b < k_S; b++)
        for (int a = 0; a <= b; a++) PS[pk(a, b) + (size_t)kkS * i] = Ds[a + (size_t)k_S * b];
      for (int b = 0; b < k_T; b++)
        for (int a = 0; a <= b; a++) PT[pk(a, b) + (size_t)kkT * i] = Dt[a + (size_t)k_T * b];
    }
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, kkS, kkT, nd, -2.0 * w->w_dcomm, PS, kkS, PT, kkT, 0.0, H,
                kkS);
    /* N[(r,c1),(r2,c2)] += H[(c1,c2),(r,r2)] */
#pragma omp parallel for schedule(static)
    for (int c2 = 0; c2 < k_S; c2++)
      for (int r2 = 0; r2 < k_T; r2++) {
        double *col = N + m * (r2 + (size_t)k_T * c2);
        for (int c1 = 0; c1 < k_S; c1++) {
          size_t hs = c1 <= c2 ? pk(c1, c2) : pk(c2, c1);
          for (int r = 0; r < k_T; r++) {
            size_t ht = r <= r2 ? pk(r, r2) : pk(r2, r);
            col[r + (size_t)k_T * c1] += H[hs + (size_t)kkS * ht];
          }
        }
      }
  }
  /* right-hand side w_d vec(B Aᵀ) */
  if (p > 0 && w->w_descr > 0)
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, k_T, k_S, p, w->w_descr, B, k_T, A, k_S, 0.0, rhs, k_T);
  /* fixed first column: move it to the right-hand side, keep the system SPD */
  if (w->fix_constant) {
    for (int r = 0; r < k_T; r++) {
      double v = r == 0 ? w->const_value : 0.0;
      size_t j = r;
      if (v != 0)
        for (size_t i = 0; i < m; i++) rhs[i] -= N[i + m * j] * v;
    }
    for (int r = 0; r < k_T; r++) {
      size_t j = r;
      for (size_t i = 0; i < m; i++) N[i + m * j] = N[j + m * i] = 0.0;
      N[j + m * j] = 1.0;
      rhs[j] = r == 0 ? w->const_value : 0.0;
    }
  }
  lapack_int info = LAPACKE_dposv(LAPACK_COL_MAJOR, 'L', (lapack_int)m, 1, N, (lapack_int)m, rhs, (lapack_int)m);
  if (info != 0) {
    st = ss_fail(err, SS_ERR_NUMERIC, "fmap: normal equations not positive definite (dposv info %d)", (int)info);
    goto done;
  }
  memcpy(C, rhs, sizeof(double) * m);
done:
  free(N);
  free(rhs);
  free(SS);
  free(ST);
  free(PS);
  free(PT);
  free(H);
  return st;
}

ss_status ss_fmap_energy(int k_S, int k_T, int p, const double *A, const double *B, const double *evals_S,
                         const double *evals_T, int nd, const double *D_S, const double *D_T,
                         const ss_fmap_weights *w, const double *C, double *E, double *grad, ss_error *err) {
  ss_status st = check_args(k_S, k_T, p, A, B, nd, D_S, D_T, w, err);
  if (st) return st;
  const size_t m = (size_t)k_S * k_T;
  double *R = malloc(sizeof(double) * (size_t)k_T * (p > 0 ? p : 1)), *Q = malloc(sizeof(double) * m),
         *g = calloc(m, sizeof(double));
  if (!R || !Q || !g) { free(R); free(Q); free(g); return ss_fail(err, SS_ERR_NOMEM, "fmap: out of memory"); }
  double e = 0;
  if (p > 0 && w->w_descr > 0) {
    memcpy(R, B, sizeof(double) * (size_t)k_T * p); /* R = C A − B */
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, k_T, p, k_S, 1.0, C, k_T, A, k_S, -1.0, R, k_T);
    e += w->w_descr * cblas_ddot(k_T * p, R, 1, R, 1);
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, k_T, k_S, p, 2 * w->w_descr, R, k_T, A, k_S, 1.0, g, k_T);
  }
  if (w->w_lap > 0)
    for (int c = 0; c < k_S; c++)
      for (int r = 0; r < k_T; r++) {
        double d = evals_T[r] - evals_S[c], x = C[r + (size_t)k_T * c];
        e += w->w_lap * d * d * x * x;
        g[r + (size_t)k_T * c] += 2 * w->w_lap * d * d * x;
      }
  if (w->w_dcomm > 0)
    for (int i = 0; i < nd; i++) {
      const double *Ds = D_S + (size_t)k_S * k_S * i, *Dt = D_T + (size_t)k_T * k_T * i;
      /* Q = C D^S − D^T C; grad += 2 w_c (Q D^S − D^T Q) (D's symmetric) */
      cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, k_T, k_S, k_S, 1.0, C, k_T, Ds, k_S, 0.0, Q, k_T);
      cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, k_T, k_S, k_T, -1.0, Dt, k_T, C, k_T, 1.0, Q, k_T);
      e += w->w_dcomm * cblas_ddot((int)m, Q, 1, Q, 1);
      cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, k_T, k_S, k_S, 2 * w->w_dcomm, Q, k_T, Ds, k_S, 1.0, g,
                  k_T);
      cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, k_T, k_S, k_T, -2 * w->w_dcomm, Dt, k_T, Q, k_T, 1.0, g,
                  k_T);
    }
  if (E) *E = e;
  if (grad) {
    memcpy(grad, g, sizeof(double) * m);
    if (w->fix_constant) memset(grad, 0, sizeof(double) * (size_t)k_T); /* the fixed column is no unknown */
  }
  free(R);
  free(Q);
  free(g);
  return SS_OK;
}
