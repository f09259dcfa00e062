/* Eq. (1) (Nogneng & Ovsjanikov 2017): spectral coefficients of probes, their multiplication
 * operators, the exact minimiser for explicit operator blocks (through fmap_system.c) and the energy
 * with its gradient (to check optimality). */
#include "specseg/fmap.h"

#include <cblas.h>
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
ss_status ss_fmap_mult_operators_packed(int n, int k, const double *evecs, const double *M, int p, const double *F,
                                        double *P, ss_error *err) {
  if (n < 1 || k < 1 || p < 0) return ss_fail(err, SS_ERR_INVALID, "operators: bad sizes");
  if (p == 0) return SS_OK;
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
  ss_status st = ss_fmap_mult_operators_packed(n, k, evecs, M, p, F, P, err);
  if (!st)
    for (int i = 0; i < p; i++) {
      double *Di = D + (size_t)k * k * i;
      for (int b = 0; b < k; b++)
        for (int a = 0; a <= b; a++) Di[a + (size_t)k * b] = Di[b + (size_t)k * a] = P[pk(a, b) + (size_t)kk * i];
    }
  free(P);
  return st;
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

/* packed upper triangles of nd full symmetric k x k blocks */
static double *pack_blocks(int k, int nd, const double *D) {
  const size_t kk = (size_t)k * (k + 1) / 2;
  double *P = malloc(sizeof(double) * kk * (nd > 0 ? nd : 1));
  if (!P) return NULL;
  for (int i = 0; i < nd; i++) {
    const double *Di = D + (size_t)k * k * i;
    for (int b = 0; b < k; b++)
      for (int a = 0; a <= b; a++) P[pk(a, b) + kk * i] = Di[a + (size_t)k * b];
  }
  return P;
}

ss_status ss_fmap_solve(int k_S, int k_T, int p, const double *A, const double *B, const double *evals_S,
                        const double *evals_T, int nd, const double *D_S, const double *D_T,
                        const ss_fmap_weights *w, double *C, ss_error *err) {
  ss_status st = check_args(k_S, k_T, p, A, B, nd, D_S, D_T, w, err);
  if (st) return st;
  ss_fmap_probes S = {k_S, p, nd, (double *)A, NULL, 0, NULL}, T = {k_T, p, nd, (double *)B, NULL, 0, NULL};
  ss_fmap_system *sys = NULL;
  if (nd > 0 && (!(S.P = pack_blocks(k_S, nd, D_S)) || !(T.P = pack_blocks(k_T, nd, D_T)))) {
    st = ss_fail(err, SS_ERR_NOMEM, "fmap: out of memory");
    goto done;
  }
  if (!(st = ss_fmap_system_new(k_S, k_T, evals_S, evals_T, &S, &T, w, &sys, err)))
    st = ss_fmap_system_solve(sys, NULL, NULL, 0.0, 0, C, err);
done:
  ss_fmap_system_free(sys);
  free(S.P);
  free(T.P);
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
