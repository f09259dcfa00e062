/* The oriented polish of a pairing (autopair_internal.h). The left / right decision can pick a
 * pairing built through the centres' symmetry σ (the mirror of the search's best), which is no local
 * minimum of the energy where σ is wrong: on a quadruped whose σ misses a leg pair, the answer keeps
 * that pair swapped while the move that mends it costs less and keeps the orientation. A move that
 * mirrors a part instead lowers the orientation score, and is refused, as is the pairing the
 * decision rejected and any scoring no better than it. */
#include "match/autopair_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* cand = p with A centre u moved to B centre w (exchanging with w's partner inv[w], if any) */
static void apply_move(int na, const int *p, const int *inv, int u, int w, int *cand) {
  memcpy(cand, p, sizeof(int) * (size_t)na);
  cand[u] = w;
  if (inv[w] >= 0) cand[inv[w]] = p[u];
}

ss_status ssi_polish_oriented(ssi_orient_ctx *oc, const ssi_search *S, int *p, double *E, double *r, int rounds, double tol,
                              const int *rejected, double r_rejected, int *cand, int *inv, double *mv, int *moves,
                              ss_error *err) {
  const int na = oc->A->m, nb = oc->B->m;
  *moves = 0;
  for (int round = 0; round < rounds; round++) {
    for (int b = 0; b < nb; b++) inv[b] = -1;
    for (int a = 0; a < na; a++) inv[p[a]] = a;
    int nm = 0; /* the moves that lower the energy: (energy, u · nb + w) */
    for (int u = 0; u < na; u++)
      for (int w = 0; w < nb; w++) {
        if (w == p[u] || (inv[w] >= 0 && inv[w] < u)) continue; /* each exchange once */
        apply_move(na, p, inv, u, w, cand);
        const double e = ssi_full_energy(S, cand, NULL);
        if (e < *E - 1e-12 * fabs(*E)) mv[2 * nm] = e, mv[2 * nm + 1] = (double)u * nb + w, nm++;
      }
    qsort(mv, (size_t)nm, 2 * sizeof(double), ssi_dbl_cmp); /* by energy, the first double */
    int applied = 0;
    for (int i = 0; i < nm && i < SSI_TOPK && !applied; i++) {
      const int code = (int)mv[2 * i + 1], u = code / nb, w = code % nb;
      apply_move(na, p, inv, u, w, cand);
      if (rejected && !memcmp(cand, rejected, sizeof(int) * (size_t)na)) continue; /* the decision's loser */
      double rc = 0;
      ss_status st = ssi_orient_ctx_score(oc, cand, &rc, NULL, err);
      if (st) return st;
      if (rc >= *r - tol && rc > r_rejected) memcpy(p, cand, sizeof(int) * (size_t)na), *E = mv[2 * i], *r = rc, applied = 1;
    }
    if (!applied) break;
    ++*moves;
  }
  return SS_OK;
}
