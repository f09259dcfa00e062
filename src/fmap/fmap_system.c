/* The normal equations of Eq. (1) (Nogneng & Ovsjanikov 2017), assembled once for a pair's base
 * probes and solved for several extra-probe blocks (STD / ASA / DIFF share everything but the
 * segments).
 *
 * With x = vec(C) (column-major, index r + k_T·c), E(C) = xᵀ N x − 2 bᵀ x + const where
 *   N = w_d (A Aᵀ ⊗ I) + w_l diag((λ_T,r − λ_S,c)²)
 *     + w_c Σ_i [ (D_i^S)² ⊗ I + I ⊗ (D_i^T)² − 2 D_i^S ⊗ D_i^T ],   b = w_d vec(B Aᵀ)
 * (the D's are symmetric), and with orientation operators (w_o > 0) w_o Σ_i ‖C O_i^S − O_i^T C‖²'s
 * terms alike. The only expensive part, the Kronecker sums Σ_i D_i^S ⊗ D_i^T (and the O's), is one
 * dgemm per block column of N (add_operator_terms). At k = 50 with ~120 probes, N is 2500 x 2500 with a condition number of
 * ~3e3 on FAUST (LAPACK dpocon): CG to a 1e-8 relative residual needs a few hundred iterations of
 * either a pass over the 50 MB N or 4·k³·p flops, both slower than one compute-bound Cholesky. The
 * Cholesky runs in single precision with iterative refinement in double (dsposv's scheme, solve_spd;
 * it falls back to a double factorisation when refinement stalls), so the solution has double
 * accuracy. */
#include "specseg/fmap.h"
#include "fmap_work.h"

#include <cblas.h>
#include <lapacke.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct ss_fmap_system {
  int k_S, k_T;
  size_t m;
  ss_fmap_weights w;
  double *N;   /* m x m, base probes, before the constant column is fixed */
  double *rhs; /* m */
  int lent;    /* N is a work's (ssi_fmap_system_new_in), not freed with the system */
};

void ssi_fmap_work_free(ssi_fmap_work *w) {
  if (!w) return;
  free(w->N), free(w->own), free(w->F);
  memset(w, 0, sizeof *w);
}

/* room for m unknowns in w (its contents are not kept when it grows) */
static int work_reserve(ssi_fmap_work *w, size_t m) {
  if (w->m >= m) return 1;
  ssi_fmap_work_free(w);
  w->N = malloc(sizeof(double) * m * m), w->own = malloc(sizeof(double) * m * m), w->F = malloc(sizeof(float) * m * m);
  if (!w->N || !w->own || !w->F) {
    ssi_fmap_work_free(w);
    return 0;
  }
  w->m = m;
  return 1;
}

static inline size_t pk(int a, int b) { /* packed upper-triangle index, a <= b */
  return (size_t)b * (b + 1) / 2 + a;
}

void ss_fmap_probes_free(ss_fmap_probes *p) {
  if (!p) return;
  free(p->A);
  free(p->P);
  free(p->O);
  memset(p, 0, sizeof *p);
}

/* Σ_i D_i² (k x k) from packed operators (nd columns of P) */
static ss_status sum_squares_packed(int k, int nd, const double *P, double *S, ss_error *err) {
  memset(S, 0, sizeof(double) * (size_t)k * k);
  if (nd <= 0) return SS_OK;
  double *D = malloc(sizeof(double) * (size_t)k * k);
  if (!D) return ss_fail(err, SS_ERR_NOMEM, "fmap: out of memory");
  const size_t kk = (size_t)k * (k + 1) / 2;
  for (int i = 0; i < nd; i++) {
    const double *p = P + kk * i;
    for (int b = 0; b < k; b++)
      for (int a = 0; a <= b; a++) D[a + (size_t)k * b] = D[b + (size_t)k * a] = p[pk(a, b)];
    cblas_dsyrk(CblasColMajor, CblasUpper, CblasNoTrans, k, k, 1.0, D, k, 1.0, S, k);
  }
  for (int b = 0; b < k; b++)
    for (int a = 0; a < b; a++) S[b + (size_t)k * a] = S[a + (size_t)k * b];
  free(D);
  return SS_OK;
}

