/* Synthetic shapes: the posable humanoid (topology, shared connectivity, near-isometry between poses,
 * determinism, extremities, triangle quality) and the torus (topology, area, volume). */
#include "specseg/mesh.h"
#include "specseg/synth.h"
#include "testlib.h"

#include <stdint.h>

static int cmp_u64(const void *a, const void *b) {
  uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return x < y ? -1 : x > y;
}

/* Every directed edge appears once and its reverse appears once: closed, no edge with more than
 * two faces, consistently oriented. Returns the number of offending half-edges. */
static int oriented_closed_defects(const ss_mesh *m) {
  size_t n = 3 * (size_t)m->nf;
  uint64_t *E = malloc(sizeof(uint64_t) * n);
  for (int f = 0; f < m->nf; f++)
    for (int c = 0; c < 3; c++)
      E[3 * (size_t)f + c] = ((uint64_t)(uint32_t)m->F[3 * f + c] << 32) | (uint32_t)m->F[3 * f + (c + 1) % 3];
  qsort(E, n, sizeof *E, cmp_u64);
  int bad = 0;
  for (size_t i = 0; i < n; i++) {
    if (i + 1 < n && E[i] == E[i + 1]) bad++;
    uint64_t r = (E[i] << 32) | (E[i] >> 32);
    if (!bsearch(&r, E, n, sizeof *E, cmp_u64)) bad++;
  }
  free(E);
  return bad;
}

static double signed_volume(const ss_mesh *m) {
  double v = 0;
  for (int f = 0; f < m->nf; f++) {
    const double *a = m->V + 3 * m->F[3 * f], *b = m->V + 3 * m->F[3 * f + 1], *c = m->V + 3 * m->F[3 * f + 2];
    v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6;
  }
  return v;
}

/* Fraction of triangles whose smallest angle is at least `deg` degrees; *minang = smallest angle. */
static double frac_min_angle(const ss_mesh *m, double deg, double *minang) {
  int ok = 0;
  *minang = 180;
  for (int f = 0; f < m->nf; f++) {
    double mn = 180;
    for (int c = 0; c < 3; c++) {
      const double *p = m->V + 3 * m->F[3 * f + c], *q = m->V + 3 * m->F[3 * f + (c + 1) % 3],
                   *r = m->V + 3 * m->F[3 * f + (c + 2) % 3];
      double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
      double x[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
      double a = atan2(sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]), u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) * 180 / M_PI;
      if (a < mn) mn = a;
    }
    if (mn < *minang) *minang = mn;
    ok += mn >= deg;
  }
  return (double)ok / m->nf;
}

static int cmp_d(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}
/* Median over edges (each face edge, so interior edges count twice: same median) of |l_p/l_0 - 1|. */
static double median_edge_strain(const ss_mesh *m0, const ss_mesh *mp, double *p95) {
  size_t n = 3 * (size_t)m0->nf;
  double *s = malloc(sizeof(double) * n);
  for (int f = 0; f < m0->nf; f++)
    for (int c = 0; c < 3; c++) {
      int a = m0->F[3 * f + c], b = m0->F[3 * f + (c + 1) % 3];
      double l0 = 0, lp = 0;
      for (int d = 0; d < 3; d++) {
        double x = m0->V[3 * a + d] - m0->V[3 * b + d], y = mp->V[3 * a + d] - mp->V[3 * b + d];
        l0 += x * x;
        lp += y * y;
      }
      s[3 * (size_t)f + c] = fabs(sqrt(lp / l0) - 1);
    }
  qsort(s, n, sizeof *s, cmp_d);
  double med = s[n / 2];
  *p95 = s[(size_t)(0.95 * (double)n)];
  free(s);
  return med;
}

/* Fraction of edges whose two opposite angles sum to more than pi (negative cotan weight). */
static double non_delaunay_fraction(const ss_mesh *m) {
  size_t n = 3 * (size_t)m->nf;
  uint64_t *E = malloc(sizeof(uint64_t) * n);
  double *A = malloc(sizeof(double) * n);
  for (int f = 0; f < m->nf; f++)
    for (int c = 0; c < 3; c++) {
      int a = m->F[3 * f + c], b = m->F[3 * f + (c + 1) % 3], o = m->F[3 * f + (c + 2) % 3];
      const double *p = m->V + 3 * o, *q = m->V + 3 * a, *r = m->V + 3 * b;
      double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
      double x[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
      E[3 * (size_t)f + c] = ((uint64_t)(uint32_t)(a < b ? a : b) << 32) | (uint32_t)(a < b ? b : a);
      A[3 * (size_t)f + c] = atan2(sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]), u[0] * v[0] + u[1] * v[1] + u[2] * v[2]);
    }
  /* pair the two half-edges of each edge: sort (undirected key, half-edge index) records by key */
  uint64_t *K = malloc(sizeof(uint64_t) * 2 * n);
  for (size_t i = 0; i < n; i++) {
    K[2 * i] = E[i];
    K[2 * i + 1] = i;
  }
  qsort(K, n, 2 * sizeof(uint64_t), cmp_u64);
  int bad = 0, edges = 0;
  for (size_t i = 0; i + 1 < n; i++)
    if (K[2 * i] == K[2 * i + 2]) {
      edges++;
      if (A[K[2 * i + 1]] + A[K[2 * i + 3]] > M_PI + 1e-12) bad++;
      i++;
    }
  free(K);
  free(E);
  free(A);
  return edges ? (double)bad / edges : 1;
}

