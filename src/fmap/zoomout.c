/* ZoomOut (Melzi, Ren, Rodolà, Sharma, Wonka, Ovsjanikov 2019): spectral up-sampling of a functional
 * map by alternating its point map and the functional map of that point map, one size larger.
 *
 * Each iteration's point map is an exact nearest-neighbour search of the target's rows of Φ_T among
 * the rows of E = Φ_S Cᵀ. Two things carry over between iterations (ss_nn_exact_guided): the previous
 * map, whose distances bound every query's search from the start, and one clustering of the source,
 * made once on Φ_S's first kmax columns: ‖E(x) − E(x')‖ ≤ ‖C‖ ‖Φ_S(x) − Φ_S(x')‖ and ZoomOut's C are
 * close to orthonormal, so clusters compact there stay compact in every E. On FAUST (50 -> 100, step
 * 1, one thread) ZoomOut went from 2.6–3.0 s to 1.0–1.25 s CPU per pair with these and the frame
 * bound of nearest_neighbor.c, with bit-identical maps and C. */
#include "fmap/fmap_options.h"

#include <cblas.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The iterations; brute: every point map by ss_nn_brute (the same maps: both searches are exact), else
 * by the guided cluster search */
static ss_status zoomout_loop(int n_S, int n_T, const double *evecs_S, const double *evecs_T, const double *M_T, int k0,
                              const double *C0, int kmax, int step, int brute, const int *part_in, const double *L, int ldl,
                              int map_at_kmax, int *map, double *C_out, ss_error *err) {
  if (n_S < 1 || n_T < 1 || k0 < 1 || kmax < k0 || step < 1)
    return ss_fail(err, SS_ERR_INVALID, "zoomout: need 1 <= k0 <= kmax and step >= 1 (k0 %d, kmax %d, step %d)", k0,
                   kmax, step);
  double *C = malloc(sizeof(double) * (size_t)kmax * kmax), *E = malloc(sizeof(double) * (size_t)n_S * kmax);
  int *own = brute || part_in ? NULL : malloc(sizeof(int) * n_S);
  const int *part = part_in ? part_in : own;
  if (!C || !E || (!brute && !part)) {
    free(C); free(E); free(own);
    return ss_fail(err, SS_ERR_NOMEM, "zoomout: out of memory");
  }
  ss_status st = own ? ss_nn_partition(n_S, kmax, evecs_S, n_S, 0, own, err) : SS_OK;
  memcpy(C, C0, sizeof(double) * (size_t)k0 * k0);
  int k = k0;
  for (int it = 0; !st; it++) {
    /* point map of C (k x k): E = Φ_S Cᵀ, then each target row's nearest row of E, warm-started from
     * the previous map (guess and result may share the array) */
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, n_S, k, k, 1.0, evecs_S, n_S, C, k, 0.0, E, n_S);
    st = brute ? ss_nn_brute(n_S, n_T, k, E, n_S, evecs_T, n_T, map, NULL, err)
               : ss_nn_exact_guided(n_S, n_T, k, E, n_S, evecs_T, n_T, part, it > 0 ? map : NULL, map, NULL, err);
    if (st || k == kmax) break;
    k = k + step < kmax ? k + step : kmax;
    st = ss_fmap_from_p2p(n_S, n_T, k, k, evecs_S, evecs_T, M_T, map, C, err);
    if (!st && L) { /* least squares: C ← G_k⁻¹ C, G_k = L_k L_kᵀ (the leading block of G's factor) */
      cblas_dtrsm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasNonUnit, k, k, 1.0, L, ldl, C, k);
      cblas_dtrsm(CblasColMajor, CblasLeft, CblasLower, CblasTrans, CblasNonUnit, k, k, 1.0, L, ldl, C, k);
    }
    if (k == kmax && !map_at_kmax) break; /* map: the previous size's (the caller's passes at kmax follow) */
  }
  if (!st && C_out) memcpy(C_out, C, sizeof(double) * (size_t)k * k);
  free(C);
  free(E);
  free(own);
  return st;
}

