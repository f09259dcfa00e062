/* Segmentation: critical points on hand-made meshes, iVd vs multi-source Dijkstra, coherency, and the
 * whole pipeline on the synthetic humanoid's poses. */
#include "testlib.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#include "specseg/geodesic.h"
#include "specseg/mesh.h"
#include "specseg/synth.h"
#include "specseg/segment.h"

/* ---- tiny meshes --------------------------------------------------------------------------------- */

/* Closed fan: centre 0 at the origin, ring 1..n on the unit circle, apex n+1 below closes it (so the
 * centre's star is exactly the n fan triangles). */
static void fan_closed(int n, ss_mesh *m) {
  ss_mesh_alloc(m, n + 2, 2 * n, NULL);
  m->V[0] = m->V[1] = m->V[2] = 0;
  for (int k = 0; k < n; k++) {
    double t = 2 * M_PI * k / n;
    m->V[3 * (k + 1)] = cos(t), m->V[3 * (k + 1) + 1] = sin(t), m->V[3 * (k + 1) + 2] = 0;
  }
  m->V[3 * (n + 1)] = 0, m->V[3 * (n + 1) + 1] = 0, m->V[3 * (n + 1) + 2] = -1;
  for (int k = 0; k < n; k++) {
    int a = 1 + k, b = 1 + (k + 1) % n;
    int *f = m->F + 6 * k;
    f[0] = 0, f[1] = a, f[2] = b;
    f[3] = n + 1, f[4] = b, f[5] = a;
  }
}

/* Open fan (boundary vertex 0): ring 1..n on a half circle, n-1 triangles. */
static void fan_open(int n, ss_mesh *m) {
  ss_mesh_alloc(m, n + 1, n - 1, NULL);
  m->V[0] = m->V[1] = m->V[2] = 0;
  for (int k = 0; k < n; k++) {
    double t = M_PI * k / (n - 1);
    m->V[3 * (k + 1)] = cos(t), m->V[3 * (k + 1) + 1] = sin(t), m->V[3 * (k + 1) + 2] = 0;
  }
  for (int k = 0; k + 1 < n; k++) m->F[3 * k] = 0, m->F[3 * k + 1] = k + 1, m->F[3 * k + 2] = k + 2;
}

/* Octahedron-like bipyramid: top 0, bottom 1, ring 2..n+1. */
static void bipyramid(int n, ss_mesh *m) {
  ss_mesh_alloc(m, n + 2, 2 * n, NULL);
  m->V[0] = 0, m->V[1] = 0, m->V[2] = 1;
  m->V[3] = 0, m->V[4] = 0, m->V[5] = -1;
  for (int k = 0; k < n; k++) {
    double t = 2 * M_PI * k / n;
    m->V[3 * (k + 2)] = cos(t), m->V[3 * (k + 2) + 1] = sin(t), m->V[3 * (k + 2) + 2] = 0;
  }
  for (int k = 0; k < n; k++) {
    int a = 2 + k, b = 2 + (k + 1) % n;
    int *f = m->F + 6 * k;
    f[0] = 0, f[1] = a, f[2] = b;
    f[3] = 1, f[4] = b, f[5] = a;
  }
}

/* Regular grid nx*ny on [0,nx-1]x[0,ny-1], vertex (i,j) = j*nx+i. */
static void grid(int nx, int ny, ss_mesh *m) {
  ss_mesh_alloc(m, nx * ny, 2 * (nx - 1) * (ny - 1), NULL);
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++) {
      double *p = m->V + 3 * (j * nx + i);
      p[0] = i, p[1] = j, p[2] = 0;
    }
  int k = 0;
  for (int j = 0; j + 1 < ny; j++)
    for (int i = 0; i + 1 < nx; i++) {
      int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      int *f = m->F + 3 * k;
      f[0] = a, f[1] = b, f[2] = d, f[3] = a, f[4] = d, f[5] = c;
      k += 2;
    }
}

