/* Polygonisation of an implicit surface: marching tetrahedra on a BCC lattice (closed manifold by
 * construction), then Delaunay flips + tangential relaxation projected back onto the surface for
 * triangle quality. Used by the synthetic humanoid. */
#include "synth/synth_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ---- small open-addressing map uint64 -> int (key 0 is "empty", so callers store key+1) ---- */
typedef struct {
  uint64_t *key;
  int *val;
  size_t cap, n;
} u64map;

static int u64map_init(u64map *m, size_t want) {
  m->cap = 64;
  while (m->cap < 2 * want) m->cap <<= 1;
  m->n = 0;
  m->key = calloc(m->cap, sizeof(uint64_t));
  m->val = malloc(m->cap * sizeof(int));
  return m->key && m->val ? 0 : -1;
}
static void u64map_free(u64map *m) {
  free(m->key);
  free(m->val);
  memset(m, 0, sizeof *m);
}
static size_t u64_slot(const u64map *m, uint64_t k) {
  /* Fibonacci hashing: the top bits of the product depend on every bit of the key */
  uint64_t x = k ^ (k >> 29);
  size_t h = (size_t)((x * 0x9E3779B97F4A7C15ull) >> 40) & (m->cap - 1);
  while (m->key[h] && m->key[h] != k) h = (h + 1) & (m->cap - 1);
  return h;
}
static int u64map_grow(u64map *m) {
  u64map g;
  g.cap = m->cap * 2;
  g.n = m->n;
  g.key = calloc(g.cap, sizeof(uint64_t));
  g.val = malloc(g.cap * sizeof(int));
  if (!g.key || !g.val) {
    free(g.key);
    free(g.val);
    return -1;
  }
  for (size_t i = 0; i < m->cap; i++)
    if (m->key[i]) {
      size_t s = u64_slot(&g, m->key[i]);
      g.key[s] = m->key[i];
      g.val[s] = m->val[i];
    }
  u64map_free(m);
  *m = g;
  return 0;
}
/* Returns the stored value, or -1 when absent. */
static int u64map_get(const u64map *m, uint64_t k) {
  size_t s = u64_slot(m, k + 1);
  return m->key[s] ? m->val[s] : -1;
}
static int u64map_put(u64map *m, uint64_t k, int v) {
  if (2 * (m->n + 1) > m->cap && u64map_grow(m)) return -1;
  size_t s = u64_slot(m, k + 1);
  if (!m->key[s]) m->n++;
  m->key[s] = k + 1;
  m->val[s] = v;
  return 0;
}
static uint64_t edge_key(int a, int b) {
  if (a > b) { int t = a; a = b; b = t; }
  return ((uint64_t)(uint32_t)a << 32) | (uint32_t)b;
}

/* ---- growable arrays ---- */
typedef struct {
  double *v;
  int n, cap;
} dvec3;
typedef struct {
  int *f;
  int n, cap;
} ivec3;
static int dvec3_push(dvec3 *a, const double p[3]) {
  if (a->n == a->cap) {
    int nc = a->cap ? 2 * a->cap : 4096;
    double *t = realloc(a->v, sizeof(double) * 3 * (size_t)nc);
    if (!t) return -1;
    a->v = t;
    a->cap = nc;
  }
  memcpy(a->v + 3 * (size_t)a->n, p, 3 * sizeof(double));
  a->n++;
  return 0;
}
static int ivec3_push(ivec3 *a, int x, int y, int z) {
  if (a->n == a->cap) {
    int nc = a->cap ? 2 * a->cap : 8192;
    int *t = realloc(a->f, sizeof(int) * 3 * (size_t)nc);
    if (!t) return -1;
    a->f = t;
    a->cap = nc;
  }
  a->f[3 * a->n] = x;
  a->f[3 * a->n + 1] = y;
  a->f[3 * a->n + 2] = z;
  a->n++;
  return 0;
}

