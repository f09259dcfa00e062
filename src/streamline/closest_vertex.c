/* Ψ: nearest target vertex of each query point, on a uniform grid (about two vertices per cell).
 * Cells are searched in growing Chebyshev shells around the query's (clamped) cell; a shell r+1
 * cannot hold anything closer than r·h, which ends the search exactly. */
#include "specseg/streamline.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

ss_status ss_closest_vertices(const double *P, int np, const ss_mesh *target, int *out, ss_error *err) {
  if (np < 0 || (np > 0 && (!P || !out))) return ss_fail(err, SS_ERR_INVALID, "closest vertices: bad query arguments");
  if (!target || target->nv <= 0) return ss_fail(err, SS_ERR_INVALID, "closest vertices: empty target mesh");
  const int n = target->nv;
  const double *V = target->V;
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) {
      double x = V[3 * i + k];
      if (!isfinite(x)) return ss_fail(err, SS_ERR_INVALID, "closest vertices: target vertex %d is not finite", i);
      if (x < lo[k]) lo[k] = x;
      if (x > hi[k]) hi[k] = x;
    }
  for (int i = 0; i < 3 * np; i++)
    if (!isfinite(P[i])) return ss_fail(err, SS_ERR_INVALID, "closest vertices: query point %d is not finite", i / 3);
  /* cell size: ~2 points per cell if they filled the box; surfaces fill far less, so use the area
   * proxy of the box's largest face pair instead of its volume */
  double ext[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
  double emax = fmax(ext[0], fmax(ext[1], ext[2]));
  if (!(emax > 0)) emax = 1;
  double surf = ext[0] * ext[1] + ext[1] * ext[2] + ext[0] * ext[2];
  double h = surf > 0 ? sqrt(2.0 * surf / n) : emax / cbrt((double)n);
  if (!(h > 0)) h = emax;
  int dim[3];
  size_t ncell = 1;
  for (int k = 0; k < 3; k++) {
    double d = floor(ext[k] / h) + 1;
    if (d > 1024) d = 1024;
    dim[k] = (int)d;
    ncell *= (size_t)dim[k];
  }
  while (ncell > (size_t)8 * n + 64) { /* keep memory proportional to n */
    h *= 1.5;
    ncell = 1;
    for (int k = 0; k < 3; k++) {
      double d = floor(ext[k] / h) + 1;
      if (d > 1024) d = 1024;
      dim[k] = (int)d;
      ncell *= (size_t)dim[k];
    }
  }
  int *start = calloc(ncell + 1, sizeof(int)), *items = malloc(sizeof(int) * (size_t)n), *cellof = malloc(sizeof(int) * (size_t)n);
  if (!start || !items || !cellof) { free(start); free(items); free(cellof); return ss_fail(err, SS_ERR_NOMEM, "closest vertices: out of memory"); }
  for (int i = 0; i < n; i++) {
    int c[3];
    for (int k = 0; k < 3; k++) {
      int x = (int)((V[3 * i + k] - lo[k]) / h);
      c[k] = x < 0 ? 0 : x >= dim[k] ? dim[k] - 1 : x;
    }
    cellof[i] = (c[2] * dim[1] + c[1]) * dim[0] + c[0];
    start[cellof[i] + 1]++;
  }
  for (size_t c = 0; c < ncell; c++) start[c + 1] += start[c];
  {
    int *pos = malloc(sizeof(int) * ncell);
    if (!pos) { free(start); free(items); free(cellof); return ss_fail(err, SS_ERR_NOMEM, "closest vertices: out of memory"); }
    memcpy(pos, start, sizeof(int) * ncell);
    for (int i = 0; i < n; i++) items[pos[cellof[i]]++] = i; /* ascending index within a cell */
    free(pos);
  }
  free(cellof);
  const int rmax = dim[0] > dim[1] ? (dim[0] > dim[2] ? dim[0] : dim[2]) : (dim[1] > dim[2] ? dim[1] : dim[2]);

  #pragma omp parallel for schedule(dynamic, 256) if (np > 50000) /* cheaper than waking threads below that */
  for (int q = 0; q < np; q++) {
    const double *p = P + 3 * q;
    int c[3];
    for (int k = 0; k < 3; k++) {
      double x = floor((p[k] - lo[k]) / h);
      c[k] = x < 0 ? 0 : x >= dim[k] ? dim[k] - 1 : (int)x;
    }
    double best = INFINITY;
    int bi = -1;
    for (int r = 0; r <= rmax; r++) {
      /* every point in shell r+1 or beyond is at least r·h away */
      for (int z = c[2] - r; z <= c[2] + r; z++) {
        if (z < 0 || z >= dim[2]) continue;
        int dz = abs(z - c[2]);
        for (int y = c[1] - r; y <= c[1] + r; y++) {
          if (y < 0 || y >= dim[1]) continue;
          int dy = abs(y - c[1]);
          int onface = dz == r || dy == r;
          for (int x = c[0] - r; x <= c[0] + r; x += (onface ? 1 : (2 * r > 0 ? 2 * r : 1))) {
            if (x < 0 || x >= dim[0]) continue;
            size_t cell = ((size_t)z * dim[1] + y) * dim[0] + x;
            for (int s = start[cell]; s < start[cell + 1]; s++) {
              int i = items[s];
              double dx = V[3 * i] - p[0], dy2 = V[3 * i + 1] - p[1], dz2 = V[3 * i + 2] - p[2];
              double d = dx * dx + dy2 * dy2 + dz2 * dz2;
              if (d < best || (d == best && i < bi)) { best = d; bi = i; }
            }
          }
        }
      }
      if (bi >= 0 && best < (double)r * h * (double)r * h) break;
    }
    out[q] = bi;
  }
  free(start);
  free(items);
  return SS_OK;
}
