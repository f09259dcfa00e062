/* Cotangent stiffness and lumped mass: exact properties on flat grids and spheres. */
#include "specseg/laplacian.h"
#include "specseg/mesh.h"
#include "specseg/synth.h"
#include "testlib.h"

/* Irregular flat grid n x n on [0,1]^2 with jittered interior vertices. */
static void flat_grid(int n, ss_mesh *m) {
  ss_mesh_alloc(m, n * n, 2 * (n - 1) * (n - 1), NULL);
  unsigned s = 12345;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      double x = (double)i / (n - 1), y = (double)j / (n - 1);
      if (i > 0 && i < n - 1 && j > 0 && j < n - 1) {
        s = s * 1103515245u + 12345u; x += 0.3 / (n - 1) * ((s >> 8) / 16777216.0 - 0.5);
        s = s * 1103515245u + 12345u; y += 0.3 / (n - 1) * ((s >> 8) / 16777216.0 - 0.5);
      }
      double *p = m->V + 3 * (j * n + i);
      p[0] = x; p[1] = y; p[2] = 0;
    }
  int k = 0;
  for (int j = 0; j + 1 < n; j++)
    for (int i = 0; i + 1 < n; i++) {
      int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      int t[6] = {a, b, d, a, d, c};
      for (int q = 0; q < 6; q++) m->F[3 * k + q] = t[q];
      k += 2;
    }
}

int main(void) {
  ss_mesh m;
  flat_grid(12, &m);
  ss_sparse W;
  CHECK(ss_cotan_stiffness(&m, &W, NULL) == SS_OK);
  /* W applied to a linear function vanishes at interior vertices; rows sum to zero everywhere */
  double *f = malloc(sizeof(double) * m.nv), *g = malloc(sizeof(double) * m.nv);
  for (int i = 0; i < m.nv; i++) f[i] = 2.0 * m.V[3 * i] - 3.0 * m.V[3 * i + 1] + 0.5;
  ss_sparse_matvec(&W, f, g);
  double worst = 0;
  for (int j = 1; j < 11; j++)
    for (int i = 1; i < 11; i++) worst = fmax(worst, fabs(g[j * 12 + i]));
  CHECK_NEAR(worst, 0, 1e-12);
  for (int i = 0; i < m.nv; i++) f[i] = 1;
  ss_sparse_matvec(&W, f, g);
  worst = 0;
  for (int i = 0; i < m.nv; i++) worst = fmax(worst, fabs(g[i]));
  CHECK_NEAR(worst, 0, 1e-12);
  /* symmetric */
  int sym = 1;
  for (int j = 0; j < W.ncols; j++)
    for (int p = W.colptr[j]; p < W.colptr[j + 1]; p++) {
      int i = W.rowind[p], found = 0;
      for (int q = W.colptr[i]; q < W.colptr[i + 1]; q++)
        if (W.rowind[q] == j && fabs(W.val[q] - W.val[p]) < 1e-14) found = 1;
      sym &= found;
    }
  CHECK(sym);
  /* Dirichlet energy of x on the unit square is its area: f^T W f = 1 */
  for (int i = 0; i < m.nv; i++) f[i] = m.V[3 * i];
  ss_sparse_matvec(&W, f, g);
  double e = 0;
  for (int i = 0; i < m.nv; i++) e += f[i] * g[i];
  CHECK_NEAR(e, 1.0, 1e-12);
  /* mass sums to the area, both kinds, with boundary */
  double *M = malloc(sizeof(double) * m.nv);
  for (int kind = 0; kind < 2; kind++) {
    CHECK(ss_mass_lumped(&m, (ss_mass_kind)kind, M, NULL) == SS_OK);
    double s = 0;
    for (int i = 0; i < m.nv; i++) { s += M[i]; }
    CHECK_NEAR(s, ss_mesh_area(&m), 1e-12);
    CHECK_NEAR(s, 1.0, 1e-12);
  }
  ss_sparse_free(&W);
  free(M); free(f); free(g);
  ss_mesh_free(&m);

  /* sphere: area -> 4π, mass sums to area */
  ss_mesh s;
  CHECK(ss_synth_icosphere(4, &s, NULL) == SS_OK);
  CHECK(s.nv == 2562 && s.nf == 5120);
  CHECK_NEAR(ss_mesh_area(&s), 4 * M_PI, 0.02);
  M = malloc(sizeof(double) * s.nv);
  ss_mass_lumped(&s, SS_MASS_VORONOI, M, NULL);
  double sum = 0;
  for (int i = 0; i < s.nv; i++) sum += M[i];
  CHECK_NEAR(sum, ss_mesh_area(&s), 1e-10);
  free(M);
  ss_mesh_free(&s);

  /* invalid index -> error, not a crash */
  ss_mesh bad;
  ss_mesh_alloc(&bad, 3, 1, NULL);
  for (int i = 0; i < 9; i++) bad.V[i] = i;
  bad.F[0] = 0; bad.F[1] = 1; bad.F[2] = 7;
  ss_error err;
  CHECK(ss_cotan_stiffness(&bad, &W, &err) == SS_ERR_INVALID);
  ss_mesh_free(&bad);
  TEST_MAIN_END();
}