static void sub3(const double *a, const double *b, double *c) { c[0] = a[0] - b[0]; c[1] = a[1] - b[1]; c[2] = a[2] - b[2]; }
static void cross3(const double *a, const double *b, double *c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}
static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* ---- marching tetrahedra ---- */
typedef struct {
  int n[3];      /* cubes per axis */
  long ncorner;  /* (n+1)^3 corners come first, then n^3 centres */
  double lo[3], h;
  const double *val;
  u64map emap;   /* lattice edge -> output vertex */
  dvec3 V;
  ivec3 F;
} mt_state;

static void lattice_pos(const mt_state *s, long id, double p[3]) {
  double off = 0;
  long nx, ny;
  if (id < s->ncorner) {
    nx = s->n[0] + 1;
    ny = s->n[1] + 1;
  } else {
    id -= s->ncorner;
    nx = s->n[0];
    ny = s->n[1];
    off = 0.5;
  }
  long i = id % nx, j = (id / nx) % ny, k = id / (nx * ny);
  p[0] = s->lo[0] + s->h * ((double)i + off);
  p[1] = s->lo[1] + s->h * ((double)j + off);
  p[2] = s->lo[2] + s->h * ((double)k + off);
}

/* The output vertex on lattice edge (a inside, b outside), created on first use. */
static int edge_point(mt_state *s, long a, long b) {
  uint64_t k = edge_key((int)a, (int)b);
  int v = u64map_get(&s->emap, k);
  if (v >= 0) return v;
  double pa[3], pb[3], p[3];
  lattice_pos(s, a, pa);
  lattice_pos(s, b, pb);
  double fa = s->val[a], fb = s->val[b];
  double t = fa / (fa - fb);
  /* keep points off the lattice nodes: coincident points would make zero-area triangles */
  if (t < 0.02) t = 0.02;
  if (t > 0.98) t = 0.98;
  for (int d = 0; d < 3; d++) p[d] = pa[d] + t * (pb[d] - pa[d]);
  v = s->V.n;
  if (dvec3_push(&s->V, p) || u64map_put(&s->emap, k, v)) return -1;
  return v;
}

/* Triangle (p0,p1,p2) whose first point lies on lattice edge in->out: orient it so its normal points
 * towards the outside. That edge crosses the triangle's plane, so the sign test is robust. */
static int emit(mt_state *s, int p0, int p1, int p2, long in, long out) {
  double a[3], b[3], e1[3], e2[3], n[3], pi[3], po[3], d[3];
  memcpy(a, s->V.v + 3 * (size_t)p1, sizeof a);
  memcpy(b, s->V.v + 3 * (size_t)p2, sizeof b);
  sub3(a, s->V.v + 3 * (size_t)p0, e1);
  sub3(b, s->V.v + 3 * (size_t)p0, e2);
  cross3(e1, e2, n);
  lattice_pos(s, in, pi);
  lattice_pos(s, out, po);
  sub3(po, pi, d);
  if (dot3(n, d) >= 0) return ivec3_push(&s->F, p0, p1, p2);
  return ivec3_push(&s->F, p0, p2, p1);
}

static int march_tet(mt_state *s, const long t[4]) {
  int ins[4], outs[4], ni = 0, no = 0;
  for (int k = 0; k < 4; k++) {
    if (s->val[t[k]] < 0) ins[ni++] = k;
    else outs[no++] = k;
  }
  if (ni == 0 || no == 0) return 0;
  if (ni == 1 || no == 1) {
    int odd_in = ni == 1;
    long odd = odd_in ? t[ins[0]] : t[outs[0]];
    const int *others = odd_in ? outs : ins;
    int p[3];
    for (int k = 0; k < 3; k++) {
      long o = t[others[k]];
      p[k] = odd_in ? edge_point(s, odd, o) : edge_point(s, o, odd);
      if (p[k] < 0) return -1;
    }
    return odd_in ? emit(s, p[0], p[1], p[2], odd, t[others[0]]) : emit(s, p[0], p[1], p[2], t[others[0]], odd);
  }
  /* two in (a,b), two out (c,d): quad ac-ad-bd-bc, split along its shorter diagonal */
  long a = t[ins[0]], b = t[ins[1]], c = t[outs[0]], d = t[outs[1]];
  int ac = edge_point(s, a, c), ad = edge_point(s, a, d), bd = edge_point(s, b, d), bc = edge_point(s, b, c);
  if (ac < 0 || ad < 0 || bd < 0 || bc < 0) return -1;
  double u[3], w[3];
  sub3(s->V.v + 3 * (size_t)ac, s->V.v + 3 * (size_t)bd, u);
  sub3(s->V.v + 3 * (size_t)ad, s->V.v + 3 * (size_t)bc, w);
  if (dot3(u, u) <= dot3(w, w)) {
    if (emit(s, ac, ad, bd, a, c) || emit(s, ac, bd, bc, a, c)) return -1;
  } else {
    if (emit(s, ac, ad, bc, a, c) || emit(s, ad, bd, bc, a, d)) return -1;
  }
  return 0;
}

