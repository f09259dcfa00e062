#include "mesh/mesh_geometry.h"
#include "mesh/mesh_topology.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int topo_face_degenerate(const ss_mesh *m, int f) {
  const int *t = m->F + 3 * (size_t)f;
  if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return 1;
  double a2, l2; /* twice the area, squared longest edge (of the triangle scaled by 2^-e at extreme sizes) */
  int e;
  ssi_triangle_measures(m->V + 3 * (size_t)t[0], m->V + 3 * (size_t)t[1], m->V + 3 * (size_t)t[2], &a2, &l2, &e);
  /* height / longest edge below 1e-14: zero up to rounding of the coordinates */
  if (a2 <= 1e-14 * l2) return 2;
  return 0;
}

ss_status topo_check_indices(const ss_mesh *m, ss_error *err) {
  if (!m || m->nv < 0 || m->nf < 0 || (m->nv > 0 && !m->V) || (m->nf > 0 && !m->F))
    return ss_fail(err, SS_ERR_INVALID, "invalid mesh (bad sizes or missing arrays)");
  for (size_t i = 0; i < 3 * (size_t)m->nf; i++)
    if (m->F[i] < 0 || m->F[i] >= m->nv)
      return ss_fail(err, SS_ERR_INVALID, "face %zu has vertex index %d out of range [0, %d)", i / 3, m->F[i], m->nv);
  return SS_OK;
}

typedef struct {
  uint64_t key;
  int he;
} hekey;

/* Counting sort on the leading vertex, then insertion sort inside each small bucket (qsort inside
 * large ones): O(n + nv) for meshes of bounded valence, O(n log n) always, and the same order a full
 * comparison sort would give. */
static int hekey_less(const hekey *x, const hekey *y) { return x->key < y->key || (x->key == y->key && x->he < y->he); }
static int hekey_cmp(const void *a, const void *b) {
  const hekey *x = a, *y = b;
  return hekey_less(x, y) ? -1 : hekey_less(y, x);
}
/* Buckets longer than this are sorted with qsort: a vertex in 10^5 faces (200,000 copies of one
 * face, a polygon fan with 10^6 corners) made the insertion sort quadratic. Both orders are total
 * (ties broken by the unique half-edge / face index), so the result is the same either way. */
#define TOPO_SMALL_BUCKET 32

static int sort_hekeys(hekey *H, size_t n, int nv) {
  size_t *start = calloc((size_t)nv + 1, sizeof(size_t));
  hekey *tmp = malloc(sizeof(hekey) * (n ? n : 1));
  if (!start || !tmp) {
    free(start);
    free(tmp);
    return -1;
  }
  for (size_t i = 0; i < n; i++) start[(H[i].key >> 32) + 1]++;
  for (int v = 0; v < nv; v++) start[v + 1] += start[v];
  for (size_t i = 0; i < n; i++) tmp[start[H[i].key >> 32]++] = H[i];
  /* start[v] now holds the end of bucket v */
  size_t b = 0;
  for (int v = 0; v < nv; v++) {
    size_t e = start[v];
    if (e - b > TOPO_SMALL_BUCKET) {
      qsort(tmp + b, e - b, sizeof *tmp, hekey_cmp);
      b = e;
      continue;
    }
    for (size_t i = b + 1; i < e; i++) {
      hekey x = tmp[i];
      size_t j = i;
      while (j > b && hekey_less(&x, &tmp[j - 1])) {
        tmp[j] = tmp[j - 1];
        j--;
      }
      tmp[j] = x;
    }
    b = e;
  }
  memcpy(H, tmp, sizeof(hekey) * n);
  free(start);
  free(tmp);
  return 0;
}

static int tri_less(const topo_tri *x, const topo_tri *y) {
  for (int k = 0; k < 3; k++)
    if (x->v[k] != y->v[k]) return x->v[k] < y->v[k];
  return x->f < y->f;
}
static int tri_cmp(const void *a, const void *b) {
  const topo_tri *x = a, *y = b;
  return tri_less(x, y) ? -1 : tri_less(y, x);
}

