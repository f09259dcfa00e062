/* HKS (ss_hks_filters, ss_hks): the times (log-spaced from 4 ln 10 / λ_max to 4 ln 10 / λ_min), the
 * filters, the descriptors against a direct sum Σ_i exp(−λ_i t) φ_i(x)² normalised in L²(M), the
 * constant function left out, invariance under a rigid motion, and the refusals. */
#include "specseg/fmap.h"
#include "specseg/laplacian.h"
#include "specseg/spectrum.h"
#include "specseg/synth.h"
#include "testlib.h"

int main(void) {
  ss_error e;
  ss_mesh m = {0};
  CHECK(ss_synth_torus(1.0, 0.4, 24, 12, &m, &e) == SS_OK);
  const int n = m.nv, k = 20, nt = 16;
  double *ev = malloc(sizeof(double) * k), *phi = malloc(sizeof(double) * (size_t)n * k), *M = malloc(sizeof(double) * n);
  double *G = malloc(sizeof(double) * nt * k), *t = malloc(sizeof(double) * nt), *D = malloc(sizeof(double) * (size_t)n * nt);
  CHECK(ss_mesh_eigs(&m, k, ev, phi, &e) == SS_OK);
  CHECK(ss_mass_lumped(&m, SS_MASS_BARYCENTRIC, M, &e) == SS_OK);

  CHECK(ss_hks_filters(ev, k, nt, G, t, &e) == SS_OK);
  double lmin = ev[1], lmax = ev[k - 1];
  CHECK_NEAR(t[0], 4 * log(10.0) / lmax, 1e-12 * t[0]);
  CHECK_NEAR(t[nt - 1], 4 * log(10.0) / lmin, 1e-12 * t[nt - 1]);
  int ascending = 1, logspaced = 1;
  for (int j = 1; j < nt; j++) {
    ascending &= t[j] > t[j - 1];
    logspaced &= fabs(log(t[j] / t[j - 1]) - log(t[1] / t[0])) < 1e-12;
  }
  CHECK(ascending && logspaced);
  CHECK(G[0] == 0 && G[nt - 1] == 0); /* λ_0 = 0: the constant is filtered out */
  CHECK_NEAR(G[0 + (size_t)nt * (k - 1)], 1e-4, 1e-12);        /* e^{-λmax t_0} */
  CHECK_NEAR(G[nt - 1 + (size_t)nt * 1], 1e-4, 1e-12);         /* e^{-λ1 t_last} */

  CHECK(ss_hks(n, k, ev, phi, M, nt, D, &e) == SS_OK);
  double worst = 0, worst_norm = 0;
  double *col = malloc(sizeof(double) * n);
  for (int j = 0; j < nt; j++) {
    double s = 0;
    for (int x = 0; x < n; x++) {
      double h = 0;
      for (int i = 1; i < k; i++) h += exp(-ev[i] * t[j]) * phi[x + (size_t)n * i] * phi[x + (size_t)n * i];
      col[x] = h, s += M[x] * h * h;
    }
    double nn = 0;
    for (int x = 0; x < n; x++) {
      worst = fmax(worst, fabs(D[x + (size_t)n * j] - col[x] / sqrt(s)));
      nn += M[x] * D[x + (size_t)n * j] * D[x + (size_t)n * j];
    }
    worst_norm = fmax(worst_norm, fabs(nn - 1));
  }
  CHECK_MSG(worst < 1e-10, "HKS vs the direct sum: %g", worst);
  CHECK_MSG(worst_norm < 1e-12, "unit L2(M) columns: %g", worst_norm);

  /* a rigid motion (rotation about z, shift) leaves the descriptors unchanged */
  ss_mesh r = {0};
  CHECK(ss_mesh_copy(&m, &r, &e) == SS_OK);
  for (int x = 0; x < n; x++) {
    double a = r.V[3 * x], b = r.V[3 * x + 1];
    r.V[3 * x] = 0.6 * a - 0.8 * b + 3, r.V[3 * x + 1] = 0.8 * a + 0.6 * b - 1;
  }
  double *ev2 = malloc(sizeof(double) * k), *phi2 = malloc(sizeof(double) * (size_t)n * k), *M2 = malloc(sizeof(double) * n);
  double *D2 = malloc(sizeof(double) * (size_t)n * nt);
  CHECK(ss_mesh_eigs(&r, k, ev2, phi2, &e) == SS_OK && ss_mass_lumped(&r, SS_MASS_BARYCENTRIC, M2, &e) == SS_OK);
  /* the torus has repeated eigenvalues: the basis differs, Σ over a full eigenspace does not; the
   * last pair may be cut in half, so compare with k - 1 when λ_{k-1} = λ_{k-2} */
  int kk = fabs(ev[k - 1] - ev[k - 2]) < 1e-8 * ev[k - 1] ? k - 1 : k;
  CHECK(ss_hks(n, kk, ev, phi, M, nt, D, &e) == SS_OK && ss_hks(n, kk, ev2, phi2, M2, nt, D2, &e) == SS_OK);
  double dr = 0;
  for (size_t i = 0; i < (size_t)n * nt; i++) dr = fmax(dr, fabs(D[i] - D2[i]));
  CHECK_MSG(dr < 1e-6, "HKS of a moved copy differs by %g", dr);

  /* refusals */
  double zero[3] = {0, 0, 0};
  CHECK(ss_hks_filters(zero, 3, 4, G, NULL, &e) == SS_ERR_INVALID);
  CHECK(ss_hks_filters(ev, 1, 4, G, NULL, &e) == SS_ERR_INVALID);
  CHECK(ss_hks(n, k, ev, phi, M, 0, D, &e) == SS_ERR_INVALID);
  CHECK(ss_hks(n, k, ev, NULL, M, nt, D, &e) == SS_ERR_INVALID);

  free(ev), free(phi), free(M), free(G), free(t), free(D), free(col), free(ev2), free(phi2), free(M2), free(D2);
  ss_mesh_free(&m), ss_mesh_free(&r);
  TEST_MAIN_END();
}
