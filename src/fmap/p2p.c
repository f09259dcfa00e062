/* The point map <-> functional map conversions. */
#include "specseg/fmap.h"

#include <cblas.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>


ss_status ss_fmap_p2p(int n_S, int n_T, int k_S, int k_T, const double *evecs_S, const double *evecs_T,
                      const double *C, int *map, ss_error *err) {
  if (n_S < 1 || n_T < 1 || k_S < 1 || k_T < 1) return ss_fail(err, SS_ERR_INVALID, "p2p: bad sizes");
  double *E = malloc(sizeof(double) * (size_t)n_S * k_T);
  if (!E) return ss_fail(err, SS_ERR_NOMEM, "p2p: out of memory");
  /* E = Φ_S Cᵀ: source deltas carried to the target basis */
  cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, n_S, k_T, k_S, 1.0, evecs_S, n_S, C, k_T, 0.0, E, n_S);
  ss_status st = ss_nn_exact(n_S, n_T, k_T, E, n_S, evecs_T, n_T, map, NULL, err);
  free(E);
  return st;
}

ss_status ss_fmap_from_p2p(int n_S, int n_T, int k_S, int k_T, const double *evecs_S, const double *evecs_T,
                           const double *M_T, const int *map, double *C, ss_error *err) {
  if (n_S < 1 || n_T < 1 || k_S < 1 || k_T < 1) return ss_fail(err, SS_ERR_INVALID, "p2p: bad sizes");
  for (int y = 0; y < n_T; y++)
    if (map[y] < 0 || map[y] >= n_S)
      return ss_fail(err, SS_ERR_INVALID, "point map: entry %d = %d out of range [0,%d)", y, map[y], n_S);
  double *G = malloc(sizeof(double) * (size_t)n_T * k_S);
  if (!G) return ss_fail(err, SS_ERR_NOMEM, "p2p: out of memory");
  /* G = M_T Π Φ_S, then C = Φ_Tᵀ G. The gather is serial: ~1 ms at FAUST size, less than what a
   * parallel region's barrier costs on a shared machine (ZoomOut calls this once per step) */
  for (int c = 0; c < k_S; c++)
    for (int y = 0; y < n_T; y++) G[y + (size_t)n_T * c] = M_T[y] * evecs_S[map[y] + (size_t)n_S * c];
  cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, k_T, k_S, n_T, 1.0, evecs_T, n_T, G, n_T, 0.0, C, k_T);
  free(G);
  return SS_OK;
}
