/* Cotangent stiffness matrix (P1 finite elements). */
#include "specseg/laplacian.h"

#include "mesh/mesh_geometry.h"

#include <math.h>
#include <stdlib.h>

ss_status ss_cotan_stiffness(const ss_mesh *m, ss_sparse *W, ss_error *err) {
  ss_status st0 = ssi_mesh_check_coordinates(m, "laplacian", err);
  if (st0) return st0;
  size_t cap = (size_t)m->nf * 12;
  int *I = malloc(sizeof(int) * (cap ? cap : 1)), *J = malloc(sizeof(int) * (cap ? cap : 1));
  double *X = malloc(sizeof(double) * (cap ? cap : 1));
  if (!I || !J || !X) {
    free(I); free(J); free(X);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory building the cotangent matrix");
  }
  size_t k = 0;
  for (int f = 0; f < m->nf; f++) {
    const int *t = m->F + 3 * f;
    for (int c = 0; c < 3; c++) {
      if (t[c] < 0 || t[c] >= m->nv) {
        free(I); free(J); free(X);
        return ss_fail(err, SS_ERR_INVALID, "face %d has vertex index %d out of range [0,%d)", f, t[c], m->nv);
      }
    }
    for (int c = 0; c < 3; c++) {
      /* the corner c is opposite the edge (a,b) */
      int o = t[c], a = t[(c + 1) % 3], b = t[(c + 2) % 3];
      const double *po = m->V + 3 * o, *pa = m->V + 3 * a, *pb = m->V + 3 * b;
      double u[3] = {pa[0] - po[0], pa[1] - po[1], pa[2] - po[2]};
      double v[3] = {pb[0] - po[0], pb[1] - po[1], pb[2] - po[2]};
      double dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
      double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2], cz = u[0] * v[1] - u[1] * v[0];
      double cr = sqrt(cx * cx + cy * cy + cz * cz);
      if (!(cr > 0) || !isfinite(dot)) continue; /* degenerate face: no contribution */
      double w = 0.5 * dot / cr;                  /* cot(angle at o) / 2 */
      I[k] = a; J[k] = b; X[k++] = -w;
      I[k] = b; J[k] = a; X[k++] = -w;
      I[k] = a; J[k] = a; X[k++] = w;
      I[k] = b; J[k] = b; X[k++] = w;
    }
  }
  ss_status st = ss_sparse_from_triplets(m->nv, m->nv, k, I, J, X, W, err);
  free(I); free(J); free(X);
  return st;
}