static int count_type(const signed char *t, int n, int type) {
  int c = 0;
  for (int i = 0; i < n; i++) c += t[i] == type;
  return c;
}

static void test_critical_tiny(void) {
  ss_error err;
  int *pts = NULL, np = 0, nraw = 0;
  signed char ty[64];

  /* cone apex: φ = height, apex above its ring → max; a pit → min */
  {
    ss_mesh m;
    fan_closed(7, &m);
    double phi[9];
    phi[0] = 1;
    for (int k = 1; k <= 7; k++) phi[k] = 0.1 * k;
    phi[8] = -1;
    CHECK(ss_fiedler_critical_points(&m, phi, 0, ty, &pts, &np, &nraw, &err) == SS_OK);
    CHECK(ty[0] == SS_CRIT_MAX);
    CHECK(ty[8] == SS_CRIT_MIN);
    free(pts);
    phi[0] = -0.5; /* below its whole 1-ring → min */
    CHECK(ss_fiedler_critical_points(&m, phi, 0, ty, &pts, &np, &nraw, &err) == SS_OK);
    CHECK(ty[0] == SS_CRIT_MIN);
    free(pts);
    phi[0] = 0.35; /* between ring values that increase around once: 2 straddling triangles → regular */
    CHECK(ss_fiedler_critical_points(&m, phi, 0, ty, &pts, &np, &nraw, &err) == SS_OK);
    CHECK(ty[0] == SS_CRIT_REGULAR);
    free(pts);
    ss_mesh_free(&m);
  }
  /* simple saddle (4 sign changes) and monkey saddle (6) around the centre of a closed fan */
  {
    ss_mesh m;
    fan_closed(8, &m);
    double phi[10] = {0};
    for (int k = 0; k < 8; k++) phi[1 + k] = cos(2 * (2 * M_PI * k / 8 + M_PI / 8));
    phi[9] = -5;
    CHECK(ss_fiedler_critical_points(&m, phi, 0, ty, &pts, &np, &nraw, &err) == SS_OK);
    CHECK(ty[0] == SS_CRIT_SADDLE);
    free(pts);
    for (int k = 0; k < 8; k++) phi[1 + k] = cos(2 * M_PI * k / 8 + 0.3); /* 2 changes: regular */
    CHECK(ss_fiedler_critical_points(&m, phi, 0, ty, &pts, &np, &nraw, &err) == SS_OK);
    CHECK(ty[0] == SS_CRIT_REGULAR);
    free(pts);
    ss_mesh_free(&m);
    fan_closed(6, &m);
    for (int k = 0; k < 6; k++) phi[1 + k] = (k % 2) ? -1.0 - 0.1 * k : 1.0 + 0.1 * k; /* monkey saddle */
    phi[7] = -5;
    CHECK(ss_fiedler_critical_points(&m, phi, 0, ty, &pts, &np, &nraw, &err) == SS_OK);
    CHECK(ty[0] == SS_CRIT_SADDLE);
    free(pts);
    ss_mesh_free(&m);
  }
  /* boundary vertex: 4 straddling triangles in an open fan → saddle; 3 → not */
  {
    ss_mesh m;
    fan_open(5, &m);
    double phi[6] = {0, 1, -1, 1, -1, 1};
    CHECK(ss_fiedler_critical_points(&m, phi, 0, ty, &pts, &np, &nraw, &err) == SS_OK);
    CHECK(ty[0] == SS_CRIT_SADDLE);
    free(pts);
    ss_mesh_free(&m);
    fan_open(4, &m);
    double phi2[5] = {0, 1, -1, 1, -1};
    CHECK(ss_fiedler_critical_points(&m, phi2, 0, ty, &pts, &np, &nraw, &err) == SS_OK);
    CHECK(ty[0] == SS_CRIT_REGULAR);
    free(pts);
    ss_mesh_free(&m);
  }
  /* ties: symbolic perturbation by index */
  {
    ss_mesh m;
    bipyramid(6, &m);
    double phi[8] = {1, -1, 0, 0, 0, 0, 0, 0}; /* flat ring */
    CHECK(ss_fiedler_critical_points(&m, phi, 0, ty, &pts, &np, &nraw, &err) == SS_OK);
    CHECK(ty[0] == SS_CRIT_MAX && ty[1] == SS_CRIT_MIN);
    CHECK(np == 2 && nraw == 2); /* the flat ring behaves as φ = index: all regular */
    free(pts);
    for (int i = 0; i < 8; i++) phi[i] = 3.0; /* constant: φ behaves as the vertex index */
    CHECK(ss_fiedler_critical_points(&m, phi, 0, ty, &pts, &np, &nraw, &err) == SS_OK);
    CHECK(ty[0] == SS_CRIT_MIN);
    CHECK(ty[7] == SS_CRIT_MAX);
    /* Morse count on a sphere: #min − #saddle + #max = 2 (simple saddles here) */
    CHECK(count_type(ty, 8, SS_CRIT_MIN) - count_type(ty, 8, SS_CRIT_SADDLE) + count_type(ty, 8, SS_CRIT_MAX) == 2);
    int *pts2 = NULL, np2 = 0;
    signed char ty2[8];
    CHECK(ss_fiedler_critical_points(&m, phi, 0, ty2, &pts2, &np2, NULL, &err) == SS_OK);
    CHECK(np2 == np && !memcmp(ty, ty2, 8)); /* deterministic */
    free(pts);
    free(pts2);
    ss_mesh_free(&m);
  }
  /* bad input */
  {
    ss_mesh m;
    bipyramid(5, &m);
    double phi[7] = {0, 1, 2, 3, NAN, 5, 6};
    CHECK(ss_fiedler_critical_points(&m, phi, 0, NULL, &pts, &np, NULL, &err) == SS_ERR_INVALID);
    phi[4] = 4;
    m.F[4] = 99;
    CHECK(ss_fiedler_critical_points(&m, phi, 0, NULL, &pts, &np, NULL, &err) == SS_ERR_INVALID);
    ss_mesh_free(&m);
  }
}

