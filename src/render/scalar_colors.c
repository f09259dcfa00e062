/* Per-vertex colours of a scalar field through a colormap (fields, distance maps, map errors). */
#include "specseg/render.h"

#include <math.h>

void ss_scalar_colors(const double *v, int n, ss_colormap_kind kind, double lo, double hi, unsigned char *rgb) {
  for (int i = 0; i < n; i++) {
    unsigned char *c = rgb + 3 * (size_t)i;
    if (!isfinite(v[i])) c[0] = c[1] = c[2] = 150; /* unreached / undefined */
    else ss_colormap_kind_rgb(kind, hi > lo ? (v[i] - lo) / (hi - lo) : 0, c);
  }
}
