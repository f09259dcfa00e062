/* Topological operations of the isotropic remesher on the corner-table mesh (see remesh_mesh.h). */
#include "remesh_mesh.h"
#include "mesh/mesh_geometry.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_VALENCE_WALK 4096 /* guard against walking a corrupted fan forever */

static int grow(void **p, size_t elem, int newcap) {
  void *q = realloc(*p, elem * (size_t)newcap);
  if (!q) return -1;
  *p = q;
  return 0;
}

ss_status rm_reserve(rm_mesh *m, int nv, int nf, ss_error *err) {
  if (nv > m->cap_v) {
    int c = m->cap_v ? m->cap_v : 16;
    while (c < nv) c *= 2;
    if (grow((void **)&m->V, 3 * sizeof(double), c) || grow((void **)&m->vh, sizeof(int), c) ||
        grow((void **)&m->val, sizeof(int), c) || grow((void **)&m->hint, sizeof(int), c) ||
        grow((void **)&m->mark, sizeof(int), c) || grow((void **)&m->vdead, 1, c))
      return ss_fail(err, SS_ERR_NOMEM, "remesh: out of memory");
    memset(m->mark + m->cap_v, 0, sizeof(int) * (size_t)(c - m->cap_v));
    m->cap_v = c;
  }
  if (nf > m->cap_f) {
    int c = m->cap_f ? m->cap_f : 16;
    while (c < nf) c *= 2;
    if (grow((void **)&m->F, 3 * sizeof(int), c) || grow((void **)&m->opp, 3 * sizeof(int), c) ||
        grow((void **)&m->fdead, 1, c))
      return ss_fail(err, SS_ERR_NOMEM, "remesh: out of memory");
    m->cap_f = c;
  }
  int s = m->cap_v > m->cap_f ? m->cap_v : m->cap_f;
  if (grow((void **)&m->scratch, sizeof(int), s)) return ss_fail(err, SS_ERR_NOMEM, "remesh: out of memory");
  return SS_OK;
}

void rm_free(rm_mesh *m) {
  free(m->V); free(m->F); free(m->opp); free(m->vh); free(m->val); free(m->hint); free(m->mark);
  free(m->vdead); free(m->fdead); free(m->scratch);
  memset(m, 0, sizeof *m);
}

