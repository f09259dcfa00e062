/* The automatic up axis of `specseg render` (rule in render.h): the axis along which a shape has a
 * wide "base" of lowest vertices, as feet or paws standing on a floor. */
#include "specseg/render.h"

#include <math.h>

/* Base spread of m along each axis (see render.h); 0 when m has no finite vertex. ext: the extents. */
static int base_spread(const ss_mesh *m, double spread[3], double ext[3]) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  int any = 0;
  for (int i = 0; i < m->nv; i++) {
    const double *p = m->V + 3 * (size_t)i;
    if (!(isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]))) continue;
    any = 1;
    for (int d = 0; d < 3; d++) {
      if (p[d] < lo[d]) lo[d] = p[d];
      if (p[d] > hi[d]) hi[d] = p[d];
    }
  }
  if (!any) return 0;
  for (int d = 0; d < 3; d++) ext[d] = hi[d] - lo[d];
  for (int a = 0; a < 3; a++) {
    int b = (a + 1) % 3, c = (a + 2) % 3;
    double blo = INFINITY, bhi = -INFINITY, clo = INFINITY, chi = -INFINITY, band = 0.01 * ext[a];
    for (int i = 0; i < m->nv; i++) {
      const double *p = m->V + 3 * (size_t)i;
      if (!(isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2])) || p[a] - lo[a] > band) continue;
      if (p[b] < blo) blo = p[b];
      if (p[b] > bhi) bhi = p[b];
      if (p[c] < clo) clo = p[c];
      if (p[c] > chi) chi = p[c];
    }
    double box = ext[b] * ext[c];
    spread[a] = box > 0 && bhi >= blo ? (bhi - blo) * (chi - clo) / box : 0;
  }
  return 1;
}

ss_up_axis ss_render_guess_up(const ss_mesh *const *meshes, int n) {
  double sum[3] = {0, 0, 0}, first[3] = {0, 0, 0};
  int used = 0;
  for (int k = 0; meshes && k < n; k++) {
    const ss_mesh *m = meshes[k];
    double s[3], e[3];
    if (!m || m->nv <= 0 || !m->V || !base_spread(m, s, e)) continue;
    if (!used)
      for (int d = 0; d < 3; d++) first[d] = e[d];
    for (int d = 0; d < 3; d++) sum[d] += s[d];
    used++;
  }
  if (!used) return SS_UP_Y;
  int best = 0;
  for (int d = 1; d < 3; d++)
    if (sum[d] > sum[best]) best = d;
  if (sum[best] / used >= 0.05) return (ss_up_axis)(best + 1);
  int z_shortest = first[2] <= first[0] && first[2] <= first[1];
  return z_shortest ? SS_UP_Y : SS_UP_Z;
}
