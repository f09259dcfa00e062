/* Exact point-to-point geodesic queries: a reusable query object, one source to a few targets, and
 * batches of pairs (the geodesic error of a map). Each query touches only the region it settles. */
#include "geodesic/vtp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SS_GEODESIC_LANDMARK_BATCH 32
#define SS_GEODESIC_DEFAULT_LANDMARKS 8

struct ss_geodesic_query {
  const ss_geodesic_mesh *gm;
  const ss_geodesic_landmarks *lm;
  ssi_vtp_ws *ws;
};

ss_status ss_geodesic_query_new(const ss_geodesic_mesh *gm, const ss_geodesic_landmarks *lm, ss_geodesic_query **out,
                                ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "null output");
  *out = NULL;
  if (!gm) return ss_fail(err, SS_ERR_INVALID, "null geodesic mesh");
  ss_geodesic_query *q = calloc(1, sizeof *q);
  if (!q || !(q->ws = ssi_vtp_ws_new(gm->nv, gm->nf))) {
    free(q);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory");
  }
  q->gm = gm;
  q->lm = lm;
  *out = q;
  return SS_OK;
}

void ss_geodesic_query_free(ss_geodesic_query *q) {
  if (!q) return;
  ssi_vtp_ws_free(q->ws);
  free(q);
}

ss_status ss_geodesic_query_run(ss_geodesic_query *q, int source, const int *targets, int ntargets, double *out,
                                ss_error *err) {
  if (!q) return ss_fail(err, SS_ERR_INVALID, "null geodesic query");
  if (ntargets < 0 || (ntargets > 0 && (!targets || !out))) return ss_fail(err, SS_ERR_INVALID, "invalid target list");
  if (source < 0 || source >= q->gm->nv) return ss_fail(err, SS_ERR_INVALID, "source vertex %d outside [0,%d)", source, q->gm->nv);
  if (ntargets == 0) return SS_OK;
  return ssi_vtp_query(q->gm, q->lm, q->ws, source, targets, ntargets, 1, 0, out, err);
}

ss_status ss_geodesic_one_to_many(const ss_geodesic_mesh *gm, const ss_geodesic_landmarks *lm, int source,
                                  const int *targets, int ntargets, double *out, ss_error *err) {
  ss_geodesic_query *q;
  ss_status st = ss_geodesic_query_new(gm, lm, &q, err);
  if (st) return st;
  st = ss_geodesic_query_run(q, source, targets, ntargets, out, err);
  ss_geodesic_query_free(q);
  return st;
}

/* Far pairs (straight distance over a tenth of the bounding-box diagonal) are what landmark bounds
 * speed up: a batch with at least SS_GEODESIC_LANDMARK_BATCH of them builds landmark fields into the
 * caller's empty accelerator slot (a few full fields; far pairs then cost a corridor instead of a
 * disc). The decision depends on the input only, never on timing. */
static int is_far(const ss_geodesic_mesh *gm, int a, int b) {
  const double *p = gm->V + 3 * (size_t)a, *q = gm->V + 3 * (size_t)b;
  double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2], r = 0.1 * gm->scale;
  return dx * dx + dy * dy + dz * dz > r * r;
}

static ss_status auto_landmarks(const ss_geodesic_mesh *gm, ss_geodesic_landmarks **lm, long nfar, ss_error *err) {
  if (!lm || *lm || nfar < SS_GEODESIC_LANDMARK_BATCH) return SS_OK;
  return ss_geodesic_landmarks_new(gm, SS_GEODESIC_DEFAULT_LANDMARKS, lm, err);
}

typedef struct {
  int root, other, idx;
} pair_ref;

static int cmp_pair(const void *x, const void *y) {
  const pair_ref *a = x, *b = y;
  if (a->root != b->root) return a->root < b->root ? -1 : 1;
  return (a->idx > b->idx) - (a->idx < b->idx);
}

/* Pairs are grouped by source. Propagating each pair from whichever end occurs in more pairs
 * (d is symmetric) was tried: it gathers the maps evaluated at the same x into one query, but a
 * multi-target query must bound the way to its nearest target, so one far target makes the whole
 * group expensive; measured slower (0.38 vs 0.26 s CPU for three maps). */