ss_status rm_init(rm_mesh *m, const ss_mesh *in, ss_error *err) {
  memset(m, 0, sizeof *m);
  if (in->nv <= 0 || in->nf <= 0) return ss_fail(err, SS_ERR_INVALID, "remesh: empty mesh");
  const int nv = in->nv, nf = in->nf;
  for (int i = 0; i < 3 * nf; i++)
    if (in->F[i] < 0 || in->F[i] >= nv)
      return ss_fail(err, SS_ERR_INVALID, "remesh: face %d has vertex index %d out of range [0,%d)", i / 3, in->F[i], nv);
  for (int i = 0; i < 3 * nv; i++)
    if (!isfinite(in->V[i])) return ss_fail(err, SS_ERR_INVALID, "remesh: vertex %d has a non-finite coordinate", i / 3);
  ss_status st0 = ssi_mesh_check_coordinates(in, "remesh", err);
  if (st0) return st0;
  for (int f = 0; f < nf; f++) {
    const int *t = in->F + 3 * f;
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      return ss_fail(err, SS_ERR_INVALID, "remesh: face %d repeats a vertex (run the mesh through sanitize first)", f);
  }
  ss_status st = rm_reserve(m, nv, nf, err);
  if (st != SS_OK) { rm_free(m); return st; }
  m->nv = nv; m->nf = nf;
  memcpy(m->V, in->V, sizeof(double) * 3 * (size_t)nv);
  memcpy(m->F, in->F, sizeof(int) * 3 * (size_t)nf);
  memset(m->fdead, 0, (size_t)nf);
  for (int v = 0; v < nv; v++) { m->vdead[v] = 1; m->val[v] = 0; m->hint[v] = -1; m->vh[v] = -1; }

  /* outgoing half-edges per vertex (CSR), then twin lookup in the head's list */
  int *start = calloc((size_t)nv + 1, sizeof(int)), *list = malloc(sizeof(int) * 3 * (size_t)nf);
  if (!start || !list) { free(start); free(list); rm_free(m); return ss_fail(err, SS_ERR_NOMEM, "remesh: out of memory"); }
  for (int h = 0; h < 3 * nf; h++) start[m->F[h] + 1]++;
  for (int v = 0; v < nv; v++) start[v + 1] += start[v];
  {
    int *pos = m->scratch;
    for (int v = 0; v < nv; v++) pos[v] = start[v];
    for (int h = 0; h < 3 * nf; h++) list[pos[m->F[h]]++] = h;
  }
  st = SS_OK;
  for (int h = 0; h < 3 * nf && st == SS_OK; h++) {
    int a = m->F[h], b = m->F[rm_next(h)], twin = -1, nt = 0, same = 0;
    for (int p = start[b]; p < start[b + 1]; p++)
      if (m->F[rm_next(list[p])] == a) { twin = list[p]; nt++; }
    for (int p = start[a]; p < start[a + 1]; p++)
      if (m->F[rm_next(list[p])] == b) same++;
    if (nt == 0 && same == 1)
      st = ss_fail(err, SS_ERR_UNSUPPORTED, "remesh: edge (%d,%d) is a boundary edge; only closed meshes are supported", a, b);
    else if (nt != 1 || same != 1)
      st = ss_fail(err, SS_ERR_UNSUPPORTED, "remesh: edge (%d,%d) is non-manifold or inconsistently oriented", a, b);
    m->opp[h] = twin;
  }
  free(start);
  free(list);
  if (st != SS_OK) { rm_free(m); return st; }
  for (int h = 0; h < 3 * nf; h++) {
    int v = m->F[h];
    m->vdead[v] = 0;
    m->val[v]++;
    m->vh[v] = h;
  }
  /* vertex-manifold: walking the fan from vh must meet every incident face */
  for (int v = 0; v < nv; v++) {
    if (m->vdead[v]) continue;
    int h = m->vh[v], n = 0;
    do { n++; h = m->opp[rm_prev(h)]; } while (h != m->vh[v] && n <= m->val[v]);
    if (n != m->val[v]) {
      rm_free(m);
      return ss_fail(err, SS_ERR_UNSUPPORTED, "remesh: vertex %d is non-manifold (pinched)", v);
    }
  }
  return SS_OK;
}

static inline double d2(const double *a, const double *b) {
  double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return x * x + y * y + z * z;
}

static inline void tri_normal(const double *a, const double *b, const double *c, double n[3]) {
  double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  n[0] = u[1] * w[2] - u[2] * w[1];
  n[1] = u[2] * w[0] - u[0] * w[2];
  n[2] = u[0] * w[1] - u[1] * w[0];
}

static inline void link(rm_mesh *m, int a, int b) { m->opp[a] = b; m->opp[b] = a; }

/* Split the edge of half-edge h at its midpoint: two faces become four. Capacity must be there. */
static void split_edge(rm_mesh *m, int h) {
  int o = m->opp[h];
  int v0 = m->F[h], v1 = m->F[rm_next(h)], a = m->F[rm_prev(h)], b = m->F[rm_prev(o)];
  int hn = rm_next(h), on = rm_next(o);
  int x1 = m->opp[hn], x2 = m->opp[on];
  int mv = m->nv++, f2 = m->nf++, g2 = m->nf++;
  for (int k = 0; k < 3; k++) m->V[3 * mv + k] = 0.5 * (m->V[3 * v0 + k] + m->V[3 * v1 + k]);
  m->vdead[mv] = 0;
  m->hint[mv] = m->hint[v0];
  m->fdead[f2] = m->fdead[g2] = 0;
  /* f = (v0, m, a), f2 = (m, v1, a) */
  m->F[hn] = mv;
  m->F[3 * f2] = mv; m->F[3 * f2 + 1] = v1; m->F[3 * f2 + 2] = a;
  /* g = (v1, m, b), g2 = (m, v0, b) */
  m->F[on] = mv;
  m->F[3 * g2] = mv; m->F[3 * g2 + 1] = v0; m->F[3 * g2 + 2] = b;
  link(m, 3 * f2 + 1, x1);
  link(m, hn, 3 * f2 + 2);
  link(m, 3 * g2 + 1, x2);
  link(m, on, 3 * g2 + 2);
  link(m, h, 3 * g2);
  link(m, o, 3 * f2);
  if (m->vh[v1] == hn) m->vh[v1] = 3 * f2 + 1;
  if (m->vh[v0] == on) m->vh[v0] = 3 * g2 + 1;
  m->vh[mv] = 3 * f2;
  m->val[mv] = 4;
  m->val[a]++;
  m->val[b]++;
}

