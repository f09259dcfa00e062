/* The k nearest of a fixed set of 3D points by a kd-tree (knn3.h). */
#include "mesh/knn3.h"

#include <float.h>
#include <stdlib.h>

#define LEAF 8

typedef struct node {
  int lo, hi;         /* the points idx[lo..hi) */
  int axis;           /* split axis, -1 for a leaf */
  double split;       /* the split coordinate */
  int left, right;    /* children (nodes), -1 for a leaf */
} node;

struct ssi_knn3 {
  const double *P;
  int n, nnode;
  int *idx;
  node *nodes;
};

/* idx[lo..hi) partly sorted so that idx[mid] holds the point of rank mid along axis (quickselect) */
static void select_rank(const double *P, int *idx, int lo, int hi, int mid, int axis) {
  while (hi - lo > 1) {
    const double pivot = P[3 * idx[lo + (hi - lo) / 2] + axis];
    int i = lo, j = hi - 1;
    while (i <= j) {
      while (P[3 * idx[i] + axis] < pivot) i++;
      while (P[3 * idx[j] + axis] > pivot) j--;
      if (i <= j) {
        const int t = idx[i];
        idx[i] = idx[j], idx[j] = t;
        i++, j--;
      }
    }
    if (mid <= j) hi = j + 1;
    else if (mid >= i) lo = i;
    else return;
  }
}

static int build(ssi_knn3 *t, int lo, int hi) {
  const int me = t->nnode++;
  node *nd = &t->nodes[me];
  nd->lo = lo, nd->hi = hi, nd->axis = -1, nd->left = nd->right = -1, nd->split = 0;
  if (hi - lo <= LEAF) return me;
  double mn[3] = {DBL_MAX, DBL_MAX, DBL_MAX}, mx[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
  for (int i = lo; i < hi; i++)
    for (int c = 0; c < 3; c++) {
      const double v = t->P[3 * t->idx[i] + c];
      if (v < mn[c]) mn[c] = v;
      if (v > mx[c]) mx[c] = v;
    }
  int axis = 0;
  for (int c = 1; c < 3; c++)
    if (mx[c] - mn[c] > mx[axis] - mn[axis]) axis = c;
  if (!(mx[axis] > mn[axis])) return me; /* all points equal: one leaf */
  const int mid = lo + (hi - lo) / 2;
  select_rank(t->P, t->idx, lo, hi, mid, axis);
  const double split = t->P[3 * t->idx[mid] + axis];
  const int l = build(t, lo, mid), r = build(t, mid, hi);
  nd = &t->nodes[me]; /* (t->nodes does not move: sized up front) */
  nd->axis = axis, nd->split = split, nd->left = l, nd->right = r;
  return me;
}

ss_status ssi_knn3_build(int n, const double *P, ssi_knn3 **out, ss_error *err) {
  *out = NULL;
  if (n < 1 || !P) return ss_fail(err, SS_ERR_INVALID, "knn3: no points");
  ssi_knn3 *t = calloc(1, sizeof *t);
  if (t) t->idx = malloc(sizeof(int) * (size_t)n), t->nodes = malloc(sizeof(node) * (2 * (size_t)n / (LEAF / 2) + 2));
  if (!t || !t->idx || !t->nodes) {
    ssi_knn3_free(t);
    return ss_fail(err, SS_ERR_NOMEM, "knn3: out of memory");
  }
  t->P = P, t->n = n;
  for (int i = 0; i < n; i++) t->idx[i] = i;
  build(t, 0, n);
  *out = t;
  return SS_OK;
}

/* the current k best as a sorted list (k is small: insertion is cheaper than a heap) */
typedef struct best {
  int k, m;
  int *idx;
  double *d2;
} best;

static void offer(best *b, int i, double d) {
  if (b->m == b->k && (d > b->d2[b->m - 1] || (d == b->d2[b->m - 1] && i > b->idx[b->m - 1]))) return;
  int p = b->m < b->k ? b->m++ : b->m - 1;
  while (p > 0 && (b->d2[p - 1] > d || (b->d2[p - 1] == d && b->idx[p - 1] > i))) {
    b->d2[p] = b->d2[p - 1], b->idx[p] = b->idx[p - 1];
    p--;
  }
  b->d2[p] = d, b->idx[p] = i;
}

static void search(const ssi_knn3 *t, int ni, const double *q, best *b) {
  const node *nd = &t->nodes[ni];
  if (nd->axis < 0) {
    for (int j = nd->lo; j < nd->hi; j++) {
      const int i = t->idx[j];
      const double *p = t->P + 3 * (size_t)i;
      const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
      offer(b, i, dx * dx + dy * dy + dz * dz);
    }
    return;
  }
  const double off = q[nd->axis] - nd->split;
  const int near = off < 0 ? nd->left : nd->right, far = off < 0 ? nd->right : nd->left;
  search(t, near, q, b);
  /* <=: a point on the split plane may lie on either side, and ties break by index */
  if (b->m < b->k || off * off <= b->d2[b->m - 1]) search(t, far, q, b);
}

void ssi_knn3_query(const ssi_knn3 *t, const double q[3], int k, int *idx, double *d2) {
  double own[64];
  best b = {k < t->n ? k : t->n, 0, idx, d2 ? d2 : own};
  if (!d2 && b.k > 64) b.k = 64;
  search(t, 0, q, &b);
}

void ssi_knn3_free(ssi_knn3 *t) {
  if (!t) return;
  free(t->idx), free(t->nodes);
  free(t);
}
