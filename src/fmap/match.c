/* The functional-map matching pipeline of paper §6: STD (WKS + landmark wave-kernel maps, descriptor
 * commutativity, NO17), plus paired extra probes (ASA raw / DIFF wave-filtered), optional ZoomOut. */
#include "specseg/fmap.h"
#include "specseg/laplacian.h"

#include <cblas.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* process CPU seconds: with --verbose the stages report wall and CPU time (the latter is what a
 * shared, overloaded machine still measures faithfully) */
static double cpu_now(void) { return (double)clock() / CLOCKS_PER_SEC; }

void ss_fmap_match_default_options(ss_fmap_match_options *o) {
  memset(o, 0, sizeof *o);
  o->k = 50;
  o->n_energies = 100;
  o->sigma_factor = 7.0;
  o->descr_step = 5;
  o->w_descr = 30.0; /* tuned on FAUST (BEST landmarks): 0.1 (pyFM) 0.0396, 1 0.0371, 10 0.0317, 30 0.0308,
                        100 0.0307, 1000 0.0345 mean Euclidean error / sqrt(area), 15 random pairs */
  o->w_lap = 1e-3;   /* 1e-3 .. 1: no measurable effect next to the commutativity term */
  o->w_dcomm = 1.0;
  o->fix_constant = 1;
  o->zoomout_kmax = 0;
  o->zoomout_step = 1;
  o->w_extra = 0.5; /* segments (tent profile, data term only), FAUST seed 7 pairs 0-9 / 10-19 vs STD:
                       1: 0.949 / 1.053 x STD, 0.5: 0.944 / 1.005, 2: 0.993 / - (see fmap.h) */
  o->extra_dcomm = 0;
}

/* All probe functions of one shape: the virtual column list [WKS | landmark maps | filtered extras]
 * (ne columns per item) sub-sampled by `step` as pyFM does, then the raw extras; each normalised in
 * L²(M). Only the kept columns are synthesised (in the spectral domain, then one dgemm). *P is
 * n x *np, malloc'd. */
static ss_status shape_probes(int n, int k, const double *evals, const double *evecs, const double *M,
                              const ss_fmap_match_options *o, int nl, const int *lm, int nextra, const double *extra,
                              ss_probe_filter filt, double **P, int *np, int *nxcol, ss_error *err) {
  const int ne = o->n_energies, step = o->descr_step;
  int nfilt = filt == SS_PROBE_WAVE ? nextra : 0, nraw = filt == SS_PROBE_WAVE ? 0 : nextra;
  for (int l = 0; l < nl; l++)
    if (lm[l] < 0 || lm[l] >= n) return ss_fail(err, SS_ERR_INVALID, "landmark %d: vertex %d out of range [0,%d)", l, lm[l], n);
  int nall = ne * (1 + nl + nfilt), nkeep = (nall + step - 1) / step, nwks = (ne + step - 1) / step;
  double *G = malloc(sizeof(double) * (size_t)ne * k), *coef = malloc(sizeof(double) * (size_t)k * (nl + nfilt + 1));
  double *fc = malloc(sizeof(double) * (size_t)k * nkeep), *sq = malloc(sizeof(double) * (size_t)n * k);
  double *Gw = malloc(sizeof(double) * (size_t)nwks * k);
  double *out = malloc(sizeof(double) * (size_t)n * ((size_t)nkeep + nraw));
  ss_status st = SS_OK;
  if (!G || !coef || !fc || !sq || !Gw || !out) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory for probes"); goto done; }
  if ((st = ss_wks_filters(evals, k, ne, o->sigma_factor, G, err))) goto done;
  /* WKS at the kept energies: Φ² G[kept,:]ᵀ */
  for (int t = 0; t < nwks; t++)
    for (int i = 0; i < k; i++) Gw[t + (size_t)nwks * i] = G[t * step + (size_t)ne * i];
  for (size_t i = 0; i < (size_t)n * k; i++) sq[i] = evecs[i] * evecs[i];
  cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, n, nwks, k, 1.0, sq, n, Gw, nwks, 0.0, out, n);
  /* spectral coefficients of the landmark deltas and of the extras to filter */
  for (int l = 0; l < nl; l++)
    for (int i = 0; i < k; i++) coef[i + (size_t)k * l] = evecs[lm[l] + (size_t)n * i];
  if (nfilt > 0 && (st = ss_fmap_project(n, k, evecs, M, nfilt, extra, coef + (size_t)k * nl, err))) goto done;
  int nf = 0;
  for (int c = nwks * step; c < nall; c += step) { /* c: virtual column index past the WKS block */
    int item = (c - ne) / ne, j = (c - ne) % ne;
    for (int i = 0; i < k; i++) fc[i + (size_t)k * nf] = G[j + (size_t)ne * i] * coef[i + (size_t)k * item];
    nf++;
  }
  /* kept columns that come from the extras: the last ones (filtered), or the raw extras */
  int firstx = (ne * (1 + nl) + step - 1) / step * step; /* first kept virtual column past the landmarks */
  int nxf = nfilt > 0 && firstx < nall ? (nall - firstx + step - 1) / step : 0;
  if (nf > 0)
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n, nf, k, 1.0, evecs, n, fc, k, 0.0, out + (size_t)n * nwks, n);
  for (int c = 0; c < nraw; c++) memcpy(out + (size_t)n * (nkeep + c), extra + (size_t)n * c, sizeof(double) * n);
  for (int c = 0; c < nkeep + nraw; c++) {
    double *f = out + (size_t)n * c, s = 0;
    for (int x = 0; x < n; x++) s += M[x] * f[x] * f[x];
    if (s > 0) cblas_dscal(n, 1.0 / sqrt(s), f, 1);
  }
  *P = out;
  *np = nkeep + nraw;
  *nxcol = nxf + nraw;
  out = NULL;
