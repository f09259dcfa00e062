/* ss_mesh_check and ss_mesh_sanitize on meshes with known topology: sphere, torus, grid with a
 * boundary, disjoint pieces, pinched vertices (two cones sharing an apex, a bow-tie), non-manifold
 * edges, duplicate / degenerate faces, unreferenced and non-finite vertices. */
#include "specseg/io.h"
#include "specseg/mesh.h"
#include "specseg/synth.h"
#include "testlib.h"

static void make(ss_mesh *m, int nv, const double *V, int nf, const int *F) {
  ss_mesh_alloc(m, nv, nf, NULL);
  memcpy(m->V, V, sizeof(double) * 3 * (size_t)nv);
  memcpy(m->F, F, sizeof(int) * 3 * (size_t)nf);
}

static void grid(int n, ss_mesh *m) {
  ss_mesh_alloc(m, n * n, 2 * (n - 1) * (n - 1), NULL);
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      double *p = m->V + 3 * (j * n + i);
      p[0] = i;
      p[1] = j;
      p[2] = 0.1 * i * j;
    }
  int k = 0;
  for (int j = 0; j + 1 < n; j++)
    for (int i = 0; i + 1 < n; i++) {
      int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      int t[6] = {a, b, d, a, d, c};
      memcpy(m->F + 3 * k, t, sizeof t);
      k += 2;
    }
}

static void torus(int nu, int nw, ss_mesh *m) {
  ss_mesh_alloc(m, nu * nw, 2 * nu * nw, NULL);
  for (int i = 0; i < nu; i++)
    for (int j = 0; j < nw; j++) {
      double u = 2 * M_PI * i / nu, w = 2 * M_PI * j / nw;
      double *p = m->V + 3 * (i * nw + j);
      p[0] = (2 + cos(w)) * cos(u);
      p[1] = (2 + cos(w)) * sin(u);
      p[2] = sin(w);
    }
  int k = 0;
  for (int i = 0; i < nu; i++)
    for (int j = 0; j < nw; j++) {
      int a = i * nw + j, b = ((i + 1) % nu) * nw + j, c = i * nw + (j + 1) % nw, d = ((i + 1) % nu) * nw + (j + 1) % nw;
      int t[6] = {a, b, d, a, d, c};
      memcpy(m->F + 3 * k, t, sizeof t);
      k += 2;
    }
}

/* Closed cone: apex, ring of k vertices, base centre. Vertices appended at offset `o` (apex shared
 * when apex >= 0). Returns the number of faces written to F. */
static int cone(double *V, int *nv, int *F, int apex, double dir, int k) {
  int a = apex;
  if (a < 0) {
    a = (*nv)++;
    V[3 * a] = V[3 * a + 1] = V[3 * a + 2] = 0;
  }
  int ring = *nv;
  for (int i = 0; i < k; i++) {
    double t = 2 * M_PI * i / k;
    V[3 * (ring + i)] = cos(t);
    V[3 * (ring + i) + 1] = sin(t);
    V[3 * (ring + i) + 2] = dir;
  }
  int c = ring + k;
  V[3 * c] = V[3 * c + 1] = 0;
  V[3 * c + 2] = dir;
  *nv = c + 1;
  int nf = 0;
  for (int i = 0; i < k; i++) {
    int r0 = ring + i, r1 = ring + (i + 1) % k;
    int t1[3] = {a, r0, r1}, t2[3] = {c, r1, r0};
    memcpy(F + 3 * nf++, t1, sizeof t1);
    memcpy(F + 3 * nf++, t2, sizeof t2);
  }
  return nf;
}

