/* Intrinsic Voronoi diagram by incremental, ρ-bounded Dijkstra runs (paper §4.3). */
#include "specseg/segment.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Binary min-heap of (distance, node) with lazy deletion: stale entries are skipped when popped. */
typedef struct {
  double d;
  int v;
} hitem;
typedef struct {
  hitem *a;
  size_t n, cap;
} heap;

static int heap_push(heap *h, double d, int v) {
  if (h->n == h->cap) {
    size_t cap = h->cap ? 2 * h->cap : 1024;
    hitem *a = realloc(h->a, cap * sizeof *a);
    if (!a) return -1;
    h->a = a;
    h->cap = cap;
  }
  size_t i = h->n++;
  while (i > 0) {
    size_t p = (i - 1) / 2;
    if (h->a[p].d <= d) break;
    h->a[i] = h->a[p];
    i = p;
  }
  h->a[i].d = d;
  h->a[i].v = v;
  return 0;
}

static hitem heap_pop(heap *h) {
  hitem top = h->a[0], last = h->a[--h->n];
  size_t i = 0, n = h->n;
  for (;;) {
    size_t c = 2 * i + 1;
    if (c >= n) break;
    if (c + 1 < n && h->a[c + 1].d < h->a[c].d) c++;
    if (last.d <= h->a[c].d) break;
    h->a[i] = h->a[c];
    i = c;
  }
  if (n) h->a[i] = last;
  return top;
}

ss_status ss_ivd(const ss_graph *g, const int *centers, int ncenters, double *s, int *tag, ss_error *err) {
  if (!g || g->n < 0 || (g->n > 0 && (!g->ptr || !s || !tag)))
    return ss_fail(err, SS_ERR_INVALID, "ivd: invalid graph or output");
  if (ncenters < 0 || (ncenters > 0 && !centers)) return ss_fail(err, SS_ERR_INVALID, "ivd: invalid centre list");
  int n = g->n;
  if (n > 0 && (g->ptr[0] != 0 || (g->ptr[n] > 0 && (!g->adj || !g->w))))
    return ss_fail(err, SS_ERR_INVALID, "ivd: malformed graph arrays");
  for (int i = 0; i < n; i++)
    for (int k = g->ptr[i]; k < g->ptr[i + 1]; k++)
      if (g->adj[k] < 0 || g->adj[k] >= n || !(g->w[k] >= 0))
        return ss_fail(err, SS_ERR_INVALID, "ivd: arc %d of node %d is invalid (node %d, weight %g)", k, i,
                       g->adj[k], g->w[k]);
  for (int i = 0; i < n; i++) {
    s[i] = INFINITY;
    tag[i] = -1;
  }
  for (int j = 0; j < ncenters; j++) {
    if (centers[j] < 0 || centers[j] >= n)
      return ss_fail(err, SS_ERR_INVALID, "ivd: centre %d is node %d, graph has %d nodes", j, centers[j], n);
    if (tag[centers[j]] >= 0)
      return ss_fail(err, SS_ERR_INVALID, "ivd: centres %d and %d are the same node %d", tag[centers[j]], j,
                     centers[j]);
    tag[centers[j]] = j;
  }
  for (int j = 0; j < ncenters; j++) tag[centers[j]] = -1;

  heap h = {0};
  double rho = INFINITY; /* the first run is unbounded */
  for (int j = 0; j < ncenters; j++) {
    int u = centers[j];
    s[u] = 0;
    tag[u] = j;
    h.n = 0;
    if (heap_push(&h, 0.0, u)) goto nomem;
    while (h.n) {
      hitem it = heap_pop(&h);
      if (it.d > s[it.v]) continue; /* stale */
      /* Every node this run can still improve has s ≤ ρ, so nothing beyond ρ is worth expanding. */
      if (it.d > rho) break;
      for (int k = g->ptr[it.v]; k < g->ptr[it.v + 1]; k++) {
        int w = g->adj[k];
        double nd = it.d + g->w[k];
        if (nd < s[w]) { /* strict: on a tie the earlier centre keeps the node */
          s[w] = nd;
          tag[w] = j;
          if (heap_push(&h, nd, w)) goto nomem;
        }
      }
    }
    /* ρ = max s; stays infinite while some node (e.g. another component) is unreached */
    rho = 0;
    for (int i = 0; i < n; i++)
      if (s[i] > rho) rho = s[i];
  }
  free(h.a);
  return SS_OK;
nomem:
  free(h.a);
  return ss_fail(err, SS_ERR_NOMEM, "ivd: out of memory for the Dijkstra queue");
}
