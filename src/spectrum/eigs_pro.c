/* Lanczos with partial reorthogonalisation (Simon 1984) for the largest eigenvalues of the
 * shift-invert operator OP (positive semi-definite for σ <= 0): ss_eigs' method on small meshes.
 *
 * Why: ARPACK reorthogonalises every new Lanczos vector against the whole basis (two to four
 * matrix-vector products over n x j per step). At FAUST size (n ~ 7k, k = 100, basis ~ 200) those
 * products, bound by cache bandwidth, took three quarters of the iteration; the solves a quarter.
 * In exact arithmetic the three-term recurrence alone keeps the basis orthogonal; in floating point
 * orthogonality is lost gradually, at a rate the recurrence below estimates (ω_{j,k} ≈ v_jᵀ v_k)
 * without touching the basis. Reorthogonalising only when an estimate nears √eps (below: 1e-11),
 * and only against the columns concerned, keeps the basis semi-orthogonal, which is enough for the
 * projected tridiagonal T to be exact to working precision
 * (Simon; Parlett & Scott): Ritz values without spurious copies, Ritz vectors as accurate as with
 * full reorthogonalisation. ss_eigs restores exact M-orthonormality of the result afterwards.
 *
 * No restarts: the basis grows until every wanted pair passes ARPACK's test ‖OP y − θ y‖ =
 * β_{m+1} |s_{m,i}| <= tol·θ_i (tightened, PRO_TOL_FACTOR), or until mmax columns (then the caller
 * runs ARPACK instead). */
#include "spectrum/eigs_internal.h"

#include <cblas.h>
#include <float.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The test on OP runs this much tighter than tol: ARPACK's restarts carry most pairs well past it,
 * and stopping right at it left relative residuals of W φ = λ M φ up to 1.2e-8 (a 4k-vertex
 * rectangle, k = 8) */
#define PRO_TOL_FACTOR 0.01

/* w ← w − V h with h = Vᵀ w over the columns lo .. hi-1 of V (one classical Gram–Schmidt pass) */
static double reorthogonalize(int n, int lo, int hi, const double *V, double *w, double *h) {
  if (hi > lo) {
    const double *B = V + (size_t)n * lo;
    cblas_dgemv(CblasColMajor, CblasTrans, n, hi - lo, 1.0, B, n, w, 1, 0.0, h, 1);
    cblas_dgemv(CblasColMajor, CblasNoTrans, n, hi - lo, -1.0, B, n, h, 1, 1.0, w, 1);
  }
  return cblas_dnrm2(n, w, 1);
}

/* The nev largest eigenpairs of T (m x m: diagonal a, off-diagonal b[1..m-1]); converged when each
 * has β_{m+1}|s_{m,i}| <= tol·θ_i. The whole spectrum by MRRR (O(m²); a subset would go to bisection
 * and inverse iteration, several times slower). Fills theta (descending) and S (m x nev) when all
 * converged; returns how many have (nev: done), -1 on LAPACK failure. */
static int ritz_check(int m, int nev, const double *a, const double *b, double beta_next, double tol, double *d,
                      double *e, double *w, double *Z, int *isupp, double *theta, double *S) {
  for (int i = 0; i < m; i++) d[i] = a[i];
  for (int i = 0; i + 1 < m; i++) e[i] = b[i + 1];
  lapack_int nfound = 0;
  lapack_int info = LAPACKE_dstevr(LAPACK_COL_MAJOR, 'V', 'A', m, d, e, 0.0, 0.0, 0, 0, 0.0, &nfound, w, Z, m, isupp);
  if (info != 0 || nfound < m) return -1;
  const double *top = Z + (size_t)m * (m - nev), *wt = w + (m - nev); /* ascending: the nev largest last */
  int nc = 0;
  for (int i = 0; i < nev; i++) {
    const double res = beta_next * fabs(top[(size_t)m * i + m - 1]);
    nc += wt[i] > 0 && res <= tol * wt[i];
  }
  if (nc < nev) return nc;
  for (int i = 0; i < nev; i++) { /* descending: dstevr's ascending order reversed */
    const int col = nev - 1 - i;
    theta[i] = wt[col];
    /* MRRR leaves the sign to rounding: the largest entry positive (dstein's rule, so the same
     * operator scaled by a power of two gives the same vectors) */
    const double *z = top + (size_t)m * col;
    int imax = 0;
    for (int r = 1; r < m; r++)
      if (fabs(z[r]) > fabs(z[imax])) imax = r;
    const double sg = z[imax] < 0 ? -1.0 : 1.0;
    for (int r = 0; r < m; r++) S[(size_t)m * i + r] = sg * z[r];
  }
  return nev;
}

