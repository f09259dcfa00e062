/* Colours that show a point map: a smooth colouring of the target by its coordinates and its
 * pull-back to the source through the map (colour transfer, the top rows of the paper's Figures 9–11). */
#include "specseg/render.h"

#include <math.h>
#include <string.h>

void ss_coordinate_colors(const ss_mesh *m, unsigned char *rgb) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int i = 0; i < m->nv; i++)
    for (int d = 0; d < 3; d++) {
      double v = m->V[3 * (size_t)i + d];
      if (v < lo[d]) lo[d] = v;
      if (v > hi[d]) hi[d] = v;
    }
  for (int i = 0; i < m->nv; i++)
    for (int d = 0; d < 3; d++) {
      double v = m->V[3 * (size_t)i + d];
      double t = hi[d] > lo[d] && isfinite(v) ? (v - lo[d]) / (hi[d] - lo[d]) : 0.5;
      /* away from black and white, so shading and the white background stay readable */
      rgb[3 * (size_t)i + d] = (unsigned char)lround(255 * (0.12 + 0.85 * t));
    }
}

ss_status ss_map_transfer_colors(int nx, const int *map, int ny, const unsigned char *target_rgb, unsigned char *out,
                                 ss_error *err) {
  if (nx < 0 || (nx > 0 && (!map || !target_rgb || !out)))
    return ss_fail(err, SS_ERR_INVALID, "map colours: NULL argument");
  for (int i = 0; i < nx; i++) {
    if (map[i] < 0 || map[i] >= ny)
      return ss_fail(err, SS_ERR_INVALID, "map line %d: vertex %d not on the target (%d vertices)", i + 1, map[i], ny);
    memcpy(out + 3 * (size_t)i, target_rgb + 3 * (size_t)map[i], 3);
  }
  return SS_OK;
}

void ss_coordinate_pattern_colors(const ss_mesh *m, double period, unsigned char *rgb) {
  ss_coordinate_colors(m, rgb);
  double p = period * ss_mesh_bbox_diagonal(m);
  if (!(p > 0) || !isfinite(p)) return;
  const double w = 2 * M_PI / p;
  for (int i = 0; i < m->nv; i++) {
    const double *v = m->V + 3 * (size_t)i;
    /* a smooth 3-D checker: the sign pattern of sin·sin·sin, softened; darkens half the cells */
    double s = sin(w * v[0]) * sin(w * v[1]) * sin(w * v[2]);
    double f = 1 - 0.35 * (0.5 + 0.5 * tanh(6 * s));
    for (int d = 0; d < 3; d++) rgb[3 * (size_t)i + d] = (unsigned char)lround(f * rgb[3 * (size_t)i + d]);
  }
}
