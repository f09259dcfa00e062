/* Exact geodesics (VTP): reference distances on FAUST, closed forms on developable and flat meshes,
 * convergence on the sphere, invariants (ordering against graphs, symmetry, multi-source, early stop,
 * pairs, batches). */
#include "specseg/geodesic.h"
#include "specseg/io.h"
#include "specseg/mesh.h"
#include "specseg/synth.h"
#include "geodesic_meshes.h"
#include "geodesic/geodesic_mesh.h"
#include "testlib.h"

#include <omp.h>

static double *field(const ss_geodesic_mesh *gm, int nv, const int *src, int ns, double maxd) {
  double *d = malloc(sizeof(double) * nv);
  ss_error e;
  if (ss_vtp_distances(gm, src, ns, maxd, d, &e)) { fprintf(stderr, "%s\n", e.msg); return d; }
  return d;
}

static ss_geodesic_mesh *build(const ss_mesh *m) {
  ss_geodesic_mesh *gm = NULL;
  ss_error e;
  if (ss_geodesic_mesh_build(m, &gm, &e)) fprintf(stderr, "%s\n", e.msg);
  return gm;
}

/* Relative error of a field against a reference (absolute where the reference is 0). */
static double rel_err(const double *d, const double *ref, int n) {
  double w = 0;
  for (int i = 0; i < n; i++) {
    double r = ref[i] > 0 ? fabs(d[i] - ref[i]) / ref[i] : fabs(d[i]);
    if (!(r <= w)) w = r;
  }
  return w;
}

static void test_faust(void) {
  const char *dir = tl_data_dir();
  if (!dir) { SKIP("FAUST / geodesic_ref data not found"); return; }
  char path[4096];
  snprintf(path, sizeof path, "%s/faust/tr_reg_000.off", dir);
  ss_mesh m;
  ss_error e;
  if (ss_read_mesh(path, &m, &e)) { CHECK_MSG(0, "%s", e.msg); return; }
  ss_geodesic_mesh *gm = build(&m);
  CHECK(gm != NULL);
  const int srcs[3] = {0, 412, 3219};
  double *all = malloc(sizeof(double) * m.nv * 3);
  CHECK(ss_geodesic_fields(gm, srcs, 3, 0, all, NULL) == SS_OK);
  for (int k = 0; k < 3; k++) {
    snprintf(path, sizeof path, "%s/geodesic_ref/tr_reg_000_src%d.txt", dir, srcs[k]);
    double *ref;
    int n;
    if (ss_read_doubles(path, &ref, &n, &e)) { SKIP("%s", e.msg); continue; }
    CHECK(n == m.nv);
    if (n != m.nv) { free(ref); continue; }
    double *d = field(gm, m.nv, srcs + k, 1, 0);
    double w = rel_err(d, ref, n);
    CHECK_MSG(w <= 1e-9, "source %d: worst relative error %g", srcs[k], w);
    CHECK_MSG(rel_err(all + (size_t)k * m.nv, d, n) == 0, "batch field differs from single field");
    /* exact <= NPP22 <= edges everywhere */
    ss_graph gn, ge;
    double *dn = malloc(sizeof(double) * n), *de = malloc(sizeof(double) * n);
    ss_graph_npp22(&m, &gn, NULL);
    ss_graph_edges(&m, &ge, NULL);
    ss_graph_dijkstra(&gn, srcs + k, 1, 0, dn, NULL, NULL);
    ss_graph_dijkstra(&ge, srcs + k, 1, 0, de, NULL, NULL);
    int ord = 1;
    for (int i = 0; i < n; i++)
      if (!(d[i] <= dn[i] * (1 + 1e-12) && dn[i] <= de[i] * (1 + 1e-12))) ord = 0;
    CHECK(ord);
    ss_graph_free(&gn); ss_graph_free(&ge);
    free(dn); free(de);
    /* pairs with early stop equal the full field */
    int tg[5] = {1, 100, 2000, 5000, 6889}, ps[5];
    double po[5];
    for (int q = 0; q < 5; q++) ps[q] = srcs[k];
    CHECK(ss_geodesic_pairs(gm, NULL, ps, tg, 5, po, NULL) == SS_OK);
    int pok = 1;
    for (int q = 0; q < 5; q++) if (fabs(po[q] - d[tg[q]]) > 1e-12 * d[tg[q]]) pok = 0;
    CHECK(pok);
    free(d); free(ref);
  }
  /* symmetry on pseudo-random pairs of a real scan (many saddles) */
  int np = 40, a[40], b[40];
  double dab[40], dba[40];
  gm_rng_state = 777;
  for (int i = 0; i < np; i++) { a[i] = (int)(gm_rand() * m.nv); b[i] = (int)(gm_rand() * m.nv); }
  CHECK(ss_geodesic_pairs(gm, NULL, a, b, np, dab, NULL) == SS_OK);
  CHECK(ss_geodesic_pairs(gm, NULL, b, a, np, dba, NULL) == SS_OK);
  double worst = 0;
  for (int i = 0; i < np; i++) worst = fmax(worst, fabs(dab[i] - dba[i]) / fmax(dab[i], 1e-300));
  CHECK_MSG(worst <= 1e-12, "symmetry %g", worst);
  free(all);
  ss_geodesic_mesh_free(gm);
  ss_mesh_free(&m);
}

