/* Mesh-edge graph: every triangle side, weighted by its Euclidean length. */
#include "geodesic/graph_build.h"

#include <math.h>
#include <stdlib.h>

ss_status ss_graph_edges(const ss_mesh *m, ss_graph *g, ss_error *err) {
  ss_status st = ssi_graph_check_mesh(m, err);
  if (st) return st;
  size_t na = 3 * (size_t)m->nf;
  ssi_arc *arcs = malloc(sizeof(ssi_arc) * (na ? na : 1));
  if (!arcs) return ss_fail(err, SS_ERR_NOMEM, "out of memory building the edge graph");
  size_t k = 0;
  for (int f = 0; f < m->nf; f++)
    for (int c = 0; c < 3; c++) {
      int a = m->F[3 * f + c], b = m->F[3 * f + (c + 1) % 3];
      /* interior edges appear once per side; ssi_graph_from_arcs merges the duplicates */
      const double *pa = m->V + 3 * (size_t)a, *pb = m->V + 3 * (size_t)b;
      double dx = pa[0] - pb[0], dy = pa[1] - pb[1], dz = pa[2] - pb[2];
      arcs[k].u = a; arcs[k].v = b; arcs[k].w = sqrt(dx * dx + dy * dy + dz * dz);
      k++;
    }
  st = ssi_graph_from_arcs(m->nv, arcs, k, g, err);
  free(arcs);
  return st;
}
