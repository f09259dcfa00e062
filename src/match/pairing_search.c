/* The search for the pairing of least energy of A's centres with B's (A->m <= B->m): the energy
 * (descriptor distances + squared differences of the centre-to-centre geodesics), the exact branch
 * and bound keeping the SSI_TOPK best leaves, or the relaxation (Hungarian on unary + distance-profile
 * costs, then local moves) with its best single-move neighbours. */
#include "match/autopair_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static double pair_inc(const ssi_search *S, int t, int b) {
  double c = S->U[(size_t)t * S->nb + b];
  for (int s = 0; s < t; s++) {
    double d = S->DA[s + (size_t)S->na * t] - S->DB[S->cur[s] + (size_t)S->nb * b];
    c += S->wg * d * d;
  }
  return c;
}

static void keep_leaf(ssi_search *S, const int *p, double e) {
  int k = S->ntop - 1;
  if (!(e < S->top_e[k])) return;
  int *slot = S->top_p[k];
  while (k > 0 && e < S->top_e[k - 1]) {
    S->top_e[k] = S->top_e[k - 1];
    S->top_p[k] = S->top_p[k - 1];
    k--;
  }
  S->top_e[k] = e;
  S->top_p[k] = slot;
  memcpy(slot, p, sizeof(int) * (size_t)S->na);
}

static void dfs(ssi_search *S, int t, double partial) {
  if (t == S->na) {
    keep_leaf(S, S->cur, partial);
    return;
  }
  for (int b = 0; b < S->nb; b++) {
    if (S->used[b]) continue;
    double c = partial + pair_inc(S, t, b);
    if (!(c + S->minU[t + 1] < S->top_e[S->ntop - 1])) continue;
    S->cur[t] = b;
    S->used[b] = 1;
    dfs(S, t + 1, c);
    S->used[b] = 0;
  }
}

/* energy of an assignment p (A index -> B index); share (may be NULL): per-centre shares */
double ssi_full_energy(const ssi_search *S, const int *p, double *share) {
  const int na = S->na, nb = S->nb;
  double E = 0;
  for (int a = 0; a < na; a++) {
    E += S->U[(size_t)a * nb + p[a]];
    if (share) share[a] = S->U[(size_t)a * nb + p[a]];
  }
  for (int a = 0; a < na; a++)
    for (int c = a + 1; c < na; c++) {
      double d = S->DA[a + (size_t)na * c] - S->DB[p[a] + (size_t)nb * p[c]], e = S->wg * d * d;
      E += e;
      if (share) share[a] += e / 2, share[c] += e / 2;
    }
  return E;
}

/* Hungarian algorithm (shortest augmenting paths, O(n² m)) for an n x m cost matrix, n <= m,
 * C[i * m + j]; assign[i] receives the column of row i. */
static int hungarian(int n, int m, const double *C, int *assign) {
  double *u = calloc((size_t)n + 1, sizeof(double)), *v = calloc((size_t)m + 1, sizeof(double));
  double *minv = malloc(sizeof(double) * ((size_t)m + 1));
  int *p = calloc((size_t)m + 1, sizeof(int)), *way = calloc((size_t)m + 1, sizeof(int));
  char *usedc = malloc((size_t)m + 1);
  if (!u || !v || !minv || !p || !way || !usedc) {
    free(u), free(v), free(minv), free(p), free(way), free(usedc);
    return 1;
  }
  for (int i = 1; i <= n; i++) {
    p[0] = i;
    int j0 = 0;
    for (int j = 0; j <= m; j++) minv[j] = INFINITY, usedc[j] = 0;
    do {
      usedc[j0] = 1;
      int i0 = p[j0], j1 = 0;
      double delta = INFINITY;
      for (int j = 1; j <= m; j++)
        if (!usedc[j]) {
          double cur = C[(size_t)(i0 - 1) * m + (j - 1)] - u[i0] - v[j];
          if (cur < minv[j]) minv[j] = cur, way[j] = j0;
          if (minv[j] < delta) delta = minv[j], j1 = j;
        }
      for (int j = 0; j <= m; j++)
        if (usedc[j]) u[p[j]] += delta, v[j] -= delta;
        else minv[j] -= delta;
      j0 = j1;
    } while (p[j0] != 0);
    do {
      int j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0);
  }
  for (int j = 1; j <= m; j++)
    if (p[j]) assign[p[j] - 1] = j - 1;
  free(u), free(v), free(minv), free(p), free(way), free(usedc);
  return 0;
}

