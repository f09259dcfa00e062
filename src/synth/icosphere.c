/* Icosphere: a regular icosahedron, each triangle split in four `subdivisions` times, projected on
 * the unit sphere. 10*4^s + 2 vertices, 20*4^s faces. */
#include "specseg/synth.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct { long long key; int mid; } edge_slot;

static int midpoint(edge_slot *tab, size_t cap, int a, int b, double *V, int *nv) {
  if (a > b) { int t = a; a = b; b = t; }
  long long key = ((long long)a << 32) | (unsigned)b;
  size_t h = (size_t)(key * 0x9E3779B97F4A7C15ull) & (cap - 1);
  while (tab[h].key != -1) {
    if (tab[h].key == key) return tab[h].mid;
    h = (h + 1) & (cap - 1);
  }
  int v = (*nv)++;
  double p[3], s = 0;
  for (int d = 0; d < 3; d++) { p[d] = 0.5 * (V[3 * a + d] + V[3 * b + d]); s += p[d] * p[d]; }
  s = sqrt(s);
  for (int d = 0; d < 3; d++) V[3 * v + d] = p[d] / s;
  tab[h].key = key;
  tab[h].mid = v;
  return v;
}

ss_status ss_synth_icosphere(int subdivisions, ss_mesh *m, ss_error *err) {
  if (subdivisions < 0 || subdivisions > 9)
    return ss_fail(err, SS_ERR_INVALID, "icosphere subdivisions %d outside [0,9]", subdivisions);
  int nf_final = 20 << (2 * subdivisions), nv_final = nf_final / 2 + 2;
  ss_status st = ss_mesh_alloc(m, nv_final, nf_final, err);
  if (st) return st;
  const double t = (1.0 + sqrt(5.0)) / 2.0;
  const double base[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                              {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  const int bf[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                         {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                         {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  double s = sqrt(1 + t * t);
  for (int i = 0; i < 12; i++)
    for (int d = 0; d < 3; d++) m->V[3 * i + d] = base[i][d] / s;
  memcpy(m->F, bf, sizeof bf);
  int nv = 12, nf = 20;
  int *tmp = malloc(sizeof(int) * 3 * (size_t)nf_final);
  size_t cap = 1;
  while (cap < (size_t)nf_final * 2) cap <<= 1;
  edge_slot *tab = malloc(sizeof(edge_slot) * cap);
  if (!tmp || !tab) {
    free(tmp); free(tab); ss_mesh_free(m);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory for an icosphere");
  }
  for (int it = 0; it < subdivisions; it++) {
    for (size_t i = 0; i < cap; i++) tab[i].key = -1;
    int k = 0;
    for (int f = 0; f < nf; f++) {
      int a = m->F[3 * f], b = m->F[3 * f + 1], c = m->F[3 * f + 2];
      int ab = midpoint(tab, cap, a, b, m->V, &nv), bc = midpoint(tab, cap, b, c, m->V, &nv),
          ca = midpoint(tab, cap, c, a, m->V, &nv);
      int quad[4][3] = {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}};
      memcpy(tmp + 3 * k, quad, sizeof quad);
      k += 4;
    }
    nf = k;
    memcpy(m->F, tmp, sizeof(int) * 3 * (size_t)nf);
  }
  free(tmp);
  free(tab);
  return SS_OK;
}