ss_status ss_zoomout(int n_S, int n_T, const double *evecs_S, const double *evecs_T, const double *M_T, int k0,
                     const double *C0, int kmax, int step, int *map, double *C_out, ss_error *err) {
  return zoomout_loop(n_S, n_T, evecs_S, evecs_T, M_T, k0, C0, kmax, step, 0, NULL, NULL, 0, 1, map, C_out, err);
}

/* Sampled iterations search by brute force up to this many source samples: among sparse samples a
 * query's nearest neighbour is about as far as the clusters are wide, so the cluster search opens most
 * of them (FAUST, 1,000 samples, k 120: 18 ms a search against 8 ms by brute force) */
#ifndef ZOOMOUT_BRUTE_MAX
#define ZOOMOUT_BRUTE_MAX 1500
#endif

ss_status ss_zoomout_sampled(int n_S, int n_T, const double *evecs_S, const double *evecs_T, int k0, const double *C0,
                             int kmax, int step, const ss_zoomout_sample *smp, int *map, double *C_out, ss_error *err) {
  if (n_S < 1 || n_T < 1 || k0 < 1 || kmax < k0 || step < 1 || !smp || !C0 || !map)
    return ss_fail(err, SS_ERR_INVALID, "zoomout: need 1 <= k0 <= kmax and step >= 1 (k0 %d, kmax %d, step %d)", k0,
                   kmax, step);
  const int full_S = !smp->sub_S, mS = full_S ? n_S : smp->ns_S, mT = smp->ns_T;
  if (mS < 1 || mS > n_S || mT < 1 || mT > n_T || !smp->sub_T || !smp->w_T)
    return ss_fail(err, SS_ERR_INVALID, "zoomout: bad samples (%d of %d, %d of %d)", mS, n_S, mT, n_T);
  for (int i = 0; i < mS && !full_S; i++)
    if (smp->sub_S[i] < 0 || smp->sub_S[i] >= n_S) return ss_fail(err, SS_ERR_INVALID, "zoomout: source sample %d out of range", i);
  if (smp->part_S)
    for (int b = 0; b < n_S; b++)
      if (smp->part_S[b] < 0 || smp->part_S[b] >= n_S) return ss_fail(err, SS_ERR_INVALID, "zoomout: part_S[%d] out of range", b);
  for (int i = 0; i < mT; i++)
    if (smp->sub_T[i] < 0 || smp->sub_T[i] >= n_T) return ss_fail(err, SS_ERR_INVALID, "zoomout: target sample %d out of range", i);
  if (smp->near_T)
    for (int t = 0; t < n_T; t++)
      if (smp->near_T[t] < 0 || smp->near_T[t] >= mT) return ss_fail(err, SS_ERR_INVALID, "zoomout: near_T[%d] out of range", t);
  if (smp->polish < 0 || (smp->polish > 0 && !smp->M_T) || (smp->lstsq != 0 && smp->lstsq != 1))
    return ss_fail(err, SS_ERR_INVALID, "zoomout: bad polish %d / lstsq %d (or no target masses)", smp->polish, smp->lstsq);
  double *PS = full_S ? NULL : malloc(sizeof(double) * (size_t)mS * kmax), *PT = malloc(sizeof(double) * (size_t)mT * kmax);
  double *C = malloc(sizeof(double) * (size_t)kmax * kmax), *E = malloc(sizeof(double) * (size_t)n_S * kmax);
  double *L = smp->lstsq ? malloc(sizeof(double) * (size_t)kmax * kmax) : NULL, *WP = NULL;
  int *smap = malloc(sizeof(int) * (size_t)mT), *guess = smp->near_T ? malloc(sizeof(int) * (size_t)n_T) : NULL;
  ss_status st = SS_OK;
  if ((!full_S && !PS) || !PT || !C || !E || !smap || (smp->near_T && !guess) || (smp->lstsq && !L)) {
    st = ss_fail(err, SS_ERR_NOMEM, "zoomout: out of memory");
    goto done;
  }
  /* the sampled rows, then ZoomOut on them (the target samples' weights as its masses) */
  for (int c = 0; c < kmax; c++) {
    for (int i = 0; i < mS && !full_S; i++) PS[i + (size_t)mS * c] = evecs_S[smp->sub_S[i] + (size_t)n_S * c];
    for (int i = 0; i < mT; i++) PT[i + (size_t)mT * c] = evecs_T[smp->sub_T[i] + (size_t)n_T * c];
  }
  if (L) { /* G = PTᵀ diag(w) PT at kmax and its Cholesky factor (lower) */
    if (!(WP = malloc(sizeof(double) * (size_t)mT * kmax))) {
      st = ss_fail(err, SS_ERR_NOMEM, "zoomout: out of memory");
      goto done;
    }
    for (int c = 0; c < kmax; c++)
      for (int i = 0; i < mT; i++) WP[i + (size_t)mT * c] = smp->w_T[i] * PT[i + (size_t)mT * c];
    cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, kmax, kmax, mT, 1.0, PT, mT, WP, mT, 0.0, L, kmax);
    if (LAPACKE_dpotrf(LAPACK_COL_MAJOR, 'L', kmax, L, kmax) != 0) free(L), L = NULL; /* the weighted sum */
  }
  /* among every source vertex: the cluster search on the given (or its own) partition; among source
   * samples: brute force up to ZOOMOUT_BRUTE_MAX of them. The samples' map at kmax would only be the
   * first pass's guess (that pass maps every vertex, the samples too, and its exact search does not
   * depend on the guess): the map of the size before serves as the guess instead. */
  if (full_S) st = zoomout_loop(n_S, mT, evecs_S, PT, smp->w_T, k0, C0, kmax, step, 0, smp->part_S, L, kmax, 0, smap, C, err);
  else st = zoomout_loop(mS, mT, PS, PT, smp->w_T, k0, C0, kmax, step, mS <= ZOOMOUT_BRUTE_MAX, NULL, L, kmax, 0, smap, C, err);
  if (st) goto done;
  /* the point map of every target vertex from the final C, then the iterations on every vertex */
  if (guess)
    for (int t = 0; t < n_T; t++) guess[t] = full_S ? smap[smp->near_T[t]] : smp->sub_S[smap[smp->near_T[t]]];
  for (int it = 0; it <= smp->polish; it++) {
    if (it > 0 && (st = ss_fmap_from_p2p(n_S, n_T, kmax, kmax, evecs_S, evecs_T, smp->M_T, map, C, err))) goto done;
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, n_S, kmax, kmax, 1.0, evecs_S, n_S, C, kmax, 0.0, E, n_S);
    if ((st = ss_nn_exact_guided(n_S, n_T, kmax, E, n_S, evecs_T, n_T, smp->part_S, it > 0 ? map : guess, map, NULL, err)))
      goto done;
  }
  if (C_out) memcpy(C_out, C, sizeof(double) * (size_t)kmax * kmax);