ss_status ssi_eigs_pro_lanczos(ssi_lanczos_ctx *c, int nev, int mmax, uint64_t seed, double *Y, double *lam,
                               int *converged, ss_error *err) {
  const int n = c->n;
  const size_t nn = (size_t)n;
  *converged = 0;
  if (nev < 1 || mmax <= nev || mmax > n - c->nnull - c->ndefl) return SS_OK; /* no room: the caller's ARPACK */
  /* reorthogonalise when an estimate passes `limit`, against the columns above `eta` around it.
   * Far tighter than Simon's √eps and eps^(3/4): the Ritz vectors' residuals follow the basis'
   * orthogonality (ss_eigs_check on the 100 FAUST shapes, k = 110: up to 1.1e-8 at 1e-10 / 1e-13,
   * up to 1.5e-10 at these for 7% more time; ARPACK's up to 3.3e-11) */
  const double eps = DBL_EPSILON, limit = 1e-11, eta = 1e-14;
  double *V = malloc(sizeof(double) * nn * (size_t)(mmax + 1));
  double *a = malloc(sizeof(double) * (size_t)mmax), *b = malloc(sizeof(double) * (size_t)(mmax + 1));
  double *om[3] = {calloc((size_t)mmax + 2, sizeof(double)), calloc((size_t)mmax + 2, sizeof(double)),
                   calloc((size_t)mmax + 2, sizeof(double))};
  double *h = malloc(sizeof(double) * (size_t)(mmax + 1));
  double *d = malloc(sizeof(double) * (size_t)mmax * 4), *Z = malloc(sizeof(double) * (size_t)mmax * mmax);
  double *S = malloc(sizeof(double) * (size_t)mmax * nev), *theta = malloc(sizeof(double) * (size_t)nev);
  int *isupp = malloc(sizeof(int) * 2 * (size_t)mmax);
  int *ilo = malloc(sizeof(int) * (size_t)(mmax + 1)), *ihi = malloc(sizeof(int) * (size_t)(mmax + 1));
  ss_status st = SS_OK;
  if (!V || !a || !b || !om[0] || !om[1] || !om[2] || !h || !d || !Z || !S || !theta || !isupp || !ilo || !ihi) {
    st = ss_fail(err, SS_ERR_NOMEM, "eigs: out of memory (n = %d, basis %d)", n, mmax);
    goto out;
  }
  double *e = d + mmax, *w = e + mmax;
  /* v_0: the deterministic start vector, projected and normalised */
  double *v0 = V;
  ssi_eigs_start_vector(v0, n, seed);
  ssi_eigs_project(c, v0);
  double nr = cblas_dnrm2(n, v0, 1);
  if (!(nr > 0)) goto out;
  cblas_dscal(n, 1.0 / nr, v0, 1);
  /* ω rows: prev = ω_{j-1,·}, cur = ω_{j,·}, next = ω_{j+1,·} */
  double *wprev = om[0], *wcur = om[1], *wnext = om[2];
  wcur[0] = 1.0;
  b[0] = 0.0;
  double anorm = 0.0; /* running estimate of ‖T‖ ≈ ‖OP‖ for the rounding terms */
  int force = 0;      /* reorthogonalise the next vector too (Simon: in pairs) */
  int nreorth = 0, nint = 0;
  /* the first convergence check at 2 nev (ARPACK's first basis), the next ones as far on as the
   * pairs still missing, at about one pair per two steps (FAUST, k = 50-110), would take */
  int next_check = 2 * nev > nev + 10 ? 2 * nev : nev + 10;
  for (int j = 0; j < mmax; j++) {
    double *vj = V + nn * (size_t)j, *r = V + nn * (size_t)(j + 1);
    if ((st = ssi_eigs_apply_op(c, vj, r, err))) goto out;
    if (j > 0) cblas_daxpy(n, -b[j], V + nn * (size_t)(j - 1), 1, r, 1);
    double al = cblas_ddot(n, vj, 1, r, 1);
    cblas_daxpy(n, -al, vj, 1, r, 1);
    const double dl = cblas_ddot(n, vj, 1, r, 1); /* local correction: keeps v_{j+1} ⟂ v_j to eps */
    cblas_daxpy(n, -dl, vj, 1, r, 1);
    a[j] = al + dl;
    double be = cblas_dnrm2(n, r, 1);
    const double tn = fabs(a[j]) + be + b[j];
    if (tn > anorm) anorm = tn;
    /* ω_{j+1,k}, k <= j (Simon's recurrence with Larsen's rounding terms) */
    if (be > 0) {
      for (int k = 0; k < j; k++) {
        double t = b[k + 1] * wcur[k + 1] + (a[k] - a[j]) * wcur[k] - b[j] * wprev[k];
        if (k > 0) t += b[k] * wcur[k - 1];
        t += (t >= 0 ? 1 : -1) * eps * (b[k + 1] + be) * 0.3;
        wnext[k] = t / be;
      }
      wnext[j] = eps * anorm / be * 0.6; /* after the local correction: rounding level */
    }
    double worst = 0;
    for (int k = 0; k <= j && be > 0; k++)
      if (fabs(wnext[k]) > worst) worst = fabs(wnext[k]);
    if (!(be > 0) || be < eps * anorm * 100) {
      /* (near) breakdown: one full pass decides whether anything new is left */
      be = reorthogonalize(n, 0, j + 1, V, r, h);
      for (int k = 0; k <= j; k++) wnext[k] = eps;
      nint = 0;
    } else if (force || worst > limit) {
      /* reorthogonalise against the columns that lost orthogonality: around each estimate above
       * limit, the interval where they exceed eta (the estimates of the rest stay as they are; at
       * FAUST size the first fifth to third of the basis, where the converged directions live); the
       * next vector against the same intervals, since its estimates inherit these (Simon: in pairs) */
      if (!force) {
        nint = 0;
        for (int k = 0; k <= j; k++) {
          if (!(fabs(wnext[k]) > limit)) continue;
          int lo = k, hi = k;
          while (lo > 0 && fabs(wnext[lo - 1]) > eta) lo--;
          while (hi < j && fabs(wnext[hi + 1]) > eta) hi++;
          if (nint > 0 && lo <= ihi[nint - 1] + 1) ihi[nint - 1] = hi;
          else ilo[nint] = lo, ihi[nint] = hi, nint++;
          k = hi;
        }
      } else if (nint > 0 && ihi[nint - 1] == j - 1)
        ihi[nint - 1] = j; /* the interval that reached the last column takes the new one */
      double before = cblas_dnrm2(n, r, 1);
      for (int pass = 0; pass < 2; pass++) {
        for (int q = 0; q < nint; q++) reorthogonalize(n, ilo[q], ihi[q] + 1, V, r, h);
        be = cblas_dnrm2(n, r, 1);
        if (be > 0.717 * before) break;
        before = be;
      }
      for (int q = 0; q < nint; q++)
        for (int k = ilo[q]; k <= ihi[q]; k++) wnext[k] = eps;
      force = !force;
      nreorth++;
    }
    if (!(be > eps * anorm * 100)) {
      /* an invariant subspace: nothing left to find from this start (the caller's ARPACK decides) */
      goto out;
    }
    b[j + 1] = be;
    cblas_dscal(n, 1.0 / be, r, 1);
    wnext[j + 1] = 1.0;
    double *t = wprev;
    wprev = wcur, wcur = wnext, wnext = t;
    const int m = j + 1;
    if (m >= next_check || m == mmax) {
      int cv = ritz_check(m, nev, a, b, b[m], c->tol * PRO_TOL_FACTOR, d, e, w, Z, isupp, theta, S);
      if (cv < 0) { st = ss_fail(err, SS_ERR_NUMERIC, "eigs: tridiagonal eigensolver failed"); goto out; }
      next_check = m + (2 * (nev - cv) > 10 ? 2 * (nev - cv) : 10);
      if (cv == nev) {
        /* Ritz vectors, ascending λ = σ + 1/ν: the largest θ first */
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n, nev, m, 1.0, V, n, S, m, 0.0, Y, n);
        /* a spurious copy of a converged pair (what a lapse of semi-orthogonality would leave) shows
         * as two nearly parallel Ritz vectors: then ARPACK decides instead. (Semi-orthogonality
         * itself leaves inner products up to ~1e-8, which ss_eigs' orthonormalisation removes:
         * TOSCA michael18, k = 100: 1.7e-8.) */
        double *G = Z; /* (T's eigenvectors are no longer needed) */
        cblas_dsyrk(CblasColMajor, CblasUpper, CblasTrans, nev, n, 1.0, Y, n, 0.0, G, nev);
        double off = 0;
        for (int q = 0; q < nev; q++)
          for (int p = 0; p <= q; p++) off = fmax(off, fabs(G[p + (size_t)nev * q] - (p == q)));
        if (!(off < 1e-5)) goto out;
        for (int i = 0; i < nev; i++) lam[i] = c->sigma + 1.0 / (theta[i] / c->opscale);
        c->restarts = nreorth;
        *converged = 1;
        goto out;
      }
    }
  }
out:
  free(V), free(a), free(b), free(om[0]), free(om[1]), free(om[2]), free(h), free(d), free(Z), free(S), free(theta);
  free(isupp), free(ilo), free(ihi);
  return st;
}
