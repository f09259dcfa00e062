/* Synthetic meshes with closed-form geodesics, shared by the geodesic tests. */
#ifndef SS_TEST_GEODESIC_MESHES_H
#define SS_TEST_GEODESIC_MESHES_H

#include <math.h>
#include <stdlib.h>

#include "specseg/core.h"

static unsigned gm_rng_state __attribute__((unused)) = 2463534242u;
static inline double gm_rand(void) { /* xorshift32 in [0,1) */
  gm_rng_state ^= gm_rng_state << 13; gm_rng_state ^= gm_rng_state >> 17; gm_rng_state ^= gm_rng_state << 5;
  return (gm_rng_state >> 8) / 16777216.0;
}

/* nx x ny grid on [0,w]x[0,h], interior vertices jittered by `jit` of a cell, diagonals chosen at
 * random (so there are many obtuse triangles when jit is large). Vertex (i,j) = j*nx+i. */
static inline void gm_flat_grid(int nx, int ny, double w, double h, double jit, ss_mesh *m) {
  ss_mesh_alloc(m, nx * ny, 2 * (nx - 1) * (ny - 1), NULL);
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++) {
      double x = w * i / (nx - 1), y = h * j / (ny - 1);
      if (i > 0 && i < nx - 1 && j > 0 && j < ny - 1) {
        x += jit * w / (nx - 1) * (gm_rand() - 0.5);
        y += jit * h / (ny - 1) * (gm_rand() - 0.5);
      }
      double *p = m->V + 3 * (j * nx + i);
      p[0] = x; p[1] = y; p[2] = 0;
    }
  int k = 0;
  for (int j = 0; j + 1 < ny; j++)
    for (int i = 0; i + 1 < nx; i++) {
      int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      int t1[6] = {a, b, d, a, d, c}, t2[6] = {a, b, c, b, d, c};
      const int *t = gm_rand() < 0.5 ? t1 : t2;
      for (int q = 0; q < 6; q++) m->F[3 * k + q] = t[q];
      k += 2;
    }
}

/* Map a flat grid built on [0, 2*pi*r) x [0,H] (nx columns, last column excluded) onto an open
 * cylinder of radius r: column nx wraps to column 0. */
static inline void gm_cylinder(int nu, int nz, double r, double H, ss_mesh *m) {
  ss_mesh_alloc(m, nu * nz, 2 * nu * (nz - 1), NULL);
  for (int j = 0; j < nz; j++)
    for (int i = 0; i < nu; i++) {
      double t = 2 * M_PI * i / nu;
      double *p = m->V + 3 * (j * nu + i);
      p[0] = r * cos(t); p[1] = r * sin(t); p[2] = H * j / (nz - 1);
    }
  int k = 0;
  for (int j = 0; j + 1 < nz; j++)
    for (int i = 0; i < nu; i++) {
      int a = j * nu + i, b = j * nu + (i + 1) % nu, c = a + nu, d = b + nu;
      int t[6] = {a, b, d, a, d, c};
      for (int q = 0; q < 6; q++) m->F[3 * k + q] = t[q];
      k += 2;
    }
}

/* Polyhedral cone without its apex: nu generators at half-opening psi, nr rings at slant distances
 * rho0 + j*dr. Each strip between two generators is planar, so the surface unrolls to an annular
 * sector of total angle nu*beta; (*beta) receives the angle between neighbouring generators. */
static inline void gm_cone(int nu, int nr, double psi, double rho0, double dr, ss_mesh *m, double *beta) {
  ss_mesh_alloc(m, nu * nr, 2 * nu * (nr - 1), NULL);
  for (int j = 0; j < nr; j++)
    for (int i = 0; i < nu; i++) {
      double t = 2 * M_PI * i / nu, rho = rho0 + j * dr;
      double *p = m->V + 3 * (j * nu + i);
      p[0] = rho * sin(psi) * cos(t); p[1] = rho * sin(psi) * sin(t); p[2] = -rho * cos(psi);
    }
  double g0[3] = {sin(psi), 0, -cos(psi)}, g1[3] = {sin(psi) * cos(2 * M_PI / nu), sin(psi) * sin(2 * M_PI / nu), -cos(psi)};
  *beta = acos(g0[0] * g1[0] + g0[1] * g1[1] + g0[2] * g1[2]);
  int k = 0;
  for (int j = 0; j + 1 < nr; j++)
    for (int i = 0; i < nu; i++) {
      int a = j * nu + i, b = j * nu + (i + 1) % nu, c = a + nu, d = b + nu;
      int t[6] = {a, d, b, a, c, d};
      for (int q = 0; q < 6; q++) m->F[3 * k + q] = t[q];
      k += 2;
    }
}

#endif