/* N += S-side block (same for every row r: N[(r,c1),(r,c2)] += SS[c1,c2]) and T-side block (same for
 * every column c: N[(r1,c),(r2,c)] += ST[r1,r2]); either may be NULL. Like every term below, only
 * N's lower triangle (row index >= column index) is formed: the solver (solve_spd) reads no other. */
static void add_side_blocks(int k_S, int k_T, size_t m, const double *SS, const double *ST, double *N) {
  if (SS)
    for (int c2 = 0; c2 < k_S; c2++)
      for (int c1 = c2; c1 < k_S; c1++) {
        double v = SS[c1 + (size_t)k_S * c2];
        if (v == 0) continue;
        for (int r = 0; r < k_T; r++) N[(r + (size_t)k_T * c1) + m * (r + (size_t)k_T * c2)] += v;
      }
  if (ST)
    for (int c = 0; c < k_S; c++)
      for (int r2 = 0; r2 < k_T; r2++)
        for (int r1 = r2; r1 < k_T; r1++) N[(r1 + (size_t)k_T * c) + m * (r2 + (size_t)k_T * c)] += ST[r1 + (size_t)k_T * r2];
}

/* N += Σ_j X_j ⊗ Y_j over the operator terms: −2 w_c D_i^S ⊗ D_i^T for the nd packed symmetric pairs
 * and −w_o (O_i^S ⊗ O_i^T + O_i^Sᵀ ⊗ O_i^Tᵀ) for the no orientation pairs, i.e. block (c1, c2) of N
 * (k_T x k_T, rows k_T·c1.., columns k_T·c2..) += Σ_j X_j[c1, c2] Y_j. With Y = [vec Y_j] (k_T² x q)
 * and the coefficients K[j, (c1, c2)] = X_j[c1, c2], the blocks of one block column c2 are one dgemm
 * Y K[:, (c2.., c2)] written straight into their places: no k_S² x k_T² product matrix and no
 * strided scatter (both cost more than the arithmetic). */
static ss_status add_operator_terms(int k_S, int k_T, size_t m, int nd, const double *PS, const double *PT, double w_c,
                                    int no, const double *OS, const double *OT, double w_o, double *N, ss_error *err) {
  const int q = nd + 2 * no;
  if (q == 0) return SS_OK;
  const size_t kS2 = (size_t)k_S * k_S, kT2 = (size_t)k_T * k_T;
  double *Y = malloc(sizeof(double) * kT2 * q), *K = malloc(sizeof(double) * kS2 * q);
  if (!Y || !K) {
    free(Y), free(K);
    return ss_fail(err, SS_ERR_NOMEM, "fmap: out of memory");
  }
  for (int i = 0; i < nd; i++) {
    const double *pS = PS + (size_t)k_S * (k_S + 1) / 2 * i, *pT = PT + (size_t)k_T * (k_T + 1) / 2 * i;
    double *y = Y + kT2 * i;
    for (int b = 0; b < k_T; b++)
      for (int a = 0; a <= b; a++) y[a + (size_t)k_T * b] = y[b + (size_t)k_T * a] = pT[pk(a, b)];
    for (int b = 0; b < k_S; b++)
      for (int a = 0; a <= b; a++) K[i + (size_t)q * (a + (size_t)k_S * b)] = K[i + (size_t)q * (b + (size_t)k_S * a)] = -2.0 * w_c * pS[pk(a, b)];
  }
  for (int i = 0; i < no; i++) {
    const double *oS = OS + kS2 * i, *oT = OT + kT2 * i;
    double *y = Y + kT2 * (nd + i), *yt = Y + kT2 * (nd + no + i);
    for (int b = 0; b < k_T; b++)
      for (int a = 0; a < k_T; a++) y[a + (size_t)k_T * b] = yt[b + (size_t)k_T * a] = oT[a + (size_t)k_T * b];
    for (int b = 0; b < k_S; b++)
      for (int a = 0; a < k_S; a++) {
        K[nd + i + (size_t)q * (a + (size_t)k_S * b)] = -w_o * oS[a + (size_t)k_S * b];
        K[nd + no + i + (size_t)q * (a + (size_t)k_S * b)] = -w_o * oS[b + (size_t)k_S * a];
      }
  }
  int failed = 0;
#pragma omp parallel
  {
    double *blk = malloc(sizeof(double) * kT2 * k_S);
    if (!blk) {
#pragma omp atomic write
      failed = 1;
    }
#pragma omp for schedule(dynamic, 1)
    for (int c2 = 0; c2 < k_S; c2++) {
      if (!blk) continue;
      /* block rows c1 = c2 .. k_S − 1 (N's lower triangle) */
      cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, (int)kT2, k_S - c2, q, 1.0, Y, (int)kT2,
                  K + (size_t)q * (c2 + (size_t)k_S * c2), q, 0.0, blk, (int)kT2);
      for (int c1 = c2; c1 < k_S; c1++) {
        const double *B = blk + kT2 * (c1 - c2);
        for (int r2 = 0; r2 < k_T; r2++) {
          double *col = N + m * (r2 + (size_t)k_T * c2) + (size_t)k_T * c1;
          for (int r1 = c1 == c2 ? r2 : 0; r1 < k_T; r1++) col[r1] += B[r1 + (size_t)k_T * r2];
        }
      }
    }
    free(blk);
  }
  free(Y), free(K);
  return failed ? ss_fail(err, SS_ERR_NOMEM, "fmap: out of memory") : SS_OK;
}

