/* Triangle BVH: median split on the longest axis of the centroid box, small leaves; nearest-point
 * queries visit the nearer child first and prune by box distance. */
#include "bvh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define LEAF_SIZE 4

/* quickselect tri[lo..hi) so that the element of rank `nth` is in place along axis k
 * (cen: 3 coordinates of each triangle's centroid, by triangle index) */
static void select_nth(const double *cen, int *tri, int lo, int hi, int nth, int k) {
  while (hi - lo > 1) {
    int mid = lo + (hi - lo) / 2;
    double pv = cen[3 * tri[mid] + k];
    int i = lo, j = hi - 1;
    while (i <= j) {
      while (cen[3 * tri[i] + k] < pv) i++;
      while (cen[3 * tri[j] + k] > pv) j--;
      if (i <= j) { int t = tri[i]; tri[i] = tri[j]; tri[j] = t; i++; j--; }
    }
    if (nth <= j) hi = j + 1;
    else if (nth >= i) lo = i;
    else return;
  }
}

static void node_bounds(const ssi_bvh *b, ssi_bvh_node *n) {
  for (int k = 0; k < 3; k++) { n->lo[k] = INFINITY; n->hi[k] = -INFINITY; }
  for (int i = n->first; i < n->first + n->count; i++) {
    const int *f = b->F + 3 * b->tri[i];
    for (int c = 0; c < 3; c++)
      for (int k = 0; k < 3; k++) {
        double x = b->V[3 * f[c] + k];
        if (x < n->lo[k]) n->lo[k] = x;
        if (x > n->hi[k]) n->hi[k] = x;
      }
  }
}

ss_status ssi_bvh_build(const ss_mesh *m, ssi_bvh *b, ss_error *err) {
  memset(b, 0, sizeof *b);
  b->V = m->V; b->F = m->F; b->nf = m->nf;
  if (m->nf <= 0) return ss_fail(err, SS_ERR_INVALID, "bvh: empty mesh");
  int cap = 2 * m->nf + 1; /* a binary tree with at most nf leaves */
  b->nodes = malloc(sizeof(ssi_bvh_node) * cap);
  b->tri = malloc(sizeof(int) * m->nf);
  int *stack = malloc(sizeof(int) * 128);
  double *cen = malloc(sizeof(double) * 3 * (size_t)m->nf);
  if (!b->nodes || !b->tri || !stack || !cen) {
    free(stack); free(cen); ssi_bvh_free(b);
    return ss_fail(err, SS_ERR_NOMEM, "bvh: out of memory");
  }
  for (int i = 0; i < m->nf; i++) {
    b->tri[i] = i;
    const int *f = m->F + 3 * i;
    for (int k = 0; k < 3; k++) cen[3 * i + k] = (m->V[3 * f[0] + k] + m->V[3 * f[1] + k] + m->V[3 * f[2] + k]) / 3.0;
  }
  b->nnodes = 1;
  b->nodes[0].first = 0; b->nodes[0].count = m->nf; b->nodes[0].left = -1;
  int sp = 0;
  stack[sp++] = 0;
  while (sp) {
    int ni = stack[--sp];
    ssi_bvh_node *n = &b->nodes[ni];
    node_bounds(b, n);
    if (n->count <= LEAF_SIZE) continue;
    double clo[3] = {INFINITY, INFINITY, INFINITY}, chi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = n->first; i < n->first + n->count; i++)
      for (int k = 0; k < 3; k++) {
        double c = cen[3 * b->tri[i] + k];
        if (c < clo[k]) clo[k] = c;
        if (c > chi[k]) chi[k] = c;
      }
    int ax = 0;
    for (int k = 1; k < 3; k++) if (chi[k] - clo[k] > chi[ax] - clo[ax]) ax = k;
    int half = n->count / 2;
    select_nth(cen, b->tri, n->first, n->first + n->count, n->first + half, ax);
    int l = b->nnodes;
    b->nnodes += 2;
    ssi_bvh_node *L = &b->nodes[l], *R = &b->nodes[l + 1];
    L->first = n->first; L->count = half; L->left = -1;
    R->first = n->first + half; R->count = n->count - half; R->left = -1;
    n->left = l;
    stack[sp++] = l;
    stack[sp++] = l + 1; /* depth ≤ log2(nf) + 1, far below 128 */
  }
  free(stack);
  free(cen);
  return SS_OK;
}