/* Connected clusters (through mesh edges) of the vertices selected by `sel`. */
static int count_clusters(const ss_mesh *m, const char *sel) {
  int *parent = malloc(sizeof(int) * (size_t)m->nv);
  for (int i = 0; i < m->nv; i++) parent[i] = i;
  for (int f = 0; f < m->nf; f++)
    for (int c = 0; c < 3; c++) {
      int a = m->F[3 * f + c], b = m->F[3 * f + (c + 1) % 3];
      if (!sel[a] || !sel[b]) continue;
      while (parent[a] != a) a = parent[a] = parent[parent[a]];
      while (parent[b] != b) b = parent[b] = parent[parent[b]];
      if (a != b) parent[a < b ? b : a] = a < b ? a : b;
    }
  int n = 0;
  for (int i = 0; i < m->nv; i++) n += sel[i] && parent[i] == i;
  free(parent);
  return n;
}

static void test_humanoid(void) {
  ss_error err;
  int np = ss_synth_humanoid_pose_count();
  CHECK(np >= 4);
  ss_mesh rest;
  double t = ss_time();
  CHECK(ss_synth_humanoid(0, &rest, &err) == SS_OK);
  printf("humanoid rest: %d vertices, %d faces, built in %.3f s\n", rest.nv, rest.nf, ss_time() - t);
  CHECK(rest.nv >= 5000 && rest.nv <= 10000);
  double area0 = ss_mesh_area(&rest);

  /* extremities in the rest pose: finger stubs (3 per hand, beyond the palm), thumbs (towards the
   * front), toe stubs (3 per foot, beyond the front of the foot) */
  char *sel = calloc((size_t)rest.nv, 1);
  for (int side = -1; side <= 1; side += 2) {
    for (int i = 0; i < rest.nv; i++) sel[i] = side * rest.V[3 * i] > 0.85;
    CHECK_MSG(count_clusters(&rest, sel) == 3, "side %d: %d finger tips", side, count_clusters(&rest, sel));
    for (int i = 0; i < rest.nv; i++) sel[i] = side * rest.V[3 * i] > 0.6 && rest.V[3 * i + 2] > 0.07;
    CHECK_MSG(count_clusters(&rest, sel) == 1, "side %d: %d thumbs", side, count_clusters(&rest, sel));
    for (int i = 0; i < rest.nv; i++) sel[i] = side * rest.V[3 * i] > 0 && rest.V[3 * i + 1] < 0.12 && rest.V[3 * i + 2] > 0.165;
    CHECK_MSG(count_clusters(&rest, sel) == 3, "side %d: %d toe tips", side, count_clusters(&rest, sel));
  }
  free(sel);

  for (int p = 0; p < np; p++) {
    ss_mesh m;
    if (p == 0) {
      CHECK(ss_mesh_copy(&rest, &m, &err) == SS_OK);
    } else {
      CHECK(ss_synth_humanoid(p, &m, &err) == SS_OK);
    }
    ss_mesh_report r;
    CHECK(ss_mesh_check(&m, &r, &err) == SS_OK);
    CHECK_MSG(r.components == 1 && r.boundary_edges == 0 && r.boundary_loops == 0 && r.manifold &&
                  r.nonmanifold_edges == 0 && r.nonmanifold_vertices == 0,
              "pose %d: components %d boundary %d manifold %d", p, r.components, r.boundary_edges, r.manifold);
    CHECK_MSG(r.euler_characteristic == 2, "pose %d: chi %d", p, r.euler_characteristic);
    CHECK(r.degenerate_faces == 0 && r.duplicate_faces == 0 && r.unreferenced_vertices == 0 && r.nonfinite_vertices == 0);
    CHECK_MSG(oriented_closed_defects(&m) == 0, "pose %d: orientation defects", p);
    CHECK(signed_volume(&m) > 0.03); /* outward orientation; a ~60 kg body is ~0.06 m^3 */
    /* one connectivity, one vertex order */
    CHECK(m.nv == rest.nv && m.nf == rest.nf);
    if (m.nf == rest.nf) CHECK(memcmp(m.F, rest.F, sizeof(int) * 3 * (size_t)m.nf) == 0);
    double minang, q20 = frac_min_angle(&m, 20, &minang), q30 = frac_min_angle(&m, 30, &minang);
    double p95, strain = median_edge_strain(&rest, &m, &p95), area = ss_mesh_area(&m);
    double nd = non_delaunay_fraction(&m);
    printf("pose %d: area %.4f (%+.2f%%), edge strain median %.4f%% p95 %.2f%%, min angle >= 20: %.1f%%, "
           ">= 30: %.1f%%, smallest %.1f deg, negative cotan weights %.2f%% of edges\n",
           p, area, 100 * (area / area0 - 1), 100 * strain, 100 * p95, 100 * q20, 100 * q30, minang, 100 * nd);
    CHECK(nd < (p == 0 ? 0.001 : 0.02));
    CHECK(q20 >= (p == 0 ? 0.99 : 0.95));
    CHECK(minang > (p == 0 ? 20 : 5));
    CHECK(strain < 0.02);
    CHECK(fabs(area / area0 - 1) < 0.03);
    /* highest point in the head, lowest in a foot (judged on the rest positions: identity map) */
    int hi = 0, lo = 0;
    for (int i = 1; i < m.nv; i++) {
      if (m.V[3 * i + 1] > m.V[3 * hi + 1]) hi = i;
      if (m.V[3 * i + 1] < m.V[3 * lo + 1]) lo = i;
    }
    CHECK_MSG(rest.V[3 * hi + 1] > 1.55 && fabs(rest.V[3 * hi]) < 0.1, "pose %d: top vertex at rest y %.3f", p, rest.V[3 * hi + 1]);
    CHECK_MSG(rest.V[3 * lo + 1] < 0.1, "pose %d: bottom vertex at rest y %.3f", p, rest.V[3 * lo + 1]);
    ss_mesh_free(&m);
  }

  /* determinism: a second build is byte-identical (a skinned pose: it runs every stage) */
  {
    const int p = 3;
    ss_mesh a, b;
    CHECK(ss_synth_humanoid(p, &a, &err) == SS_OK);
    CHECK(ss_synth_humanoid(p, &b, &err) == SS_OK);
    CHECK(a.nv == b.nv && a.nf == b.nf);
    if (a.nv == b.nv && a.nf == b.nf) {
      CHECK(memcmp(a.V, b.V, sizeof(double) * 3 * (size_t)a.nv) == 0);
      CHECK(memcmp(a.F, b.F, sizeof(int) * 3 * (size_t)a.nf) == 0);
    }
    ss_mesh_free(&a);
    ss_mesh_free(&b);
  }

  ss_mesh bad = {0};
  CHECK(ss_synth_humanoid(-1, &bad, &err) == SS_ERR_INVALID);
  CHECK(ss_synth_humanoid(np, &bad, &err) == SS_ERR_INVALID);
  CHECK(bad.V == NULL && bad.F == NULL);
  ss_mesh_free(&rest);
}