/* the side blocks of the orientation term: w_o Σ_i O_i^S O_i^Sᵀ (k_S x k_S) and w_o Σ_i O_i^Tᵀ O_i^T
 * (k_T x k_T), added to SS and ST */
static void orientation_sides(int k_S, int k_T, int no, const double *OS, const double *OT, double w_o, double *SS,
                              double *ST) {
  const size_t kS2 = (size_t)k_S * k_S, kT2 = (size_t)k_T * k_T;
  for (int i = 0; i < no; i++) {
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, k_S, k_S, k_S, w_o, OS + kS2 * i, k_S, OS + kS2 * i, k_S, 1.0, SS, k_S);
    cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, k_T, k_T, k_T, w_o, OT + kT2 * i, k_T, OT + kT2 * i, k_T, 1.0, ST, k_T);
  }
}

/* All terms of one probe block pair: data weight wd, commutativity weight wc over the first nd
 * columns, orientation weight wo over the no orientation operators (0: none). */
static ss_status add_block(int k_S, int k_T, size_t m, const ss_fmap_probes *S, const ss_fmap_probes *T, double wd,
                           double wc, int use_ops, double wo, double *N, double *rhs, ss_error *err) {
  ss_status st = SS_OK;
  double *SS = calloc((size_t)k_S * k_S, sizeof(double)), *ST = calloc((size_t)k_T * k_T, sizeof(double));
  if (!SS || !ST) { st = ss_fail(err, SS_ERR_NOMEM, "fmap: out of memory"); goto done; }
  const int p = S->p, nd = use_ops && wc > 0 ? S->nd : 0, no = wo > 0 ? S->no : 0;
  if (p > 0 && wd > 0) {
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, k_S, k_S, p, wd, S->A, k_S, S->A, k_S, 0.0, SS, k_S);
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, k_T, k_S, p, wd, T->A, k_T, S->A, k_S, 1.0, rhs, k_T);
  }
  if (nd > 0) {
    double *tmp = malloc(sizeof(double) * (size_t)(k_S > k_T ? k_S : k_T) * (k_S > k_T ? k_S : k_T));
    if (!tmp) { st = ss_fail(err, SS_ERR_NOMEM, "fmap: out of memory"); goto done; }
    if (!(st = sum_squares_packed(k_S, nd, S->P, tmp, err))) cblas_daxpy(k_S * k_S, wc, tmp, 1, SS, 1);
    if (!st && !(st = sum_squares_packed(k_T, nd, T->P, tmp, err))) cblas_daxpy(k_T * k_T, wc, tmp, 1, ST, 1);
    free(tmp);
    if (st) goto done;
  }
  if (no > 0) orientation_sides(k_S, k_T, no, S->O, T->O, wo, SS, ST);
  add_side_blocks(k_S, k_T, m, SS, nd > 0 || no > 0 ? ST : NULL, N);
  st = add_operator_terms(k_S, k_T, m, nd, S->P, T->P, wc, no, S->O, T->O, wo, N, err);