ss_status ssi_implicit_polygonize_bcc(ssi_implicit_fn f, const void *ctx, const double lo[3],
                                     const double hi[3], double h, ss_mesh *out, ss_error *err) {
  memset(out, 0, sizeof *out);
  if (!(h > 0)) return ss_fail(err, SS_ERR_INVALID, "lattice spacing must be positive");
  mt_state s;
  memset(&s, 0, sizeof s);
  s.h = h;
  long total = 1;
  for (int d = 0; d < 3; d++) {
    double ext = hi[d] - lo[d];
    if (!(ext > 0) || ext / h > 2000) return ss_fail(err, SS_ERR_INVALID, "bad polygonisation box");
    s.n[d] = (int)ceil(ext / h);
    s.lo[d] = lo[d];
    total *= s.n[d] + 1;
  }
  s.ncorner = total;
  long ncentre = (long)s.n[0] * s.n[1] * s.n[2];
  if (total + ncentre > 0x7fffffffL) return ss_fail(err, SS_ERR_INVALID, "polygonisation lattice too large");
  double *val = malloc(sizeof(double) * (size_t)(total + ncentre));
  if (!val) return ss_fail(err, SS_ERR_NOMEM, "out of memory for the lattice");
  /* each node independently: the result does not depend on the thread count */
#pragma omp parallel for schedule(static)
  for (long id = 0; id < total + ncentre; id++) {
    double p[3];
    lattice_pos(&s, id, p);
    val[id] = f(p, ctx);
  }
  s.val = val;
  if (u64map_init(&s.emap, 1 << 14)) {
    free(val);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory");
  }
  const long cx = s.n[0] + 1, cy = s.n[1] + 1, zx = s.n[0], zy = s.n[1];
#define CORNER(i, j, k) ((long)(i) + cx * ((long)(j) + cy * (long)(k)))
#define CENTRE(i, j, k) (total + (long)(i) + zx * ((long)(j) + zy * (long)(k)))
  int fail = 0;
  /* Every tetrahedron = two face-adjacent cube centres + one edge of their shared face. */
  for (int k = 0; k < s.n[2] && !fail; k++)
    for (int j = 0; j < s.n[1] && !fail; j++)
      for (int i = 0; i < s.n[0] && !fail; i++) {
        long c1 = CENTRE(i, j, k);
        for (int dir = 0; dir < 3 && !fail; dir++) {
          int ii = i + (dir == 0), jj = j + (dir == 1), kk = k + (dir == 2);
          if (ii >= s.n[0] || jj >= s.n[1] || kk >= s.n[2]) continue;
          long c2 = CENTRE(ii, jj, kk);
          long q[4]; /* the shared face's corners, in cyclic order */
          int u = (dir + 1) % 3, v = (dir + 2) % 3;
          const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
          for (int c = 0; c < 4; c++) {
            int g[3] = {i, j, k};
            g[dir] += 1;
            g[u] += du[c];
            g[v] += dv[c];
            q[c] = CORNER(g[0], g[1], g[2]);
          }
          /* quick reject: all six nodes on one side */
          int neg = (val[c1] < 0) + (val[c2] < 0) + (val[q[0]] < 0) + (val[q[1]] < 0) + (val[q[2]] < 0) +
                    (val[q[3]] < 0);
          if (neg == 0 || neg == 6) continue;
          for (int e = 0; e < 4; e++) {
            long t[4] = {c1, c2, q[e], q[(e + 1) & 3]};
            if (march_tet(&s, t)) { fail = 1; break; }
          }
        }
      }
#undef CORNER
#undef CENTRE
  free(val);
  u64map_free(&s.emap);
  if (fail) {
    free(s.V.v);
    free(s.F.f);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory while polygonising");
  }
  if (s.F.n == 0) {
    free(s.V.v);
    free(s.F.f);
    return ss_fail(err, SS_ERR_INVALID, "implicit surface has no zero crossing in the box");
  }
  out->nv = s.V.n;
  out->nf = s.F.n;
  out->V = s.V.v;
  out->F = s.F.f;
  return SS_OK;
}

