/* 1->4 midpoint subdivision: one new vertex at the midpoint of every edge (found through an
 * open-addressing hash on the sorted vertex pair), each triangle replaced by four. Positions of the
 * input vertices are unchanged, so the surface is the same polyhedron, four times finer. */
#include "specseg/mesh.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  uint64_t key; /* (a << 32 | b) + 1 with a < b; 0 = empty */
  int mid;
} edge_slot;

static int edge_midpoint(edge_slot *tab, size_t cap, int a, int b, ss_mesh *out, int *nv) {
  if (a > b) { int t = a; a = b; b = t; }
  uint64_t key = (((uint64_t)(uint32_t)a << 32) | (uint32_t)b) + 1;
  size_t h = (size_t)((key * 0x9E3779B97F4A7C15ull) >> 17) & (cap - 1);
  while (tab[h].key) {
    if (tab[h].key == key) return tab[h].mid;
    h = (h + 1) & (cap - 1);
  }
  int v = (*nv)++;
  for (int d = 0; d < 3; d++) out->V[3 * v + d] = 0.5 * (out->V[3 * a + d] + out->V[3 * b + d]);
  tab[h].key = key;
  tab[h].mid = v;
  return v;
}

ss_status ss_mesh_subdivide(const ss_mesh *in, ss_mesh *out, ss_error *err) {
  memset(out, 0, sizeof *out);
  if (!in || in->nv < 0 || in->nf < 0) return ss_fail(err, SS_ERR_INVALID, "subdivide: invalid mesh");
  for (int f = 0; f < in->nf; f++)
    for (int c = 0; c < 3; c++) {
      int v = in->F[3 * f + c];
      if (v < 0 || v >= in->nv)
        return ss_fail(err, SS_ERR_INVALID, "subdivide: face %d has vertex index %d out of range [0,%d)", f, v,
                       in->nv);
    }
  /* at most 3 nf distinct edges; the result must still fit an int */
  if ((long long)in->nv + 3LL * in->nf > INT32_MAX / 3 || 4LL * in->nf > INT32_MAX / 3)
    return ss_fail(err, SS_ERR_INVALID, "subdivide: mesh too large (%d vertices, %d faces)", in->nv, in->nf);
  int nv_max = in->nv + 3 * in->nf;
  ss_status st = ss_mesh_alloc(out, nv_max, 4 * in->nf, err);
  if (st) return st;
  size_t cap = 16;
  while (cap < 6 * (size_t)in->nf) cap <<= 1; /* load factor <= 1/2 */
  edge_slot *tab = calloc(cap, sizeof *tab);
  if (!tab) {
    ss_mesh_free(out);
    return ss_fail(err, SS_ERR_NOMEM, "subdivide: out of memory");
  }
  memcpy(out->V, in->V, sizeof(double) * 3 * (size_t)in->nv);
  int nv = in->nv;
  for (int f = 0; f < in->nf; f++) {
    int a = in->F[3 * f], b = in->F[3 * f + 1], c = in->F[3 * f + 2];
    int ab = edge_midpoint(tab, cap, a, b, out, &nv);
    int bc = edge_midpoint(tab, cap, b, c, out, &nv);
    int ca = edge_midpoint(tab, cap, c, a, out, &nv);
    /* corner triangles keep the input orientation; the middle one (ab, bc, ca) too */
    int t[12] = {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca};
    memcpy(out->F + 12 * (size_t)f, t, sizeof t);
  }
  free(tab);
  out->nv = nv;
  double *V = realloc(out->V, sizeof(double) * 3 * (size_t)(nv > 0 ? nv : 1));
  if (V) out->V = V;
  return SS_OK;
}
