#include "specseg/core.h"
#include "mesh/mesh_geometry.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

ss_status ss_mesh_alloc(ss_mesh *m, int nv, int nf, ss_error *err) {
  memset(m, 0, sizeof *m);
  if (nv < 0 || nf < 0) return ss_fail(err, SS_ERR_INVALID, "negative mesh size (%d vertices, %d faces)", nv, nf);
  m->V = malloc(sizeof(double) * 3 * (size_t)(nv > 0 ? nv : 1));
  m->F = malloc(sizeof(int) * 3 * (size_t)(nf > 0 ? nf : 1));
  if (!m->V || !m->F) {
    ss_mesh_free(m);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory for a mesh of %d vertices, %d faces", nv, nf);
  }
  m->nv = nv;
  m->nf = nf;
  return SS_OK;
}

ss_status ss_mesh_copy(const ss_mesh *src, ss_mesh *dst, ss_error *err) {
  ss_status st = ss_mesh_alloc(dst, src->nv, src->nf, err);
  if (st) return st;
  memcpy(dst->V, src->V, sizeof(double) * 3 * (size_t)src->nv);
  memcpy(dst->F, src->F, sizeof(int) * 3 * (size_t)src->nf);
  return SS_OK;
}

void ss_mesh_free(ss_mesh *m) {
  if (!m) return;
  free(m->V);
  free(m->F);
  memset(m, 0, sizeof *m);
}

double ss_mesh_area(const ss_mesh *m) {
  double a = 0;
  for (int f = 0; f < m->nf; f++)
    a += ssi_triangle_area(m->V + 3 * m->F[3 * f], m->V + 3 * m->F[3 * f + 1], m->V + 3 * m->F[3 * f + 2]);
  return a;
}

double ss_mesh_bbox_diagonal(const ss_mesh *m) {
  if (m->nv == 0) return 0;
  double lo[3], hi[3];
  for (int d = 0; d < 3; d++) lo[d] = hi[d] = m->V[d];
  for (int i = 1; i < m->nv; i++)
    for (int d = 0; d < 3; d++) {
      double x = m->V[3 * i + d];
      if (x < lo[d]) lo[d] = x;
      if (x > hi[d]) hi[d] = x;
    }
  return ssi_box_diagonal(lo, hi);
}
