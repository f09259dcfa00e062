/* Internal: assemble an ss_graph from a list of weighted undirected arcs (duplicates keep the
 * smallest weight, self-loops dropped). Shared by the edge graph and the NPP22 graph. */
#ifndef SS_GEODESIC_GRAPH_BUILD_H
#define SS_GEODESIC_GRAPH_BUILD_H

#include "specseg/geodesic.h"

typedef struct ssi_arc {
  int u, v;
  double w;
} ssi_arc;

/* Arcs are given once per undirected pair (either orientation). */
ss_status ssi_graph_from_arcs(int n, const ssi_arc *arcs, size_t narcs, ss_graph *g, ss_error *err);

/* Checks nv/nf/F indices, finite coordinates. */
ss_status ssi_graph_check_mesh(const ss_mesh *m, ss_error *err);

#endif