static void test_closed(void) {
  ss_mesh m;
  ss_mesh_report r;
  ss_error err = {{0}};
  CHECK(ss_synth_icosphere(3, &m, &err) == SS_OK);
  CHECK(ss_mesh_check(&m, &r, &err) == SS_OK);
  CHECK(r.vertices == m.nv && r.faces == m.nf);
  CHECK(r.components == 1 && r.boundary_loops == 0 && r.boundary_edges == 0 && r.manifold == 1);
  CHECK(r.euler_characteristic == 2 && r.nonmanifold_edges == 0 && r.nonmanifold_vertices == 0);
  CHECK(r.degenerate_faces == 0 && r.duplicate_faces == 0 && r.unreferenced_vertices == 0 && r.nonfinite_vertices == 0);
  CHECK_NEAR(r.area, 4 * M_PI, 0.05 * 4 * M_PI);
  CHECK_NEAR(r.bbox_diagonal, 2 * sqrt(3.0), 0.1);
  /* sanitize leaves a clean mesh exactly as it is */
  ss_mesh s;
  int *map;
  char warn[256];
  CHECK(ss_mesh_sanitize(&m, &s, &map, warn, sizeof warn, &err) == SS_OK);
  CHECK(s.nv == m.nv && s.nf == m.nf && !memcmp(s.F, m.F, sizeof(int) * 3 * (size_t)m.nf) && warn[0] == '\0');
  int ident = 1;
  for (int i = 0; i < s.nv; i++) ident &= map[i] == i;
  CHECK(ident);
  free(map);
  ss_mesh_free(&s);
  ss_mesh_free(&m);

  torus(24, 12, &m);
  CHECK(ss_mesh_check(&m, &r, &err) == SS_OK);
  CHECK(r.components == 1 && r.boundary_loops == 0 && r.manifold && r.euler_characteristic == 0);
  ss_mesh_free(&m);
}

static void test_boundary(void) {
  ss_mesh m;
  ss_mesh_report r;
  ss_error err = {{0}};
  grid(6, &m);
  CHECK(ss_mesh_check(&m, &r, &err) == SS_OK);
  CHECK(r.components == 1 && r.boundary_loops == 1 && r.boundary_edges == 20 && r.manifold && r.euler_characteristic == 1);
  /* punch a hole: drop the two triangles of an interior quad (ones at (2,2)) -> 2 loops, chi 0 */
  int q = 2 * (2 * 5 + 2);
  memmove(m.F + 3 * q, m.F + 3 * (q + 2), sizeof(int) * 3 * (size_t)(m.nf - q - 2));
  m.nf -= 2;
  CHECK(ss_mesh_check(&m, &r, &err) == SS_OK);
  CHECK(r.components == 1 && r.boundary_loops == 2 && r.boundary_edges == 24 && r.manifold && r.euler_characteristic == 0);
  ss_mesh_free(&m);

  /* two disjoint triangles */
  double V[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 0, 0, 6, 0, 0, 5, 1, 0};
  int F[6] = {0, 1, 2, 3, 4, 5};
  make(&m, 6, V, 2, F);
  CHECK(ss_mesh_check(&m, &r, &err) == SS_OK);
  CHECK(r.components == 2 && r.boundary_loops == 2 && r.boundary_edges == 6 && r.manifold && r.euler_characteristic == 2);
  CHECK_NEAR(r.area, 1.0, 1e-15);
  ss_mesh_free(&m);

  /* bow-tie: two triangles sharing only vertex 0 -> one component, two loops, one pinched vertex */
  double Vb[15] = {0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, -1, 0};
  int Fb[6] = {0, 1, 2, 0, 3, 4};
  make(&m, 5, Vb, 2, Fb);
  CHECK(ss_mesh_check(&m, &r, &err) == SS_OK);
  CHECK(r.components == 1 && r.boundary_loops == 2 && r.nonmanifold_vertices == 1 && r.nonmanifold_edges == 0 && !r.manifold);
  ss_mesh s;
  int *map;
  CHECK(ss_mesh_sanitize(&m, &s, &map, NULL, 0, &err) == SS_OK);
  CHECK(s.nv == 6 && s.nf == 2 && map[0] == 0 && map[1] == 0);
  ss_mesh_report rs;
  CHECK(ss_mesh_check(&s, &rs, &err) == SS_OK && rs.manifold && rs.components == 2 && rs.boundary_loops == 2);
  free(map);
  ss_mesh_free(&s);
  ss_mesh_free(&m);
}

