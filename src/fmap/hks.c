/* Heat kernel signature (Sun, Ovsjanikov, Guibas 2009) in the style of the WKS next door: a filter
 * matrix over the eigenvalues, then Φ² Gᵀ, each column normalised in L²(M). */
#include "specseg/fmap.h"

#include <cblas.h>
#include <math.h>
#include <stdlib.h>

ss_status ss_hks_filters(const double *evals, int k, int nt, double *G, double *times, ss_error *err) {
  if (k < 2 || nt < 1 || !evals || !G) return ss_fail(err, SS_ERR_INVALID, "HKS needs k >= 2 eigenpairs and >= 1 time");
  double lmax = 0;
  for (int i = 0; i < k; i++) lmax = fmax(lmax, fabs(evals[i]));
  double tiny = 1e-8 * lmax; /* as the WKS: eigenvalues below this are the constant function(s) */
  double lmin = INFINITY;
  for (int i = 0; i < k; i++)
    if (fabs(evals[i]) > tiny) lmin = fmin(lmin, fabs(evals[i]));
  if (!(lmax > 0) || !isfinite(lmax) || !(lmin <= lmax)) return ss_fail(err, SS_ERR_INVALID, "HKS needs a non-zero eigenvalue");
  /* t from 4 ln 10 / λ_max (e^{-λ_max t} = 1e-4) to 4 ln 10 / λ_min, log-spaced */
  double t0 = log(4 * log(10.0) / lmax), t1 = log(4 * log(10.0) / lmin);
  for (int j = 0; j < nt; j++) {
    double t = exp(nt > 1 ? t0 + (t1 - t0) * j / (nt - 1) : 0.5 * (t0 + t1));
    if (times) times[j] = t;
    for (int i = 0; i < k; i++) {
      double l = fabs(evals[i]);
      G[j + (size_t)nt * i] = l > tiny ? exp(-l * t) : 0.0;
    }
  }
  return SS_OK;
}

ss_status ss_hks(int n, int k, const double *evals, const double *evecs, const double *M, int nt, double *out,
                 ss_error *err) {
  if (n < 1 || k < 2 || !evecs || !M || !out) return ss_fail(err, SS_ERR_INVALID, "HKS: empty shape or basis");
  if (nt < 1) return ss_fail(err, SS_ERR_INVALID, "HKS: %d times", nt);
  double *G = malloc(sizeof(double) * (size_t)nt * k), *sq = malloc(sizeof(double) * (size_t)n * k);
  if (!G || !sq) {
    free(G), free(sq);
    return ss_fail(err, SS_ERR_NOMEM, "HKS: out of memory");
  }
  ss_status st = ss_hks_filters(evals, k, nt, G, NULL, err);
  if (!st) {
    for (size_t i = 0; i < (size_t)n * k; i++) sq[i] = evecs[i] * evecs[i];
    /* out (n x nt) = Φ² Gᵀ, then unit L²(M) columns */
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, n, nt, k, 1.0, sq, n, G, nt, 0.0, out, n);
    for (int c = 0; c < nt; c++) {
      double *f = out + (size_t)n * c, s = 0;
      for (int x = 0; x < n; x++) s += M[x] * f[x] * f[x];
      if (s > 0) cblas_dscal(n, 1.0 / sqrt(s), f, 1);
    }
  }
  free(G), free(sq);
  return st;
}