/* Flat meshes: convex domains give the Euclidean distance (jittered, obtuse and near-degenerate
 * triangles, boundary sources). */
static void test_flat(double jit, double shear, double sliver) {
  ss_mesh m;
  gm_flat_grid(25, 21, 2.0, 1.5, jit, &m);
  /* sliver > 0: column 6 moved next to column 5 (gap sliver * cell): needle triangles */
  if (sliver > 0)
    for (int j = 0; j < 21; j++) m.V[3 * (j * 25 + 6)] = m.V[3 * (j * 25 + 5)] + sliver * 2.0 / 24;
  for (int i = 0; i < m.nv; i++) m.V[3 * i] += shear * m.V[3 * i + 1]; /* parallelogram: obtuse */
  int inverted = 0;
  double minang = M_PI;
  for (int f = 0; f < m.nf; f++) {
    const double *a = m.V + 3 * m.F[3 * f], *b = m.V + 3 * m.F[3 * f + 1], *c = m.V + 3 * m.F[3 * f + 2];
    if ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) <= 0) inverted++;
    for (int k = 0; k < 3; k++) {
      const double *p = m.V + 3 * m.F[3 * f + k], *q = m.V + 3 * m.F[3 * f + (k + 1) % 3], *r = m.V + 3 * m.F[3 * f + (k + 2) % 3];
      double ux = q[0] - p[0], uy = q[1] - p[1], vx = r[0] - p[0], vy = r[1] - p[1];
      minang = fmin(minang, fabs(atan2(ux * vy - uy * vx, ux * vx + uy * vy)));
    }
  }
  CHECK(inverted == 0); /* a valid flat embedding, so distances are Euclidean */
  printf("flat jitter %.2f shear %.2f sliver %g: smallest angle %.3g deg\n", jit, shear, sliver, minang * 180 / M_PI);
  ss_geodesic_mesh *gm = build(&m);
  int srcs[3] = {0, 10 * 25 + 12, m.nv - 1};
  for (int k = 0; k < 3; k++) {
    double *d = field(gm, m.nv, srcs + k, 1, 0);
    const double *s = m.V + 3 * srcs[k];
    double w = 0;
    for (int i = 0; i < m.nv; i++) w = fmax(w, fabs(d[i] - hypot(m.V[3 * i] - s[0], m.V[3 * i + 1] - s[1])));
    CHECK_MSG(w < 1e-12, "flat jit %g shear %g sliver %g src %d: %g", jit, shear, sliver, srcs[k], w);
    free(d);
  }
  ss_geodesic_mesh_free(gm);
  ss_mesh_free(&m);
}

