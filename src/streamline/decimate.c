/* Quadric-error edge-collapse decimation (Garland & Heckbert 1997) on the remesher's corner-table mesh,
 * keeping the topology: see decimate.h. Edges are taken cheapest first from a binary heap with lazy
 * deletion (an entry is stale when either endpoint changed since it was queued: every change gives
 * the vertex a fresh, larger stamp, so one stamp per entry, the larger of its endpoints', tells). */
#include "decimate.h"
#include "remesh_mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_WALK 4096
#define MAX_VALENCE 20      /* a collapse may not create a vertex of higher valence */
#define MIN_QUALITY 0.08    /* new triangles below this shape quality (1 = equilateral) are refused ... */
#define MIN_NORMAL_COS 0.2  /* ... and so are collapses that turn a triangle by more than ~78° */
#define LENGTH_WEIGHT 1e-3  /* cost += this · |e|⁴: flat regions (zero quadric error) go shortest edge first */

typedef struct { double key; int h, stamp; } item;

/* Bucket queue on a logarithmic scale of the cost (BINS_PER_OCTAVE bins per factor of 2, around the
 * median of the first costs): push and pop in O(1); within a bin the order is last in, first out.
 * This orders the collapses by cost up to a factor of 2^(1/BINS_PER_OCTAVE), which is all the
 * ordering a decimation to a mesh that is remeshed anyway needs, at a fraction of a heap's cost. */
#define BINS_PER_OCTAVE 8
#define OCTAVES 96
#define NBINS (BINS_PER_OCTAVE * OCTAVES + 2)
typedef struct { item *a; int n, cap; } bin;
typedef struct {
  bin b[NBINS];
  int lo;       /* no item in a bin below this */
  double scale; /* cost at the middle bin */
  size_t count;
} bqueue;

static int bin_of(const bqueue *q, double key) {
  if (!(key > 0)) return 0;
  double l = log2(key / q->scale) * BINS_PER_OCTAVE + (double)(NBINS / 2);
  if (!(l >= 1)) return 1;
  if (l > NBINS - 1) return NBINS - 1;
  return (int)l;
}

static int bq_push(bqueue *q, item it) {
  int k = bin_of(q, it.key);
  bin *b = &q->b[k];
  if (b->n == b->cap) {
    int c = b->cap ? 2 * b->cap : 256;
    item *a = realloc(b->a, sizeof(item) * (size_t)c);
    if (!a) return -1;
    b->a = a, b->cap = c;
  }
  b->a[b->n++] = it;
  if (k < q->lo) q->lo = k;
  q->count++;
  return 0;
}

static int bq_pop(bqueue *q, item *it) {
  while (q->lo < NBINS && q->b[q->lo].n == 0) q->lo++;
  if (q->lo >= NBINS) return 0;
  *it = q->b[q->lo].a[--q->b[q->lo].n];
  q->count--;
  return 1;
}

static void bq_clear(bqueue *q) {
  for (int k = 0; k < NBINS; k++) q->b[k].n = 0;
  q->lo = NBINS;
  q->count = 0;
}

