/* Coherency of a segmentation with a reference segmentation (paper §5). */
#include "specseg/segment.h"

ss_status ss_coherency(const int *labels0, int nv0, const int *labels, const int *centers, int m, int nv,
                       const int *gt, double *coherency, ss_error *err) {
  if (!coherency) return ss_fail(err, SS_ERR_INVALID, "coherency: NULL output");
  *coherency = 0;
  if (nv <= 0 || nv0 <= 0 || m <= 0 || !labels0 || !labels || !centers)
    return ss_fail(err, SS_ERR_INVALID, "coherency: empty input (%d vertices, %d reference vertices, %d segments)",
                   nv, nv0, m);
  if (!gt && nv != nv0)
    return ss_fail(err, SS_ERR_INVALID, "coherency: identity map needs equal vertex counts (%d vs %d)", nv, nv0);
  for (int s = 0; s < m; s++)
    if (centers[s] < 0 || centers[s] >= nv)
      return ss_fail(err, SS_ERR_INVALID, "coherency: centre %d is vertex %d, shape has %d", s, centers[s], nv);
  long pass = 0;
  for (int y = 0; y < nv; y++) {
    int s = labels[y];
    if (s < 0 || s >= m) return ss_fail(err, SS_ERR_INVALID, "coherency: label %d of vertex %d is not in [0,%d)", s, y, m);
    int u = centers[s];
    int gy = gt ? gt[y] : y, gu = gt ? gt[u] : u;
    if (gy < 0 || gy >= nv0 || gu < 0 || gu >= nv0)
      return ss_fail(err, SS_ERR_INVALID, "coherency: map sends vertex %d or %d outside [0,%d)", y, u, nv0);
    pass += labels0[gy] == labels0[gu];
  }
  *coherency = (double)pass / nv;
  return SS_OK;
}
