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