done:
  free(SS);
  free(ST);
  return st;
}

/* x = N⁻¹ b for the SPD N (m x m, leading dimension ld, lower triangle read, not written): LAPACK dsposv's scheme — Cholesky in single precision, refinement with double residuals
 * until max|b − N x| ≤ max|x|·‖N‖∞·ε·√m, a double factorisation when the single one fails or 30
 * steps do not converge — without its NaN scan, its separate norm pass and its repacking of N for
 * every residual (dsymm; dsymv reads the triangle in place). */
static ss_status solve_spd(size_t m, const double *N, size_t ld, const double *b, float *F_work, double *x,
                           ss_error *err) {
  float *F_own = F_work ? NULL : malloc(sizeof(float) * m * m), *F = F_work ? F_work : F_own,
        *r32 = malloc(sizeof(float) * m);
  double *r = malloc(sizeof(double) * m), *rowsum = calloc(m, sizeof(double));
  ss_status st = SS_OK;
  if (!F || !r32 || !r || !rowsum) { st = ss_fail(err, SS_ERR_NOMEM, "fmap: out of memory (%zu unknowns)", m); goto done; }
  int single = 1;
  for (size_t j = 0; j < m; j++)
    for (size_t i = j; i < m; i++) {
      const double v = N[i + ld * j], a = fabs(v);
      if (!(a <= FLT_MAX)) single = 0; /* overflow (or NaN): the double factorisation decides */
      F[i + m * j] = (float)v;
      rowsum[i] += a;
      if (i != j) rowsum[j] += a;
    }
  double anrm = 0;
  for (size_t i = 0; i < m; i++) anrm = rowsum[i] > anrm ? rowsum[i] : anrm;
  const double cte = anrm * DBL_EPSILON / 2 * sqrt((double)m); /* LAPACK's dlamch('E') is ε/2 */
  int done = 0;
  if (single && LAPACKE_spotrf_work(LAPACK_COL_MAJOR, 'L', (lapack_int)m, F, (lapack_int)m) == 0) {
    for (size_t i = 0; i < m; i++) r32[i] = (float)b[i];
    LAPACKE_spotrs_work(LAPACK_COL_MAJOR, 'L', (lapack_int)m, 1, F, (lapack_int)m, r32, (lapack_int)m);
    for (size_t i = 0; i < m; i++) x[i] = r32[i];
    for (int it = 0; it <= 30 && !done; it++) {
      memcpy(r, b, sizeof(double) * m);
      cblas_dsymv(CblasColMajor, CblasLower, (int)m, -1.0, N, (int)ld, x, 1, 1.0, r, 1);
      double rn = 0, xn = 0;
      for (size_t i = 0; i < m; i++) {
        rn = fabs(r[i]) > rn ? fabs(r[i]) : rn;
        xn = fabs(x[i]) > xn ? fabs(x[i]) : xn;
      }
      if (rn <= xn * cte) { done = 1; break; }
      if (it == 30 || !isfinite(rn)) break;
      for (size_t i = 0; i < m; i++) r32[i] = (float)r[i];
      LAPACKE_spotrs_work(LAPACK_COL_MAJOR, 'L', (lapack_int)m, 1, F, (lapack_int)m, r32, (lapack_int)m);
      for (size_t i = 0; i < m; i++) x[i] += r32[i];
    }
  }
  if (!done) { /* the double factorisation, of a copy (N is the caller's) */
    free(F_own), F_own = NULL;
    double *D = malloc(sizeof(double) * m * m);
    if (!D) { st = ss_fail(err, SS_ERR_NOMEM, "fmap: out of memory (%zu unknowns)", m); goto done; }
    for (size_t j = 0; j < m; j++) memcpy(D + j + m * j, N + j + ld * j, sizeof(double) * (m - j));
    memcpy(x, b, sizeof(double) * m);
    lapack_int info = LAPACKE_dpotrf_work(LAPACK_COL_MAJOR, 'L', (lapack_int)m, D, (lapack_int)m);
    if (info == 0) info = LAPACKE_dpotrs_work(LAPACK_COL_MAJOR, 'L', (lapack_int)m, 1, D, (lapack_int)m, x, (lapack_int)m);
    free(D);
    if (info != 0) st = ss_fail(err, SS_ERR_NUMERIC, "fmap: normal equations not positive definite (dpotrf info %d)", (int)info);
  }
done:
  free(F_own), free(r32), free(r), free(rowsum);
  return st;
}