static void test_torus(void) {
  ss_error err;
  const double R = 1.0, r = 0.3;
  ss_mesh m;
  CHECK(ss_synth_torus(R, r, 96, 48, &m, &err) == SS_OK);
  CHECK(m.nv == 96 * 48 && m.nf == 2 * 96 * 48);
  ss_mesh_report rep;
  CHECK(ss_mesh_check(&m, &rep, &err) == SS_OK);
  CHECK(rep.components == 1 && rep.boundary_edges == 0 && rep.manifold && rep.degenerate_faces == 0);
  CHECK(rep.euler_characteristic == 0);
  CHECK(oriented_closed_defects(&m) == 0);
  double A = 4 * M_PI * M_PI * R * r, Vol = 2 * M_PI * M_PI * R * r * r;
  CHECK_NEAR(ss_mesh_area(&m) / A, 1, 0.01);
  CHECK_NEAR(signed_volume(&m) / Vol, 1, 0.01); /* positive: outward normals */
  printf("torus 96x48: area %.6f (exact %.6f), volume %.6f (exact %.6f)\n", ss_mesh_area(&m), A, signed_volume(&m), Vol);
  ss_mesh_free(&m);
  /* coarse odd resolutions are still closed tori */
  CHECK(ss_synth_torus(2, 0.5, 7, 5, &m, &err) == SS_OK);
  CHECK(ss_mesh_check(&m, &rep, &err) == SS_OK && rep.euler_characteristic == 0 && rep.boundary_edges == 0 && rep.manifold);
  CHECK(oriented_closed_defects(&m) == 0);
  ss_mesh_free(&m);
  CHECK(ss_synth_torus(1, 1, 10, 10, &m, &err) == SS_ERR_INVALID);
  CHECK(ss_synth_torus(1, 0, 10, 10, &m, &err) == SS_ERR_INVALID);
  CHECK(ss_synth_torus(1, 0.2, 2, 10, &m, &err) == SS_ERR_INVALID);
  CHECK(ss_synth_torus(1, 0.2, 10, 1 << 30, &m, &err) == SS_ERR_INVALID);
  CHECK(ss_synth_torus(NAN, 0.2, 10, 10, &m, &err) == SS_ERR_INVALID);
}

int main(void) {
  test_humanoid();
  test_torus();
  TEST_MAIN_END();
}