/* L-shaped flat domain: around the reflex corner the path bends at the corner (boundary vertex). */
static void test_lshape(void) {
  ss_mesh g;
  int n = 21;
  gm_flat_grid(n, n, 2.0, 2.0, 0.0, &g); /* straight notch sides; diagonals still random */
  /* keep faces outside the square (1,2]x(1,2] */
  ss_mesh m;
  ss_mesh_copy(&g, &m, NULL);
  int nf = 0;
  for (int f = 0; f < g.nf; f++) {
    double cx = 0, cy = 0;
    for (int c = 0; c < 3; c++) { cx += g.V[3 * g.F[3 * f + c]] / 3; cy += g.V[3 * g.F[3 * f + c] + 1] / 3; }
    if (cx > 1 && cy > 1) continue;
    memcpy(m.F + 3 * nf, g.F + 3 * f, sizeof(int) * 3);
    nf++;
  }
  m.nf = nf;
  ss_geodesic_mesh *gm = build(&m);
  int corner = (n / 2) * n + n / 2; /* the reflex corner (1,1) */
  int src = n - 1;                   /* (2,0) */
  double *d = field(gm, m.nv, &src, 1, 0);
  const double *s = m.V + 3 * src, *c = m.V + 3 * corner;
  double w = 0;
  int used = 0;
  for (int i = 0; i < m.nv; i++) {
    const double *p = m.V + 3 * i;
    if (isinf(d[i])) continue; /* vertices of the removed square only */
    double ex;
    /* visible from (2,0) directly when the segment does not enter x>1,y>1 */
    if (p[1] <= 1 + 1e-12 || p[0] <= 1 + 1e-12) {
      /* segment s->p: s has x=2,y=0. It enters the notch iff it reaches y>1 while x>1 */
      double t = (p[1] - s[1]) > 0 ? (1 - s[1]) / (p[1] - s[1]) : 2;
      double xat = s[0] + t * (p[0] - s[0]);
      if (t < 1 && xat > c[0] + 1e-9) ex = hypot(c[0] - s[0], c[1] - s[1]) + hypot(p[0] - c[0], p[1] - c[1]);
      else ex = hypot(p[0] - s[0], p[1] - s[1]);
      if (t < 1 && fabs(xat - c[0]) < 1e-6) continue;
      w = fmax(w, fabs(d[i] - ex));
      used++;
    }
  }
  CHECK(used > 100);
  CHECK_MSG(w < 1e-12, "L-shape error %g", w);
  free(d);
  ss_geodesic_mesh_free(gm);
  ss_mesh_free(&m);
  ss_mesh_free(&g);
}

static void test_cylinder(void) {
  int nu = 24, nz = 15;
  double r = 0.5, H = 2.0;
  ss_mesh m;
  gm_cylinder(nu, nz, r, H, &m);
  ss_geodesic_mesh *gm = build(&m);
  double c = 2 * r * sin(M_PI / nu), per = nu * c;
  int src = 7 * nu + 3;
  double *d = field(gm, m.nv, &src, 1, 0);
  double w = 0;
  for (int i = 0; i < m.nv; i++) {
    double dx = fabs((double)(i % nu - src % nu)) * c, dz = (double)(i / nu - src / nu) * H / (nz - 1);
    if (dx > per / 2) dx = per - dx;
    w = fmax(w, fabs(d[i] - hypot(dx, dz)));
  }
  CHECK_MSG(w < 1e-12, "cylinder error %g", w);
  free(d);
  ss_geodesic_mesh_free(gm);
  ss_mesh_free(&m);
}