static void test_pinched_cones(void) {
  enum { K = 8 };
  double V[3 * (2 * K + 3)];
  int F[3 * 4 * K];
  int nv = 0, nf = 0;
  nf += cone(V, &nv, F + 3 * nf, -1, 1.0, K);
  nf += cone(V, &nv, F + 3 * nf, 0, -1.0, K); /* second cone shares apex 0 */
  ss_mesh m;
  make(&m, nv, V, nf, F);
  ss_mesh_report r;
  ss_error err = {{0}};
  CHECK(ss_mesh_check(&m, &r, &err) == SS_OK);
  CHECK(r.components == 1 && r.boundary_loops == 0 && r.boundary_edges == 0);
  CHECK(r.nonmanifold_vertices == 1 && r.nonmanifold_edges == 0 && r.manifold == 0);
  CHECK(r.euler_characteristic == 3); /* two spheres (chi 4) glued at a point lose one vertex */

  ss_mesh s;
  int *map = NULL;
  char warn[256];
  CHECK_MSG(ss_mesh_sanitize(&m, &s, &map, warn, sizeof warn, &err) == SS_OK, "%s", err.msg);
  CHECK(s.nv == m.nv + 1 && s.nf == m.nf);
  CHECK(strstr(warn, "split 1 non-manifold (pinched) vertex into 2 copies") != NULL);
  ss_mesh_report rs;
  CHECK(ss_mesh_check(&s, &rs, &err) == SS_OK);
  CHECK(rs.manifold && rs.components == 2 && rs.boundary_loops == 0 && rs.euler_characteristic == 4);
  /* to_input maps back: every output vertex sits where its input vertex is, each face maps to the
   * input face, and exactly two outputs come from the apex */
  int ok = 1, apex = 0;
  for (int i = 0; i < s.nv; i++) {
    ok &= map[i] >= 0 && map[i] < m.nv && !memcmp(s.V + 3 * i, m.V + 3 * map[i], 3 * sizeof(double));
    apex += map[i] == 0;
  }
  for (int f = 0; f < s.nf; f++)
    for (int j = 0; j < 3; j++) ok &= map[s.F[3 * f + j]] == m.F[3 * f + j];
  CHECK(ok && apex == 2);
  free(map);
  ss_mesh_free(&s);
  ss_mesh_free(&m);
}

