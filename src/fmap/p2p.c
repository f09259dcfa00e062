/* Exact nearest neighbours in a spectral embedding and the point map <-> functional map conversions.
 *
 * Brute force through BLAS: for a block of queries and a block of database points, one dgemm gives
 * q·b and the squared distance is ‖q‖² − 2 q·b + ‖b‖². That formula loses digits when ‖q‖, ‖b‖ are
 * large compared with their distance, so each query keeps every candidate whose approximate value is
 * within a rounding bound of its running minimum and the winner is decided on exact Σ (q_j − b_j)². */
#include "specseg/fmap.h"

#include <cblas.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NN_QB 256  /* queries per block */
#define NN_BB 2048 /* database points per block */
#define NN_NC 8    /* candidate slots per query before falling back to an exact scan */

typedef struct nn_state {
  double best;    /* approximate minimum of ‖b‖² − 2 q·b */
  int nc;         /* candidates kept, −1 = overflow */
  int cand[NN_NC];
  double cval[NN_NC];
} nn_state;

static double exact_d2(int d, const double *db, int lddb, int b, const double *q, int ldq, int i) {
  double s = 0;
  for (int j = 0; j < d; j++) {
    double t = q[i + (size_t)ldq * j] - db[b + (size_t)lddb * j];
    s += t * t;
  }
  return s;
}

ss_status ss_nn_brute(int ndb, int nq, int d, const double *db, int lddb, const double *q, int ldq, int *idx,
                      double *dist2, ss_error *err) {
  if (ndb < 1 || nq < 0 || d < 1 || lddb < ndb || ldq < nq)
    return ss_fail(err, SS_ERR_INVALID, "nearest neighbours: bad sizes (ndb %d, nq %d, d %d)", ndb, nq, d);
  if (nq == 0) return SS_OK;
  if (!db || !q || !idx) return ss_fail(err, SS_ERR_INVALID, "nearest neighbours: NULL array");
  double *bn = malloc(sizeof(double) * (size_t)ndb), *qn = malloc(sizeof(double) * (size_t)nq);
  double *S = malloc(sizeof(double) * (size_t)NN_QB * NN_BB);
  nn_state *stt = malloc(sizeof(nn_state) * (size_t)NN_QB);
  if (!bn || !qn || !S || !stt) {
    free(bn); free(qn); free(S); free(stt);
    return ss_fail(err, SS_ERR_NOMEM, "nearest neighbours: out of memory");
  }
  double bmax = 0;
  for (int b = 0; b < ndb; b++) bn[b] = 0;
  for (int j = 0; j < d; j++)
    for (int b = 0; b < ndb; b++) bn[b] += db[b + (size_t)lddb * j] * db[b + (size_t)lddb * j];
  for (int b = 0; b < ndb; b++) bmax = fmax(bmax, bn[b]);
  for (int i = 0; i < nq; i++) qn[i] = 0;
  for (int j = 0; j < d; j++)
    for (int i = 0; i < nq; i++) qn[i] += q[i + (size_t)ldq * j] * q[i + (size_t)ldq * j];

  for (int q0 = 0; q0 < nq; q0 += NN_QB) {
    int mq = nq - q0 < NN_QB ? nq - q0 : NN_QB;
    for (int i = 0; i < mq; i++) { stt[i].best = INFINITY; stt[i].nc = 0; }
    for (int b0 = 0; b0 < ndb; b0 += NN_BB) {
      int mb = ndb - b0 < NN_BB ? ndb - b0 : NN_BB;
      /* S (mq x mb) = Q_blk B_blkᵀ */
      cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, mq, mb, d, 1.0, q + q0, ldq, db + b0, lddb, 0.0, S, mq);
#pragma omp parallel for schedule(static)
      for (int i = 0; i < mq; i++) {
        nn_state *s = stt + i;
        /* rounding bound of the expanded formula, with a wide safety factor */
        double tol = 1e-12 * (d + 8) * (qn[q0 + i] + bmax);
        for (int bb = 0; bb < mb; bb++) {
          double v = bn[b0 + bb] - 2.0 * S[i + (size_t)mq * bb];
          if (v > s->best + tol) continue;
          if (v < s->best) {
            s->best = v;
            if (s->nc >= 0) { /* drop candidates no longer within tol of the new minimum */
              int w = 0;
              for (int c = 0; c < s->nc; c++)
                if (s->cval[c] <= v + tol) { s->cand[w] = s->cand[c]; s->cval[w] = s->cval[c]; w++; }
              s->nc = w;
            }
          }
          if (s->nc >= 0) {
            if (s->nc < NN_NC) { s->cand[s->nc] = b0 + bb; s->cval[s->nc] = v; s->nc++; }
            else s->nc = -1;
          }
        }
      }
    }
#pragma omp parallel for schedule(dynamic, 16)
    for (int i = 0; i < mq; i++) {
      nn_state *s = stt + i;
      int qi = q0 + i, bi = -1;
      double bd = INFINITY;
      if (s->nc > 0) {
        for (int c = 0; c < s->nc; c++) {
          double e = exact_d2(d, db, lddb, s->cand[c], q, ldq, qi);
          if (e < bd || (e == bd && s->cand[c] < bi)) { bd = e; bi = s->cand[c]; }
        }
      } else { /* many near-ties (or NaN): settle it exactly over the whole database */
        for (int b = 0; b < ndb; b++) {
          double e = exact_d2(d, db, lddb, b, q, ldq, qi);
          if (e < bd) { bd = e; bi = b; }
        }
        if (bi < 0) bi = 0;
      }
      idx[qi] = bi;
      if (dist2) dist2[qi] = bd;
    }
  }
  free(bn);
  free(qn);
  free(S);
  free(stt);
  return SS_OK;
}