static void test_cone(void) {
  int nu = 30, nr = 12;
  double beta, rho0 = 1.0, dr = 0.15;
  ss_mesh m;
  gm_cone(nu, nr, 0.7, rho0, dr, &m, &beta);
  ss_geodesic_mesh *gm = build(&m);
  int src = (nr - 1) * nu + 4; /* outer ring */
  double *d = field(gm, m.nv, &src, 1, 0);
  double total = nu * beta, w = 0;
  int used = 0;
  double rs = rho0 + (nr - 1) * dr, as = 4 * beta;
  for (int i = 0; i < m.nv; i++) {
    double rp = rho0 + (i / nu) * dr, ap = (i % nu) * beta;
    double best = INFINITY;
    int ok = 0;
    for (int k = -1; k <= 1; k++) {
      double da = ap - as + k * total;
      if (fabs(da) >= M_PI) continue;
      double x0 = rs, y0 = 0, x1 = rp * cos(da), y1 = rp * sin(da);
      double len = hypot(x1 - x0, y1 - y0);
      /* distance from the apex to the segment must stay outside the removed disc */
      double t = len > 0 ? -(x0 * (x1 - x0) + y0 * (y1 - y0)) / (len * len) : 0;
      t = t < 0 ? 0 : (t > 1 ? 1 : t);
      double clear = hypot(x0 + t * (x1 - x0), y0 + t * (y1 - y0));
      if (len < best) { best = len; ok = clear > rho0 + 1e-9; }
    }
    if (!ok) continue;
    used++;
    w = fmax(w, fabs(d[i] - best));
  }
  CHECK(used > m.nv / 2);
  CHECK_MSG(w < 1e-12, "cone error %g (%d vertices)", w, used);
  free(d);
  ss_geodesic_mesh_free(gm);
  ss_mesh_free(&m);
}

static void test_sphere(void) {
  double prev = INFINITY;
  for (int s = 1; s <= 4; s++) {
    ss_mesh m;
    CHECK(ss_synth_icosphere(s, &m, NULL) == SS_OK);
    ss_geodesic_mesh *gm = build(&m);
    int src = 0;
    double *d = field(gm, m.nv, &src, 1, 0);
    double w = 0;
    for (int i = 0; i < m.nv; i++) {
      double dot = m.V[0] * m.V[3 * i] + m.V[1] * m.V[3 * i + 1] + m.V[2] * m.V[3 * i + 2];
      double arc = acos(fmax(-1, fmin(1, dot)));
      w = fmax(w, fabs(d[i] - arc));
      /* the inscribed polyhedron is shorter than the sphere, never shorter than the chord */
      if (!(d[i] <= arc + 1e-12 && d[i] >= 2 * sin(arc / 2) - 1e-12)) w = INFINITY;
    }
    CHECK_MSG(w < prev, "level %d error %g (previous %g)", s, w, prev);
    if (s == 4) CHECK_MSG(w < 0.01, "level 4 error %g", w);
    prev = w;
    free(d);
    ss_geodesic_mesh_free(gm);
    ss_mesh_free(&m);
  }
}

