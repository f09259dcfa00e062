/* Sparse symmetric factorisation with CHOLMOD. Simplicial LDL^T: on these mesh matrices its
 * single-column solves were ~3x faster than supernodal ones (shared/design/paper-notes.md), and
 * LDL^T also copes with an indefinite shift (sigma inside the spectrum). Supernodal LL^T for
 * positive definite matrices solved against blocks of many columns at once. */
#include "linalg/cholmod_wrap.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <suitesparse/cholmod.h>

/* a solve workspace of ssi_chol_solve_slot (slots 1..; slot 0 is the factor's own common) */
typedef struct {
  cholmod_common cc;
  cholmod_dense *X, *Y, *E;
  int started;
} chol_ws;

#define CHOL_MAX_WS SSI_CHOL_SLOTS

struct ssi_chol {
  cholmod_common cc;
  cholmod_factor *L;
  cholmod_dense *X, *Y, *E; /* solve workspaces, reused across calls */
  int n;
  chol_ws ws[CHOL_MAX_WS];
};

int ssi_chol_size(const ssi_chol *c) { return c->n; }
double ssi_chol_nnz(const ssi_chol *c) {
  if (!c->L) return 0;
  if (c->L->is_super) return c->cc.lnz;
  if (!c->L->p) return 0;
  const int *p = c->L->p;
  return (double)p[c->n];
}

void ssi_chol_free(ssi_chol *c) {
  if (!c) return;
  for (int t = 0; t < CHOL_MAX_WS; t++) {
    chol_ws *w = &c->ws[t];
    if (!w->started) continue;
    if (w->X) cholmod_free_dense(&w->X, &w->cc);
    if (w->Y) cholmod_free_dense(&w->Y, &w->cc);
    if (w->E) cholmod_free_dense(&w->E, &w->cc);
    cholmod_finish(&w->cc);
  }
  if (c->L) cholmod_free_factor(&c->L, &c->cc);
  if (c->X) cholmod_free_dense(&c->X, &c->cc);
  if (c->Y) cholmod_free_dense(&c->Y, &c->cc);
  if (c->E) cholmod_free_dense(&c->E, &c->cc);
  cholmod_finish(&c->cc);
  free(c);
}

/* Upper triangle of A + alpha*diag(d) as a CHOLMOD matrix, with a diagonal entry in every column. */
static ss_status shifted_upper(const ss_sparse *A, double alpha, const double *d, cholmod_common *cc,
                               cholmod_sparse **out, ss_error *err) {
  int n = A->ncols;
  size_t nz = 0;
  for (int j = 0; j < n; j++) {
    for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++)
      if (A->rowind[p] < j) nz++;
    nz++; /* the diagonal, present or not in A */
  }
  cholmod_sparse *S = cholmod_allocate_sparse((size_t)n, (size_t)n, nz, 1, 1, 1, CHOLMOD_REAL, cc);
  if (!S) return ss_fail(err, SS_ERR_NOMEM, "out of memory for a %d x %d sparse matrix", n, n);
  int *Sp = S->p, *Si = S->i;
  double *Sx = S->x;
  size_t q = 0;
  for (int j = 0; j < n; j++) {
    Sp[j] = (int)q;
    double diag = (d ? alpha * d[j] : 0.0);
    for (int p = A->colptr[j]; p < A->colptr[j + 1]; p++) {
      int i = A->rowind[p];
      double v = A->val[p];
      if (!isfinite(v)) {
        cholmod_free_sparse(&S, cc);
        return ss_fail(err, SS_ERR_INVALID, "matrix entry (%d,%d) is not finite", i, j);
      }
      if (i < j) { Si[q] = i; Sx[q] = v; q++; }
      else if (i == j) diag += v;
    }
    Si[q] = j; Sx[q] = diag; q++;
  }
  Sp[n] = (int)q;
  *out = S;
  return SS_OK;
}

