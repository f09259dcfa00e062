/* ZoomOut (Melzi, Ren, Rodolà, Sharma, Wonka, Ovsjanikov 2019): spectral up-sampling of a functional
 * map by alternating its point map and the functional map of that point map, one size larger.
 *
 * Each iteration's point map is an exact nearest-neighbour search of the target's rows of Φ_T among
 * the rows of E = Φ_S Cᵀ. Two things carry over between iterations (ss_nn_exact_guided): the previous
 * map, whose distances bound every query's search from the start, and one clustering of the source,
 * made once on Φ_S's first kmax columns: ‖E(x) − E(x')‖ ≤ ‖C‖ ‖Φ_S(x) − Φ_S(x')‖ and ZoomOut's C are
 * close to orthonormal, so clusters compact there stay compact in every E. On FAUST (50 -> 100, step
 * 1, one thread) ZoomOut went from 2.6–3.0 s to 1.0–1.25 s CPU per pair with these and the frame
 * bound of nearest_neighbor.c, with bit-identical maps and C. */
#include "specseg/fmap.h"

#include <cblas.h>
#include <stdlib.h>
#include <string.h>

ss_status ss_zoomout(int n_S, int n_T, const double *evecs_S, const double *evecs_T, const double *M_T, int k0,
                     const double *C0, int kmax, int step, int *map, double *C_out, ss_error *err) {
  if (n_S < 1 || n_T < 1 || k0 < 1 || kmax < k0 || step < 1)
    return ss_fail(err, SS_ERR_INVALID, "zoomout: need 1 <= k0 <= kmax and step >= 1 (k0 %d, kmax %d, step %d)", k0,
                   kmax, step);
  double *C = malloc(sizeof(double) * (size_t)kmax * kmax), *E = malloc(sizeof(double) * (size_t)n_S * kmax);
  int *part = malloc(sizeof(int) * n_S);
  if (!C || !E || !part) {
    free(C); free(E); free(part);
    return ss_fail(err, SS_ERR_NOMEM, "zoomout: out of memory");
  }
  ss_status st = ss_nn_partition(n_S, kmax, evecs_S, n_S, 0, part, err);
  memcpy(C, C0, sizeof(double) * (size_t)k0 * k0);
  int k = k0;
  for (int it = 0; !st; it++) {
    /* point map of C (k x k): E = Φ_S Cᵀ, then each target row's nearest row of E, warm-started from
     * the previous map (guess and result may share the array) */
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, n_S, k, k, 1.0, evecs_S, n_S, C, k, 0.0, E, n_S);
    st = ss_nn_exact_guided(n_S, n_T, k, E, n_S, evecs_T, n_T, part, it > 0 ? map : NULL, map, NULL, err);
    if (st || k == kmax) break;
    k = k + step < kmax ? k + step : kmax;
    st = ss_fmap_from_p2p(n_S, n_T, k, k, evecs_S, evecs_T, M_T, map, C, err);
  }
  if (!st && C_out) memcpy(C_out, C, sizeof(double) * (size_t)k * k);
  free(C);
  free(E);
  free(part);
  return st;
}

ss_status ss_p2p_energy(int n_S, int n_T, const double *evals_S, const double *evals_T, const double *evecs_S,
                        const double *evecs_T, const double *M_T, const int *map, int k0, int K, int step, double w_lap,
                        double *E, double *E_orth, double *E_lap, ss_error *err) {
  if (n_S < 1 || n_T < 1 || k0 < 1 || K < k0 || step < 1 || !evals_S || !evals_T || !evecs_S || !evecs_T || !M_T ||
      !map || !E || !(w_lap >= 0))
    return ss_fail(err, SS_ERR_INVALID, "p2p energy: bad arguments (k0 %d, K %d, step %d)", k0, K, step);
  for (int y = 0; y < n_T; y++)
    if (map[y] < 0 || map[y] >= n_S) return ss_fail(err, SS_ERR_INVALID, "p2p energy: map[%d] = %d out of range", y, map[y]);
  double *C = malloc(sizeof(double) * (size_t)K * K), *G = malloc(sizeof(double) * (size_t)K * K);
  if (!C || !G) {
    free(C), free(G);
    return ss_fail(err, SS_ERR_NOMEM, "p2p energy: out of memory");
  }
  ss_status st = ss_fmap_from_p2p(n_S, n_T, K, K, evecs_S, evecs_T, M_T, map, C, err);
  double eo = 0, num = 0, den = 0;
  int ns = 0;
  if (!st) {
    /* G = C_kᵀ C_k (upper triangle) for each size, C_k the leading block of C: ~k³ flops a size,
     * negligible next to a point map */
    for (int k = k0;; k = k + step < K ? k + step : K) {
      cblas_dsyrk(CblasColMajor, CblasUpper, CblasTrans, k, k, 1.0, C, K, 0.0, G, K);
      double s = 0;
      for (int j = 0; j < k; j++)
        for (int i = 0; i <= j; i++) {
          double d = G[i + (size_t)K * j] - (i == j);
          s += (i == j ? 1.0 : 2.0) * d * d;
        }
      eo += s / k;
      ns++;
      if (k == K) break;
    }
    eo /= ns;
    for (int j = 0; j < K; j++)
      for (int i = 0; i < K; i++) {
        double c2 = C[i + (size_t)K * j] * C[i + (size_t)K * j], d = evals_T[i] - evals_S[j];
        num += c2 * d * d;
        den += c2 * (evals_T[i] * evals_T[i] + evals_S[j] * evals_S[j]);
      }
  }
  if (!st) {
    double el = den > 0 ? num / den : 0.0;
    *E = eo + w_lap * el;
    if (E_orth) *E_orth = eo;
    if (E_lap) *E_lap = el;
  }
  free(C), free(G);
  return st;
}

ss_status ss_p2p_descr_residual(int n_S, int n_T, const double *evecs_S, const double *evecs_T, const double *M_T,
                                const ss_fmap_probes *S, const ss_fmap_probes *T, const int *map, double *E,
                                ss_error *err) {
  if (n_S < 1 || n_T < 1 || !evecs_S || !evecs_T || !M_T || !S || !T || !S->A || !T->A || !map || !E || S->p != T->p ||
      S->p < 1 || S->k < 1 || T->k < 1)
    return ss_fail(err, SS_ERR_INVALID, "descriptor residual: bad arguments");
  for (int t = 0; t < n_T; t++)
    if (map[t] < 0 || map[t] >= n_S) return ss_fail(err, SS_ERR_INVALID, "descriptor residual: map[%d] = %d out of range", t, map[t]);
  const int p = S->p;
  double *FS = malloc(sizeof(double) * (size_t)n_S * p), *FT = malloc(sizeof(double) * (size_t)n_T * p);
  if (!FS || !FT) {
    free(FS), free(FT);
    return ss_fail(err, SS_ERR_NOMEM, "descriptor residual: out of memory");
  }
  cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n_S, p, S->k, 1.0, evecs_S, n_S, S->A, S->k, 0.0, FS, n_S);
  cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n_T, p, T->k, 1.0, evecs_T, n_T, T->A, T->k, 0.0, FT, n_T);
  double num = 0, den = 0;
  for (int j = 0; j < p; j++) {
    const double *fs = FS + (size_t)n_S * j, *ft = FT + (size_t)n_T * j;
    for (int t = 0; t < n_T; t++) {
      double d = ft[t] - fs[map[t]];
      num += M_T[t] * d * d;
      den += M_T[t] * ft[t] * ft[t];
    }
  }
  *E = den > 0 ? num / den : 0.0;
  free(FS), free(FT);
  return SS_OK;
}
