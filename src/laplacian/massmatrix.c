/* Lumped mass matrix: barycentric or mixed Voronoi (Meyer, Desbrun, Schröder, Barr 2003). */
#include "specseg/laplacian.h"

#include "mesh/mesh_geometry.h"

#include <math.h>
#include <string.h>

ss_status ss_mass_lumped(const ss_mesh *m, ss_mass_kind kind, double *M, ss_error *err) {
  ss_status st = ssi_mesh_check_coordinates(m, "mass matrix", err);
  if (st) return st;
  memset(M, 0, sizeof(double) * (size_t)m->nv);
  for (int f = 0; f < m->nf; f++) {
    const int *t = m->F + 3 * f;
    for (int c = 0; c < 3; c++)
      if (t[c] < 0 || t[c] >= m->nv)
        return ss_fail(err, SS_ERR_INVALID, "face %d has vertex index %d out of range [0,%d)", f, t[c], m->nv);
    const double *p[3] = {m->V + 3 * t[0], m->V + 3 * t[1], m->V + 3 * t[2]};
    double e[3][3], l2[3];
    for (int c = 0; c < 3; c++) { /* e[c] = edge opposite corner c */
      for (int d = 0; d < 3; d++) e[c][d] = p[(c + 2) % 3][d] - p[(c + 1) % 3][d];
      l2[c] = e[c][0] * e[c][0] + e[c][1] * e[c][1] + e[c][2] * e[c][2];
    }
    double cx = e[0][1] * e[1][2] - e[0][2] * e[1][1], cy = e[0][2] * e[1][0] - e[0][0] * e[1][2],
           cz = e[0][0] * e[1][1] - e[0][1] * e[1][0];
    double area = 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
    if (!(area > 0)) continue;
    if (kind == SS_MASS_BARYCENTRIC) {
      for (int c = 0; c < 3; c++) M[t[c]] += area / 3.0;
      continue;
    }
    /* mixed Voronoi: obtuse triangles give half their area to the obtuse corner, a quarter to others */
    int obtuse = -1;
    for (int c = 0; c < 3; c++)
      if (l2[c] > l2[(c + 1) % 3] + l2[(c + 2) % 3]) obtuse = c;
    if (obtuse >= 0) {
      for (int c = 0; c < 3; c++) M[t[c]] += (c == obtuse ? 0.5 : 0.25) * area;
    } else {
      /* cot of angle at corner c = (l_a^2 + l_b^2 - l_c^2) / (4 area) */
      for (int c = 0; c < 3; c++) {
        double cot = (l2[(c + 1) % 3] + l2[(c + 2) % 3] - l2[c]) / (4.0 * area);
        /* the edge opposite c contributes cot_c * |e_c|^2 / 8 to each of its two endpoints */
        double a = cot * l2[c] / 8.0;
        M[t[(c + 1) % 3]] += a;
        M[t[(c + 2) % 3]] += a;
      }
    }
  }
  return SS_OK;
}
