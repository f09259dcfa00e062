/* Torus of revolution about the z axis: centre-line radius R, tube radius r, nu samples around the
 * axis and nv around the tube; nu*nv vertices, 2*nu*nv triangles, outward-oriented, genus 1.
 * Each quad is split along alternating diagonals (checkerboard) so the triangulation has no
 * preferred direction. */
#include "specseg/synth.h"

#include <math.h>
#include <string.h>

ss_status ss_synth_torus(double R, double r, int nu, int nv, ss_mesh *m, ss_error *err) {
  memset(m, 0, sizeof *m);
  if (!(r > 0) || !(R > r) || !isfinite(R))
    return ss_fail(err, SS_ERR_INVALID, "torus needs 0 < r < R (got R=%g, r=%g)", R, r);
  if (nu < 3 || nv < 3 || nu > 100000 || nv > 100000 || (long long)nu * nv > 50000000LL)
    return ss_fail(err, SS_ERR_INVALID, "torus resolution %d x %d outside [3, 100000] (and at most 5e7 vertices)",
                   nu, nv);
  ss_status st = ss_mesh_alloc(m, nu * nv, 2 * nu * nv, err);
  if (st) return st;
  for (int i = 0; i < nu; i++) {
    double u = 2 * M_PI * i / nu;
    for (int j = 0; j < nv; j++) {
      double v = 2 * M_PI * j / nv;
      double *p = m->V + 3 * ((size_t)i * nv + j);
      p[0] = (R + r * cos(v)) * cos(u);
      p[1] = (R + r * cos(v)) * sin(u);
      p[2] = r * sin(v);
    }
  }
  int *F = m->F;
  for (int i = 0; i < nu; i++) {
    int i1 = (i + 1) % nu;
    for (int j = 0; j < nv; j++) {
      int j1 = (j + 1) % nv;
      int a = i * nv + j, b = i1 * nv + j, c = i1 * nv + j1, d = i * nv + j1;
      /* (u, v) is a right-handed chart with the outward normal (d/du x d/dv points out) */
      if ((i + j) & 1) {
        F[0] = a; F[1] = b; F[2] = c;
        F[3] = a; F[4] = c; F[5] = d;
      } else {
        F[0] = a; F[1] = b; F[2] = d;
        F[3] = b; F[4] = c; F[5] = d;
      }
      F += 6;
    }
  }
  return SS_OK;
}