/* A bumpy open surface with saddles, boundary and obtuse triangles: invariants. */
static void test_invariants(void) {
  ss_mesh m;
  gm_flat_grid(30, 26, 3.0, 2.5, 0.8, &m);
  for (int i = 0; i < m.nv; i++) {
    double *p = m.V + 3 * i;
    p[2] = 0.4 * sin(3 * p[0]) * cos(2.5 * p[1]) + 0.2 * p[0] * p[1];
  }
  ss_geodesic_mesh *gm = build(&m);
  int n = m.nv, sa = 31, sb = 500, sc = 777;
  double *da = field(gm, n, &sa, 1, 0), *db = field(gm, n, &sb, 1, 0), *dc = field(gm, n, &sc, 1, 0);
  int three[3] = {sa, sb, sc};
  double *dm = field(gm, n, three, 3, 0);
  int ok = 1;
  for (int i = 0; i < n; i++)
    if (fabs(dm[i] - fmin(da[i], fmin(db[i], dc[i]))) > 1e-12 * dm[i]) ok = 0;
  CHECK_MSG(ok, "multi-source field is not the minimum of single-source fields");
  /* ordering against the graphs */
  ss_graph gn, ge;
  ss_graph_npp22(&m, &gn, NULL);
  ss_graph_edges(&m, &ge, NULL);
  double *dn = malloc(sizeof(double) * n), *de = malloc(sizeof(double) * n);
  ss_graph_dijkstra(&gn, &sa, 1, 0, dn, NULL, NULL);
  ss_graph_dijkstra(&ge, &sa, 1, 0, de, NULL, NULL);
  ok = 1;
  for (int i = 0; i < n; i++)
    if (!(da[i] <= dn[i] * (1 + 1e-12) && dn[i] <= de[i] * (1 + 1e-12))) ok = 0;
  CHECK(ok);
  /* symmetry */
  double worst = 0;
  for (int i = 0; i < n; i += 37) {
    double *di = field(gm, n, &i, 1, 0);
    worst = fmax(worst, fabs(di[sa] - da[i]) / fmax(da[i], 1e-300));
    free(di);
  }
  CHECK_MSG(worst <= 1e-12, "symmetry %g", worst);
  /* early stop at a radius: same values inside, inf outside */
  double R = 0.6 * da[sb];
  double *dr = field(gm, n, &sa, 1, R);
  ok = 1;
  int inside = 0;
  for (int i = 0; i < n; i++) {
    if (da[i] <= R) { inside++; if (dr[i] != da[i]) ok = 0; }
    else if (!isinf(dr[i])) ok = 0;
  }
  CHECK(ok && inside > 10 && inside < n);
  /* early stop on targets */
  int tg[3] = {sb, sc, 5}, bad_target = n;
  double *dt = malloc(sizeof(double) * n);
  CHECK(ss_vtp_distances_targets(gm, &sa, 1, tg, 3, dt, NULL) == SS_OK);
  CHECK(dt[sb] == da[sb] && dt[sc] == da[sc] && dt[5] == da[5]);
  /* batch of fields and pairs */
  double *bf = malloc(sizeof(double) * n * 3);
  CHECK(ss_geodesic_fields(gm, three, 3, 0, bf, NULL) == SS_OK);
  CHECK(rel_err(bf, da, n) == 0 && rel_err(bf + n, db, n) == 0 && rel_err(bf + 2 * n, dc, n) == 0);
  /* a batch stopping at targets: the full fields' values there, bit for bit */
  double *bt = malloc(sizeof(double) * n * 3);
  CHECK(ss_geodesic_fields_targets(gm, three, 3, tg, 3, bt, NULL) == SS_OK);
  ok = 1;
  for (int j = 0; j < 3; j++)
    for (int t = 0; t < 3; t++) ok &= bt[tg[t] + (size_t)n * j] == bf[tg[t] + (size_t)n * j];
  CHECK(ok);
  CHECK(ss_geodesic_fields_targets(gm, three, 3, &bad_target, 1, bt, NULL) == SS_ERR_INVALID);
  free(bt);
  int ps[6] = {sa, sb, sa, sc, sa, sb}, pt[6] = {sb, 3, 700, 0, sa, 779};
  double po[6];
  CHECK(ss_geodesic_pairs(gm, NULL, ps, pt, 6, po, NULL) == SS_OK);
  CHECK(po[0] == da[sb] && po[1] == db[3] && po[2] == da[700] && po[3] == dc[0] && po[4] == 0 && po[5] == db[779]);
  /* errors */
  ss_error e;
  int bad = n;
  CHECK(ss_vtp_distances(gm, &bad, 1, 0, dt, &e) == SS_ERR_INVALID);
  CHECK(ss_geodesic_pairs(gm, NULL, &sa, &bad, 1, po, &e) == SS_ERR_INVALID);
  CHECK(ss_vtp_distances(gm, &sa, 0, 0, dt, &e) == SS_ERR_INVALID);
  /* method switch */
  CHECK(ss_geodesic_distances(&m, SS_GEODESIC_GRAPH, &sa, 1, 0, dt, NULL) == SS_OK && dt[sb] == dn[sb]);
  CHECK(ss_geodesic_distances(&m, SS_GEODESIC_EXACT, &sa, 1, 0, dt, NULL) == SS_OK && dt[sb] == da[sb]);
  free(bf); free(dt); free(dr); free(dn); free(de);
  ss_graph_free(&gn); ss_graph_free(&ge);
  free(da); free(db); free(dc); free(dm);
  ss_geodesic_mesh_free(gm);
  ss_mesh_free(&m);
}

