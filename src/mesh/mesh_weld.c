/* Exact welding of vertices with equal coordinates (ssi_mesh_weld): the readers of vertex soups (STL
 * stores three vertices per facet) and of formats that split vertices at normal creases or texture
 * seams (glTF, or through assimp) join the surface back into one connected mesh. */
#include <stdlib.h>
#include <string.h>

#include "mesh/io_internal.h"

/* Total order on the coordinates: lexicographic x, y, z; NaN after every number (NaN == NaN here, so
 * the order is consistent, but NaN vertices are never merged below); ties by index (the first
 * occurrence heads its group). */
static int cmp_coord(double a, double b) {
  int na = a != a, nb = b != b;
  if (na || nb) return na - nb;
  return (a > b) - (a < b);
}

/* idx[a] before idx[b]: coordinates in the order above, then the index */
static int vertex_less(const double *V, int a, int b) {
  for (int c = 0; c < 3; c++) {
    int r = cmp_coord(V[3 * (size_t)a + c], V[3 * (size_t)b + c]);
    if (r) return r < 0;
  }
  return a < b;
}

static void merge_sort(const double *V, int *idx, int *tmp, int n) {
  /* bottom-up, O(n log n), stable */
  for (int w = 1; w < n; w *= 2) {
    for (int lo = 0; lo < n; lo += 2 * w) {
      int mid = lo + w < n ? lo + w : n, hi = lo + 2 * w < n ? lo + 2 * w : n;
      int i = lo, j = mid, k = lo;
      while (i < mid && j < hi) tmp[k++] = vertex_less(V, idx[j], idx[i]) ? idx[j++] : idx[i++];
      while (i < mid) tmp[k++] = idx[i++];
      while (j < hi) tmp[k++] = idx[j++];
    }
    memcpy(idx, tmp, sizeof(int) * (size_t)n);
  }
}

ss_status ssi_mesh_weld(ss_mesh *m, int *merged, ss_error *err) {
  if (merged) *merged = 0;
  if (!m || m->nv < 0 || m->nf < 0 || (m->nv > 0 && !m->V) || (m->nf > 0 && !m->F))
    return ss_fail(err, SS_ERR_INVALID, "weld: invalid mesh");
  const int n = m->nv;
  if (n < 2) return SS_OK;
  int *idx = malloc(sizeof(int) * (size_t)n), *tmp = malloc(sizeof(int) * (size_t)n);
  int *rep = malloc(sizeof(int) * (size_t)n);
  if (!idx || !tmp || !rep) {
    free(idx), free(tmp), free(rep);
    return ss_fail(err, SS_ERR_NOMEM, "weld: out of memory (%d vertices)", n);
  }
  for (int i = 0; i < n; i++) idx[i] = i;
  merge_sort(m->V, idx, tmp, n);
  /* rep[v]: the first vertex with v's coordinates (groups are runs of equal coordinates; -0 == 0) */
  for (int s = 0; s < n;) {
    int e = s + 1, head = idx[s];
    const double *a = m->V + 3 * (size_t)head;
    while (e < n) {
      const double *b = m->V + 3 * (size_t)idx[e];
      if (!(a[0] == b[0] && a[1] == b[1] && a[2] == b[2])) break;
      e++;
    }
    for (int q = s; q < e; q++) rep[idx[q]] = head;
    s = e;
  }
  /* new numbering in order of first occurrence; tmp[v] = new index of v's group */
  int nn = 0;
  for (int v = 0; v < n; v++) {
    if (rep[v] == v) {
      tmp[v] = nn;
      if (nn != v) memcpy(m->V + 3 * (size_t)nn, m->V + 3 * (size_t)v, 3 * sizeof(double));
      nn++;
    }
  }
  for (size_t f = 0; f < 3 * (size_t)m->nf; f++) {
    int v = m->F[f];
    if (v >= 0 && v < n) m->F[f] = tmp[rep[v]];
  }
  if (merged) *merged = n - nn;
  m->nv = nn;
  double *V2 = realloc(m->V, sizeof(double) * 3 * (size_t)(nn > 0 ? nn : 1));
  if (V2) m->V = V2;
  free(idx), free(tmp), free(rep);
  return SS_OK;
}