static ss_status check_probes(const ss_fmap_probes *S, const ss_fmap_probes *T, int k_S, int k_T, const char *what,
                              ss_error *err) {
  if (!S || !T || S->k != k_S || T->k != k_T || S->p != T->p || S->p < 0 || (S->p > 0 && (!S->A || !T->A)))
    return ss_fail(err, SS_ERR_INVALID, "fmap: %s probes: sizes do not match (k %d/%d, p %d/%d)", what, S ? S->k : -1,
                   T ? T->k : -1, S ? S->p : -1, T ? T->p : -1);
  if (S->nd != T->nd || S->nd < 0 || (S->nd > 0 && (!S->P || !T->P)))
    return ss_fail(err, SS_ERR_INVALID, "fmap: %s probes: operator counts do not match", what);
  if (S->no != T->no || S->no < 0 || (S->no > 0 && (!S->O || !T->O)))
    return ss_fail(err, SS_ERR_INVALID, "fmap: %s probes: orientation operator counts do not match", what);
  return SS_OK;
}

ss_status ss_fmap_system_new(int k_S, int k_T, const double *evals_S, const double *evals_T, const ss_fmap_probes *S,
                             const ss_fmap_probes *T, const ss_fmap_weights *w, ss_fmap_system **out, ss_error *err) {
  return ssi_fmap_system_new_in(k_S, k_T, evals_S, evals_T, S, T, w, NULL, out, err);
}

ss_status ssi_fmap_system_new_in(int k_S, int k_T, const double *evals_S, const double *evals_T, const ss_fmap_probes *S,
                                 const ss_fmap_probes *T, const ss_fmap_weights *w, ssi_fmap_work *work,
                                 ss_fmap_system **out, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "fmap: NULL output");
  *out = NULL;
  if (k_S < 1 || k_T < 1 || !w || !evals_S || !evals_T) return ss_fail(err, SS_ERR_INVALID, "fmap: bad sizes");
  if (!(w->w_descr >= 0 && w->w_lap >= 0 && w->w_dcomm >= 0 && w->w_orient >= 0))
    return ss_fail(err, SS_ERR_INVALID, "fmap: weights must be non-negative");
  ss_status st = check_probes(S, T, k_S, k_T, "base", err);
  if (st) return st;
  const size_t m = (size_t)k_S * k_T;
  if (m > 40000) return ss_fail(err, SS_ERR_INVALID, "fmap: %d x %d basis too large for the dense solver", k_T, k_S);
  ss_fmap_system *s = calloc(1, sizeof *s);
  if (!s) return ss_fail(err, SS_ERR_NOMEM, "fmap: out of memory");
  s->k_S = k_S, s->k_T = k_T, s->m = m, s->w = *w;
  if (work && work_reserve(work, m)) {
    s->N = work->N, s->lent = 1;
    for (size_t j = 0; j < m; j++) memset(s->N + j + m * j, 0, sizeof(double) * (m - j)); /* the triangle formed */
  } else if (!work)
    s->N = calloc(m * m, sizeof(double));
  s->rhs = calloc(m, sizeof(double));
  if (!s->N || !s->rhs) {
    ss_fmap_system_free(s);
    return ss_fail(err, SS_ERR_NOMEM, "fmap: out of memory (%zu unknowns)", m);
  }
  if (w->w_lap > 0)
    for (int c = 0; c < k_S; c++)
      for (int r = 0; r < k_T; r++) {
        double d = evals_T[r] - evals_S[c];
        size_t i = r + (size_t)k_T * c;
        s->N[i + m * i] += w->w_lap * d * d;
      }
  if ((st = add_block(k_S, k_T, m, S, T, w->w_descr, w->w_dcomm, 1, w->w_orient, s->N, s->rhs, err))) {
    ss_fmap_system_free(s);
    return st;
  }
  *out = s;
  return SS_OK;
}