/* Two components and a zero-area face: unreachable vertices stay inf, nothing crashes. */
static void test_degenerate(void) {
  double V[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 0, 0, 5, 5, 5, 6, 5, 5, 5, 6, 5};
  int F[] = {0, 1, 2, 1, 3, 2, 1, 4, 3, 5, 6, 7, 0, 1, 4};
  ss_mesh m = {8, 5, V, F};
  ss_geodesic_mesh *gm = build(&m);
  CHECK(gm != NULL);
  double d[8];
  int s = 0;
  CHECK(ss_vtp_distances(gm, &s, 1, 0, d, NULL) == SS_OK);
  CHECK_NEAR(d[3], sqrt(2.0), 1e-15);
  CHECK_NEAR(d[4], 2.0, 1e-15);
  CHECK(isinf(d[5]) && isinf(d[6]) && isinf(d[7]));
  ss_geodesic_mesh_free(gm);
}

/* ---- point-to-point queries (early stop, A* bounds, landmarks, pairs) against full fields ---- */
static int close_rel(double a, double b, double scale) {
  if (isinf(b)) return isinf(a);
  return fabs(a - b) <= 1e-12 * fmax(b, 1e-3 * scale);
}

/* nsrc sources; for each: near targets (within 10% of the field's range), far random targets;
 * one_to_many with 1, 3 and 12 targets (12 > the A* limit), one reused query object, then a batch
 * of pairs in both orientations (many far pairs: attaches landmarks when `landmarks` < 0), and the
 * same batch on 1 and 2 threads must agree bit for bit. */