static ss_status chol_factor(const ss_sparse *A, double alpha, const double *d, int super, ssi_chol **out,
                             ss_error *err) {
  *out = NULL;
  if (!A || A->nrows != A->ncols || A->nrows < 1)
    return ss_fail(err, SS_ERR_INVALID, "factorisation needs a non-empty square matrix");
  int n = A->ncols;
  ssi_chol *c = calloc(1, sizeof *c);
  if (!c) return ss_fail(err, SS_ERR_NOMEM, "out of memory for a factorisation");
  c->n = n;
  cholmod_start(&c->cc);
  c->cc.print = 0;
  c->cc.error_handler = NULL;
  c->cc.supernodal = super ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
  c->cc.final_ll = 0;

  cholmod_sparse *S = NULL;
  ss_status st = shifted_upper(A, alpha, d, &c->cc, &S, err);
  if (st) {
    ssi_chol_free(c);
    return st;
  }
  c->L = cholmod_analyze(S, &c->cc);
  if (!c->L) {
    int st = c->cc.status;
    cholmod_free_sparse(&S, &c->cc);
    ssi_chol_free(c);
    return ss_fail(err, st == CHOLMOD_OUT_OF_MEMORY ? SS_ERR_NOMEM : SS_ERR_NUMERIC,
                   "CHOLMOD analysis failed (status %d)", st);
  }
  int ok = cholmod_factorize(S, c->L, &c->cc);
  cholmod_free_sparse(&S, &c->cc);
  if (!ok || c->cc.status == CHOLMOD_OUT_OF_MEMORY) {
    int st = c->cc.status;
    ssi_chol_free(c);
    return ss_fail(err, st == CHOLMOD_OUT_OF_MEMORY ? SS_ERR_NOMEM : SS_ERR_NUMERIC,
                   "CHOLMOD factorisation failed (status %d)", st);
  }
  if (c->L->minor < (size_t)n) {
    size_t minor = c->L->minor;
    ssi_chol_free(c);
    return ss_fail(err, SS_ERR_NUMERIC, "factorisation broke down at column %zu: matrix is singular (choose another shift)",
                   minor);
  }
  if (c->L->is_super) {
    /* LL^T ran to the end: every pivot was positive (CHOLMOD stops at the first that is not) */
    *out = c;
    return SS_OK;
  }
  /* LDL^T keeps D on the factor's diagonal (first entry of each column). Only zero or non-finite
   * pivots are fatal: a tiny pivot (shift very close to an eigenvalue) is exactly what shift-invert
   * thrives on, and callers judge the final residuals. */
  const int *Lp = c->L->p;
  const double *Lx = c->L->x;
  for (int j = 0; j < n; j++) {
    double dj = Lx[Lp[j]];
    if (!isfinite(dj) || dj == 0.0) {
      ssi_chol_free(c);
      return ss_fail(err, SS_ERR_NUMERIC,
                     "shifted matrix is singular (pivot %g at column %d); choose another shift", dj, j);
    }
  }
  *out = c;
  return SS_OK;
}

ss_status ssi_chol_factor(const ss_sparse *A, double alpha, const double *d, ssi_chol **out, ss_error *err) {
  return chol_factor(A, alpha, d, 0, out, err);
}

ss_status ssi_chol_factor_super(const ss_sparse *A, double alpha, const double *d, ssi_chol **out, ss_error *err) {
  return chol_factor(A, alpha, d, 1, out, err);
}

/* X = A^-1 B for one column block through the given common and workspaces. */
static int solve_block(const cholmod_factor *L, int n, const double *B, double *X, int nrhs, cholmod_common *cc,
                       cholmod_dense **Xw, cholmod_dense **Yw, cholmod_dense **Ew) {
  cholmod_dense b;
  memset(&b, 0, sizeof b);
  b.nrow = (size_t)n;
  b.ncol = (size_t)nrhs;
  b.nzmax = b.nrow * b.ncol;
  b.d = b.nrow;
  b.x = (void *)B;
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  /* cholmod_solve2 only reads the factor */
  if (!cholmod_solve2(CHOLMOD_A, (cholmod_factor *)L, &b, NULL, Xw, NULL, Yw, Ew, cc)) return 0;
  memcpy(X, (*Xw)->x, sizeof(double) * b.nzmax);
  return 1;
}

ss_status ssi_chol_solve_slot(ssi_chol *c, int slot, const double *B, double *X, int nrhs, ss_error *err) {
  if (nrhs < 1) return SS_OK;
  if (slot <= 0) return ssi_chol_solve(c, B, X, nrhs, err);
  if (slot >= CHOL_MAX_WS) return ss_fail(err, SS_ERR_INVALID, "CHOLMOD solve: no workspace slot %d", slot);
  chol_ws *w = &c->ws[slot];
  if (!w->started) {
    cholmod_start(&w->cc);
    w->cc.print = 0;
    w->cc.error_handler = NULL;
    w->started = 1;
  }
  if (!solve_block(c->L, c->n, B, X, nrhs, &w->cc, &w->X, &w->Y, &w->E))
    return ss_fail(err, w->cc.status == CHOLMOD_OUT_OF_MEMORY ? SS_ERR_NOMEM : SS_ERR_NUMERIC,
                   "CHOLMOD solve failed (status %d)", w->cc.status);
  return SS_OK;
}

