/* Wave kernel signature (Aubry, Schlickewei, Cremers 2011) and wave-kernel filtering of functions
 * (the landmark "wave-kernel maps" of Nogneng & Ovsjanikov 2017). */
#include "specseg/fmap.h"

#include <cblas.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

ss_status ss_wks_filters(const double *evals, int k, int ne, double sigma_factor, double *G, ss_error *err) {
  if (k < 3 || ne < 1 || !(sigma_factor > 0))
    return ss_fail(err, SS_ERR_INVALID, "WKS needs k >= 3 eigenpairs, >= 1 energy and sigma_factor > 0");
  double lmax = 0;
  for (int i = 0; i < k; i++) lmax = fmax(lmax, fabs(evals[i]));
  double tiny = 1e-8 * lmax; /* eigenvalues below this are the constant function(s) */
  double lmin = INFINITY;
  for (int i = 0; i < k; i++)
    if (fabs(evals[i]) > tiny) lmin = fmin(lmin, fabs(evals[i]));
  if (!(lmax > 0) || !(lmin < lmax))
    return ss_fail(err, SS_ERR_INVALID, "WKS needs two distinct non-zero eigenvalues");
  double emin = log(lmin), emax = log(lmax);
  double sigma = sigma_factor * (emax - emin) / ne;
  /* as in the WKS reference code: keep the energies 2σ away from the ends of the spectrum */
  double e0 = emin + 2 * sigma, e1 = emax - 2 * sigma;
  for (int j = 0; j < ne; j++) {
    double e = ne > 1 ? e0 + (e1 - e0) * j / (ne - 1) : 0.5 * (e0 + e1);
    for (int i = 0; i < k; i++) {
      double l = fabs(evals[i]);
      G[j + (size_t)ne * i] = l > tiny ? exp(-(e - log(l)) * (e - log(l)) / (2 * sigma * sigma)) : 0.0;
    }
  }
  return SS_OK;
}

/* Scale each column of out (n x m) to unit L²(M) norm; zero columns stay zero. */
static void normalise_columns(int n, int m, const double *M, double *out) {
  for (int c = 0; c < m; c++) {
    double *f = out + (size_t)n * c, s = 0;
    for (int x = 0; x < n; x++) s += M[x] * f[x] * f[x];
    if (s > 0) cblas_dscal(n, 1.0 / sqrt(s), f, 1);
  }
}

static ss_status check_basis(int n, int k, const double *evecs, const double *M, ss_error *err) {
  if (n < 1 || k < 3 || !evecs || !M) return ss_fail(err, SS_ERR_INVALID, "WKS: empty shape or basis");
  return SS_OK;
}

ss_status ss_wks(int n, int k, const double *evals, const double *evecs, const double *M, int ne,
                 double sigma_factor, double *out, ss_error *err) {
  ss_status st = check_basis(n, k, evecs, M, err);
  if (st) return st;
  double *G = malloc(sizeof(double) * (size_t)ne * k), *sq = malloc(sizeof(double) * (size_t)n * k);
  if (!G || !sq) { free(G); free(sq); return ss_fail(err, SS_ERR_NOMEM, "WKS: out of memory"); }
  st = ss_wks_filters(evals, k, ne, sigma_factor, G, err);
  if (!st) {
    for (size_t i = 0; i < (size_t)n * k; i++) sq[i] = evecs[i] * evecs[i];
    /* out (n x ne) = Φ² Gᵀ */
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, n, ne, k, 1.0, sq, n, G, ne, 0.0, out, n);
    normalise_columns(n, ne, M, out);
  }
  free(G);
  free(sq);
  return st;
}

/* out[:, f·ne + j] = Φ (G[j,:] ∘ coef[:, f]) for coefficient vectors coef (k x nf). */
static void synthesise(int n, int k, const double *evecs, int ne, const double *G, int nf, const double *coef,
                       double *filt, double *out) {
  /* filt (k x nf·ne): the filtered coefficients, then one dgemm back to the vertices */
  for (int f = 0; f < nf; f++)
    for (int j = 0; j < ne; j++)
      for (int i = 0; i < k; i++)
        filt[i + (size_t)k * ((size_t)f * ne + j)] = G[j + (size_t)ne * i] * coef[i + (size_t)k * f];
  cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n, nf * ne, k, 1.0, evecs, n, filt, k, 0.0, out, n);
}

ss_status ss_wks_filter(int n, int k, const double *evals, const double *evecs, const double *M, int ne,
                        double sigma_factor, int nf, const double *F, double *out, ss_error *err) {
  ss_status st = check_basis(n, k, evecs, M, err);
  if (st) return st;
  if (nf < 0) return ss_fail(err, SS_ERR_INVALID, "WKS filter: negative function count");
  if (nf == 0) return SS_OK;
  double *G = malloc(sizeof(double) * (size_t)ne * k), *coef = malloc(sizeof(double) * (size_t)k * nf),
         *filt = malloc(sizeof(double) * (size_t)k * nf * ne);
  if (!G || !coef || !filt) { st = ss_fail(err, SS_ERR_NOMEM, "WKS filter: out of memory"); goto done; }
  st = ss_wks_filters(evals, k, ne, sigma_factor, G, err);
  if (st) goto done;
  st = ss_fmap_project(n, k, evecs, M, nf, F, coef, err);
  if (st) goto done;
  synthesise(n, k, evecs, ne, G, nf, coef, filt, out);
  normalise_columns(n, nf * ne, M, out);
done:
  free(G);
  free(coef);
  free(filt);
  return st;
}

ss_status ss_wks_landmarks(int n, int k, const double *evals, const double *evecs, const double *M, int ne,
                           double sigma_factor, int nl, const int *lm, double *out, ss_error *err) {
  ss_status st = check_basis(n, k, evecs, M, err);
  if (st) return st;
  for (int l = 0; l < nl; l++)
    if (lm[l] < 0 || lm[l] >= n)
      return ss_fail(err, SS_ERR_INVALID, "landmark %d: vertex %d out of range [0,%d)", l, lm[l], n);
  if (nl <= 0) return SS_OK;
  double *G = malloc(sizeof(double) * (size_t)ne * k), *coef = malloc(sizeof(double) * (size_t)k * nl),
         *filt = malloc(sizeof(double) * (size_t)k * nl * ne);
  if (!G || !coef || !filt) { st = ss_fail(err, SS_ERR_NOMEM, "WKS landmarks: out of memory"); goto done; }
  st = ss_wks_filters(evals, k, ne, sigma_factor, G, err);
  if (st) goto done;
  /* the (L²-)delta at vertex v has coefficients φ_i(v) */
  for (int l = 0; l < nl; l++)
    for (int i = 0; i < k; i++) coef[i + (size_t)k * l] = evecs[lm[l] + (size_t)n * i];
  synthesise(n, k, evecs, ne, G, nl, coef, filt, out);
  normalise_columns(n, nl * ne, M, out);
done:
  free(G);
  free(coef);
  free(filt);
  return st;
}
