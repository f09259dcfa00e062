/* Exact geodesic errors of many maps onto one target shape, each distinct (image, vertex) pair
 * queried once. The maps of one target (STD / ASA / DIFF of a pair, the landmark sets, the other
 * shapes matched to it) send most vertices to the same few images, so the union of their queries is
 * far smaller than the sum (the exact distance of a pair does not depend on which other pairs are
 * queried with it, so batching changes no bit of the result). */
#include "eval_internal.h"
#include "specseg/geodesic.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static int int_cmp(const void *a, const void *b) {
  int x = *(const int *)a, y = *(const int *)b;
  return (x > y) - (x < y);
}

ss_status ev_batch_errors(const ss_geodesic_mesh *gm, int nv, const int *sym, const int *gt, int nmaps,
                          const int *const *maps, double *sum, double *sum_sym, ss_error *err) {
  if (nmaps <= 0) return SS_OK;
  ss_status st = SS_OK;
  /* per vertex x: the sorted distinct images, at off[x] .. off[x+1) of img */
  size_t cap = (size_t)nv * nmaps;
  if (cap > INT_MAX) /* off[] and the geodesic queries count pairs in int */
    return ss_fail(err, SS_ERR_INVALID, "eval: %d maps of %d vertices: too many (image, vertex) pairs", nmaps, nv);
  int *off = malloc(sizeof(int) * ((size_t)nv + 1)), *img = malloc(sizeof(int) * cap), *tmp = malloc(sizeof(int) * nmaps);
  int *src = NULL, *dst = NULL, *dst2 = NULL;
  double *d = NULL, *ds = NULL;
  ss_geodesic_landmarks *acc = NULL; /* built by the first batch that has enough far pairs */
  if (!off || !img || !tmp) { st = ss_fail(err, SS_ERR_NOMEM, "eval: out of memory"); goto done; }
  size_t nq = 0;
  for (int x = 0; x < nv; x++) {
    off[x] = (int)nq;
    for (int r = 0; r < nmaps; r++) tmp[r] = maps[r][x];
    qsort(tmp, (size_t)nmaps, sizeof(int), int_cmp);
    for (int r = 0; r < nmaps; r++)
      if (r == 0 || tmp[r] != tmp[r - 1]) img[nq++] = tmp[r];
  }
  off[nv] = (int)nq;
  src = malloc(sizeof(int) * (nq > 0 ? nq : 1));
  dst = malloc(sizeof(int) * (nq > 0 ? nq : 1));
  dst2 = malloc(sizeof(int) * 2 * (nq > 0 ? nq : 1));
  d = malloc(sizeof(double) * (nq > 0 ? nq : 1));
  ds = malloc(sizeof(double) * (nq > 0 ? nq : 1));
  if (!src || !dst || !dst2 || !d || !ds) { st = ss_fail(err, SS_ERR_NOMEM, "eval: out of memory"); goto done; }
  /* d(image, x), grouped by image (as ss_geodesic_pairs does) */
  for (int x = 0; x < nv; x++)
    for (int q = off[x]; q < off[x + 1]; q++) src[q] = img[q], dst[q] = gt ? gt[x] : x;
  if ((st = ss_geodesic_pairs(gm, &acc, src, dst, (int)nq, d, err))) goto done;
  /* symmetric error min(d(image, x), d(image, sym x)): when a lower bound on d(image, sym x) (straight
   * distance, landmark fields) already exceeds d(image, x), the minimum is d(image, x) (a good map's
   * every vertex, a bad map's many); otherwise one query from the image stopping at the nearer */
  size_t nn = 0;
  for (int x = 0; x < nv; x++) {
    const int t = gt ? gt[x] : x;
    for (int q = off[x]; q < off[x + 1]; q++) {
      if (ss_geodesic_lower_bound(gm, acc, img[q], sym[t]) > d[q] * (1 + 1e-9)) {
        ds[q] = d[q];
        continue;
      }
      src[nn] = img[q], dst[nn] = q; /* dst: where the answer goes */
      dst2[2 * nn] = t, dst2[2 * nn + 1] = sym[t];
      nn++;
    }
  }
  if (nn > 0) {
    double *dn = malloc(sizeof(double) * nn);
    if (!dn) { st = ss_fail(err, SS_ERR_NOMEM, "eval: out of memory"); goto done; }
    if ((st = ss_geodesic_nearest_of(gm, &acc, src, dst2, 2, (int)nn, dn, err))) { free(dn); goto done; }
    for (size_t i = 0; i < nn; i++) ds[dst[i]] = dn[i];
    free(dn);
  }
  for (int r = 0; r < nmaps; r++) {
    double s = 0, s2 = 0;
    for (int x = 0; x < nv; x++) {
      int p = maps[r][x], lo = off[x], hi = off[x + 1];
      while (hi - lo > 1) { /* img[lo..hi) sorted, contains p */
        int mid = (lo + hi) / 2;
        if (img[mid] <= p) lo = mid;
        else hi = mid;
      }
      s += d[lo], s2 += ds[lo];
    }
    sum[r] = s, sum_sym[r] = s2;
  }
done:
  ss_geodesic_landmarks_free(acc);
  free(off), free(img), free(tmp), free(src), free(dst), free(dst2), free(d), free(ds);
  return st;
}