static void bq_free(bqueue *q) {
  for (int k = 0; k < NBINS; k++) free(q->b[k].a);
  memset(q, 0, sizeof *q);
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

/* Symmetric 4×4 quadric, upper triangle: a11 a12 a13 a14 a22 a23 a24 a33 a34 a44. */
static double quadric_eval(const double *q, const double *x) {
  return q[0] * x[0] * x[0] + 2 * q[1] * x[0] * x[1] + 2 * q[2] * x[0] * x[2] + 2 * q[3] * x[0] + q[4] * x[1] * x[1] +
         2 * q[5] * x[1] * x[2] + 2 * q[6] * x[1] + q[7] * x[2] * x[2] + 2 * q[8] * x[2] + q[9];
}

static inline double d2(const double *a, const double *b) {
  double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return x * x + y * y + z * z;
}

/* Cost of merging the edge's ends (quadrics q0 + q1) and where the merged vertex goes. */
static double edge_cost(const double *q0, const double *q1, const double *p0, const double *p1, double x[3]) {
  double q[10];
  for (int k = 0; k < 10; k++) q[k] = q0[k] + q1[k];
  const double L2 = d2(p0, p1), len4 = L2 * L2;
  double mid[3] = {0.5 * (p0[0] + p1[0]), 0.5 * (p0[1] + p1[1]), 0.5 * (p0[2] + p1[2])};
  /* optimal point: A x = -b, when A is well conditioned and x stays near the edge */
  const double a = q[0], b = q[1], c = q[2], d = q[4], e = q[5], f = q[7];
  const double c00 = d * f - e * e, c01 = c * e - b * f, c02 = b * e - c * d;
  const double det = a * c00 + b * c01 + c * c02, tr = a + d + f;
  if (tr > 0 && fabs(det) > 1e-6 * tr * tr * tr) {
    const double c11 = a * f - c * c, c12 = b * c - a * e, c22 = a * d - b * b;
    const double r0 = -q[3], r1 = -q[6], r2 = -q[8];
    double y[3] = {(c00 * r0 + c01 * r1 + c02 * r2) / det, (c01 * r0 + c11 * r1 + c12 * r2) / det,
                   (c02 * r0 + c12 * r1 + c22 * r2) / det};
    if (d2(y, mid) <= L2) {
      memcpy(x, y, sizeof y);
      double v = quadric_eval(q, y);
      return (v > 0 ? v : 0) + LENGTH_WEIGHT * len4;
    }
  }
  const double *cand[3] = {mid, p0, p1};
  double best = quadric_eval(q, mid);
  memcpy(x, mid, sizeof mid);
  for (int i = 1; i < 3; i++) { /* an end only when clearly better than the midpoint */
    double v = quadric_eval(q, cand[i]);
    if (v < best - 1e-12 * fabs(best)) best = v, memcpy(x, cand[i], 3 * sizeof(double));
  }
  return (best > 0 ? best : 0) + LENGTH_WEIGHT * len4;
}

static inline void tri_normal(const double *a, const double *b, const double *c, double n[3]) {
  double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  n[0] = u[1] * w[2] - u[2] * w[1];
  n[1] = u[2] * w[0] - u[0] * w[2];
  n[2] = u[0] * w[1] - u[1] * w[0];
}

/* 2√3·|n| / (sum of squared edge lengths): 1 for an equilateral triangle, 0 for a degenerate one. */
static inline double quality(const double *a, const double *b, const double *c, const double *n) {
  double s = d2(a, b) + d2(b, c) + d2(c, a);
  return s > 0 ? 3.4641016151377544 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) / s : 0;
}

/* Geometry of the collapse of h with the merged vertex at p: no triangle turned over or by much, none
 * made much worse than the quality floor, no high valence. */
static int geometry_ok(const rm_mesh *m, int h, const double *p) {
  const int o = m->opp[h], fa = h / 3, fb = o / 3;
  const int ends[2] = {m->F[h], m->F[o]};
  if (m->val[ends[0]] + m->val[ends[1]] - 4 > MAX_VALENCE) return 0;
  for (int e = 0; e < 2; e++) {
    int v = ends[e], s = m->vh[v], hh = s, n = 0;
    do {
      int f = hh / 3;
      if (f != fa && f != fb) {
        const double *px = m->V + 3 * m->F[rm_next(hh)], *py = m->V + 3 * m->F[rm_prev(hh)];
        double nold[3], nnew[3];
        tri_normal(m->V + 3 * v, px, py, nold);
        tri_normal(p, px, py, nnew);
        double dot = nold[0] * nnew[0] + nold[1] * nnew[1] + nold[2] * nnew[2];
        double lo = sqrt(nold[0] * nold[0] + nold[1] * nold[1] + nold[2] * nold[2]);
        double ln = sqrt(nnew[0] * nnew[0] + nnew[1] * nnew[1] + nnew[2] * nnew[2]);
        if (!(dot > MIN_NORMAL_COS * lo * ln)) return 0;
        double qn = quality(p, px, py, nnew);
        if (qn < MIN_QUALITY && qn < quality(m->V + 3 * v, px, py, nold)) return 0;
      }
      hh = m->opp[rm_prev(hh)];
    } while (hh != s && ++n < MAX_WALK);
  }
  return 1;
}

