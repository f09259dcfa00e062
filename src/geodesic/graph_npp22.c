/* NPP22 graph (Nazzaro, Puppo, Pellacini 2022): the mesh edges plus, for each interior edge (a,b)
 * shared by triangles (a,b,c) and (b,a,d), the arc c–d with the length of the straight segment in
 * the plane where both triangles are unfolded — kept only when that segment crosses the open edge
 * (a,b), i.e. when it is a true surface path. */
#include "geodesic/graph_build.h"

#include <math.h>
#include <stdlib.h>

typedef struct {
  int lo, hi, opp;
} half_edge;

static int cmp_half(const void *x, const void *y) {
  const half_edge *a = x, *b = y;
  if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
  if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
  return (a->opp > b->opp) - (a->opp < b->opp);
}

/* Length of the unfolded segment c–d across edge a–b, or -1 when it does not cross the edge. */
static double unfolded_length(const double *a, const double *b, const double *c, const double *d) {
  double e[3], ac[3], ad[3];
  for (int k = 0; k < 3; k++) { e[k] = b[k] - a[k]; ac[k] = c[k] - a[k]; ad[k] = d[k] - a[k]; }
  double L2 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
  if (!(L2 > 0)) return -1;
  double L = sqrt(L2);
  double xc = (e[0] * ac[0] + e[1] * ac[1] + e[2] * ac[2]) / L;
  double xd = (e[0] * ad[0] + e[1] * ad[1] + e[2] * ad[2]) / L;
  double cc[3] = {e[1] * ac[2] - e[2] * ac[1], e[2] * ac[0] - e[0] * ac[2], e[0] * ac[1] - e[1] * ac[0]};
  double cd[3] = {e[1] * ad[2] - e[2] * ad[1], e[2] * ad[0] - e[0] * ad[2], e[0] * ad[1] - e[1] * ad[0]};
  double yc = sqrt(cc[0] * cc[0] + cc[1] * cc[1] + cc[2] * cc[2]) / L;   /* c above the edge */
  double yd = -sqrt(cd[0] * cd[0] + cd[1] * cd[1] + cd[2] * cd[2]) / L;  /* d below it */
  double h = yc - yd;
  if (!(h > 0)) return -1;
  double x = xc + (xd - xc) * (yc / h); /* where the segment meets the edge line */
  if (!(x > 0 && x < L)) return -1;
  double dx = xc - xd;
  return sqrt(dx * dx + h * h);
}

ss_status ss_graph_npp22(const ss_mesh *m, ss_graph *g, ss_error *err) {
  ss_status st = ssi_graph_check_mesh(m, err);
  if (st) return st;
  size_t nh = 3 * (size_t)m->nf;
  half_edge *he = malloc(sizeof(half_edge) * (nh ? nh : 1));
  ssi_arc *arcs = malloc(sizeof(ssi_arc) * (2 * nh + 1));
  if (!he || !arcs) {
    free(he); free(arcs);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory building the NPP22 graph");
  }
  size_t na = 0;
  for (int f = 0; f < m->nf; f++)
    for (int c = 0; c < 3; c++) {
      int a = m->F[3 * f + c], b = m->F[3 * f + (c + 1) % 3], o = m->F[3 * f + (c + 2) % 3];
      he[3 * (size_t)f + c].lo = a < b ? a : b;
      he[3 * (size_t)f + c].hi = a < b ? b : a;
      he[3 * (size_t)f + c].opp = o;
      const double *pa = m->V + 3 * (size_t)a, *pb = m->V + 3 * (size_t)b;
      double dx = pa[0] - pb[0], dy = pa[1] - pb[1], dz = pa[2] - pb[2];
      arcs[na].u = a; arcs[na].v = b; arcs[na].w = sqrt(dx * dx + dy * dy + dz * dz);
      na++;
    }
  qsort(he, nh, sizeof(half_edge), cmp_half);
  for (size_t i = 0; i < nh;) {
    size_t j = i + 1;
    while (j < nh && he[j].lo == he[i].lo && he[j].hi == he[i].hi) j++;
    if (j - i == 2) { /* manifold interior edge; non-manifold fans are left to the 1-ring arcs */
      int a = he[i].lo, b = he[i].hi, c = he[i].opp, d = he[i + 1].opp;
      if (c != d && c != a && c != b && d != a && d != b) {
        double len = unfolded_length(m->V + 3 * (size_t)a, m->V + 3 * (size_t)b, m->V + 3 * (size_t)c,
                                     m->V + 3 * (size_t)d);
        if (len >= 0) { arcs[na].u = c; arcs[na].v = d; arcs[na].w = len; na++; }
      }
    }
    i = j;
  }
  free(he);
  st = ssi_graph_from_arcs(m->nv, arcs, na, g, err);
  free(arcs);
  return st;
}