/* ---- quality improvement ---- */

/* One pass of Delaunay flips: an interior edge whose opposite angles sum to more than pi is
 * replaced by the other diagonal, unless that edge exists already or the flip would fold the
 * surface. Each face takes part in at most one flip per pass. Returns flips done, -1 on OOM. */
static double cot_at(const double *p, const double *a, const double *b) {
  double u[3], v[3], c[3];
  sub3(a, p, u);
  sub3(b, p, v);
  cross3(u, v, c);
  return dot3(u, v) / (sqrt(dot3(c, c)) + 1e-300);
}
static void tri_normal(const double *V, int a, int b, int c, double n[3]) {
  double u[3], v[3];
  sub3(V + 3 * (size_t)b, V + 3 * (size_t)a, u);
  sub3(V + 3 * (size_t)c, V + 3 * (size_t)a, v);
  cross3(u, v, n);
  double l = sqrt(dot3(n, n));
  if (l > 0) for (int d = 0; d < 3; d++) n[d] /= l;
}
static uint64_t dir_key(int a, int b) { return ((uint64_t)(uint32_t)a << 32) | (uint32_t)b; }

static int flip_pass(ss_mesh *m) {
  size_t nh = 3 * (size_t)m->nf;
  char *touched = calloc((size_t)m->nf, 1);
  u64map he; /* directed edge a->b -> 3*face + corner (entries of flipped faces go stale) */
  if (!touched || u64map_init(&he, nh)) {
    free(touched);
    return -1;
  }
  for (int f = 0; f < m->nf; f++)
    for (int c = 0; c < 3; c++)
      if (u64map_put(&he, dir_key(m->F[3 * f + c], m->F[3 * f + (c + 1) % 3]), 3 * f + c)) {
        free(touched);
        u64map_free(&he);
        return -1;
      }
  int flips = 0;
  for (int f1 = 0; f1 < m->nf && flips >= 0; f1++)
    for (int c1 = 0; c1 < 3; c1++) {
      if (touched[f1]) break;
      int a = m->F[3 * f1 + c1], b = m->F[3 * f1 + (c1 + 1) % 3], c = m->F[3 * f1 + (c1 + 2) % 3];
      if (a > b) continue; /* each edge once */
      int h2 = u64map_get(&he, dir_key(b, a));
      if (h2 < 0) continue;
      int f2 = h2 / 3, c2 = h2 % 3;
      if (touched[f2] || f2 == f1) continue;
      if (m->F[3 * f2 + c2] != b || m->F[3 * f2 + (c2 + 1) % 3] != a) continue;
      int d = m->F[3 * f2 + (c2 + 2) % 3];
      if (c == d || u64map_get(&he, dir_key(c, d)) >= 0 || u64map_get(&he, dir_key(d, c)) >= 0) continue;
      const double *V = m->V;
      /* opposite angles summing to more than pi <=> cot + cot < 0 (negative cotan weight) */
      double cc = cot_at(V + 3 * (size_t)c, V + 3 * (size_t)a, V + 3 * (size_t)b);
      double cd = cot_at(V + 3 * (size_t)d, V + 3 * (size_t)a, V + 3 * (size_t)b);
      if (cc + cd >= -1e-9) continue;
      double n1[3], n2[3], m1[3], m2[3];
      tri_normal(V, a, b, c, n1);
      tri_normal(V, b, a, d, n2);
      tri_normal(V, c, a, d, m1);
      tri_normal(V, d, b, c, m2);
      double nsum[3] = {n1[0] + n2[0], n1[1] + n2[1], n1[2] + n2[2]};
      /* no folding, and no flip across a crease sharper than 60 degrees */
      if (dot3(m1, m2) < 0.5 || dot3(m1, nsum) <= 0 || dot3(m2, nsum) <= 0 || dot3(n1, n2) < 0.5) continue;
      m->F[3 * f1] = c; m->F[3 * f1 + 1] = a; m->F[3 * f1 + 2] = d;
      m->F[3 * f2] = d; m->F[3 * f2 + 1] = b; m->F[3 * f2 + 2] = c;
      touched[f1] = touched[f2] = 1;
      if (u64map_put(&he, dir_key(d, c), 3 * f1 + 2) || u64map_put(&he, dir_key(c, d), 3 * f2 + 2)) {
        flips = -1;
        break;
      }
      flips++;
    }
  free(touched);
  u64map_free(&he);
  return flips;
}

