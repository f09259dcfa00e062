/* CSR assembly of a weighted undirected graph from an arc list. */
#include "geodesic/graph_build.h"

#include "mesh/mesh_geometry.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

ss_status ssi_graph_check_mesh(const ss_mesh *m, ss_error *err) {
  if (!m || m->nv < 0 || m->nf < 0 || (m->nv > 0 && !m->V) || (m->nf > 0 && !m->F))
    return ss_fail(err, SS_ERR_INVALID, "invalid mesh");
  for (long i = 0; i < 3L * m->nf; i++)
    if (m->F[i] < 0 || m->F[i] >= m->nv)
      return ss_fail(err, SS_ERR_INVALID, "face %ld references vertex %d outside [0,%d)", i / 3, m->F[i], m->nv);
  for (long i = 0; i < 3L * m->nv; i++)
    if (!isfinite(m->V[i])) return ss_fail(err, SS_ERR_INVALID, "vertex %ld has a non-finite coordinate", i / 3);
  return ssi_mesh_check_coordinates(m, NULL, err);
}

static int row_cmp(const void *a, const void *b) {
  const ssi_arc *x = a, *y = b;
  if (x->v != y->v) return x->v < y->v ? -1 : 1;
  return (x->w > y->w) - (x->w < y->w);
}

ss_status ssi_graph_from_arcs(int n, const ssi_arc *arcs, size_t narcs, ss_graph *g, ss_error *err) {
  memset(g, 0, sizeof *g);
  int *ptr = calloc((size_t)n + 1, sizeof(int));
  int *adj = malloc(sizeof(int) * (2 * narcs + 1));
  double *w = malloc(sizeof(double) * (2 * narcs + 1));
  int *pos = malloc(sizeof(int) * ((size_t)n + 1));
  if (!ptr || !adj || !w || !pos) {
    free(ptr); free(adj); free(w); free(pos);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory building a graph");
  }
  for (size_t k = 0; k < narcs; k++)
    if (arcs[k].u != arcs[k].v) { ptr[arcs[k].u + 1]++; ptr[arcs[k].v + 1]++; }
  for (int i = 0; i < n; i++) ptr[i + 1] += ptr[i];
  memcpy(pos, ptr, sizeof(int) * ((size_t)n + 1));
  for (size_t k = 0; k < narcs; k++) {
    int u = arcs[k].u, v = arcs[k].v;
    if (u == v) continue;
    int p = pos[u]++; adj[p] = v; w[p] = arcs[k].w;
    p = pos[v]++; adj[p] = u; w[p] = arcs[k].w;
  }
  /* sort each row by neighbour and merge duplicates keeping the minimum: insertion sort for short
   * rows, qsort for long ones (a vertex in 10^5 faces — copies of one face, a fan-triangulated
   * polygon of 10^6 corners — made the insertion sort quadratic); the merged rows are the same */
  int out = 0, start = 0;
  int maxrow = 0;
  for (int i = 0; i < n; i++)
    if (ptr[i + 1] - ptr[i] > maxrow) maxrow = ptr[i + 1] - ptr[i];
  ssi_arc *row = NULL;
  if (maxrow > 32) {
    row = malloc(sizeof(ssi_arc) * (size_t)maxrow);
    if (!row) {
      free(ptr); free(adj); free(w); free(pos);
      return ss_fail(err, SS_ERR_NOMEM, "out of memory building a graph");
    }
  }
  for (int i = 0; i < n; i++) {
    int end = ptr[i + 1];
    if (end - start > 32) {
      for (int a = start; a < end; a++) row[a - start].v = adj[a], row[a - start].w = w[a];
      qsort(row, (size_t)(end - start), sizeof *row, row_cmp);
      for (int a = start; a < end; a++) adj[a] = row[a - start].v, w[a] = row[a - start].w;
    }
    else for (int a = start + 1; a < end; a++) {
      int v = adj[a]; double x = w[a]; int b = a - 1;
      while (b >= start && adj[b] > v) { adj[b + 1] = adj[b]; w[b + 1] = w[b]; b--; }
      adj[b + 1] = v; w[b + 1] = x;
    }
    int rs = out;
    for (int a = start; a < end; a++) {
      if (out > rs && adj[out - 1] == adj[a]) { if (w[a] < w[out - 1]) w[out - 1] = w[a]; }
      else { adj[out] = adj[a]; w[out] = w[a]; out++; }
    }
    start = end;
    ptr[i] = rs;
  }
  ptr[n] = out;
  free(pos);
  free(row);
  g->n = n; g->ptr = ptr; g->adj = adj; g->w = w;
  return SS_OK;
}

void ss_graph_free(ss_graph *g) {
  if (!g) return;
  free(g->ptr); free(g->adj); free(g->w);
  memset(g, 0, sizeof *g);
}