done:
  free(PS), free(PT), free(C), free(E), free(smap), free(guess), free(L), free(WP);
  return st;
}

ss_status ss_zoomout_samples(const ss_mesh *m, const double *M, int ns, int *sub, double *w, int *near, ss_error *err) {
  if (!m || !sub || !near || (w && !M) || m->nv < 1 || ns < 1 || ns > m->nv)
    return ss_fail(err, SS_ERR_INVALID, "zoomout samples: bad arguments (%d of %d)", ns, m ? m->nv : 0);
  const int n = m->nv;
  const double *V = m->V;
  double *mind = malloc(sizeof(double) * (size_t)n);
  if (!mind) return ss_fail(err, SS_ERR_NOMEM, "zoomout samples: out of memory");
  for (int x = 0; x < n; x++) mind[x] = INFINITY, near[x] = 0;
  int cur = 0;
  for (int s = 0; s < ns; s++) {
    sub[s] = cur;
    const double *p = V + 3 * (size_t)cur;
    int far = 0;
    double fd = -1;
    for (int x = 0; x < n; x++) {
      const double *q = V + 3 * (size_t)x;
      double d = (q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) + (q[2] - p[2]) * (q[2] - p[2]);
      if (d < mind[x]) mind[x] = d, near[x] = s;
      if (mind[x] > fd) fd = mind[x], far = x;
    }
    cur = far; /* duplicate positions (fd = 0) only repeat a sample */
  }
  if (w) {
    for (int s = 0; s < ns; s++) w[s] = 0;
    for (int x = 0; x < n; x++) w[near[x]] += M[x];
  }
  free(mind);
  return SS_OK;
}