/* Newton steps along the (finite-difference) gradient onto f = 0. */
static void project(ssi_implicit_fn f, const void *ctx, double p[3]) {
  const double e = 1e-6;
  for (int it = 0; it < 3; it++) {
    double v = f(p, ctx), g[3];
    if (fabs(v) < 1e-9) return;
    for (int d = 0; d < 3; d++) {
      double q[3] = {p[0], p[1], p[2]};
      q[d] += e;
      g[d] = (f(q, ctx) - v) / e;
    }
    double gg = dot3(g, g);
    if (!(gg > 1e-12)) return;
    for (int d = 0; d < 3; d++) p[d] -= v * g[d] / gg;
  }
}


/* One pass of short-edge collapses (Botsch & Kobbelt style decimation towards edge length L):
 * edges shorter than 4/5 L, shortest first, collapse to their midpoint when the link condition
 * holds (the two endpoints share exactly the two opposite vertices, so the surface stays a closed
 * manifold of the same genus), no vertex drops below valence 3, no new edge exceeds 4/3 L and no
 * face turns over. Collapses in one pass touch disjoint neighbourhoods. Returns the number of
 * collapses, -1 on OOM. Removes the dead vertices/faces and renumbers. */
typedef struct {
  double len;
  int a, b;
} cand;
static int cmp_cand(const void *x, const void *y) {
  const cand *p = x, *q = y;
  if (p->len != q->len) return p->len < q->len ? -1 : 1;
  if (p->a != q->a) return p->a - q->a;
  return p->b - q->b;
}

