/* Geodesic error of a point map, plain and symmetric (paper §6, "sym" rows of Table 1). */
#include "specseg/fmap.h"
#include "specseg/geodesic.h"

#include <math.h>
#include <stdlib.h>

ss_status ss_map_geodesic_error(const ss_mesh *Y, int nX, const int *map, const int *gt, const int *sym,
                                double *errors, double *mean, ss_error *err) {
  if (!Y || !map || nX < 1) return ss_fail(err, SS_ERR_INVALID, "map error: empty map");
  const int nY = Y->nv;
  for (int x = 0; x < nX; x++) {
    if (map[x] < 0 || map[x] >= nY)
      return ss_fail(err, SS_ERR_INVALID, "map line %d: vertex %d not on the target (%d vertices)", x + 1, map[x], nY);
    int g = gt ? gt[x] : x;
    if (g < 0 || g >= nY)
      return ss_fail(err, SS_ERR_INVALID, "ground truth line %d: vertex %d not on the target (%d vertices)", x + 1, g,
                     nY);
    if (sym && (sym[x] < 0 || sym[x] >= nX))
      return ss_fail(err, SS_ERR_INVALID, "symmetry line %d: vertex %d not on the source (%d vertices)", x + 1, sym[x],
                     nX);
  }
  double area = ss_mesh_area(Y);
  if (!(area > 0)) return ss_fail(err, SS_ERR_INVALID, "map error: target has zero area");
  int k = sym ? 2 : 1;
  int *src = malloc(sizeof(int) * (size_t)nX), *dst = malloc(sizeof(int) * (size_t)nX * k);
  double *d = malloc(sizeof(double) * (size_t)nX);
  ss_geodesic_mesh *gm = NULL;
  ss_geodesic_landmarks *acc = NULL;
  ss_status st = SS_OK;
  if (!src || !dst || !d) { st = ss_fail(err, SS_ERR_NOMEM, "map error: out of memory"); goto done; }
  /* sources are the estimated images; with a symmetry map each query stops at the nearer of the
   * ground-truth image and its mirror, so a left-right flip costs no far propagation */
  for (int x = 0; x < nX; x++) {
    src[x] = map[x];
    dst[k * x] = gt ? gt[x] : x;
    if (sym) dst[k * x + 1] = gt ? gt[sym[x]] : sym[x];
  }
  if ((st = ss_geodesic_mesh_build(Y, &gm, err))) goto done;
  if ((st = ss_geodesic_nearest_of(gm, &acc, src, dst, k, nX, d, err))) goto done;
  double s = 0, scale = 1.0 / sqrt(area);
  for (int x = 0; x < nX; x++) {
    double e = d[x] * scale;
    if (errors) errors[x] = e;
    s += e;
  }
  *mean = s / nX;
done:
  ss_geodesic_landmarks_free(acc);
  if (gm) ss_geodesic_mesh_free(gm);
  free(src);
  free(dst);
  free(d);
  return st;
}