ss_status ss_p2p_energy(int n_S, int n_T, const double *evals_S, const double *evals_T, const double *evecs_S,
                        const double *evecs_T, const double *M_T, const int *map, int k0, int K, int step, double w_lap,
                        double *E, double *E_orth, double *E_lap, ss_error *err) {
  if (n_S < 1 || n_T < 1 || k0 < 1 || K < k0 || step < 1 || !evals_S || !evals_T || !evecs_S || !evecs_T || !M_T ||
      !map || !E || !(w_lap >= 0))
    return ss_fail(err, SS_ERR_INVALID, "p2p energy: bad arguments (k0 %d, K %d, step %d)", k0, K, step);
  for (int y = 0; y < n_T; y++)
    if (map[y] < 0 || map[y] >= n_S) return ss_fail(err, SS_ERR_INVALID, "p2p energy: map[%d] = %d out of range", y, map[y]);
  double *C = malloc(sizeof(double) * (size_t)K * K), *G = malloc(sizeof(double) * (size_t)K * K);
  if (!C || !G) {
    free(C), free(G);
    return ss_fail(err, SS_ERR_NOMEM, "p2p energy: out of memory");
  }
  ss_status st = ss_fmap_from_p2p(n_S, n_T, K, K, evecs_S, evecs_T, M_T, map, C, err);
  double eo = 0, num = 0, den = 0;
  int ns = 0;
  if (!st) {
    /* G = C_kᵀ C_k (upper triangle) for each size, C_k the leading block of C: ~k³ flops a size,
     * negligible next to a point map */
    for (int k = k0;; k = k + step < K ? k + step : K) {
      cblas_dsyrk(CblasColMajor, CblasUpper, CblasTrans, k, k, 1.0, C, K, 0.0, G, K);
      double s = 0;
      for (int j = 0; j < k; j++)
        for (int i = 0; i <= j; i++) {
          double d = G[i + (size_t)K * j] - (i == j);
          s += (i == j ? 1.0 : 2.0) * d * d;
        }
      eo += s / k;
      ns++;
      if (k == K) break;
    }
    eo /= ns;
    for (int j = 0; j < K; j++)
      for (int i = 0; i < K; i++) {
        double c2 = C[i + (size_t)K * j] * C[i + (size_t)K * j], d = evals_T[i] - evals_S[j];
        num += c2 * d * d;
        den += c2 * (evals_T[i] * evals_T[i] + evals_S[j] * evals_S[j]);
      }
  }
  if (!st) {
    double el = den > 0 ? num / den : 0.0;
    *E = eo + w_lap * el;
    if (E_orth) *E_orth = eo;
    if (E_lap) *E_lap = el;
  }
  free(C), free(G);
  return st;
}

