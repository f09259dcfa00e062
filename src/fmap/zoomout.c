/* ZoomOut (Melzi, Ren, Rodolà, Sharma, Wonka, Ovsjanikov 2019): spectral up-sampling of a functional
 * map by alternating its point map and the functional map of that point map, one size larger. */
#include "specseg/fmap.h"

#include <stdlib.h>
#include <string.h>

ss_status ss_zoomout(int n_S, int n_T, const double *evecs_S, const double *evecs_T, const double *M_T, int k0,
                     const double *C0, int kmax, int step, int *map, double *C_out, ss_error *err) {
  if (n_S < 1 || n_T < 1 || k0 < 1 || kmax < k0 || step < 1)
    return ss_fail(err, SS_ERR_INVALID, "zoomout: need 1 <= k0 <= kmax and step >= 1 (k0 %d, kmax %d, step %d)", k0,
                   kmax, step);
  double *C = malloc(sizeof(double) * (size_t)kmax * kmax);
  if (!C) return ss_fail(err, SS_ERR_NOMEM, "zoomout: out of memory");
  memcpy(C, C0, sizeof(double) * (size_t)k0 * k0);
  int k = k0;
  ss_status st = SS_OK;
  while (k < kmax) {
    st = ss_fmap_p2p(n_S, n_T, k, k, evecs_S, evecs_T, C, map, err);
    if (st) break;
    k = k + step < kmax ? k + step : kmax;
    st = ss_fmap_from_p2p(n_S, n_T, k, k, evecs_S, evecs_T, M_T, map, C, err);
    if (st) break;
  }
  if (!st) st = ss_fmap_p2p(n_S, n_T, k, k, evecs_S, evecs_T, C, map, err);
  if (!st && C_out) memcpy(C_out, C, sizeof(double) * (size_t)k * k);
  free(C);
  return st;
}