int topo_sort_tris(topo_tri *t, size_t n, int nv) {
  size_t *start = calloc((size_t)nv + 1, sizeof(size_t));
  topo_tri *tmp = malloc(sizeof(topo_tri) * (n ? n : 1));
  if (!start || !tmp) {
    free(start);
    free(tmp);
    return -1;
  }
  for (size_t i = 0; i < n; i++) start[t[i].v[0] + 1]++;
  for (int v = 0; v < nv; v++) start[v + 1] += start[v];
  for (size_t i = 0; i < n; i++) tmp[start[t[i].v[0]]++] = t[i];
  size_t b = 0;
  for (int v = 0; v < nv; v++) {
    size_t e = start[v];
    if (e - b > TOPO_SMALL_BUCKET) {
      qsort(tmp + b, e - b, sizeof *tmp, tri_cmp);
      b = e;
      continue;
    }
    for (size_t i = b + 1; i < e; i++) {
      topo_tri x = tmp[i];
      size_t j = i;
      while (j > b && tri_less(&x, &tmp[j - 1])) {
        tmp[j] = tmp[j - 1];
        j--;
      }
      tmp[j] = x;
    }
    b = e;
  }
  memcpy(t, tmp, sizeof(topo_tri) * n);
  free(start);
  free(tmp);
  return 0;
}

size_t topo_collect_tris(const ss_mesh *m, const unsigned char *use, topo_tri *t) {
  size_t n = 0;
  for (int f = 0; f < m->nf; f++) {
    const int *F = m->F + 3 * (size_t)f;
    if ((use && !use[f]) || F[0] == F[1] || F[1] == F[2] || F[0] == F[2]) continue;
    int a = F[0], b = F[1], c = F[2], s;
    if (a > b) { s = a; a = b; b = s; }
    if (b > c) { s = b; b = c; c = s; }
    if (a > b) { s = a; a = b; b = s; }
    t[n].v[0] = a;
    t[n].v[1] = b;
    t[n].v[2] = c;
    t[n].f = f;
    n++;
  }
  return n;
}

static int uf_find(int *p, int x) {
  while (p[x] != x) {
    p[x] = p[p[x]]; /* path halving */
    x = p[x];
  }
  return x;
}
static void uf_union(int *p, int a, int b) {
  a = uf_find(p, a);
  b = uf_find(p, b);
  if (a == b) return;
  if (a < b) p[b] = a; /* smallest corner represents the set: deterministic */
  else p[a] = b;
}