/* Two bumps 3 cells apart on a grid: max, saddle, max cluster; the 5-ring clean-up keeps only the
 * flattest of them (smallest vertex gradient). */
static void test_cleanup(void) {
  ss_error err;
  int nx = 41, ny = 41;
  ss_mesh m;
  grid(nx, ny, &m);
  double *phi = malloc(sizeof(double) * m.nv), *g = malloc(sizeof(double) * m.nv);
  for (int i = 0; i < m.nv; i++) {
    double x = m.V[3 * i], y = m.V[3 * i + 1];
    double d1 = (x - 19.2) * (x - 19.2) + (y - 20.1) * (y - 20.1), d2 = (x - 23.3) * (x - 23.3) + (y - 20.2) * (y - 20.2);
    phi[i] = exp(-d1 / 4.0) + 0.8 * exp(-d2 / 4.0) + 1e-3 * (x + 0.37 * y) / nx;
  }
  signed char *t0 = malloc(m.nv), *t1 = malloc(m.nv);
  int *p0 = NULL, *p1 = NULL, n0 = 0, n1 = 0, raw = 0;
  CHECK(ss_fiedler_critical_points(&m, phi, 0, t0, &p0, &n0, &raw, &err) == SS_OK);
  CHECK(raw == n0);
  CHECK(ss_fiedler_critical_points(&m, phi, 5, t1, &p1, &n1, &raw, &err) == SS_OK);
  CHECK(raw == n0);
  CHECK(n1 < n0);
  CHECK(ss_vertex_gradient_norm(&m, phi, g, &err) == SS_OK);
  /* the central cluster: critical points within 8 cells of (20,20) */
  int c0 = 0, c1 = 0, best = -1, survivor = -1;
  for (int k = 0; k < n0; k++) {
    int v = p0[k], x = v % nx, y = v / nx;
    if (abs(x - 20) <= 8 && abs(y - 20) <= 8) {
      c0++;
      if (best < 0 || g[v] < g[best]) best = v;
    }
  }
  for (int k = 0; k < n1; k++) {
    int v = p1[k], x = v % nx, y = v / nx;
    if (abs(x - 20) <= 8 && abs(y - 20) <= 8) c1++, survivor = v;
  }
  CHECK_MSG(c0 == 3, "raw cluster %d (2 maxima + 1 saddle expected)", c0);
  CHECK(c1 == 1);
  CHECK(survivor == best);
  /* types: survivors keep their type, the dropped are regular */
  for (int k = 0; k < n1; k++) CHECK(t1[p1[k]] == t0[p1[k]] && t1[p1[k]] != SS_CRIT_REGULAR);
  CHECK(count_type(t1, m.nv, SS_CRIT_REGULAR) == m.nv - n1);
  /* gradient of a linear function is exact */
  for (int i = 0; i < m.nv; i++) phi[i] = 2 * m.V[3 * i] - m.V[3 * i + 1];
  CHECK(ss_vertex_gradient_norm(&m, phi, g, &err) == SS_OK);
  double maxe = 0;
  for (int i = 0; i < m.nv; i++) maxe = fmax(maxe, fabs(g[i] - sqrt(5.0)));
  CHECK(maxe < 1e-12);
  free(phi), free(g), free(t0), free(t1), free(p0), free(p1);
  ss_mesh_free(&m);
}

