/* Orientation operators of functions in the reduced basis (Ren, Poulenard, Wonka, Ovsjanikov 2018,
 * "Continuous and orientation-preserving correspondences via functional maps").
 *
 * With hat-function gradients ∇h_a = n × e_a / (2A) per face (e_a the edge opposite a), the face
 * value ⟨n × ∇f, ∇g⟩ is J_t(f, g) / (2A_t) up to one sign fixed by the winding, with
 * J_t(f, g) = f_a (g_b − g_c) + f_b (g_c − g_a) + f_c (g_a − g_b). Averaged to the vertices by area
 * (weights A_t/3) and integrated against φ_i with the lumped masses M_v = Σ_t∋v A_t/3, the areas
 * cancel: O[i, j] = Σ_t s_i(t) J_t(f, φ_j) / 6, s_i(t) = φ_i(a) + φ_i(b) + φ_i(c). So O = Sᵀ J_f with
 * S (nf x k) shared by every f. */
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
  /* J_t(f, g) = u_t(f) w_t(g) − w_t(f) u_t(g) with u_t(g) = g_b − g_a, w_t(g) = g_c − g_a: the
   * basis' U, W once; then per block of faces every function's J columns side by side, so all the
   * operators come out of one dgemm per block, [O_1 … O_p] += S_blockᵀ [J_1 … J_p] */
  const int nb = 256;
  const size_t pk = (size_t)p * k;
  double *S = malloc(sizeof(double) * (size_t)nf * k), *U = malloc(sizeof(double) * (size_t)nf * k);
  double *W = malloc(sizeof(double) * (size_t)nf * k), *J = malloc(sizeof(double) * (size_t)nb * pk);
  double *uf = malloc(sizeof(double) * (size_t)nf * p), *wf = malloc(sizeof(double) * (size_t)nf * p);
  if (!S || !U || !W || !J || !uf || !wf) {
    free(S), free(U), free(W), free(J), free(uf), free(wf);
    return ss_fail(err, SS_ERR_NOMEM, "orientation operators: out of memory");
  }
  for (int i = 0; i < k; i++) {
    const double *phi = evecs + (size_t)n * i;
    double *s = S + (size_t)nf * i, *u = U + (size_t)nf * i, *w = W + (size_t)nf * i;
    for (int t = 0; t < nf; t++) {
      const int *v = T + 3 * (size_t)t;
      s[t] = (phi[v[0]] + phi[v[1]] + phi[v[2]]) / 6.0;
      u[t] = phi[v[1]] - phi[v[0]];
      w[t] = phi[v[2]] - phi[v[0]];
    }
  }
  for (int q = 0; q < p; q++) {
    const double *f = F + (size_t)n * q;
    double *u = uf + (size_t)nf * q, *w = wf + (size_t)nf * q;
    for (int t = 0; t < nf; t++) {
      const int *v = T + 3 * (size_t)t;
      u[t] = f[v[1]] - f[v[0]];
      w[t] = f[v[2]] - f[v[0]];
    }
  }
  memset(O, 0, sizeof(double) * (size_t)k * pk);
  for (int t0 = 0; t0 < nf; t0 += nb) {
    const int mb = nf - t0 < nb ? nf - t0 : nb;
#pragma omp parallel for schedule(static)
    for (int c = 0; c < (int)pk; c++) { /* column j of function q */
      const int q = c / k, j = c % k;
      const double *u = uf + (size_t)nf * q + t0, *w = wf + (size_t)nf * q + t0;
      const double *Uj = U + (size_t)nf * j + t0, *Wj = W + (size_t)nf * j + t0;
      double *col = J + (size_t)mb * c;
      for (int t = 0; t < mb; t++) col[t] = u[t] * Wj[t] - w[t] * Uj[t];
    }
    cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, k, (int)pk, mb, 1.0, S + t0, nf, J, mb, 1.0, O, k);
  }
  free(S), free(U), free(W), free(J), free(uf), free(wf);
  return SS_OK;
}