static void check_queries(const ss_mesh *m, const char *name, int nsrc, int landmarks) {
  ss_geodesic_mesh *gm = build(m);
  CHECK(gm != NULL);
  if (!gm) return;
  /* landmarks > 0: an accelerator of that many; 0: none; < 0: built by the first large batch */
  ss_geodesic_landmarks *acc = NULL, **slot = landmarks == 0 ? NULL : &acc;
  if (landmarks > 0) CHECK(ss_geodesic_landmarks_new(gm, landmarks, &acc, NULL) == SS_OK);
  int n = m->nv;
  double scale = ss_mesh_bbox_diagonal(m);
  int *src = malloc(sizeof(int) * nsrc);
  double **fld = malloc(sizeof(double *) * nsrc);
  ss_geodesic_query *q = NULL;
  CHECK(ss_geodesic_query_new(gm, acc, &q, NULL) == SS_OK);
  int np = 0, cap = 48 * nsrc;
  int *pa = malloc(sizeof(int) * 2 * cap), *pb = malloc(sizeof(int) * 2 * cap);
  int bad_one = 0, bad_query = 0, nnear = 0;
  for (int k = 0; k < nsrc; k++) {
    src[k] = (int)(gm_rand() * n);
    fld[k] = field(gm, n, src + k, 1, 0);
    double dmax = 0;
    for (int i = 0; i < n; i++) if (isfinite(fld[k][i])) dmax = fmax(dmax, fld[k][i]);
    int tg[12];
    for (int j = 0; j < 12; j++) {
      int t = (int)(gm_rand() * n);
      if (j < 6) /* near: rejection-sample a vertex within 10% of the range */
        for (int tries = 0; tries < 2000 && !(fld[k][t] <= 0.1 * dmax); tries++) t = (int)(gm_rand() * n);
      if (fld[k][t] <= 0.1 * dmax) nnear++;
      tg[j] = t;
    }
    int order[3][12] = {{0}, {0, 6, 1}, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}}, cnt[3] = {1, 3, 12};
    for (int c = 0; c < 3; c++) {
      int t[12];
      double out[12];
      for (int j = 0; j < cnt[c]; j++) t[j] = tg[order[c][j]];
      CHECK(ss_geodesic_one_to_many(gm, acc, src[k], t, cnt[c], out, NULL) == SS_OK);
      for (int j = 0; j < cnt[c]; j++) if (!close_rel(out[j], fld[k][t[j]], scale)) bad_one++;
    }
    for (int j = 0; j < 12; j++) { /* the reused object, one target at a time, near and far mixed */
      double o;
      CHECK(ss_geodesic_query_run(q, src[k], tg + j, 1, &o, NULL) == SS_OK);
      if (!close_rel(o, fld[k][tg[j]], scale)) bad_query++;
    }
    for (int j = 0; j < 48 && np < cap; j++) {
      int t = j < 12 ? tg[j] : (int)(gm_rand() * n);
      pa[np] = src[k]; pb[np] = t; np++;
    }
  }
  CHECK_MSG(bad_one == 0, "%s: %d one-to-many values differ from the fields", name, bad_one);
  { /* nearest of k targets (stop at the first final one) == min over the fields */
    int ks[3] = {1, 2, 10}, bad_min = 0;
    for (int c = 0; c < 3; c++) {
      int k = ks[c], *t = malloc(sizeof(int) * nsrc * k);
      double *o = malloc(sizeof(double) * nsrc);
      for (int i = 0; i < nsrc * k; i++) t[i] = (int)(gm_rand() * n);
      CHECK(ss_geodesic_nearest_of(gm, slot, src, t, k, nsrc, o, NULL) == SS_OK);
      for (int i = 0; i < nsrc; i++) {
        double ref = INFINITY;
        for (int j = 0; j < k; j++) ref = fmin(ref, fld[i][t[i * k + j]]);
        if (!close_rel(o[i], ref, scale)) bad_min++;
      }
      free(t); free(o);
    }
    CHECK_MSG(bad_min == 0, "%s: %d nearest-of values differ from the fields", name, bad_min);
  }
  CHECK_MSG(bad_query == 0, "%s: %d reused-query values differ from the fields", name, bad_query);
  CHECK_MSG(nnear >= 3 * nsrc, "%s: too few near targets (%d)", name, nnear);
  /* both orientations, and padding pairs between the sources */
  int base = np;
  for (int i = 0; i < base; i++) { pa[np] = pb[i]; pb[np] = pa[i]; np++; }
  while (np < 2 * cap && np < 520) { pa[np] = src[np % nsrc]; pb[np] = src[(np / nsrc) % nsrc]; np++; }
  double *o1 = malloc(sizeof(double) * np), *o2 = malloc(sizeof(double) * np);
  omp_set_num_threads(1);
  CHECK(ss_geodesic_pairs(gm, slot, pa, pb, np, o1, NULL) == SS_OK);
  omp_set_num_threads(2);
  CHECK(ss_geodesic_pairs(gm, slot, pa, pb, np, o2, NULL) == SS_OK);
  int bad = 0, same = 1;
  for (int i = 0; i < np; i++) {
    int k = 0;
    while (k < nsrc && src[k] != pa[i] && src[k] != pb[i]) k++;
    if (k == nsrc) { bad++; continue; }
    double ref = fld[k][src[k] == pa[i] ? pb[i] : pa[i]];
    if (!close_rel(o1[i], ref, scale)) bad++;
    if (memcmp(o1 + i, o2 + i, sizeof(double))) same = 0;
  }
  CHECK_MSG(bad == 0, "%s: %d of %d pairs differ from the fields", name, bad, np);
  CHECK_MSG(same, "%s: pairs differ between 1 and 2 threads", name);
  if (landmarks < 0) CHECK_MSG(acc != NULL && acc->nlm == 8, "%s: far pairs did not build landmarks", name);
  if (landmarks == 0) CHECK_MSG(acc == NULL, "%s: landmarks built although none were asked for", name);
  free(o1); free(o2); free(pa); free(pb);
  for (int k = 0; k < nsrc; k++) free(fld[k]);
  free(fld); free(src);
  ss_geodesic_query_free(q);
  ss_geodesic_landmarks_free(acc);
  ss_geodesic_mesh_free(gm);
}