/* Max-heap of (squared length, half-edge) with lazy deletion. */
typedef struct { double key; int h; } heap_item;
typedef struct { heap_item *a; int n, cap; } heap;

static int heap_push(heap *q, double key, int h) {
  if (q->n == q->cap) {
    int c = q->cap ? 2 * q->cap : 1024;
    heap_item *a = realloc(q->a, sizeof(heap_item) * (size_t)c);
    if (!a) return -1;
    q->a = a; q->cap = c;
  }
  int i = q->n++;
  while (i > 0 && q->a[(i - 1) / 2].key < key) { q->a[i] = q->a[(i - 1) / 2]; i = (i - 1) / 2; }
  q->a[i].key = key; q->a[i].h = h;
  return 0;
}

static heap_item heap_pop(heap *q) {
  heap_item top = q->a[0], last = q->a[--q->n];
  int i = 0;
  for (;;) {
    int c = 2 * i + 1;
    if (c >= q->n) break;
    if (c + 1 < q->n && q->a[c + 1].key > q->a[c].key) c++;
    if (q->a[c].key <= last.key) break;
    q->a[i] = q->a[c];
    i = c;
  }
  if (q->n) q->a[i] = last;
  return top;
}

static inline double hlen2(const rm_mesh *m, int h) { return d2(m->V + 3 * m->F[h], m->V + 3 * m->F[rm_next(h)]); }

/* Longest edge first, over the edges present at the start of the pass and their halves. */
int rm_split_long(rm_mesh *m, double hi, ss_error *err) {
  const double hi2 = hi * hi;
  int count = 0;
  heap q = {0};
  for (int f = 0; f < m->nf; f++) {
    if (m->fdead[f]) continue;
    for (int k = 0; k < 3; k++) {
      int h = 3 * f + k;
      if (m->opp[h] < h) continue;
      double l = hlen2(m, h);
      if (l > hi2 && heap_push(&q, l, h)) goto nomem;
    }
  }
  while (q.n) {
    heap_item it = heap_pop(&q);
    int h = it.h;
    if (hlen2(m, h) != it.key) continue; /* stale: this half-edge changed since it was queued */
    if (m->nv + 1 > m->cap_v || m->nf + 2 > m->cap_f) {
      if (rm_reserve(m, m->nv + 1, m->nf + 2, err) != SS_OK) { free(q.a); return -1; }
    }
    int o = m->opp[h];
    split_edge(m, h);
    count++;
    /* the halves go back in the queue; the new edges to the opposite corners wait for the next
     * round (after relaxation): queueing them too can breed endless chains of degenerate slivers */
    int cand[2] = {h, o};
    for (int c = 0; c < 2; c++) {
      double l = hlen2(m, cand[c]);
      if (l > hi2 && heap_push(&q, l, cand[c])) goto nomem;
    }
  }
  free(q.a);
  return count;
nomem:
  free(q.a);
  ss_fail(err, SS_ERR_NOMEM, "remesh: out of memory");
  return -1;
}

/* May the edge (v0 -> v1 of half-edge h) collapse with the merged vertex placed at p? */
static int collapse_ok(rm_mesh *m, int h, const double *p, double hi2) {
  int o = m->opp[h];
  int fa = h / 3, fb = o / 3;
  int ends[2] = {m->F[h], m->F[o]};
  for (int e = 0; e < 2; e++) {
    int v = ends[e], s = m->vh[v], hh = s, n = 0;
    do {
      int f = hh / 3;
      if (f != fa && f != fb) {
        int x = m->F[rm_next(hh)], y = m->F[rm_prev(hh)];
        const double *px = m->V + 3 * x, *py = m->V + 3 * y;
        double nold[3], nnew[3];
        tri_normal(m->V + 3 * v, px, py, nold);
        tri_normal(p, px, py, nnew);
        if (nold[0] * nnew[0] + nold[1] * nnew[1] + nold[2] * nnew[2] <= 0) return 0;
        if (d2(p, px) > hi2) return 0;
      }
      hh = m->opp[rm_prev(hh)];
    } while (hh != s && ++n < MAX_VALENCE_WALK);
  }
  return 1;
}