void ss_fmap_system_free(ss_fmap_system *s) {
  if (!s) return;
  if (!s->lent) free(s->N);
  free(s->rhs);
  free(s);
}

ss_status ss_fmap_system_solve(const ss_fmap_system *s, const ss_fmap_probes *S_extra, const ss_fmap_probes *T_extra,
                               double w_extra, int extra_dcomm, double *C, ss_error *err) {
  return ssi_fmap_system_solve_in(s, S_extra, T_extra, w_extra, extra_dcomm, NULL, C, err);
}

ss_status ssi_fmap_system_solve_in(const ss_fmap_system *s, const ss_fmap_probes *S_extra, const ss_fmap_probes *T_extra,
                                   double w_extra, int extra_dcomm, ssi_fmap_work *work, double *C, ss_error *err) {
  if (!s || !C) return ss_fail(err, SS_ERR_INVALID, "fmap: NULL system or output");
  const int k_S = s->k_S, k_T = s->k_T;
  const size_t m = s->m;
  const int have_extra = S_extra || T_extra;
  ss_status st = SS_OK;
  if (have_extra && (st = check_probes(S_extra, T_extra, k_S, k_T, "extra", err))) return st;
  if (have_extra && !(w_extra >= 0)) return ss_fail(err, SS_ERR_INVALID, "fmap: negative extra-probe weight %g", w_extra);
  /* the base system as it is, or a copy with the extra block's terms */
  const int add = have_extra && S_extra->p > 0;
  /* a work's buffers when they have room (not grown here: its N may be lent to a live system) */
  const int use_work = work && work->m >= m;
  double *own_alloc = add && !use_work ? malloc(sizeof(double) * m * m) : NULL, *own = use_work && add ? work->own : own_alloc;
  double *rhs = malloc(sizeof(double) * m), *x = malloc(sizeof(double) * m);
  const double *N = add ? own : s->N;
  if ((add && !own) || !rhs || !x) { st = ss_fail(err, SS_ERR_NOMEM, "fmap: out of memory (%zu unknowns)", m); goto done; }
  memcpy(rhs, s->rhs, sizeof(double) * m);
  if (add) {
    for (size_t j = 0; j < m; j++) /* the lower triangle (all the solver reads) */
      memcpy(own + j + m * j, s->N + j + m * j, sizeof(double) * (m - j));
    if ((st = add_block(k_S, k_T, m, S_extra, T_extra, s->w.w_descr * w_extra, s->w.w_dcomm, extra_dcomm, 0.0, own, rhs, err)))
      goto done;
  }
  /* fixed first column (C[:, 0] = (v, 0, …, 0)): its terms move to the right-hand side and the
   * system of the other columns, N's trailing block, is solved */
  size_t f0 = 0;
  if (s->w.fix_constant) {
    const double v = s->w.const_value;
    f0 = (size_t)k_T;
    for (size_t i = f0; i < m; i++) rhs[i] -= N[i] * v; /* column j = 0 */
    memset(x, 0, sizeof(double) * f0);
    x[0] = v;
  }
  if ((st = solve_spd(m - f0, N + f0 + m * f0, m, rhs + f0, use_work ? work->F : NULL, x + f0, err))) goto done;
  /* a solution of infinities or NaNs, or all zero (the probes carry nothing, or weights near
   * DBL_MAX overflowed the system: its diagonal infinite, the solution 0), would make a point map
   * of no meaning without a word; no real pair's system gives either */
  int nonzero = 0, finite = 1;
  for (size_t i = f0; i < m; i++) nonzero |= x[i] != 0, finite &= isfinite(x[i]) != 0;
  if (!finite || (!nonzero && m > f0)) {
    st = ss_fail(err, SS_ERR_NUMERIC, "fmap: the functional map is %s (a weight too large for the system, or "
                 "probes that carry nothing)", finite ? "all zero" : "not finite");
    goto done;
  }
  memcpy(C, x, sizeof(double) * m);
done:
  free(own_alloc);
  free(rhs);
  free(x);
  return st;
}
