/* specseg — geodesic distances: graph (NPP22, mesh edges) Dijkstra and exact VTP. */
#ifndef SPECSEG_GEODESIC_H
#define SPECSEG_GEODESIC_H

#include "specseg/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Weighted undirected graph on the mesh vertices, CSR: neighbours of i are adj[ptr[i]..ptr[i+1]). */
typedef struct ss_graph {
  int n;
  int *ptr;
  int *adj;
  double *w;
} ss_graph;

/* Mesh edges weighted by their length. */
ss_status ss_graph_edges(const ss_mesh *m, ss_graph *g, ss_error *err);
/* NPP22 geodesic graph: 1-ring arcs plus, across each interior edge, the arc between the two
 * opposite vertices, weighted by the straight length in the unfolded pair of triangles, kept only
 * where that segment crosses the shared edge. */
ss_status ss_graph_npp22(const ss_mesh *m, ss_graph *g, ss_error *err);
void ss_graph_free(ss_graph *g);

/* Multi-source Dijkstra: dist[n] = distance to the nearest source (INFINITY when unreached or
 * farther than max_dist; max_dist <= 0 or INFINITY means no limit). nearest (may be NULL) receives
 * the index into `sources` of the nearest source, -1 when unreached. */
ss_status ss_graph_dijkstra(const ss_graph *g, const int *sources, int nsources, double max_dist,
                            double *dist, int *nearest, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