/* ---- iVd ------------------------------------------------------------------------------------------ */

static void check_ivd_equals_dijkstra(const ss_mesh *m, const int *centers, int nc) {
  ss_error err;
  ss_graph g = {0};
  CHECK(ss_graph_npp22(m, &g, &err) == SS_OK);
  int n = g.n;
  double *s = malloc(sizeof(double) * n), *d = malloc(sizeof(double) * n), *dc = malloc(sizeof(double) * n * (size_t)nc);
  int *tag = malloc(sizeof(int) * n), *near = malloc(sizeof(int) * n);
  CHECK(ss_ivd(&g, centers, nc, s, tag, &err) == SS_OK);
  CHECK(ss_graph_dijkstra(&g, centers, nc, 0, d, near, &err) == SS_OK);
  for (int c = 0; c < nc; c++) CHECK(ss_graph_dijkstra(&g, centers + c, 1, 0, dc + (size_t)c * n, NULL, &err) == SS_OK);
  double maxd = 0;
  int diff = 0, bad = 0;
  for (int i = 0; i < n; i++) {
    maxd = fmax(maxd, fabs(s[i] - d[i]));
    if (tag[i] != near[i]) {
      diff++;
      /* allowed only on a tie: both centres at the same distance */
      if (tag[i] < 0 || near[i] < 0 || fabs(dc[(size_t)tag[i] * n + i] - dc[(size_t)near[i] * n + i]) > 1e-12 * (1 + d[i])) bad++;
    }
    if (tag[i] >= 0 && fabs(dc[(size_t)tag[i] * n + i] - s[i]) > 1e-12 * (1 + s[i])) bad++;
  }
  CHECK_MSG(maxd < 1e-12, "max |s - d| = %g", maxd);
  CHECK_MSG(bad == 0, "%d tag mismatches that are not ties (%d differences)", bad, diff);
  for (int c = 0; c < nc; c++) CHECK(tag[centers[c]] == c && s[centers[c]] == 0);
  free(s), free(d), free(dc), free(tag), free(near);
  ss_graph_free(&g);
}