ss_status ss_p2p_descr_residual(int n_S, int n_T, const double *evecs_S, const double *evecs_T, const double *M_T,
                                const ss_fmap_probes *S, const ss_fmap_probes *T, const int *map, double *E,
                                ss_error *err) {
  if (n_S < 1 || n_T < 1 || !evecs_S || !evecs_T || !M_T || !S || !T || !S->A || !T->A || !map || !E || S->p != T->p ||
      S->p < 1 || S->k < 1 || T->k < 1)
    return ss_fail(err, SS_ERR_INVALID, "descriptor residual: bad arguments");
  for (int t = 0; t < n_T; t++)
    if (map[t] < 0 || map[t] >= n_S) return ss_fail(err, SS_ERR_INVALID, "descriptor residual: map[%d] = %d out of range", t, map[t]);
  const int p = S->p;
  double *FS = malloc(sizeof(double) * (size_t)n_S * p), *FT = malloc(sizeof(double) * (size_t)n_T * p);
  if (!FS || !FT) {
    free(FS), free(FT);
    return ss_fail(err, SS_ERR_NOMEM, "descriptor residual: out of memory");
  }
  cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n_S, p, S->k, 1.0, evecs_S, n_S, S->A, S->k, 0.0, FS, n_S);
  cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n_T, p, T->k, 1.0, evecs_T, n_T, T->A, T->k, 0.0, FT, n_T);
  double num = 0, den = 0;
  for (int j = 0; j < p; j++) {
    const double *fs = FS + (size_t)n_S * j, *ft = FT + (size_t)n_T * j;
    for (int t = 0; t < n_T; t++) {
      double d = ft[t] - fs[map[t]];
      num += M_T[t] * d * d;
      den += M_T[t] * ft[t] * ft[t];
    }
  }
  *E = den > 0 ? num / den : 0.0;
  free(FS), free(FT);
  return SS_OK;
}

void ssi_zoomout_plan_free(ssi_zoomout_plan *p) {
  if (!p) return;
  free(p->sub_S), free(p->sub_T), free(p->near_T), free(p->near_S), free(p->part_S), free(p->w_T), free(p->w_S);
  memset(p, 0, sizeof *p);
}

ss_status ssi_zoomout_plan_new(const ss_mesh *mS, const double *M_S, const double *evecs_S, const ss_mesh *mT,
                               const double *M_T, int ns, int kmax, ssi_zoomout_plan *p, ss_error *err) {
  memset(p, 0, sizeof *p);
  p->n_S = mS->nv, p->n_T = mT->nv;
  if (ns <= 0 || ns >= mT->nv) return SS_OK; /* plain */
  (void)M_S;
  p->sub_T = malloc(sizeof(int) * (size_t)ns), p->w_T = malloc(sizeof(double) * (size_t)ns);
  p->near_T = malloc(sizeof(int) * (size_t)mT->nv), p->part_S = malloc(sizeof(int) * (size_t)mS->nv);
  ss_status st = SS_OK;
  if (!p->sub_T || !p->w_T || !p->near_T || !p->part_S) st = ss_fail(err, SS_ERR_NOMEM, "zoomout: out of memory");
  if (!st) st = ss_zoomout_samples(mT, M_T, ns, p->sub_T, p->w_T, p->near_T, err);
  if (!st) st = ss_nn_partition(mS->nv, kmax, evecs_S, mS->nv, 0, p->part_S, err);
  if (st) {
    ssi_zoomout_plan_free(p);
    return st;
  }
  /* target samples against every source vertex, least squares, one iteration on every vertex at the
   * end (docs/tuning.md) */
  ss_zoomout_sample smp = {0, ns, NULL, p->sub_T, p->w_T, p->near_T, p->part_S, 1, 1, M_T};
  p->smp = smp;
  return SS_OK;
}

ss_status ssi_zoomout_plan_run(const ssi_zoomout_plan *p, const double *evecs_S, const double *evecs_T, const double *M_T,
                               int k0, const double *C0, int kmax, int step, int *map, double *C_out, ss_error *err) {
  if (!p->smp.sub_T) return ss_zoomout(p->n_S, p->n_T, evecs_S, evecs_T, M_T, k0, C0, kmax, step, map, C_out, err);
  return ss_zoomout_sampled(p->n_S, p->n_T, evecs_S, evecs_T, k0, C0, kmax, step, &p->smp, map, C_out, err);
}