done:
  free(G); free(coef); free(fc); free(sq); free(Gw); free(out);
  return st;
}

static ss_status check_shape(const ss_fmap_shape *s, const char *name, int need, ss_error *err) {
  if (!s || !s->mesh || !s->evals || !s->evecs || s->mesh->nv < 1)
    return ss_fail(err, SS_ERR_INVALID, "match: shape %s incomplete", name);
  if (s->kev < need)
    return ss_fail(err, SS_ERR_INVALID, "match: shape %s has %d eigenpairs, %d needed", name, s->kev, need);
  return SS_OK;
}

ss_status ss_fmap_match(const ss_fmap_shape *X, const ss_fmap_shape *Y, int nl, const int *lmX, const int *lmY,
                        int nextra, const double *extraX, const double *extraY, ss_probe_filter extra_filter,
                        const ss_fmap_match_options *opts, int *map, double *C, ss_error *err) {
  ss_fmap_match_options o;
  if (opts) o = *opts;
  else ss_fmap_match_default_options(&o);
  if (!(o.w_extra >= 0)) return ss_fail(err, SS_ERR_INVALID, "match: negative extra-probe weight %g", o.w_extra);
  if (o.k < 3 || o.n_energies < 1 || o.descr_step < 1 || !(o.sigma_factor > 0) || o.zoomout_step < 1)
    return ss_fail(err, SS_ERR_INVALID, "match: invalid options (k %d, energies %d, step %d)", o.k, o.n_energies,
                   o.descr_step);
  if (o.zoomout_kmax != 0 && o.zoomout_kmax < o.k)
    return ss_fail(err, SS_ERR_INVALID, "match: ZoomOut size %d below k = %d", o.zoomout_kmax, o.k);
  int need = o.zoomout_kmax > o.k ? o.zoomout_kmax : o.k;
  ss_status st = check_shape(X, "X", need, err);
  if (!st) st = check_shape(Y, "Y", need, err);
  if (st) return st;
  if (nl < 0 || nextra < 0 || (nl > 0 && (!lmX || !lmY)) || (nextra > 0 && (!extraX || !extraY)))
    return ss_fail(err, SS_ERR_INVALID, "match: missing landmarks or extra probes");
  const int nX = X->mesh->nv, nY = Y->mesh->nv, k = o.k;
  double t0 = ss_time(), t1, c0 = cpu_now(), c1;

  double *MX = NULL, *MY = NULL, *PX = NULL, *PY = NULL, *A = NULL, *B = NULL, *DS = NULL, *DT = NULL, *Ck = NULL;
  const double *mX = X->M, *mY = Y->M;
  if (!mX) {
    if (!(MX = malloc(sizeof(double) * nX))) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
    if ((st = ss_mass_lumped(X->mesh, SS_MASS_BARYCENTRIC, MX, err))) goto done;
    mX = MX;
  }
  if (!mY) {
    if (!(MY = malloc(sizeof(double) * nY))) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
    if ((st = ss_mass_lumped(Y->mesh, SS_MASS_BARYCENTRIC, MY, err))) goto done;
    mY = MY;
  }
  int pX, pY, xX, xY;
  if ((st = shape_probes(nX, k, X->evals, X->evecs, mX, &o, nl, lmX, nextra, extraX, extra_filter, &PX, &pX, &xX, err)))
    goto done;
  if ((st = shape_probes(nY, k, Y->evals, Y->evecs, mY, &o, nl, lmY, nextra, extraY, extra_filter, &PY, &pY, &xY, err)))
    goto done;
  t1 = ss_time();
  c1 = cpu_now();
  if (o.verbose) fprintf(stderr, "timing: fmap_probes %.4f cpu %.4f (%d probes)\n", t1 - t0, c1 - c0, pX);
  t0 = t1;
  c0 = c1;

  /* source S = Y, target T = X: C maps functions on Y to functions on X, so its point map is X -> Y */
  A = malloc(sizeof(double) * k * pY);
  B = malloc(sizeof(double) * k * pX);
  DS = malloc(sizeof(double) * (size_t)k * k * pY);
  DT = malloc(sizeof(double) * (size_t)k * k * pX);
  Ck = malloc(sizeof(double) * k * k);
  if (!A || !B || !DS || !DT || !Ck) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
  if ((st = ss_fmap_project(nY, k, Y->evecs, mY, pY, PY, A, err))) goto done;
  if ((st = ss_fmap_project(nX, k, X->evecs, mX, pX, PX, B, err))) goto done;
  if (o.w_dcomm > 0) {
    if ((st = ss_fmap_mult_operators(nY, k, Y->evecs, mY, pY, PY, DS, err))) goto done;
    if ((st = ss_fmap_mult_operators(nX, k, X->evecs, mX, pX, PX, DT, err))) goto done;
  }
  /* the extra (segment) block: its own data weight, and in the commutativity term only on request
   * (its operators are the last xY of the pY; ss_fmap_solve uses the first nd) */
  if (xY > 0 && o.w_extra != 1.0)
    for (int c = pY - xY; c < pY; c++) {
      cblas_dscal(k, sqrt(o.w_extra), A + (size_t)k * c, 1);
      cblas_dscal(k, sqrt(o.w_extra), B + (size_t)k * c, 1);
    }
  int nd = o.w_dcomm > 0 ? (o.extra_dcomm ? pY : pY - xY) : 0;
  t1 = ss_time();
  c1 = cpu_now();
  if (o.verbose) fprintf(stderr, "timing: fmap_operators %.4f cpu %.4f\n", t1 - t0, c1 - c0);
  t0 = t1;
  c0 = c1;

  double sd = 0, areaX = 0, areaY = 0;
  for (int r = 0; r < k; r++)
    for (int c = 0; c < k; c++) sd += (X->evals[r] - Y->evals[c]) * (X->evals[r] - Y->evals[c]);
  for (int x = 0; x < nX; x++) areaX += mX[x];
  for (int y = 0; y < nY; y++) areaY += mY[y];
  ss_fmap_weights w = {o.w_descr, sd > 0 ? o.w_lap / sd : 0.0, o.w_dcomm, o.fix_constant, 0.0};
  w.const_value = (X->evecs[0] * Y->evecs[0] < 0 ? -1.0 : 1.0) * sqrt(areaX / areaY);
  if ((st = ss_fmap_solve(k, k, pY, A, B, Y->evals, X->evals, nd, DS, DT, &w, Ck, err)))
    goto done;
  t1 = ss_time();
  c1 = cpu_now();
  if (o.verbose) fprintf(stderr, "timing: fmap_solve %.4f cpu %.4f\n", t1 - t0, c1 - c0);
  t0 = t1;
  c0 = c1;

  if (o.zoomout_kmax > k) {
    st = ss_zoomout(nY, nX, Y->evecs, X->evecs, mX, k, Ck, o.zoomout_kmax, o.zoomout_step, map, C, err);
    t1 = ss_time();
    c1 = cpu_now();
  c1 = cpu_now();
    if (o.verbose) fprintf(stderr, "timing: zoomout %.4f cpu %.4f\n", t1 - t0, c1 - c0);
  } else {
    st = ss_fmap_p2p(nY, nX, k, k, Y->evecs, X->evecs, Ck, map, err);
    if (!st && C) memcpy(C, Ck, sizeof(double) * k * k);
    t1 = ss_time();
    c1 = cpu_now();
  c1 = cpu_now();
    if (o.verbose) fprintf(stderr, "timing: fmap_p2p %.4f cpu %.4f\n", t1 - t0, c1 - c0);
  }
done:
  free(MX);
  free(MY);
  free(PX);
  free(PY);
  free(A);
  free(B);
  free(DS);
  free(DT);
  free(Ck);
  return st;
}