ss_status topo_build(const ss_mesh *m, const unsigned char *use, topo *T, ss_error *err) {
  memset(T, 0, sizeof *T);
  T->nf = m->nf;
  size_t nc = 3 * (size_t)m->nf;
  hekey *H = malloc(sizeof(hekey) * (nc ? nc : 1));
  T->fan = malloc(sizeof(int) * (nc ? nc : 1));
  T->loop = malloc(sizeof(int) * (nc ? nc : 1));
  if (!H || !T->fan || !T->loop) {
    free(H);
    topo_free(T);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory for mesh topology (%d faces)", m->nf);
  }
  size_t nh = 0;
  for (int f = 0; f < m->nf; f++) {
    const int *t = m->F + 3 * (size_t)f;
    int ok = (!use || use[f]) && t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
    for (int j = 0; j < 3; j++) {
      size_t c = 3 * (size_t)f + (size_t)j;
      T->fan[c] = ok ? (int)c : -1;
      T->loop[c] = -1;
      if (!ok) continue;
      uint32_t a = (uint32_t)t[j], b = (uint32_t)t[(j + 1) % 3];
      if (a > b) {
        uint32_t s = a;
        a = b;
        b = s;
      }
      H[nh].key = ((uint64_t)a << 32) | b;
      H[nh].he = (int)c;
      nh++;
    }
  }
  if (sort_hekeys(H, nh, m->nv)) {
    free(H);
    topo_free(T);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory for mesh topology (%d faces)", m->nf);
  }
  /* Glue corners across every edge shared by two or more used faces. */
  for (size_t i = 0; i < nh;) {
    size_t j = i + 1;
    while (j < nh && H[j].key == H[i].key) j++;
    size_t cnt = j - i;
    T->nedges++;
    if (cnt == 1) T->boundary_edges++;
    if (cnt > 2) {
      if (T->nonmanifold_edges == 0) {
        T->first_nm_a = (int)(H[i].key >> 32);
        T->first_nm_b = (int)(H[i].key & 0xffffffffu);
        T->first_nm_count = (int)cnt;
      }
      T->nonmanifold_edges++;
    }
    int h0 = H[i].he, f0 = h0 / 3, j0 = h0 % 3;
    int a0 = m->F[h0];
    for (size_t k = i + 1; k < j; k++) {
      int h = H[k].he, f = h / 3, jj = h % 3;
      int ca = 3 * f + jj, cb = 3 * f + (jj + 1) % 3; /* corners at this half-edge's start and end */
      int c0a = 3 * f0 + j0, c0b = 3 * f0 + (j0 + 1) % 3;
      if (m->F[ca] == a0) {
        uf_union(T->fan, c0a, ca);
        uf_union(T->fan, c0b, cb);
      } else {
        uf_union(T->fan, c0a, cb);
        uf_union(T->fan, c0b, ca);
      }
    }
    i = j;
  }
  for (size_t c = 0; c < nc; c++)
    if (T->fan[c] >= 0) T->fan[c] = uf_find(T->fan, (int)c);
  /* Boundary loops: a boundary edge links the fans at its two ends; connected pieces are loops.
   * Working on fans (not vertices) keeps two loops touching at a pinched vertex apart. */
  for (size_t i = 0; i < nh;) {
    size_t j = i + 1;
    while (j < nh && H[j].key == H[i].key) j++;
    if (j - i == 1) {
      int h = H[i].he, f = h / 3, jj = h % 3;
      int ra = T->fan[3 * f + jj], rb = T->fan[3 * f + (jj + 1) % 3];
      if (T->loop[ra] < 0) T->loop[ra] = ra;
      if (T->loop[rb] < 0) T->loop[rb] = rb;
      uf_union(T->loop, ra, rb);
    }
    i = j;
  }
  /* loop[] was only seeded at fan representatives: resolve each corner through its fan's representative
   * (non-representative corners are never parents in the union-find, so overwriting them is safe). */
  for (size_t c = 0; c < nc; c++) {
    int r = T->fan[c];
    T->loop[c] = (r >= 0 && T->loop[r] >= 0) ? uf_find(T->loop, r) : -1;
  }
  free(H);
  return SS_OK;
}

void topo_free(topo *T) {
  free(T->fan);
  free(T->loop);
  memset(T, 0, sizeof *T);
}

/* Connected components of the faces of a (sanitized) mesh through shared vertices: comp[v] for every
 * vertex (numbered by lowest vertex; -1 for a vertex in no face). Returns the count, -1 on OOM. */
int ssi_mesh_components(const ss_mesh *m, int *comp) {
  int *p = malloc(sizeof(int) * (size_t)m->nv);
  if (!p) return -1;
  for (int i = 0; i < m->nv; i++) p[i] = i, comp[i] = -1;
  for (int f = 0; f < m->nf; f++)
    for (int j = 0; j < 3; j++) {
      int a = m->F[3 * f + j], b = m->F[3 * f + (j + 1) % 3];
      while (p[a] != a) a = p[a] = p[p[a]];
      while (p[b] != b) b = p[b] = p[p[b]];
      if (a != b) { if (a < b) p[b] = a; else p[a] = b; }
    }
  unsigned char *used = calloc((size_t)m->nv, 1);
  if (!used) { free(p); return -1; }
  for (int i = 0; i < 3 * m->nf; i++) used[m->F[i]] = 1;
  int nc = 0;
  for (int i = 0; i < m->nv; i++) {
    int r = i;
    while (p[r] != r) r = p[r];
    p[i] = r;
    if (!used[i]) continue;
    if (comp[r] < 0) comp[r] = nc++;
    comp[i] = comp[r];
  }
  free(p);
  free(used);
  return nc;
}