static void test_defects(void) {
  ss_mesh m, s;
  ss_mesh_report r;
  ss_error err = {{0}};
  int *map;
  char warn[512];
  /* grid 4x4 (18 faces) plus: a duplicate (reversed), a repeated-index face, a zero-area face with
   * distinct collinear vertices (extra vertex 16 on edge 0-1), an unreferenced vertex 17 */
  ss_mesh g;
  grid(4, &g);
  ss_mesh_alloc(&m, g.nv + 2, g.nf + 3, NULL);
  memcpy(m.V, g.V, sizeof(double) * 3 * (size_t)g.nv);
  memcpy(m.F, g.F, sizeof(int) * 3 * (size_t)g.nf);
  double extra[6] = {0.5, 0, 0, 9, 9, 9};
  memcpy(m.V + 3 * g.nv, extra, sizeof extra);
  int add[9] = {g.F[5], g.F[4], g.F[3], 5, 5, 6, 0, 16, 1};
  memcpy(m.F + 3 * g.nf, add, sizeof add);
  CHECK(ss_mesh_check(&m, &r, &err) == SS_OK);
  CHECK_MSG(r.degenerate_faces == 2 && r.duplicate_faces == 1 && r.unreferenced_vertices == 1, "deg %d dup %d unref %d",
            r.degenerate_faces, r.duplicate_faces, r.unreferenced_vertices);
  CHECK(r.nonmanifold_edges > 0 && !r.manifold); /* the duplicate puts 2+ faces on each of its edges */
  CHECK(ss_mesh_sanitize(&m, &s, &map, warn, sizeof warn, &err) == SS_OK);
  CHECK(s.nf == g.nf && s.nv == g.nv && !memcmp(s.F, g.F, sizeof(int) * 3 * (size_t)g.nf));
  CHECK(strstr(warn, "2 degenerate") && strstr(warn, "1 duplicate") && strstr(warn, "2 unreferenced"));
  CHECK(ss_mesh_check(&s, &r, &err) == SS_OK && r.manifold && r.boundary_loops == 1 && r.degenerate_faces == 0);
  free(map);
  ss_mesh_free(&s);
  /* tiny warnings buffer: truncated, still terminated */
  char small[8];
  CHECK(ss_mesh_sanitize(&m, &s, &map, small, sizeof small, &err) == SS_OK && strlen(small) < sizeof small);
  free(map);
  ss_mesh_free(&s);
  ss_mesh_free(&m);

  /* non-manifold edge: three triangles on edge 0-1 -> reported; sanitize refuses */
  double V[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1};
  int F[9] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
  make(&m, 5, V, 3, F);
  CHECK(ss_mesh_check(&m, &r, &err) == SS_OK && r.nonmanifold_edges == 1 && r.nonmanifold_vertices == 0 && !r.manifold);
  CHECK(ss_mesh_sanitize(&m, &s, &map, NULL, 0, &err) == SS_ERR_INVALID && strstr(err.msg, "non-manifold edge"));
  CHECK(s.V == NULL && map == NULL);
  /* NaN coordinate: counted by the check, refused by sanitize */
  m.V[3 * 4 + 1] = NAN;
  CHECK(ss_mesh_check(&m, &r, &err) == SS_OK && r.nonfinite_vertices == 1);
  m.nf = 1;
  m.V[3 * 2] = INFINITY;
  CHECK(ss_mesh_sanitize(&m, &s, &map, NULL, 0, &err) == SS_ERR_INVALID && strstr(err.msg, "non-finite"));
  /* index out of range */
  m.F[2] = 5;
  CHECK(ss_mesh_check(&m, &r, &err) == SS_ERR_INVALID);
  CHECK(ss_mesh_sanitize(&m, &s, &map, NULL, 0, &err) == SS_ERR_INVALID);
  /* only degenerate faces: nothing left */
  m.F[0] = m.F[1] = m.F[2] = 0;
  CHECK(ss_mesh_sanitize(&m, &s, &map, NULL, 0, &err) == SS_ERR_INVALID);
  ss_mesh_free(&m);
  ss_mesh_free(&g);
}

static void test_faust(void) {
  const char *d = tl_data_dir();
  if (!d) { SKIP("FAUST data not found (SS_DATA_DIR)"); return; }
  char path[4096];
  snprintf(path, sizeof path, "%s/faust/tr_reg_000.off", d);
  ss_mesh m;
  ss_mesh_report r;
  ss_error err = {{0}};
  CHECK_MSG(ss_read_mesh(path, &m, &err) == SS_OK, "%s", err.msg);
  CHECK(ss_mesh_check(&m, &r, &err) == SS_OK);
  CHECK(r.vertices == 6890 && r.faces == 13776 && r.components == 1 && r.boundary_loops == 0 && r.manifold);
  CHECK(r.euler_characteristic == 2 && r.degenerate_faces == 0 && r.duplicate_faces == 0);
  ss_mesh_free(&m);
  /* TOSCA cats have small holes: loops reported, still manifold */
  snprintf(path, sizeof path, "%s/tosca/cat0.off", d);
  if (ss_read_mesh(path, &m, &err) == SS_OK) {
    CHECK(ss_mesh_check(&m, &r, &err) == SS_OK && r.boundary_loops == 2 && r.manifold && r.components == 1);
    ss_mesh_free(&m);
  }
}

int main(void) {
  test_closed();
  test_boundary();
  test_pinched_cones();
  test_defects();
  test_faust();
  TEST_MAIN_END();
}