ss_status ssi_chol_solve(ssi_chol *c, const double *B, double *X, int nrhs, ss_error *err) {
  if (nrhs < 1) return SS_OK;
  cholmod_dense b;
  memset(&b, 0, sizeof b);
  b.nrow = (size_t)c->n;
  b.ncol = (size_t)nrhs;
  b.nzmax = b.nrow * b.ncol;
  b.d = b.nrow;
  b.x = (void *)B;
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  if (!cholmod_solve2(CHOLMOD_A, c->L, &b, NULL, &c->X, NULL, &c->Y, &c->E, &c->cc))
    return ss_fail(err, c->cc.status == CHOLMOD_OUT_OF_MEMORY ? SS_ERR_NOMEM : SS_ERR_NUMERIC,
                   "CHOLMOD solve failed (status %d)", c->cc.status);
  memcpy(X, c->X->x, sizeof(double) * b.nzmax);
  return SS_OK;
}


ss_status ssi_chol_refactor(ssi_chol *c, const ss_sparse *A, double alpha, const double *d, ss_error *err) {
  if (!A || A->ncols != c->n || A->nrows != c->n) return ss_fail(err, SS_ERR_INVALID, "refactor: size mismatch");
  cholmod_sparse *S = NULL;
  ss_status st = shifted_upper(A, alpha, d, &c->cc, &S, err);
  if (st) return st;
  int ok = cholmod_factorize(S, c->L, &c->cc);
  cholmod_free_sparse(&S, &c->cc);
  if (!ok || c->cc.status == CHOLMOD_OUT_OF_MEMORY)
    return ss_fail(err, c->cc.status == CHOLMOD_OUT_OF_MEMORY ? SS_ERR_NOMEM : SS_ERR_NUMERIC,
                   "CHOLMOD factorisation failed (status %d)", c->cc.status);
  if (c->L->minor < (size_t)c->n)
    return ss_fail(err, SS_ERR_NUMERIC, "factorisation broke down at column %zu: matrix is singular", (size_t)c->L->minor);
  if (!c->L->is_super) {
    const int *Lp = c->L->p;
    const double *Lx = c->L->x;
    for (int j = 0; j < c->n; j++)
      if (!isfinite(Lx[Lp[j]]) || Lx[Lp[j]] == 0.0)
        return ss_fail(err, SS_ERR_NUMERIC, "shifted matrix is singular (pivot %g at column %d)", Lx[Lp[j]], j);
  }
  return SS_OK;
}

ss_status ssi_chol_inertia(ssi_chol *c, const ss_sparse *A, double alpha, const double *d, int *negative,
                          ss_error *err) {
  if (!A || A->ncols != c->n || A->nrows != c->n) return ss_fail(err, SS_ERR_INVALID, "inertia: size mismatch");
  cholmod_sparse *S = NULL;
  ss_status st = shifted_upper(A, alpha, d, &c->cc, &S, err);
  if (st) return st;
  cholmod_factor *L2 = NULL;
  if (c->L->is_super) {
    /* LL^T cannot count negative pivots: a simplicial LDL^T in the same fill-reducing ordering */
    int keep_super = c->cc.supernodal, keep_n = c->cc.nmethods, keep_ord = c->cc.method[0].ordering;
    c->cc.supernodal = CHOLMOD_SIMPLICIAL;
    c->cc.nmethods = 1;
    c->cc.method[0].ordering = CHOLMOD_GIVEN;
    L2 = cholmod_analyze_p(S, (int *)c->L->Perm, NULL, 0, &c->cc);
    c->cc.supernodal = keep_super;
    c->cc.nmethods = keep_n;
    c->cc.method[0].ordering = keep_ord;
  } else {
    /* same pattern, same ordering: refactor a copy of the factor, no new analysis */
    L2 = cholmod_copy_factor(c->L, &c->cc);
  }
  if (!L2) {
    cholmod_free_sparse(&S, &c->cc);
    return ss_fail(err, SS_ERR_NOMEM, "inertia: out of memory");
  }
  int ok = cholmod_factorize(S, L2, &c->cc);
  cholmod_free_sparse(&S, &c->cc);
  if (!ok || L2->minor < (size_t)c->n || L2->is_super || L2->is_ll) {
    cholmod_free_factor(&L2, &c->cc);
    return ss_fail(err, SS_ERR_NUMERIC, "inertia: LDL^T factorisation broke down");
  }
  const int *Lp = L2->p;
  const double *Lx = L2->x;
  int neg = 0;
  for (int j = 0; j < c->n; j++) {
    double dj = Lx[Lp[j]];
    if (!isfinite(dj) || dj == 0.0) {
      cholmod_free_factor(&L2, &c->cc);
      return ss_fail(err, SS_ERR_NUMERIC, "inertia: zero pivot");
    }
    neg += dj < 0;
  }
  cholmod_free_factor(&L2, &c->cc);
  *negative = neg;
  return SS_OK;
}