ss_status ssi_decimate(const ss_mesh *in, int target_faces, ss_mesh *out, int *to_coarse, int **src_out,
                       ss_error *err) {
  if (src_out) *src_out = NULL;
  if (!in || !out || !to_coarse) return ss_fail(err, SS_ERR_INVALID, "decimate: NULL argument");
  memset(out, 0, sizeof *out);
  if (target_faces < 4) return ss_fail(err, SS_ERR_INVALID, "decimate: target of %d faces below 4", target_faces);
  rm_mesh m;
  ss_status st = rm_init(&m, in, err);
  if (st) return st;
  const int nv = m.nv;
  double *Q = calloc((size_t)nv * 10, sizeof(double));
  int *ver = calloc((size_t)nv, sizeof(int)), *parent = malloc(sizeof(int) * (size_t)nv);
  int *vmap = NULL, *src = NULL;
  static const bqueue q0;
  bqueue q = q0;
  double *costs = NULL;
  int *edges = NULL;
  if (!Q || !ver || !parent) goto nomem;
  for (int v = 0; v < nv; v++) parent[v] = v;

  /* area-weighted plane quadrics */
  for (int f = 0; f < m.nf; f++) {
    const int *t = m.F + 3 * f;
    const double *a = m.V + 3 * t[0], *b = m.V + 3 * t[1], *c = m.V + 3 * t[2];
    double n[3];
    tri_normal(a, b, c, n);
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(l > 0)) continue;
    double w = 0.5 * l; /* area */
    n[0] /= l, n[1] /= l, n[2] /= l;
    double dd = -(n[0] * a[0] + n[1] * a[1] + n[2] * a[2]);
    double k[10] = {n[0] * n[0], n[0] * n[1], n[0] * n[2], n[0] * dd, n[1] * n[1],
                    n[1] * n[2], n[1] * dd,   n[2] * n[2], n[2] * dd, dd * dd};
    for (int j = 0; j < 3; j++)
      for (int i = 0; i < 10; i++) Q[10 * (size_t)t[j] + i] += w * k[i];
  }

  int live = m.nf, stamp = 0;
  size_t ne = 0;
  for (int round = 0; live > target_faces && round < 8; round++) {
    /* every edge once (the half-edge whose twin has the larger index) */
    free(costs), free(edges);
    costs = malloc(sizeof(double) * (size_t)live * 3 / 2 + sizeof(double));
    edges = malloc(sizeof(int) * (size_t)live * 3 / 2 + sizeof(int));
    if (!costs || !edges) goto nomem;
    ne = 0;
    for (int h = 0; h < 3 * m.nf; h++) {
      if (m.fdead[h / 3] || m.opp[h] < h) continue;
      int v0 = m.F[h], v1 = m.F[rm_next(h)];
      double x[3];
      costs[ne] = edge_cost(Q + 10 * (size_t)v0, Q + 10 * (size_t)v1, m.V + 3 * v0, m.V + 3 * v1, x);
      edges[ne++] = h;
    }
    if (round == 0) { /* the queue's scale: the median cost of a sample of the edges */
      double sample[1024];
      int ns = 0;
      for (size_t i = 0; i < ne && ns < 1024; i += ne / 1024 + 1) sample[ns++] = costs[i];
      qsort(sample, (size_t)ns, sizeof(double), cmp_double);
      q.scale = ns && sample[ns / 2] > 0 ? sample[ns / 2] : 1;
    }
    bq_clear(&q);
    for (size_t i = ne; i-- > 0;) { /* reversed: within a bin, the lower edge first */
      int h = edges[i], v0 = m.F[h], v1 = m.F[rm_next(h)];
      item it = {costs[i], h, ver[v0] > ver[v1] ? ver[v0] : ver[v1]};
      if (bq_push(&q, it)) goto nomem;
    }
    free(costs), free(edges);
    costs = NULL, edges = NULL;
    int done = 0;
    item it;
    while (live > target_faces && bq_pop(&q, &it)) {
      int h = it.h;
      if (m.fdead[h / 3]) continue;
      int v0 = m.F[h], v1 = m.F[rm_next(h)];
      if ((ver[v0] > ver[v1] ? ver[v0] : ver[v1]) != it.stamp) continue; /* stale */
      double x[3];
      edge_cost(Q + 10 * (size_t)v0, Q + 10 * (size_t)v1, m.V + 3 * v0, m.V + 3 * v1, x);
      if (!rm_link_ok(&m, h) || !geometry_ok(&m, h, x)) continue;
      rm_collapse_edge(&m, h, x); /* v0 goes, v1 stays at x */
      for (int k = 0; k < 10; k++) Q[10 * (size_t)v1 + k] += Q[10 * (size_t)v0 + k];
      parent[v0] = v1;
      ver[v1] = ++stamp;
      live -= 2;
      done++;
      /* the edges around the merged vertex, at their new cost */
      int s = m.vh[v1], hh = s, n = 0;
      do {
        int w = m.F[rm_next(hh)];
        double y[3];
        item ni = {edge_cost(Q + 10 * (size_t)v1, Q + 10 * (size_t)w, m.V + 3 * v1, m.V + 3 * w, y), hh,
                   ver[v1] > ver[w] ? ver[v1] : ver[w]};
        if (bq_push(&q, ni)) goto nomem;
        hh = m.opp[rm_prev(hh)];
      } while (hh != s && ++n < MAX_WALK);
    }
    if (done == 0) break; /* nothing left that keeps the topology and the triangles */
  }
  bq_free(&q);

  /* the coarse mesh: live vertices in input order */
  vmap = malloc(sizeof(int) * (size_t)nv);
  if (!vmap) goto nomem;
  int nc = 0;
  for (int v = 0; v < nv; v++) vmap[v] = m.vdead[v] ? -1 : nc++;
  if ((st = ss_mesh_alloc(out, nc, live, err))) goto fail;
  src = malloc(sizeof(int) * (size_t)(nc > 0 ? nc : 1));
  if (!src) goto nomem;
  for (int v = 0; v < nv; v++)
    if (vmap[v] >= 0) {
      memcpy(out->V + 3 * (size_t)vmap[v], m.V + 3 * (size_t)v, 3 * sizeof(double));
      src[vmap[v]] = v;
    }
  {
    int g = 0;
    for (int f = 0; f < m.nf; f++) {
      if (m.fdead[f]) continue;
      for (int k = 0; k < 3; k++) out->F[3 * (size_t)g + k] = vmap[m.F[3 * f + k]];
      g++;
    }
  }

  /* input vertex -> its survivor (path compression), then a greedy walk to the nearest coarse vertex */
  for (int v = 0; v < in->nv; v++) {
    int r = v;
    while (parent[r] != r) r = parent[r];
    for (int u = v; parent[u] != r && u != r;) {
      int nx = parent[u];
      parent[u] = r;
      u = nx;
    }
  }
  #pragma omp parallel for schedule(static) if (in->nv > 50000)
  for (int v = 0; v < in->nv; v++) {
    int cur = parent[v];
    if (m.vdead[cur]) { to_coarse[v] = -1; continue; }
    const double *p = in->V + 3 * (size_t)v;
    double best = d2(p, m.V + 3 * (size_t)cur);
    for (int step = 0; step < 64; step++) {
      int s = m.vh[cur], hh = s, n = 0, next = cur;
      do {
        int w = m.F[rm_next(hh)];
        double dw = d2(p, m.V + 3 * (size_t)w);
        if (dw < best) best = dw, next = w;
        hh = m.opp[rm_prev(hh)];
      } while (hh != s && ++n < MAX_WALK);
      if (next == cur) break;
      cur = next;
    }
    to_coarse[v] = vmap[cur];
  }
  if (src_out) *src_out = src, src = NULL;
  st = SS_OK;
  goto done;

nomem:
  st = ss_fail(err, SS_ERR_NOMEM, "decimate: out of memory");
fail:
  ss_mesh_free(out);
done:
  rm_free(&m);
  free(Q), free(ver), free(parent), free(vmap), free(src), free(costs), free(edges);
  bq_free(&q);
  return st;
}
