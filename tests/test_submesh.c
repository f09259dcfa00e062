/* The sub-mesh module (src/submesh): a mesh's components as a mesh of their own (vertices and faces
 * in input order, the vertex maps both ways), the restriction of per-vertex columns to it, the lifts
 * of values and vertex indices back, and the nearest-vertex fill of the vertices it left out. */
#include "testlib.h"
#include "specseg/core.h"
#include "mesh/mesh_topology.h"
#include "submesh/submesh.h"

/* Two tetrahedra: vertices 0..3 at the origin, 4..7 shifted by 10 in x, interleaved in the input
 * order (component of vertex i: i % 2) so that the kept vertices are renumbered. */
static void two_tets(ss_mesh *m) {
  static const double P[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  static const int T[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  ss_error e = {0};
  CHECK(ss_mesh_alloc(m, 8, 8, &e) == SS_OK);
  for (int c = 0; c < 2; c++)
    for (int v = 0; v < 4; v++)
      for (int k = 0; k < 3; k++) m->V[3 * (2 * v + c) + k] = P[v][k] + (k == 0 ? 10.0 * c : 0.0);
  for (int c = 0; c < 2; c++)
    for (int f = 0; f < 4; f++)
      for (int j = 0; j < 3; j++) m->F[3 * (4 * c + f) + j] = 2 * T[f][j] + c;
}

int main(void) {
  ss_mesh m;
  two_tets(&m);
  int comp[8];
  CHECK(ssi_mesh_components(&m, comp) == 2);
  const unsigned char keep[2] = {0, 1};
  ssi_submesh s;
  ss_error e = {0};
  CHECK(ssi_submesh_components(&m, comp, keep, &s, &e) == SS_OK);
  CHECK(s.active && s.mesh.nv == 4 && s.mesh.nf == 4);
  for (int v = 0; v < 4; v++) {
    CHECK(s.to_in[v] == 2 * v + 1);                                  /* input order kept */
    CHECK(ssi_submesh_input_vertex(&s, v) == 2 * v + 1);
    CHECK(!memcmp(s.mesh.V + 3 * v, m.V + 3 * (2 * v + 1), sizeof(double) * 3));
  }
  for (int i = 0; i < 8; i++) CHECK(ssi_submesh_sub_vertex(&s, i) == (i % 2 ? i / 2 : -1));
  for (int f = 0; f < 4; f++)
    for (int j = 0; j < 3; j++) CHECK(s.to_in[s.mesh.F[3 * f + j]] == m.F[3 * (4 + f) + j]);

  /* restriction of two columns, then the lift of values and of indices back */
  double col[16], sub[8];
  for (int i = 0; i < 16; i++) col[i] = i;
  ssi_submesh_restrict(&s, 8, 2, col, sub);
  for (int v = 0; v < 4; v++) CHECK(sub[v] == 2 * v + 1 && sub[4 + v] == 8 + 2 * v + 1);
  const int val[4] = {30, 31, 32, 33};
  int lifted[8];
  ssi_submesh_lift_values(&s, 8, val, lifted);
  for (int i = 0; i < 8; i++) CHECK(lifted[i] == (i % 2 ? 30 + i / 2 : -1));
  int idx[3] = {3, -1, 0};
  ssi_submesh_lift_indices(&s, 3, idx);
  CHECK(idx[0] == 7 && idx[1] == -1 && idx[2] == 1);

  /* the left-out vertices take the value of the nearest kept one: the kept tetrahedron's corner
   * across x = 10 (corners 0 and 1 of the left-out one are both nearest to its corner 0) */
  CHECK(ssi_fill_from_nearest(&m, lifted, "test", &e) == SS_OK);
  const int across[4] = {30, 30, 32, 33};
  for (int i = 0; i < 8; i++) CHECK(lifted[i] == (i % 2 ? 30 + i / 2 : across[i / 2]));
  int none[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
  CHECK(ssi_fill_from_nearest(&m, none, "test", &e) == SS_ERR_NUMERIC);

  /* not active: the identity */
  ssi_submesh id = {0};
  CHECK(ssi_submesh_sub_vertex(&id, 5) == 5 && ssi_submesh_input_vertex(&id, 5) == 5);
  ssi_submesh_lift_values(&id, 4, val, lifted);
  CHECK(lifted[0] == 30 && lifted[3] == 33);
  ssi_submesh_free(&s);
  ssi_submesh_free(&id);
  ss_mesh_free(&m);
  TEST_MAIN_END();
}