/* Remove v0 = F[h], merge it into v1 = F[next(h)], placed at p. */
void rm_collapse_edge(rm_mesh *m, int h, const double *p) {
  int o = m->opp[h];
  int v0 = m->F[h], v1 = m->F[rm_next(h)], a = m->F[rm_prev(h)], b = m->F[rm_prev(o)];
  int e1 = m->opp[rm_next(h)], e2 = m->opp[rm_prev(h)];
  int e3 = m->opp[rm_next(o)], e4 = m->opp[rm_prev(o)];
  /* re-point every half-edge leaving v0 to leave v1 */
  int s = m->vh[v0], hh = s, n = 0;
  do {
    m->F[hh] = v1;
    hh = m->opp[rm_prev(hh)];
  } while (hh != s && ++n < MAX_VALENCE_WALK);
  link(m, e1, e2);
  link(m, e3, e4);
  m->fdead[h / 3] = m->fdead[o / 3] = 1;
  m->vdead[v0] = 1;
  m->vh[v1] = e2;
  m->vh[a] = e1;
  m->vh[b] = e3;
  m->val[v1] = m->val[v0] + m->val[v1] - 4;
  m->val[a]--;
  m->val[b]--;
  memcpy(m->V + 3 * v1, p, 3 * sizeof(double));
}

/* Collapse the edge of h if the link condition, the valences and the geometry allow it. */
int rm_link_ok(rm_mesh *m, int h) {
  int o = m->opp[h];
  int v0 = m->F[h], v1 = m->F[rm_next(h)];
  int a = m->F[rm_prev(h)], b = m->F[rm_prev(o)];
  if (a == b || m->val[a] <= 3 || m->val[b] <= 3) return 0;
  /* link condition: the only common neighbours of v0 and v1 are a and b */
  int st = ++m->stamp, common = 0, s, hh, n;
  s = m->vh[v0]; hh = s; n = 0;
  do { m->mark[m->F[rm_next(hh)]] = st; hh = m->opp[rm_prev(hh)]; } while (hh != s && ++n < MAX_VALENCE_WALK);
  s = m->vh[v1]; hh = s; n = 0;
  do { if (m->mark[m->F[rm_next(hh)]] == st) common++; hh = m->opp[rm_prev(hh)]; } while (hh != s && ++n < MAX_VALENCE_WALK);
  return common == 2;
}

static int try_collapse(rm_mesh *m, int h, double hi2) {
  int v0 = m->F[h], v1 = m->F[rm_next(h)];
  const double *p0 = m->V + 3 * v0, *p1 = m->V + 3 * v1;
  if (!rm_link_ok(m, h)) return 0;
  double mid[3] = {0.5 * (p0[0] + p1[0]), 0.5 * (p0[1] + p1[1]), 0.5 * (p0[2] + p1[2])};
  double q0[3] = {p0[0], p0[1], p0[2]}, q1[3] = {p1[0], p1[1], p1[2]};
  const double *cand[3] = {mid, q1, q0};
  for (int c = 0; c < 3; c++) {
    if (collapse_ok(m, h, cand[c], hi2)) {
      rm_collapse_edge(m, h, cand[c]);
      return 1;
    }
  }
  return 0;
}

int rm_collapse_short(rm_mesh *m, double lo, double hi) {
  const double lo2 = lo * lo, hi2 = hi * hi;
  int count = 0;
  for (int f = 0; f < m->nf; f++) {
    for (int k = 0; k < 3 && !m->fdead[f]; k++) {
      int h = 3 * f + k;
      if (hlen2(m, h) >= lo2) continue;
      count += try_collapse(m, h, hi2);
    }
  }
  return count;
}