ss_status ss_geodesic_pairs(const ss_geodesic_mesh *gm, ss_geodesic_landmarks **lm, const int *src, const int *dst,
                            int npairs, double *out, ss_error *err) {
  if (!gm || npairs < 0 || (npairs > 0 && (!src || !dst || !out)))
    return ss_fail(err, SS_ERR_INVALID, "invalid arguments to ss_geodesic_pairs");
  int nv = gm->nv;
  for (int i = 0; i < npairs; i++)
    if (src[i] < 0 || src[i] >= nv || dst[i] < 0 || dst[i] >= nv)
      return ss_fail(err, SS_ERR_INVALID, "pair %d (%d,%d) outside [0,%d)", i, src[i], dst[i], nv);
  if (npairs == 0) return SS_OK;
  long nfar = 0;
  for (int i = 0; i < npairs; i++) nfar += is_far(gm, src[i], dst[i]);
  ss_status lst = auto_landmarks(gm, lm, nfar, err);
  if (lst) return lst;
  const ss_geodesic_landmarks *acc = lm ? *lm : NULL;
  pair_ref *pr = malloc(sizeof(pair_ref) * (size_t)npairs);
  int *groups = malloc(sizeof(int) * ((size_t)npairs + 1));
  if (!pr || !groups) {
    free(pr); free(groups);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory");
  }
  int np = 0;
  for (int i = 0; i < npairs; i++) {
    if (src[i] == dst[i]) { out[i] = 0; continue; }
    pr[np].root = src[i];
    pr[np].other = dst[i];
    pr[np].idx = i;
    np++;
  }
  qsort(pr, (size_t)np, sizeof(pair_ref), cmp_pair);
  int ng = 0;
  for (int i = 0; i < np; i++)
    if (i == 0 || pr[i].root != pr[i - 1].root) groups[ng++] = i;
  groups[ng] = np;
  int failed = 0;
#pragma omp parallel if (ng > 1)
  {
    ssi_vtp_ws *ws = ssi_vtp_ws_new(nv, gm->nf);
    int cap = 0, *tg = NULL;
    double *val = NULL;
    if (!ws) {
#pragma omp atomic write
      failed = 1;
    }
    /* each group writes only its own outputs: the result does not depend on the schedule */
#pragma omp for schedule(dynamic, 4)
    for (int g = 0; g < ng; g++) {
      if (!ws) continue;
      int a = groups[g], b = groups[g + 1], nt = 0;
      if (b - a > cap) {
        int nc = b - a;
        int *t2 = realloc(tg, sizeof(int) * (size_t)nc);
        if (t2) tg = t2;
        double *v2 = realloc(val, sizeof(double) * (size_t)nc);
        if (v2) val = v2;
        if (!t2 || !v2) {
#pragma omp atomic write
          failed = 1;
          continue;
        }
        cap = nc;
      }
      /* distinct targets (quadratic de-duplication for small groups; a large group is served by
       * one early-stop front whatever its repeats) */
      int dedup = b - a <= 4 * SS_VTP_MAX_HEUR;
      for (int i = a; i < b; i++) {
        int o = pr[i].other, k = 0;
        if (dedup)
          while (k < nt && tg[k] != o) k++;
        else
          k = nt;
        if (k == nt) tg[nt++] = o;
      }
      if (ssi_vtp_query(gm, acc, ws, pr[a].root, tg, nt, 1, 0, val, NULL)) {
#pragma omp atomic write
        failed = 1;
        continue;
      }
      for (int i = a; i < b; i++) {
        int k = i - a;
        if (dedup) { k = 0; while (tg[k] != pr[i].other) k++; }
        out[pr[i].idx] = val[k];
      }
    }
    free(tg); free(val);
    ssi_vtp_ws_free(ws);
  }
  free(pr); free(groups);
  if (failed) return ss_fail(err, SS_ERR_NOMEM, "out of memory computing geodesic pairs");
  return SS_OK;
}

ss_status ss_geodesic_nearest_of(const ss_geodesic_mesh *gm, ss_geodesic_landmarks **lm, const int *src,
                                 const int *dst, int k, int n, double *out, ss_error *err) {
  if (!gm || n < 0 || k < 1 || (n > 0 && (!src || !dst || !out)))
    return ss_fail(err, SS_ERR_INVALID, "invalid arguments to ss_geodesic_nearest_of");
  int nv = gm->nv;
  for (long i = 0; i < (long)n * k; i++)
    if (dst[i] < 0 || dst[i] >= nv) return ss_fail(err, SS_ERR_INVALID, "target %d outside [0,%d)", dst[i], nv);
  for (int i = 0; i < n; i++)
    if (src[i] < 0 || src[i] >= nv) return ss_fail(err, SS_ERR_INVALID, "source %d outside [0,%d)", src[i], nv);
  if (n == 0) return SS_OK;
  long nfar = 0;
  for (int i = 0; i < n; i++) {
    int all = 1;
    for (int j = 0; j < k && all; j++) all = is_far(gm, src[i], dst[(size_t)i * k + j]);
    nfar += all;
  }
  ss_status lst = auto_landmarks(gm, lm, nfar, err);
  if (lst) return lst;
  const ss_geodesic_landmarks *acc = lm ? *lm : NULL;
  int failed = 0;
#pragma omp parallel if (n > 1)
  {
    ssi_vtp_ws *ws = ssi_vtp_ws_new(nv, gm->nf);
    if (!ws) {
#pragma omp atomic write
      failed = 1;
    }
#pragma omp for schedule(dynamic, 4)
    for (int i = 0; i < n; i++) {
      if (!ws) continue;
      const int *t = dst + (size_t)i * k;
      int zero = 0;
      for (int j = 0; j < k; j++) zero |= t[j] == src[i];
      if (zero) { out[i] = 0; continue; }
      if (ssi_vtp_query(gm, acc, ws, src[i], t, k, 1, 1, out + i, NULL)) {
#pragma omp atomic write
        failed = 1;
      }
    }
    ssi_vtp_ws_free(ws);
  }
  if (failed) return ss_fail(err, SS_ERR_NOMEM, "out of memory computing geodesic distances");
  return SS_OK;
}