ss_status ss_fmap_p2p(int n_S, int n_T, int k_S, int k_T, const double *evecs_S, const double *evecs_T,
                      const double *C, int *map, ss_error *err) {
  if (n_S < 1 || n_T < 1 || k_S < 1 || k_T < 1) return ss_fail(err, SS_ERR_INVALID, "p2p: bad sizes");
  double *E = malloc(sizeof(double) * (size_t)n_S * k_T);
  if (!E) return ss_fail(err, SS_ERR_NOMEM, "p2p: out of memory");
  /* E = Φ_S Cᵀ: source deltas carried to the target basis */
  cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, n_S, k_T, k_S, 1.0, evecs_S, n_S, C, k_T, 0.0, E, n_S);
  ss_status st = ss_nn_exact(n_S, n_T, k_T, E, n_S, evecs_T, n_T, map, NULL, err);
  free(E);
  return st;
}

ss_status ss_fmap_from_p2p(int n_S, int n_T, int k_S, int k_T, const double *evecs_S, const double *evecs_T,
                           const double *M_T, const int *map, double *C, ss_error *err) {
  if (n_S < 1 || n_T < 1 || k_S < 1 || k_T < 1) return ss_fail(err, SS_ERR_INVALID, "p2p: bad sizes");
  for (int y = 0; y < n_T; y++)
    if (map[y] < 0 || map[y] >= n_S)
      return ss_fail(err, SS_ERR_INVALID, "point map: entry %d = %d out of range [0,%d)", y, map[y], n_S);
  double *G = malloc(sizeof(double) * (size_t)n_T * k_S);
  if (!G) return ss_fail(err, SS_ERR_NOMEM, "p2p: out of memory");
  /* G = M_T Π Φ_S, then C = Φ_Tᵀ G. The gather is serial: ~1 ms at FAUST size, less than what a
   * parallel region's barrier costs on a shared machine (ZoomOut calls this once per step) */
  for (int c = 0; c < k_S; c++)
    for (int y = 0; y < n_T; y++) G[y + (size_t)n_T * c] = M_T[y] * evecs_S[map[y] + (size_t)n_S * c];
  cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, k_T, k_S, n_T, 1.0, evecs_T, n_T, G, n_T, 0.0, C, k_T);
  free(G);
  return SS_OK;
}