int rm_adjust_count(rm_mesh *m, int target, double hi, ss_error *err) {
  int live = rm_live_faces(m), done = 0;
  if (live == target || target < 4) return 0;
  const int grow_ = live < target;
  int need = (grow_ ? target - live : live - target) / 2; /* each operation adds / removes 2 faces */
  if (need == 0) return 0;
  heap q = {0};
  for (int f = 0; f < m->nf; f++) {
    if (m->fdead[f]) continue;
    for (int k = 0; k < 3; k++) {
      int h = 3 * f + k;
      if (m->opp[h] < h) continue;
      double l = hlen2(m, h);
      if (heap_push(&q, grow_ ? l : -l, h)) { free(q.a); ss_fail(err, SS_ERR_NOMEM, "remesh: out of memory"); return -1; }
    }
  }
  const double hi2 = hi * hi;
  while (q.n && done < need) {
    heap_item it = heap_pop(&q);
    int h = it.h;
    if (m->fdead[h / 3] || hlen2(m, h) != (grow_ ? it.key : -it.key)) continue; /* stale */
    if (grow_) {
      if (m->nv + 1 > m->cap_v || m->nf + 2 > m->cap_f) {
        if (rm_reserve(m, m->nv + 1, m->nf + 2, err) != SS_OK) { free(q.a); return -1; }
      }
      split_edge(m, h);
      done++;
    } else {
      done += try_collapse(m, h, hi2);
    }
  }
  free(q.a);
  return done;
}

static inline int dev(int v) { return v > 6 ? v - 6 : 6 - v; }

int rm_flip_valence(rm_mesh *m) {
  int count = 0;
  for (int f = 0; f < m->nf; f++) {
    if (m->fdead[f]) continue;
    for (int k = 0; k < 3; k++) {
      int h = 3 * f + k, o = m->opp[h];
      if (o < h) continue;
      int v0 = m->F[h], v1 = m->F[rm_next(h)], a = m->F[rm_prev(h)], b = m->F[rm_prev(o)];
      if (a == b || m->val[v0] <= 3 || m->val[v1] <= 3) continue;
      int before = dev(m->val[v0]) + dev(m->val[v1]) + dev(m->val[a]) + dev(m->val[b]);
      int after = dev(m->val[v0] - 1) + dev(m->val[v1] - 1) + dev(m->val[a] + 1) + dev(m->val[b] + 1);
      if (after >= before) continue;
      /* the new edge must not exist already */
      int s = m->vh[a], hh = s, n = 0, exists = 0;
      do { if (m->F[rm_next(hh)] == b) { exists = 1; break; } hh = m->opp[rm_prev(hh)]; } while (hh != s && ++n < MAX_VALENCE_WALK);
      if (exists) continue;
      /* no fold-over: both new triangles face the way the old pair did */
      const double *P0 = m->V + 3 * v0, *P1 = m->V + 3 * v1, *PA = m->V + 3 * a, *PB = m->V + 3 * b;
      double n1[3], n2[3], N[3], t1[3], t2[3];
      tri_normal(P0, P1, PA, n1);
      tri_normal(P1, P0, PB, n2);
      for (int c = 0; c < 3; c++) N[c] = n1[c] + n2[c];
      tri_normal(PA, P0, PB, t1);
      tri_normal(PB, P1, PA, t2);
      if (t1[0] * N[0] + t1[1] * N[1] + t1[2] * N[2] <= 0) continue;
      if (t2[0] * N[0] + t2[1] * N[1] + t2[2] * N[2] <= 0) continue;
      int fa = h / 3, fb = o / 3;
      int eh1 = m->opp[rm_next(h)], eh2 = m->opp[rm_prev(h)], eo1 = m->opp[rm_next(o)], eo2 = m->opp[rm_prev(o)];
      /* fa = (a, v0, b), fb = (b, v1, a) */
      m->F[3 * fa] = a; m->F[3 * fa + 1] = v0; m->F[3 * fa + 2] = b;
      m->F[3 * fb] = b; m->F[3 * fb + 1] = v1; m->F[3 * fb + 2] = a;
      link(m, 3 * fa, eh2);
      link(m, 3 * fa + 1, eo1);
      link(m, 3 * fb, eo2);
      link(m, 3 * fb + 1, eh1);
      link(m, 3 * fa + 2, 3 * fb + 2);
      m->vh[a] = 3 * fa;
      m->vh[v0] = 3 * fa + 1;
      m->vh[b] = 3 * fb;
      m->vh[v1] = 3 * fb + 1;
      m->val[v0]--; m->val[v1]--; m->val[a]++; m->val[b]++;
      count++;
      if (f == fa) break; /* this face's half-edges were renumbered */
    }
  }
  return count;
}