int ssi_dbl_cmp(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The relaxation: Hungarian on unary + distance-profile costs, then swaps / moves to free centres
 * while the energy decreases; top[0] = that local minimum, top[1..] = its best single-move
 * neighbours. */
static int relaxed(ssi_search *S, int self) {
  const int na = S->na, nb = S->nb, q = na - 1, lq = q > 0 ? q : 1;
  double *C = malloc(sizeof(double) * (size_t)na * nb), *pa = malloc(sizeof(double) * (size_t)na * lq);
  double *pb = malloc(sizeof(double) * (size_t)nb * lq), *tmp = malloc(sizeof(double) * (size_t)nb);
  int *p = malloc(sizeof(int) * (size_t)na), *inv = malloc(sizeof(int) * (size_t)nb);
  int rc = 1;
  if (!C || !pa || !pb || !tmp || !p || !inv) goto out;
  for (int side = 0; side < 2; side++) { /* sorted distance profiles: the q smallest distances */
    const int n = side ? nb : na;
    const double *D = side ? S->DB : S->DA;
    double *prof = side ? pb : pa;
    for (int a = 0; a < n; a++) {
      int c = 0;
      for (int x = 0; x < n; x++)
        if (x != a) tmp[c++] = D[a + (size_t)n * x];
      qsort(tmp, (size_t)c, sizeof(double), ssi_dbl_cmp);
      for (int i = 0; i < q; i++) prof[(size_t)a * lq + i] = i < c ? tmp[i] : 0.0;
    }
  }
  for (int a = 0; a < na; a++)
    for (int b = 0; b < nb; b++) {
      double s = 0;
      for (int i = 0; i < q; i++) {
        double d = pa[(size_t)a * lq + i] - pb[(size_t)b * lq + i];
        s += d * d;
      }
      C[(size_t)a * nb + b] = S->U[(size_t)a * nb + b] + S->wg * s / 2;
    }
  if (hungarian(na, nb, C, p)) goto out;
  double E = self ? INFINITY : ssi_full_energy(S, p, NULL);
  if (self) { /* A with itself: the identity is the trivial optimum; start from the best swap */
    for (int a = 0; a < na; a++) p[a] = a;
    int ba = -1, bc = -1;
    for (int a = 0; a < na; a++)
      for (int c = a + 1; c < na; c++) {
        p[a] = c, p[c] = a;
        double e = ssi_full_energy(S, p, NULL);
        if (e < E) E = e, ba = a, bc = c;
        p[a] = a, p[c] = c;
      }
    if (ba >= 0) p[ba] = bc, p[bc] = ba;
  }
  for (int improved = 1; improved && !self;) {
    improved = 0;
    for (int b = 0; b < nb; b++) inv[b] = -1;
    for (int a = 0; a < na; a++) inv[p[a]] = a;
    for (int a = 0; a < na && !improved; a++)
      for (int b = 0; b < nb && !improved; b++) {
        if (b == p[a]) continue;
        int c = inv[b], old = p[a];
        p[a] = b;
        if (c >= 0) p[c] = old;
        double e = ssi_full_energy(S, p, NULL);
        if (e < E - 1e-15 * fabs(E)) E = e, improved = 1;
        else {
          p[a] = old;
          if (c >= 0) p[c] = b;
        }
      }
  }
  for (int k = 0; k < S->ntop; k++) S->top_e[k] = INFINITY;
  keep_leaf(S, p, E);
  for (int b = 0; b < nb; b++) inv[b] = -1;
  for (int a = 0; a < na; a++) inv[p[a]] = a;
  for (int a = 0; a < na; a++)
    for (int b = 0; b < nb; b++) {
      if (b == p[a]) continue;
      int c = inv[b], old = p[a];
      if (c >= 0 && c < a) continue; /* each swap once */
      p[a] = b;
      if (c >= 0) p[c] = old;
      keep_leaf(S, p, ssi_full_energy(S, p, NULL));
      p[a] = old;
      if (c >= 0) p[c] = b;
    }
  rc = 0;
out:
  free(C), free(pa), free(pb), free(tmp), free(p), free(inv);
  return rc;
}

double ssi_count_injections(int na, int nb) {
  double c = 1;
  for (int i = 0; i < na; i++) c *= nb - i;
  return c;
}

void ssi_run_search(ssi_search *S, int exact, int ntop, int self, int *status) {
  S->ntop = ntop;
  for (int k = 0; k < SSI_TOPK; k++) S->top_e[k] = INFINITY;
  for (int b = 0; b < S->nb; b++) S->used[b] = 0;
  if (exact) dfs(S, 0, 0.0);
  else if (relaxed(S, self)) *status = 1;
}

/* unary costs of A's centres against Q's and their suffix minima (the search's bound) */
void ssi_fill_unary(ssi_search *S, double *U, double *minU, const ss_centre_signature *A, const ss_centre_signature *Q,
                    double w_descr) {
  const int na = A->m, nq = Q->m, nd = A->nd;
  S->nb = nq, S->DB = Q->D;
  for (int a = 0; a < na; a++)
    for (int b = 0; b < nq; b++) {
      double s = 0;
      for (int j = 0; j < nd; j++) {
        double d = A->descr[(size_t)a * nd + j] - Q->descr[(size_t)b * nd + j];
        s += d * d;
      }
      U[(size_t)a * nq + b] = w_descr * s / na;
    }
  minU[na] = 0;
  for (int a = na - 1; a >= 0; a--) {
    double mn = INFINITY;
    for (int b = 0; b < nq; b++) mn = U[(size_t)a * nq + b] < mn ? U[(size_t)a * nq + b] : mn;
    minU[a] = minU[a + 1] + mn;
  }
}

void ssi_init_search(ssi_search *S, const ss_centre_signature *A, const ss_autopair_options *o, double *U, double *minU,
                     int *cur, int *used, int *buf) {
  const int na = A->m;
  double d2 = 0;
  for (int a = 0; a < na; a++)
    for (int c = a + 1; c < na; c++) d2 += A->D[a + (size_t)na * c] * A->D[a + (size_t)na * c];
  memset(S, 0, sizeof *S);
  S->na = na, S->U = U, S->DA = A->D, S->wg = d2 > 0 ? o->w_geo / d2 : 0.0, S->minU = minU, S->cur = cur, S->used = used;
  for (int k = 0; k < SSI_TOPK; k++) S->top_p[k] = buf + (size_t)na * k;
}
