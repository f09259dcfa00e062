/* Multi-source Dijkstra on a CSR graph with an indexed binary heap (decrease-key in place). */
#include "specseg/geodesic.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
  int *heap;   /* vertex ids, heap-ordered by key */
  int *where;  /* position in heap, -1 when absent */
  const double *key;
  int size;
} iheap;

static void sift_up(iheap *h, int i) {
  int v = h->heap[i];
  double k = h->key[v];
  while (i > 0) {
    int p = (i - 1) >> 1;
    int pv = h->heap[p];
    if (h->key[pv] <= k) break;
    h->heap[i] = pv; h->where[pv] = i;
    i = p;
  }
  h->heap[i] = v; h->where[v] = i;
}

static void sift_down(iheap *h, int i) {
  int v = h->heap[i];
  double k = h->key[v];
  for (;;) {
    int c = 2 * i + 1;
    if (c >= h->size) break;
    if (c + 1 < h->size && h->key[h->heap[c + 1]] < h->key[h->heap[c]]) c++;
    int cv = h->heap[c];
    if (h->key[cv] >= k) break;
    h->heap[i] = cv; h->where[cv] = i;
    i = c;
  }
  h->heap[i] = v; h->where[v] = i;
}

ss_status ss_graph_dijkstra(const ss_graph *g, const int *sources, int nsources, double max_dist,
                            double *dist, int *nearest, ss_error *err) {
  if (!g || g->n < 0 || !dist || (g->n > 0 && (!g->ptr || !g->adj || !g->w)))
    return ss_fail(err, SS_ERR_INVALID, "invalid graph");
  if (nsources < 1 || !sources) return ss_fail(err, SS_ERR_INVALID, "no source vertex given");
  int n = g->n;
  for (int s = 0; s < nsources; s++)
    if (sources[s] < 0 || sources[s] >= n)
      return ss_fail(err, SS_ERR_INVALID, "source vertex %d outside [0,%d)", sources[s], n);
  if (!(max_dist > 0) || isnan(max_dist)) max_dist = INFINITY;
  int *tag = nearest ? nearest : malloc(sizeof(int) * (size_t)n);
  int *heap = malloc(sizeof(int) * (size_t)n), *where = malloc(sizeof(int) * (size_t)n);
  if (!tag || !heap || !where) {
    if (!nearest) free(tag);
    free(heap); free(where);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory in Dijkstra");
  }
  for (int i = 0; i < n; i++) { dist[i] = INFINITY; tag[i] = -1; where[i] = -1; }
  iheap h = {heap, where, dist, 0};
  for (int s = 0; s < nsources; s++) {
    int v = sources[s];
    if (where[v] >= 0) continue; /* repeated source: the first occurrence names it */
    dist[v] = 0; tag[v] = s;
    heap[h.size] = v; where[v] = h.size; h.size++;
  }
  /* all keys are zero: already a heap */
  while (h.size > 0) {
    int u = heap[0];
    where[u] = -2; /* settled */
    h.size--;
    if (h.size > 0) { heap[0] = heap[h.size]; where[heap[0]] = 0; sift_down(&h, 0); }
    double du = dist[u];
    for (int p = g->ptr[u]; p < g->ptr[u + 1]; p++) {
      int v = g->adj[p];
      if (where[v] == -2) continue;
      double nd = du + g->w[p];
      if (nd < dist[v] && nd <= max_dist) {
        dist[v] = nd; tag[v] = tag[u];
        if (where[v] < 0) { heap[h.size] = v; where[v] = h.size; h.size++; }
        sift_up(&h, where[v]);
      }
    }
  }
  if (!nearest) free(tag);
  free(heap); free(where);
  return SS_OK;
}
