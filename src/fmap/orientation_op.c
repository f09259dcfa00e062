/* Orientation operators of functions in the reduced basis (Ren, Poulenard, Wonka, Ovsjanikov 2018,
 * "Continuous and orientation-preserving correspondences via functional maps").
 *
 * With hat-function gradients ∇h_a = n × e_a / (2A) per face (e_a the edge opposite a), the face
 * value ⟨n × ∇f, ∇g⟩ is J_t(f, g) / (2A_t) up to one sign fixed by the winding, with
 * J_t(f, g) = f_a (g_b − g_c) + f_b (g_c − g_a) + f_c (g_a − g_b). Averaged to the vertices by area
 * (weights A_t/3) and integrated against φ_i with the lumped masses M_v = Σ_t∋v A_t/3, the areas
 * cancel: O[i, j] = Σ_t s_i(t) J_t(f, φ_j) / 6, s_i(t) = φ_i(a) + φ_i(b) + φ_i(c). So O = Sᵀ J_f with
 * S (nf x k) shared by every f: one dgemm per function. */
#include "specseg/fmap.h"

#include <cblas.h>
#include <stdlib.h>
#include <string.h>

ss_status ss_fmap_orientation_operators(const ss_mesh *m, int k, const double *evecs, int p, const double *F,
                                        double *O, ss_error *err) {
  if (!m || !m->F || m->nv < 1 || m->nf < 1 || k < 1 || p < 0 || !evecs || (p > 0 && (!F || !O)))
    return ss_fail(err, SS_ERR_INVALID, "orientation operators: bad arguments (k %d, p %d)", k, p);
  if (p == 0) return SS_OK;
  const int n = m->nv, nf = m->nf;
  const int *T = m->F;
  for (size_t c = 0; c < 3 * (size_t)nf; c++)
    if (T[c] < 0 || T[c] >= n)
      return ss_fail(err, SS_ERR_INVALID, "orientation operators: face %zu has vertex %d out of range", c / 3, T[c]);
  double *S = malloc(sizeof(double) * (size_t)nf * k), *J = malloc(sizeof(double) * (size_t)nf * k);
  if (!S || !J) {
    free(S), free(J);
    return ss_fail(err, SS_ERR_NOMEM, "orientation operators: out of memory");
  }
  for (int i = 0; i < k; i++) {
    const double *phi = evecs + (size_t)n * i;
    double *s = S + (size_t)nf * i;
    for (int t = 0; t < nf; t++) {
      const int *v = T + 3 * (size_t)t;
      s[t] = (phi[v[0]] + phi[v[1]] + phi[v[2]]) / 6.0;
    }
  }
  for (int q = 0; q < p; q++) {
    const double *f = F + (size_t)n * q;
#pragma omp parallel for schedule(static)
    for (int j = 0; j < k; j++) {
      const double *g = evecs + (size_t)n * j;
      double *col = J + (size_t)nf * j;
      for (int t = 0; t < nf; t++) {
        const int a = T[3 * (size_t)t], b = T[3 * (size_t)t + 1], c = T[3 * (size_t)t + 2];
        col[t] = f[a] * (g[b] - g[c]) + f[b] * (g[c] - g[a]) + f[c] * (g[a] - g[b]);
      }
    }
    cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, k, k, nf, 1.0, S, nf, J, nf, 0.0, O + (size_t)k * k * q, k);
  }
  free(S), free(J);
  return SS_OK;
}