static void test_ivd(void) {
  ss_error err;
  /* a path 0-1-2-3-4 with known distances */
  {
    int ptr[6] = {0, 1, 3, 5, 7, 8}, adj[8] = {1, 0, 2, 1, 3, 2, 4, 3};
    double w[8] = {1, 1, 2, 2, 2, 2, 5, 5}; /* 0 -1- 1 -2- 2 -2- 3 -5- 4 */
    ss_graph g = {5, ptr, adj, w};
    int c[2] = {0, 4};
    double s[5];
    int tag[5];
    CHECK(ss_ivd(&g, c, 2, s, tag, &err) == SS_OK);
    CHECK(s[0] == 0 && s[1] == 1 && s[2] == 3 && s[3] == 5 && s[4] == 0);
    CHECK(tag[0] == 0 && tag[1] == 0 && tag[2] == 0 && tag[3] == 0 && tag[4] == 1); /* 3: tie, earlier wins */
    int c2[2] = {1, 3}; /* node 2: 2 from both → tie goes to the earlier centre */
    CHECK(ss_ivd(&g, c2, 2, s, tag, &err) == SS_OK);
    CHECK(tag[2] == 0 && s[2] == 2 && tag[4] == 1 && s[4] == 5 && tag[0] == 0 && s[0] == 1);
    int dup[2] = {2, 2};
    CHECK(ss_ivd(&g, dup, 2, s, tag, &err) == SS_ERR_INVALID);
    int oob[1] = {7};
    CHECK(ss_ivd(&g, oob, 1, s, tag, &err) == SS_ERR_INVALID);
  }
  /* two components: a centre in each must cover its own */
  {
    int ptr[5] = {0, 1, 2, 3, 4}, adj[4] = {1, 0, 3, 2};
    double w[4] = {1, 1, 1, 1};
    ss_graph g = {4, ptr, adj, w};
    int c[2] = {0, 2};
    double s[4];
    int tag[4];
    CHECK(ss_ivd(&g, c, 2, s, tag, &err) == SS_OK);
    CHECK(tag[1] == 0 && tag[3] == 1 && s[3] == 1);
    CHECK(ss_ivd(&g, c, 1, s, tag, &err) == SS_OK);
    CHECK(tag[3] == -1 && isinf(s[3]));
  }
  /* against plain multi-source Dijkstra on NPP22 graphs */
  {
    ss_mesh m;
    CHECK(ss_synth_icosphere(4, &m, &err) == SS_OK);
    int c[12];
    unsigned r = 12345;
    for (int k = 0; k < 12; k++) {
      r = r * 1103515245u + 12345u;
      c[k] = (int)((r >> 8) % (unsigned)m.nv);
      for (int j = 0; j < k; j++)
        if (c[j] == c[k]) c[k] = (c[k] + 1) % m.nv, j = -1;
    }
    check_ivd_equals_dijkstra(&m, c, 12);
    ss_mesh_free(&m);
    grid(30, 20, &m); /* many exact ties on a regular grid */
    int cg[4] = {0, 29, 599, 310};
    check_ivd_equals_dijkstra(&m, cg, 4);
    ss_mesh_free(&m);
  }
}

/* ---- coherency ------------------------------------------------------------------------------------ */

static void test_coherency(void) {
  ss_error err;
  int lab0[6] = {0, 0, 0, 1, 1, 1};
  int lab[6] = {0, 0, 1, 1, 1, 1}, cen[2] = {0, 4};
  double c;
  CHECK(ss_coherency(lab0, 6, lab, cen, 2, 6, NULL, &c, &err) == SS_OK);
  CHECK_NEAR(c, 5.0 / 6.0, 1e-15); /* vertex 2: centre 4 is in X0 segment 1, vertex 2 in segment 0 */
  CHECK(ss_coherency(lab0, 6, lab0, cen, 2, 6, NULL, &c, &err) == SS_OK);
  CHECK_NEAR(c, 1.0, 0);
  int gt[6] = {5, 4, 3, 2, 1, 0}; /* reversed: Y's 0..2 land on X0's segment 1 */
  CHECK(ss_coherency(lab0, 6, lab0, cen, 2, 6, gt, &c, &err) == SS_OK);
  CHECK_NEAR(c, 1.0, 0);
  int badlab[6] = {0, 0, 0, 1, 1, 2};
  CHECK(ss_coherency(lab0, 6, badlab, cen, 2, 6, NULL, &c, &err) == SS_ERR_INVALID);
  int badgt[6] = {0, 1, 2, 3, 4, 6};
  CHECK(ss_coherency(lab0, 6, lab, cen, 2, 6, badgt, &c, &err) == SS_ERR_INVALID);
}