static int collapse_pass(ss_mesh *m, double L) {
  const int nv = m->nv, nf = m->nf;
  int *vf_ptr = calloc((size_t)nv + 1, sizeof(int)), *vf = malloc(sizeof(int) * 3 * (size_t)nf);
  cand *C = malloc(sizeof(cand) * 3 * (size_t)nf);
  char *lock = calloc((size_t)nv, 1), *vdead = calloc((size_t)nv, 1), *fdead = calloc((size_t)nf, 1);
  int *nb = NULL, cap_nb = 0, done = 0;
  if (!vf_ptr || !vf || !C || !lock || !vdead || !fdead) { done = -1; goto out; }
  for (int f = 0; f < nf; f++)
    for (int c = 0; c < 3; c++) vf_ptr[m->F[3 * f + c] + 1]++;
  for (int i = 0; i < nv; i++) vf_ptr[i + 1] += vf_ptr[i];
  {
    int *fill = malloc(sizeof(int) * (size_t)(nv > 0 ? nv : 1));
    if (!fill) { done = -1; goto out; }
    memcpy(fill, vf_ptr, sizeof(int) * (size_t)nv);
    for (int f = 0; f < nf; f++)
      for (int c = 0; c < 3; c++) vf[fill[m->F[3 * f + c]]++] = f;
    free(fill);
  }
  const double lmin = 0.8 * L, lmax = 4.0 / 3.0 * L;
  int nc = 0;
  for (int f = 0; f < nf; f++)
    for (int c = 0; c < 3; c++) {
      int a = m->F[3 * f + c], b = m->F[3 * f + (c + 1) % 3];
      if (a > b) continue; /* each undirected edge once (closed oriented manifold) */
      double d[3];
      sub3(m->V + 3 * (size_t)a, m->V + 3 * (size_t)b, d);
      double l = sqrt(dot3(d, d));
      if (l < lmin) C[nc++] = (cand){l, a, b};
    }
  qsort(C, (size_t)nc, sizeof(cand), cmp_cand);
  for (int e = 0; e < nc; e++) {
    int a = C[e].a, b = C[e].b;
    if (lock[a] || lock[b]) continue;
    /* neighbours of a and of b (with multiplicity 2 on a closed manifold: collect once) */
    int na = 0, nbb = 0, need = 2 * (vf_ptr[a + 1] - vf_ptr[a] + vf_ptr[b + 1] - vf_ptr[b]) + 4;
    if (need > cap_nb) {
      int *t = realloc(nb, sizeof(int) * (size_t)need);
      if (!t) { done = -1; goto out; }
      nb = t;
      cap_nb = need;
    }
    for (int k = vf_ptr[a]; k < vf_ptr[a + 1]; k++) {
      const int *F = m->F + 3 * vf[k];
      for (int c = 0; c < 3; c++) {
        int x = F[c], seen = 0;
        if (x == a) continue;
        for (int q = 0; q < na; q++) seen |= nb[q] == x;
        if (!seen) nb[na++] = x;
      }
    }
    int *nbB = nb + na;
    for (int k = vf_ptr[b]; k < vf_ptr[b + 1]; k++) {
      const int *F = m->F + 3 * vf[k];
      for (int c = 0; c < 3; c++) {
        int x = F[c], seen = 0;
        if (x == b) continue;
        for (int q = 0; q < nbb; q++) seen |= nbB[q] == x;
        if (!seen) nbB[nbb++] = x;
      }
    }
    int common = 0, bad = 0;
    for (int p = 0; p < na; p++)
      for (int q = 0; q < nbb; q++)
        if (nb[p] == nbB[q]) {
          common++;
          /* each opposite vertex loses one edge: keep it at valence >= 3 */
          if (vf_ptr[nb[p] + 1] - vf_ptr[nb[p]] <= 3) bad = 1;
        }
    if (common != 2 || bad || na + nbb - 4 < 3) continue;
    double p[3];
    for (int d = 0; d < 3; d++) p[d] = 0.5 * (m->V[3 * (size_t)a + d] + m->V[3 * (size_t)b + d]);
    for (int q = 0; q < na + nbb && !bad; q++) {
      double d[3];
      sub3(m->V + 3 * (size_t)nb[q], p, d);
      if (dot3(d, d) > lmax * lmax) bad = 1;
    }
    /* faces that survive must keep their orientation */
    for (int side = 0; side < 2 && !bad; side++) {
      int v = side ? b : a;
      for (int k = vf_ptr[v]; k < vf_ptr[v + 1] && !bad; k++) {
        const int *F = m->F + 3 * vf[k];
        int hasa = F[0] == a || F[1] == a || F[2] == a, hasb = F[0] == b || F[1] == b || F[2] == b;
        if (hasa && hasb) continue;
        double n0[3], n1[3], P[3][3];
        tri_normal(m->V, F[0], F[1], F[2], n0);
        for (int c = 0; c < 3; c++)
          for (int d = 0; d < 3; d++) P[c][d] = F[c] == v ? p[d] : m->V[3 * (size_t)F[c] + d];
        double u[3], w[3];
        sub3(P[1], P[0], u);
        sub3(P[2], P[0], w);
        cross3(u, w, n1);
        double l1 = sqrt(dot3(n1, n1));
        if (!(l1 > 0) || dot3(n0, n1) < 0.3 * l1) bad = 1;
      }
    }
    if (bad) continue;
    for (int k = vf_ptr[b]; k < vf_ptr[b + 1]; k++) {
      int f = vf[k];
      int *F = m->F + 3 * f;
      if (F[0] == a || F[1] == a || F[2] == a) fdead[f] = 1;
      else
        for (int c = 0; c < 3; c++)
          if (F[c] == b) F[c] = a;
    }
    memcpy(m->V + 3 * (size_t)a, p, sizeof p);
    vdead[b] = 1;
    lock[a] = lock[b] = 1;
    for (int q = 0; q < na + nbb; q++) lock[nb[q]] = 1;
    done++;
  }
  if (done > 0) {
    int *remap = vf_ptr; /* reuse: new index of each vertex */
    int k = 0;
    for (int i = 0; i < nv; i++) {
      remap[i] = vdead[i] ? -1 : k;
      if (!vdead[i]) {
        memmove(m->V + 3 * (size_t)k, m->V + 3 * (size_t)i, 3 * sizeof(double));
        k++;
      }
    }
    m->nv = k;
    k = 0;
    for (int f = 0; f < nf; f++) {
      if (fdead[f]) continue;
      for (int c = 0; c < 3; c++) m->F[3 * k + c] = remap[m->F[3 * f + c]];
      k++;
    }
    m->nf = k;
  }
out:
  free(vf_ptr);
  free(vf);
  free(C);
  free(lock);
  free(vdead);
  free(fdead);
  free(nb);
  return done;
}