static void test_queries(void) {
  ss_mesh m;
  gm_rng_state = 4242;
  /* open bumpy sheet: boundary everywhere near, saddles inside */
  gm_flat_grid(30, 26, 3.0, 2.5, 0.8, &m);
  for (int i = 0; i < m.nv; i++) {
    double *p = m.V + 3 * i;
    p[2] = 0.4 * sin(3 * p[0]) * cos(2.5 * p[1]) + 0.2 * p[0] * p[1];
  }
  check_queries(&m, "bumpy sheet, auto landmarks", 6, -1);
  check_queries(&m, "bumpy sheet, no landmarks", 4, 0);
  ss_mesh_free(&m);
  gm_cylinder(24, 15, 0.5, 2.0, &m); /* two boundary loops, flat */
  check_queries(&m, "cylinder, 16 landmarks", 5, 16);
  ss_mesh_free(&m);
  const char *dir = tl_data_dir();
  if (!dir) { SKIP("FAUST data not found"); }
  else {
    char path[4096];
    snprintf(path, sizeof path, "%s/faust/tr_reg_000.off", dir);
    ss_error e;
    if (ss_read_mesh(path, &m, &e)) CHECK_MSG(0, "%s", e.msg);
    else {
      check_queries(&m, "faust, auto landmarks", 6, -1);
      ss_mesh_free(&m);
    }
  }
  /* two components: unreachable targets are inf, also with landmarks; same vertex: 0 */
  ss_error e;
  double V[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 0, 0, 5, 5, 5, 6, 5, 5, 5, 6, 5};
  int F[] = {0, 1, 2, 1, 3, 2, 1, 4, 3, 5, 6, 7, 0, 1, 4};
  ss_mesh d = {8, 5, V, F};
  ss_geodesic_mesh *gm = build(&d);
  ss_geodesic_landmarks *acc = NULL;
  CHECK(ss_geodesic_landmarks_new(gm, 4, &acc, NULL) == SS_OK);
  int tg[4] = {3, 5, 0, 3};
  double out[4];
  CHECK(ss_geodesic_one_to_many(gm, acc, 0, tg, 4, out, NULL) == SS_OK);
  CHECK_NEAR(out[0], sqrt(2.0), 1e-15);
  CHECK(isinf(out[1]) && out[2] == 0 && out[3] == out[0]);
  int pa[3] = {0, 6, 2}, pb[3] = {6, 7, 2};
  CHECK(ss_geodesic_pairs(gm, &acc, pa, pb, 3, out, NULL) == SS_OK);
  CHECK(isinf(out[0]) && fabs(out[1] - sqrt(2.0)) < 1e-15 && out[2] == 0);
  int ns[2] = {0, 5}, nt[4] = {6, 4, 7, 5};
  CHECK(ss_geodesic_nearest_of(gm, &acc, ns, nt, 2, 2, out, NULL) == SS_OK);
  CHECK(fabs(out[0] - 2.0) < 1e-15 && out[1] == 0);
  nt[1] = 7;
  CHECK(ss_geodesic_nearest_of(gm, &acc, ns, nt, 2, 1, out, NULL) == SS_OK && isinf(out[0]));
  CHECK(ss_geodesic_nearest_of(gm, &acc, ns, nt, 0, 1, out, &e) == SS_ERR_INVALID);
  /* errors */
  int bad = 8;
  CHECK(ss_geodesic_one_to_many(gm, acc, 0, &bad, 1, out, &e) == SS_ERR_INVALID);
  CHECK(ss_geodesic_one_to_many(gm, acc, -1, tg, 1, out, &e) == SS_ERR_INVALID);
  ss_geodesic_landmarks *big = NULL;
  CHECK(ss_geodesic_landmarks_new(gm, 17, &big, &e) == SS_ERR_INVALID && big == NULL);
  CHECK(ss_geodesic_landmarks_new(gm, 0, &big, &e) == SS_ERR_INVALID && big == NULL);
  CHECK(ss_geodesic_one_to_many(gm, acc, 0, tg, 0, out, &e) == SS_OK);
  ss_geodesic_landmarks_free(acc);
  ss_geodesic_mesh_free(gm);
}

int main(void) {
  test_faust();
  test_flat(0.0, 0.0, 0);
  test_flat(0.66, 0.0, 0);
  test_flat(0.5, 1.7, 0);
  test_flat(0.0, 0.0, 1e-7);
  test_flat(0.0, 0.9, 1e-9);
  test_lshape();
  test_cylinder();
  test_cone();
  test_sphere();
  test_invariants();
  test_degenerate();
  test_queries();
  TEST_MAIN_END();
}
