/* A landmark must lie on the segmentation: a crumb (a component under 1% of the area) is given its
 * neighbours' segment only after the fact, so it has no segment of its own to pair. */
#include "match/landmark_check.h"

#include <stdlib.h>

/* landmark order by (x, y), then position: conflicts and repeats are neighbours */
typedef struct lm_key {
  int u, v, i;
} lm_key;

static int cmp_key(const void *p, const void *q) {
  const lm_key *a = p, *b = q;
  if (a->u != b->u) return a->u < b->u ? -1 : 1;
  if (a->v != b->v) return a->v < b->v ? -1 : 1;
  return (a->i > b->i) - (a->i < b->i);
}

/* In keys sorted by u: for each u given several partners, its first landmark and the first one that
 * disagrees with it; the pair whose first landmark comes earliest in *a < *b (1), else 0. Exact
 * repeats (same u, same v): the earliest in *ra < *rb. */
static int first_conflict(const lm_key *k, int n, int *a, int *b, int *ra, int *rb) {
  int found = 0;
  for (int s = 0; s < n;) {
    int e = s, f = s; /* [s, e): one u; f: its first landmark */
    while (e < n && k[e].u == k[s].u) e++;
    for (int t = s; t < e; t++)
      if (k[t].i < k[f].i) f = t;
    int q = -1, r = -1; /* the first landmark that disagrees with f; the first that repeats it */
    for (int t = s; t < e; t++) {
      if (t == f) continue;
      if (k[t].v != k[f].v && (q < 0 || k[t].i < k[q].i)) q = t;
      if (k[t].v == k[f].v && (r < 0 || k[t].i < k[r].i)) r = t;
    }
    if (q >= 0) {
      int x = k[f].i < k[q].i ? k[f].i : k[q].i, y = k[f].i < k[q].i ? k[q].i : k[f].i;
      if (!found || x < *a || (x == *a && y < *b)) *a = x, *b = y;
      found = 1;
    }
    if (r >= 0 && (*ra < 0 || k[f].i < *ra)) *ra = k[f].i, *rb = k[r].i;
    s = e;
  }
  return found;
}

ss_status ss_landmarks_check(int nl, const int *lmX, const int *lmY, int *a, int *b, ss_error *err) {
  int da, db;
  if (!a) a = &da;
  if (!b) b = &db;
  *a = *b = -1;
  if (nl < 0 || (nl > 0 && (!lmX || !lmY))) return ss_fail(err, SS_ERR_INVALID, "match: bad landmarks");
  if (nl > SS_MAX_LANDMARKS)
    return ss_fail(err, SS_ERR_INVALID,
                   "match: %d landmarks: at most %d (each adds probe functions and a geodesic field; keep the most "
                   "reliable ones, spread over the shape)",
                   nl, SS_MAX_LANDMARKS);
  if (nl < 2) return SS_OK;
  lm_key *k = malloc(sizeof *k * (size_t)nl);
  if (!k) return ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
  int ra = -1, rb = -1, ca = -1, cb = -1, side = -1;
  for (int s = 0; s < 2; s++) { /* s 0: a vertex of X with two partners; 1: a vertex of Y */
    for (int i = 0; i < nl; i++) k[i] = (lm_key){s ? lmY[i] : lmX[i], s ? lmX[i] : lmY[i], i};
    qsort(k, (size_t)nl, sizeof *k, cmp_key);
    int x = -1, y = -1;
    if (first_conflict(k, nl, &x, &y, &ra, &rb) && (side < 0 || x < ca)) ca = x, cb = y, side = s;
  }
  free(k);
  if (side >= 0) {
    *a = ca, *b = cb;
    const int *own = side ? lmY : lmX, *other = side ? lmX : lmY;
    return ss_fail(err, SS_ERR_INVALID, "match: landmarks %d and %d: vertex %d of %s has two partners on %s (%d and %d)", ca,
                   cb, own[ca], side ? "Y" : "X", side ? "X" : "Y", other[ca], other[cb]);
  }
  *a = ra, *b = rb;
  return SS_OK;
}

ss_status ssi_check_landmarks_segmented(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lx,
                                        const int *ly, const int *in_x, const int *in_y, ss_error *err) {
  for (int i = 0; i < 2 * nl; i++) {
    const int onx = i < nl, l = onx ? i : i - nl;
    const ss_shape_prep *p = onx ? X : Y;
    const int v = onx ? lx[l] : ly[l];
    if (p->seg.psi && p->seg.psi[v] < 0)
      return ss_fail(err, SS_ERR_INVALID,
                     "match: %s: landmark %d (vertex %d) is on no segmented part of the shape (a component under 1%% "
                     "of the area, a crumb, gets no segmentation of its own); put the landmarks on its main components",
                     onx ? "X (the first mesh)" : "Y (the second mesh)", l, onx ? in_x[l] : in_y[l]);
  }
  return SS_OK;
}
