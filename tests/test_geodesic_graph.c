/* Graph distances: edge graph and NPP22 graph, multi-source Dijkstra, max distance, nearest tags. */
#include "specseg/geodesic.h"
#include "specseg/mesh.h"
#include "geodesic_meshes.h"
#include "testlib.h"

int main(void) {
  /* Two triangles forming a unit square split along (0,2): opposite vertices 1 and 3 are joined by
   * the unfolded diagonal of length sqrt(2). */
  {
    double V[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    int F[6] = {0, 1, 2, 0, 2, 3};
    ss_mesh m = {4, 2, V, F};
    ss_graph ge, gn;
    CHECK(ss_graph_edges(&m, &ge, NULL) == SS_OK);
    CHECK(ss_graph_npp22(&m, &gn, NULL) == SS_OK);
    CHECK(ge.ptr[4] == 10); /* 5 undirected edges */
    CHECK(gn.ptr[4] == 12); /* + the diagonal 1-3 */
    double d[4];
    int near[4];
    int src = 1;
    CHECK(ss_graph_dijkstra(&gn, &src, 1, 0, d, near, NULL) == SS_OK);
    CHECK_NEAR(d[3], sqrt(2.0), 1e-15);
    CHECK(ss_graph_dijkstra(&ge, &src, 1, 0, d, NULL, NULL) == SS_OK);
    CHECK_NEAR(d[3], 2.0, 1e-15);
    /* a folded (non-convex) pair: move vertex 3 so that the segment 1-3 misses edge 0-2 */
    V[9] = 2.0; V[10] = 3.0;
    ss_graph g2;
    CHECK(ss_graph_npp22(&m, &g2, NULL) == SS_OK);
    CHECK(g2.ptr[4] == 10);
    ss_graph_free(&g2);
    /* bad input */
    ss_error e;
    int bad = 7;
    CHECK(ss_graph_dijkstra(&gn, &bad, 1, 0, d, NULL, &e) == SS_ERR_INVALID);
    CHECK(ss_graph_dijkstra(&gn, &bad, 0, 0, d, NULL, &e) == SS_ERR_INVALID);
    F[5] = 9;
    CHECK(ss_graph_npp22(&m, &g2, &e) == SS_ERR_INVALID);
    ss_graph_free(&ge);
    ss_graph_free(&gn);
  }
  /* Flat jittered grid: Euclidean <= NPP22 <= edges, NPP22 much closer to Euclidean. */
  {
    ss_mesh m;
    gm_flat_grid(30, 25, 3.0, 2.5, 0.5, &m);
    ss_graph ge, gn;
    CHECK(ss_graph_edges(&m, &ge, NULL) == SS_OK);
    CHECK(ss_graph_npp22(&m, &gn, NULL) == SS_OK);
    int n = m.nv, src[2] = {0, n - 1};
    double *de = malloc(sizeof(double) * n), *dn = malloc(sizeof(double) * n), *d1 = malloc(sizeof(double) * n);
    int *near = malloc(sizeof(int) * n);
    CHECK(ss_graph_dijkstra(&ge, src, 1, 0, de, NULL, NULL) == SS_OK);
    CHECK(ss_graph_dijkstra(&gn, src, 1, 0, dn, NULL, NULL) == SS_OK);
    int order_ok = 1;
    double err_e = 0, err_n = 0;
    for (int i = 0; i < n; i++) {
      double ex = hypot(m.V[3 * i], m.V[3 * i + 1]);
      if (!(ex <= dn[i] + 1e-12 && dn[i] <= de[i] + 1e-12)) order_ok = 0;
      err_e = fmax(err_e, de[i] - ex);
      err_n = fmax(err_n, dn[i] - ex);
    }
    CHECK(order_ok);
    CHECK_MSG(err_n < 0.5 * err_e, "npp22 %g edge %g", err_n, err_e);
    /* two sources: minimum of single-source fields and correct tags */
    double *d2 = malloc(sizeof(double) * n);
    CHECK(ss_graph_dijkstra(&gn, src + 1, 1, 0, d2, NULL, NULL) == SS_OK);
    CHECK(ss_graph_dijkstra(&gn, src, 2, 0, d1, near, NULL) == SS_OK);
    int multi_ok = 1;
    for (int i = 0; i < n; i++) {
      if (d1[i] != fmin(dn[i], d2[i])) multi_ok = 0;
      if (dn[i] != d2[i] && near[i] != (dn[i] < d2[i] ? 0 : 1)) multi_ok = 0;
    }
    CHECK(multi_ok);
    /* max distance: same values inside, inf outside */
    CHECK(ss_graph_dijkstra(&gn, src, 1, 1.2, d1, near, NULL) == SS_OK);
    int lim_ok = 1;
    for (int i = 0; i < n; i++) {
      if (dn[i] <= 1.2 && d1[i] != dn[i]) lim_ok = 0;
      if (dn[i] > 1.2 && (!isinf(d1[i]) || near[i] != -1)) lim_ok = 0;
    }
    CHECK(lim_ok);
    free(de); free(dn); free(d1); free(d2); free(near);
    ss_graph_free(&ge); ss_graph_free(&gn);
    ss_mesh_free(&m);
  }
  /* Disconnected vertex stays unreached. */
  {
    double V[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5};
    int F[3] = {0, 1, 2};
    ss_mesh m = {4, 1, V, F};
    ss_graph g;
    CHECK(ss_graph_npp22(&m, &g, NULL) == SS_OK);
    double d[4]; int near[4]; int s = 0;
    CHECK(ss_graph_dijkstra(&g, &s, 1, 0, d, near, NULL) == SS_OK);
    CHECK(isinf(d[3]) && near[3] == -1 && near[1] == 0);
    ss_graph_free(&g);
  }
  TEST_MAIN_END();
}