ss_status ssi_implicit_remesh(ssi_implicit_fn f, const void *ctx, ss_mesh *m, double L, int iterations,
                             ss_error *err) {
  double *acc = malloc(sizeof(double) * 7 * (size_t)m->nv);
  if (!acc) return ss_fail(err, SS_ERR_NOMEM, "out of memory");
  for (int it = 0; it < iterations; it++) {
    if (L > 0 && collapse_pass(m, L) < 0) { free(acc); return ss_fail(err, SS_ERR_NOMEM, "out of memory"); }
    for (int pass = 0; pass < 3; pass++) {
      int fl = flip_pass(m);
      if (fl < 0) { free(acc); return ss_fail(err, SS_ERR_NOMEM, "out of memory"); }
      if (fl == 0) break;
    }
    /* acc: area-weighted centroid sum (3), area sum (1), area-weighted normal (3) */
    memset(acc, 0, sizeof(double) * 7 * (size_t)m->nv);
    for (int t = 0; t < m->nf; t++) {
      const int *F = m->F + 3 * t;
      const double *p = m->V + 3 * (size_t)F[0], *q = m->V + 3 * (size_t)F[1], *r = m->V + 3 * (size_t)F[2];
      double u[3], v[3], n[3];
      sub3(q, p, u);
      sub3(r, p, v);
      cross3(u, v, n);
      double A = 0.5 * sqrt(dot3(n, n));
      for (int c = 0; c < 3; c++) {
        double *a = acc + 7 * (size_t)F[c];
        for (int d = 0; d < 3; d++) {
          a[d] += A * (p[d] + q[d] + r[d]) / 3.0;
          a[4 + d] += 0.5 * n[d];
        }
        a[3] += A;
      }
    }
#pragma omp parallel for schedule(static)
    for (int i = 0; i < m->nv; i++) {
      double *a = acc + 7 * (size_t)i, *x = m->V + 3 * (size_t)i;
      if (!(a[3] > 0)) {
        memcpy(a, x, 3 * sizeof(double));
        continue;
      }
      double c[3] = {a[0] / a[3] - x[0], a[1] / a[3] - x[1], a[2] / a[3] - x[2]};
      double nl = sqrt(dot3(a + 4, a + 4));
      if (nl > 0) {
        double cn = dot3(c, a + 4) / (nl * nl);
        for (int d = 0; d < 3; d++) c[d] -= cn * a[4 + d];
      }
      /* store the new position in acc so the update is order independent (Jacobi) */
      for (int d = 0; d < 3; d++) a[d] = x[d] + c[d];
      project(f, ctx, a);
    }
    for (int i = 0; i < m->nv; i++)
      for (int d = 0; d < 3; d++) m->V[3 * (size_t)i + d] = acc[7 * (size_t)i + d];
  }
  free(acc);
  return SS_OK;
}