void ssi_bvh_free(ssi_bvh *b) {
  free(b->nodes);
  free(b->tri);
  memset(b, 0, sizeof *b);
}

static inline double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Region test in barycentric terms (Voronoi regions of the vertices, edges and face). */
void ssi_closest_point_triangle(const double p[3], const double a[3], const double b[3], const double c[3],
                               double q[3]) {
  double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
  double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  if (d1 <= 0 && d2 <= 0) { memcpy(q, a, 3 * sizeof(double)); return; }
  double bp[3] = {p[0] - b[0], p[1] - b[1], p[2] - b[2]};
  double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  if (d3 >= 0 && d4 <= d3) { memcpy(q, b, 3 * sizeof(double)); return; }
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    double t = d1 / (d1 - d3);
    for (int k = 0; k < 3; k++) q[k] = a[k] + t * ab[k];
    return;
  }
  double cp[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
  double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  if (d6 >= 0 && d5 <= d6) { memcpy(q, c, 3 * sizeof(double)); return; }
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    double t = d2 / (d2 - d6);
    for (int k = 0; k < 3; k++) q[k] = a[k] + t * ac[k];
    return;
  }
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    for (int k = 0; k < 3; k++) q[k] = b[k] + t * (c[k] - b[k]);
    return;
  }
  double den = va + vb + vc;
  if (!(den != 0)) { memcpy(q, a, 3 * sizeof(double)); return; } /* degenerate triangle */
  double v = vb / den, w = vc / den;
  for (int k = 0; k < 3; k++) q[k] = a[k] + v * ab[k] + w * ac[k];
}

static inline double box_d2(const ssi_bvh_node *n, const double p[3]) {
  double d = 0;
  for (int k = 0; k < 3; k++) {
    double e = 0;
    if (p[k] < n->lo[k]) e = n->lo[k] - p[k];
    else if (p[k] > n->hi[k]) e = p[k] - n->hi[k];
    d += e * e;
  }
  return d;
}

static inline double tri_d2(const ssi_bvh *b, int t, const double p[3], double q[3]) {
  const int *f = b->F + 3 * t;
  ssi_closest_point_triangle(p, b->V + 3 * f[0], b->V + 3 * f[1], b->V + 3 * f[2], q);
  double dx = q[0] - p[0], dy = q[1] - p[1], dz = q[2] - p[2];
  return dx * dx + dy * dy + dz * dz;
}

int ssi_bvh_closest(const ssi_bvh *b, const double p[3], int hint, double q[3], double *d2) {
  double best = INFINITY, bq[3] = {0, 0, 0}, tq[3];
  int bt = -1;
  if (hint >= 0 && hint < b->nf) {
    best = tri_d2(b, hint, p, bq);
    bt = hint;
  }
  int stack[128], sp = 0;
  stack[sp++] = 0;
  while (sp) {
    const ssi_bvh_node *n = &b->nodes[stack[--sp]];
    if (box_d2(n, p) >= best && bt >= 0) continue;
    if (n->left < 0) {
      for (int i = n->first; i < n->first + n->count; i++) {
        int t = b->tri[i];
        if (t == hint) continue;
        double d = tri_d2(b, t, p, tq);
        if (d < best || bt < 0) { best = d; bt = t; memcpy(bq, tq, sizeof bq); }
      }
      continue;
    }
    const ssi_bvh_node *L = &b->nodes[n->left], *R = &b->nodes[n->left + 1];
    double dl = box_d2(L, p), dr = box_d2(R, p);
    /* push the farther child first so the nearer one is explored first */
    if (dl <= dr) {
      if (dr < best || bt < 0) stack[sp++] = n->left + 1;
      if (dl < best || bt < 0) stack[sp++] = n->left;
    } else {
      if (dl < best || bt < 0) stack[sp++] = n->left;
      if (dr < best || bt < 0) stack[sp++] = n->left + 1;
    }
  }
  if (q) memcpy(q, bq, sizeof bq);
  if (d2) *d2 = best;
  return bt;
}