/* ---- the pipeline on the synthetic humanoid ----------------------------------------------------- */

#ifndef SS_TEST_NO_HUMANOID
static void test_humanoid(void) {
  ss_error err;
  int npose = ss_synth_humanoid_pose_count();
  CHECK(npose >= 4);
  if (npose > 4) npose = 4;
  ss_segment_options opt;
  ss_segment_default_options(&opt);
  opt.target_faces = 6000; /* the humanoid is small; keeps the test quick under ASan */
  ss_segmentation seg[8];
  ss_mesh mesh[8];
  memset(seg, 0, sizeof seg);
  memset(mesh, 0, sizeof mesh);
  int ok = 1;
  for (int p = 0; p < npose && ok; p++) {
    ok = ss_synth_humanoid(p, &mesh[p], &err) == SS_OK;
    CHECK_MSG(ok, "humanoid pose %d: %s", p, err.msg);
    if (!ok) break;
    ok = ss_segment(&mesh[p], &opt, &seg[p], &err) == SS_OK;
    CHECK_MSG(ok, "segment pose %d: %s", p, err.msg);
    if (!ok) break;
    printf("pose %d: %d segments (%d raw critical points), %d empty, remeshed %d faces\n", p, seg[p].m,
           seg[p].ncrit_raw, seg[p].empty_segments, seg[p].work.nf);
  }
  if (ok) {
    /* same number of segments in every pose */
    for (int p = 1; p < npose; p++) CHECK_MSG(seg[p].m == seg[0].m, "pose %d: %d segments vs %d", p, seg[p].m, seg[0].m);
    for (int p = 0; p < npose; p++) {
      CHECK(seg[p].empty_segments == 0);
      /* labels valid, every centre lies in its own segment */
      int bad = 0;
      for (int i = 0; i < seg[p].nv; i++) bad += seg[p].labels[i] < 0 || seg[p].labels[i] >= seg[p].m;
      CHECK(bad == 0);
      for (int s = 0; s < seg[p].m; s++) CHECK(seg[p].labels[seg[p].centers[s]] == s);
      /* Ψ and the work-mesh cells are what the labels come from */
      int badpsi = 0;
      for (int i = 0; i < seg[p].nv; i++)
        badpsi += seg[p].psi[i] < 0 || seg[p].psi[i] >= seg[p].work.nv ||
                  seg[p].work_labels[seg[p].psi[i]] != seg[p].labels[i];
      CHECK(badpsi == 0);
      for (int s = 0; s < seg[p].m; s++)
        CHECK(seg[p].work_labels[seg[p].crit[s]] == s && seg[p].work_dist[seg[p].crit[s]] == 0 &&
              seg[p].crit_type[s] != SS_CRIT_REGULAR);
      CHECK(seg[p].lambda2 > 0 && seg[p].t_total > 0);
    }
    /* coherency with pose 0 as X0 (ground truth = identity) */
    for (int p = 1; p < npose; p++) {
      double c = 0;
      CHECK(ss_coherency(seg[0].labels, seg[0].nv, seg[p].labels, seg[p].centers, seg[p].m, seg[p].nv, NULL, &c, &err) == SS_OK);
      printf("pose %d: coherency with pose 0 = %.4f\n", p, c);
      CHECK_MSG(c >= 0.9, "pose %d coherency %.4f", p, c);
    }
    /* centres at the extremities: the 5 tips (the farthest points of the shape from its body, found
     * as the local maxima of the geodesic distance from the centroid's closest vertex) each host a
     * centre within a small geodesic radius */
    for (int p = 0; p < npose; p++) {
      const ss_mesh *m = &mesh[p];
      ss_graph g = {0};
      CHECK(ss_graph_npp22(m, &g, &err) == SS_OK);
      double c[3] = {0, 0, 0};
      for (int i = 0; i < m->nv; i++)
        for (int d = 0; d < 3; d++) c[d] += m->V[3 * i + d] / m->nv;
      int root = 0;
      double bd = INFINITY;
      for (int i = 0; i < m->nv; i++) {
        double dx = m->V[3 * i] - c[0], dy = m->V[3 * i + 1] - c[1], dz = m->V[3 * i + 2] - c[2];
        double d2 = dx * dx + dy * dy + dz * dz;
        if (d2 < bd) bd = d2, root = i;
      }
      double *d = malloc(sizeof(double) * m->nv), *dcen = malloc(sizeof(double) * m->nv);
      CHECK(ss_graph_dijkstra(&g, &root, 1, 0, d, NULL, &err) == SS_OK);
      CHECK(ss_graph_dijkstra(&g, seg[p].centers, seg[p].m, 0, dcen, NULL, &err) == SS_OK);
      /* tips: vertices whose d is maximal within a geodesic ball of radius 0.25·max d (coarse peaks) */
      double dmax = 0;
      for (int i = 0; i < m->nv; i++) dmax = fmax(dmax, d[i]);
      int ntips = 0, far = 0;
      double *tmp = malloc(sizeof(double) * m->nv);
      for (int i = 0; i < m->nv; i++) {
        int peak = 1;
        for (int k = g.ptr[i]; k < g.ptr[i + 1] && peak; k++) peak = d[g.adj[k]] <= d[i];
        if (!peak || d[i] < 0.4 * dmax) continue;
        CHECK(ss_graph_dijkstra(&g, &i, 1, 0.25 * dmax, tmp, NULL, &err) == SS_OK);
        for (int j = 0; j < m->nv && peak; j++)
          if (isfinite(tmp[j]) && (d[j] > d[i] || (d[j] == d[i] && j < i))) peak = 0;
        if (!peak) continue;
        ntips++;
        if (dcen[i] > 0.12 * dmax) far++;
      }
      free(tmp);
      printf("pose %d: %d tips, %d without a centre nearby\n", p, ntips, far);
      CHECK_MSG(ntips >= 5, "pose %d: %d tips", p, ntips);
      CHECK_MSG(far == 0, "pose %d: %d tips without a centre nearby", p, far);
      free(d), free(dcen);
      ss_graph_free(&g);
    }
    /* CMCF + remeshing lowers the number of critical points (paper Figure 2) */
    ss_segment_options raw = opt;
    raw.no_streamline = 1;
    raw.cleanup_rings = 0;
    ss_segmentation s0 = {0};
    CHECK(ss_segment(&mesh[0], &raw, &s0, &err) == SS_OK);
    ss_segment_options sm = opt;
    sm.cleanup_rings = 0;
    ss_segmentation s1 = {0};
    CHECK(ss_segment(&mesh[0], &sm, &s1, &err) == SS_OK);
    printf("critical points without clean-up: %d on the input, %d after streamlining\n", s0.ncrit_raw, s1.ncrit_raw);
    CHECK(s1.ncrit_raw < s0.ncrit_raw);
    ss_segmentation_free(&s0);
    ss_segmentation_free(&s1);
  }
  for (int p = 0; p < 8; p++) {
    ss_segmentation_free(&seg[p]);
    ss_mesh_free(&mesh[p]);
  }
}
#endif

static void test_bad_pipeline_input(void) {
  ss_error err;
  ss_segmentation s;
  ss_mesh empty = {0};
  CHECK(ss_segment(&empty, NULL, &s, &err) == SS_ERR_INVALID);
  ss_mesh m;
  bipyramid(6, &m);
  m.F[5] = -3;
  CHECK(ss_segment(&m, NULL, &s, &err) != SS_OK);
  CHECK(s.labels == NULL);
  ss_mesh_free(&m);
}

int main(void) {
  test_critical_tiny();
  test_cleanup();
  test_ivd();
  test_coherency();
  test_bad_pipeline_input();
#ifndef SS_TEST_NO_HUMANOID
  test_humanoid();
#endif
  TEST_MAIN_END();
}