int rm_live_faces(const rm_mesh *m) {
  int n = 0;
  for (int f = 0; f < m->nf; f++) n += !m->fdead[f];
  return n;
}

void rm_compact(rm_mesh *m) {
  int *vmap = m->mark; /* stamps are reset below */
  int nv = 0;
  for (int v = 0; v < m->nv; v++) {
    if (m->vdead[v]) { vmap[v] = -1; continue; }
    vmap[v] = nv;
    if (nv != v) {
      memcpy(m->V + 3 * nv, m->V + 3 * v, 3 * sizeof(double));
      m->val[nv] = m->val[v];
      m->hint[nv] = m->hint[v];
      m->vh[nv] = m->vh[v];
    }
    m->vdead[nv] = 0;
    nv++;
  }
  int *fmap = m->scratch, nf = 0;
  for (int f = 0; f < m->nf; f++) fmap[f] = m->fdead[f] ? -1 : nf++;
  for (int f = 0; f < m->nf; f++) {
    if (m->fdead[f]) continue;
    int g = fmap[f];
    for (int k = 0; k < 3; k++) {
      int h = m->opp[3 * f + k];
      m->F[3 * g + k] = vmap[m->F[3 * f + k]];
      m->opp[3 * g + k] = 3 * fmap[h / 3] + h % 3;
    }
    m->fdead[g] = 0;
  }
  for (int v = 0; v < nv; v++) m->vh[v] = 3 * fmap[m->vh[v] / 3] + m->vh[v] % 3;
  m->nv = nv;
  m->nf = nf;
  memset(m->mark, 0, sizeof(int) * (size_t)m->cap_v);
  m->stamp = 0;
}

#ifdef SS_REMESH_CHECK
/* Debug aid (build with -DSS_REMESH_CHECK): full consistency check of twins, fans and valences. */
#include <stdio.h>
int rm_check(const rm_mesh *m, const char *where) {
  for (int f = 0; f < m->nf; f++) {
    if (m->fdead[f]) continue;
    for (int k = 0; k < 3; k++) {
      int h = 3 * f + k, o = m->opp[h];
      if (o < 0 || o >= 3 * m->nf || m->fdead[o / 3] || m->opp[o] != h || m->F[o] != m->F[rm_next(h)] || m->F[rm_next(o)] != m->F[h]) {
        fprintf(stderr, "%s: bad twin at h %d (o %d)\n", where, h, o);
        return 1;
      }
      if (m->vdead[m->F[h]]) { fprintf(stderr, "%s: dead vertex in face %d\n", where, f); return 1; }
    }
  }
  for (int v = 0; v < m->nv; v++) {
    if (m->vdead[v]) continue;
    int h = m->vh[v];
    if (h < 0 || m->fdead[h / 3] || m->F[h] != v) { fprintf(stderr, "%s: bad vh at %d\n", where, v); return 1; }
    int n = 0, s = h;
    do { n++; h = m->opp[rm_prev(h)]; } while (h != s && n < 1000);
    if (n != m->val[v]) { fprintf(stderr, "%s: valence %d vs %d at %d\n", where, n, m->val[v], v); return 1; }
    int nb[1000], k = 0; h = s;
    do { nb[k++] = m->F[rm_next(h)]; h = m->opp[rm_prev(h)]; } while (h != s && k < 1000);
    for (int i = 0; i < k; i++) for (int j = i + 1; j < k; j++) if (nb[i] == nb[j]) { fprintf(stderr, "%s: duplicate edge %d-%d\n", where, v, nb[i]); return 1; }
  }
  return 0;
}
#endif
