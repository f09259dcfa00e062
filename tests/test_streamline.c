/* Streamlining: CMCF smoothing, isotropic remeshing quality, closest-vertex map Ψ. */
#include "specseg/specseg.h"
#include "specseg/synth.h"
#include "testlib.h"

static void centroid_area(const ss_mesh *m, double c[3], double *area) {
  double A = 0, s[3] = {0, 0, 0};
  for (int f = 0; f < m->nf; f++) {
    const double *a = m->V + 3 * m->F[3 * f], *b = m->V + 3 * m->F[3 * f + 1], *d = m->V + 3 * m->F[3 * f + 2];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    double n0 = u[1] * v[2] - u[2] * v[1], n1 = u[2] * v[0] - u[0] * v[2], n2 = u[0] * v[1] - u[1] * v[0];
    double t = 0.5 * sqrt(n0 * n0 + n1 * n1 + n2 * n2);
    A += t;
    for (int k = 0; k < 3; k++) s[k] += t * (a[k] + b[k] + d[k]) / 3;
  }
  *area = A;
  for (int k = 0; k < 3; k++) c[k] = s[k] / A;
}

static void test_cmcf_sphere(void) {
  ss_mesh s = {0}, out = {0};
  ss_error e = {{0}};
  CHECK(ss_synth_icosphere(4, &s, &e) == SS_OK);
  for (int i = 0; i < s.nv; i++) { s.V[3 * i] += 0.3; s.V[3 * i + 1] -= 0.2; s.V[3 * i + 2] += 2.0; } /* off-centre */
  ss_cmcf_options o;
  ss_cmcf_default_options(&o);
  o.dt = 1e-3; /* a strong flow: a round sphere must still stay round */
  CHECK_MSG(ss_cmcf_smooth(&s, &o, &out, &e) == SS_OK, "%s", e.msg);
  CHECK(out.nv == s.nv && out.nf == s.nf && !memcmp(out.F, s.F, sizeof(int) * 3 * s.nf));
  double c0[3], c1[3], a0, a1;
  centroid_area(&s, c0, &a0);
  centroid_area(&out, c1, &a1);
  CHECK_NEAR(a1, a0, 1e-9 * a0);
  for (int k = 0; k < 3; k++) CHECK_NEAR(c1[k], c0[k], 1e-9);
  double rmin = INFINITY, rmax = 0, move = 0;
  for (int i = 0; i < out.nv; i++) {
    double d[3] = {out.V[3 * i] - c1[0], out.V[3 * i + 1] - c1[1], out.V[3 * i + 2] - c1[2]};
    double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    rmin = fmin(rmin, r);
    rmax = fmax(rmax, r);
    double dx = out.V[3 * i] - s.V[3 * i], dy = out.V[3 * i + 1] - s.V[3 * i + 1], dz = out.V[3 * i + 2] - s.V[3 * i + 2];
    move = fmax(move, sqrt(dx * dx + dy * dy + dz * dz));
  }
  CHECK_MSG((rmax - rmin) / rmax < 0.01, "radii %.6f..%.6f", rmin, rmax);
  CHECK_MSG(move < 0.01, "a sphere moved by %g", move);
  ss_mesh_free(&out);

  /* the symbolic analysis reused across steps gives the fresh factorisation's result */
  ss_mesh out2 = {0};
  o.steps = 5;
  CHECK(ss_cmcf_smooth(&s, &o, &out, &e) == SS_OK);
  o.refactor_symbolic = 1;
  CHECK(ss_cmcf_smooth(&s, &o, &out2, &e) == SS_OK);
  double diff = 0;
  for (int i = 0; i < 3 * s.nv; i++) diff = fmax(diff, fabs(out.V[i] - out2.V[i]));
  CHECK_MSG(diff < 1e-12, "reuse vs fresh: %g", diff);
  ss_mesh_free(&out);
  ss_mesh_free(&out2);

  /* an unreferenced vertex does not break the solve and stays put */
  ss_mesh extra = {0};
  CHECK(ss_mesh_alloc(&extra, s.nv + 1, s.nf, &e) == SS_OK);
  memcpy(extra.V, s.V, sizeof(double) * 3 * s.nv);
  memcpy(extra.F, s.F, sizeof(int) * 3 * s.nf);
  extra.V[3 * s.nv] = 5; extra.V[3 * s.nv + 1] = 6; extra.V[3 * s.nv + 2] = 7;
  o.refactor_symbolic = 0;
  CHECK_MSG(ss_cmcf_smooth(&extra, &o, &out, &e) == SS_OK, "%s", e.msg);
  if (out.V) {
    CHECK_NEAR(out.V[3 * s.nv], 5, 1e-6);
    CHECK_NEAR(out.V[3 * s.nv + 2], 7, 1e-6);
  }
  ss_mesh_free(&out);
  ss_mesh_free(&extra);

  /* bad arguments */
  o.dt = -1;
  CHECK(ss_cmcf_smooth(&s, &o, &out, &e) == SS_ERR_INVALID);
  ss_mesh_free(&s);
}

/* An elongated body (ellipsoid 2:1:1) with a thin spike: the spike must shrink much faster than
 * the body. */
static void test_cmcf_protrusion(void) {
  ss_mesh s = {0}, out = {0};
  ss_error e = {{0}};
  CHECK(ss_synth_icosphere(4, &s, &e) == SS_OK);
  for (int i = 0; i < s.nv; i++) {
    double *p = s.V + 3 * i;
    double z = p[2], h = z > 0.97 ? (z - 0.97) / 0.03 : 0; /* spike of base radius ~0.24 */
    double r = 1 + 1.2 * h;
    p[0] *= 2 * r; p[1] *= r; p[2] *= r;
  }
  double zmax0 = -INFINITY, xmax0 = -INFINITY;
  for (int i = 0; i < s.nv; i++) { zmax0 = fmax(zmax0, s.V[3 * i + 2]); xmax0 = fmax(xmax0, s.V[3 * i]); }
  ss_cmcf_options o;
  ss_cmcf_default_options(&o);
  o.dt = 1e-3;
  CHECK_MSG(ss_cmcf_smooth(&s, &o, &out, &e) == SS_OK, "%s", e.msg);
  double c[3], a;
  centroid_area(&out, c, &a);
  double zmax1 = -INFINITY, xmax1 = -INFINITY;
  for (int i = 0; i < out.nv; i++) { zmax1 = fmax(zmax1, out.V[3 * i + 2] - c[2]); xmax1 = fmax(xmax1, out.V[3 * i] - c[0]); }
  double spike0 = zmax0 - 1, spike1 = zmax1 - 1; /* spike length above the body's unit half-height */
  double body = xmax1 / xmax0;
  printf("protrusion: spike length %.3f -> %.3f, body half-length ratio %.3f\n", spike0, spike1, body);
  CHECK_MSG(spike1 < 0.5 * spike0 && body > 0.9, "spike %.3f -> %.3f, body ratio %.3f", spike0, spike1, body);
  ss_mesh_free(&out);
  ss_mesh_free(&s);
}

static void check_remesh(const char *name, const ss_mesh *in, int target, int genus_chi) {
  ss_remesh_options o;
  ss_remesh_default_options(&o);
  o.target_faces = target;
  ss_mesh r = {0};
  ss_error e = {{0}};
  ss_status st = ss_remesh(in, &o, &r, &e);
  CHECK_MSG(st == SS_OK, "%s: %s", name, e.msg);
  if (st != SS_OK) return;
  ss_remesh_quality q;
  CHECK(ss_remesh_quality_measure(&r, in, &q, &e) == SS_OK);
  printf("%s: faces %d (target %d) min angle >= 30: %.3f valence 6: %.3f min angle %.1f deviation %.2e\n",
         name, q.faces, target, q.frac_min_angle_30, q.frac_valence_6, q.min_angle_deg, q.max_deviation);
  CHECK_MSG(abs(q.faces - target) <= 0.05 * target, "%s: %d faces", name, q.faces);
  CHECK_MSG(q.frac_min_angle_30 >= 0.9, "%s: %.3f", name, q.frac_min_angle_30);
  CHECK_MSG(q.frac_valence_6 >= 0.7, "%s: %.3f", name, q.frac_valence_6);
  CHECK_MSG(q.max_deviation <= 0.005, "%s: %g", name, q.max_deviation);
  ss_mesh_report ri, ro;
  CHECK(ss_mesh_check(in, &ri, &e) == SS_OK);
  CHECK(ss_mesh_check(&r, &ro, &e) == SS_OK);
  CHECK_MSG(ro.manifold && ro.boundary_edges == 0 && ro.degenerate_faces == 0 && ro.duplicate_faces == 0 &&
                ro.unreferenced_vertices == 0,
            "%s: not a clean closed manifold", name);
  CHECK_MSG(ro.components == ri.components && ro.euler_characteristic == ri.euler_characteristic &&
                ro.euler_characteristic == genus_chi,
            "%s: components %d/%d, chi %d/%d", name, ro.components, ri.components, ro.euler_characteristic,
            ri.euler_characteristic);
  ss_mesh_free(&r);
}

static void test_remesh_synthetic(void) {
  ss_mesh s = {0};
  ss_error e = {{0}};
  CHECK(ss_synth_icosphere(4, &s, &e) == SS_OK);
  check_remesh("icosphere 5120 -> 3000", &s, 3000, 2);
  check_remesh("icosphere 5120 -> 12000", &s, 12000, 2);
  ss_mesh_free(&s);
  CHECK(ss_synth_icosphere(1, &s, &e) == SS_OK);
  check_remesh("icosphere 80 -> 2000 (refinement)", &s, 2000, 2);
  ss_mesh_free(&s);
  CHECK(ss_synth_torus(1.0, 0.35, 80, 30, &s, &e) == SS_OK);
  check_remesh("torus -> 4000", &s, 4000, 0);
  ss_mesh_free(&s);

  /* two spheres: same component count */
  ss_mesh a = {0}, two = {0};
  CHECK(ss_synth_icosphere(3, &a, &e) == SS_OK);
  CHECK(ss_mesh_alloc(&two, 2 * a.nv, 2 * a.nf, &e) == SS_OK);
  for (int i = 0; i < a.nv; i++)
    for (int k = 0; k < 3; k++) {
      two.V[3 * i + k] = a.V[3 * i + k];
      two.V[3 * (i + a.nv) + k] = a.V[3 * i + k] + (k == 0 ? 3.0 : 0.0);
    }
  for (int i = 0; i < 3 * a.nf; i++) { two.F[i] = a.F[i]; two.F[i + 3 * a.nf] = a.F[i] + a.nv; }
  check_remesh("two spheres -> 3000", &two, 3000, 4);
  ss_mesh_free(&two);

  /* an open mesh is refused */
  a.nf -= 1;
  ss_mesh r = {0};
  CHECK(ss_remesh(&a, NULL, &r, &e) == SS_ERR_UNSUPPORTED);
  a.nf += 1;
  ss_mesh_free(&a);
}

static void test_faust(void) {
  const char *d = tl_data_dir();
  if (!d) { SKIP("FAUST data not found"); return; }
  char path[4096];
  snprintf(path, sizeof path, "%s/faust/tr_reg_000.off", d);
  ss_mesh m = {0}, s = {0};
  ss_error e = {{0}};
  if (ss_read_mesh(path, &m, &e) != SS_OK) { CHECK_MSG(0, "%s", e.msg); return; }
  CHECK_MSG(ss_cmcf_smooth(&m, NULL, &s, &e) == SS_OK, "%s", e.msg);
  /* fingers and toes collapse (the vertex that moves most is on a hand or a foot and moves far
   * more than the typical vertex) while the limbs stay (height and arm span kept) */
  double h0 = ss_mesh_bbox_diagonal(&m), h1 = ss_mesh_bbox_diagonal(&s);
  CHECK_MSG(h1 > 0.95 * h0 && h1 < 1.2 * h0, "bbox diagonal %.3f -> %.3f", h0, h1);
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  double lo1[3] = {INFINITY, INFINITY, INFINITY}, hi1[3] = {-INFINITY, -INFINITY, -INFINITY};
  double *disp = malloc(sizeof(double) * m.nv), dmax = 0;
  int imax = 0;
  for (int i = 0; i < m.nv; i++) {
    double dd = 0;
    for (int k = 0; k < 3; k++) {
      lo[k] = fmin(lo[k], m.V[3 * i + k]); hi[k] = fmax(hi[k], m.V[3 * i + k]);
      lo1[k] = fmin(lo1[k], s.V[3 * i + k]); hi1[k] = fmax(hi1[k], s.V[3 * i + k]);
      dd += (s.V[3 * i + k] - m.V[3 * i + k]) * (s.V[3 * i + k] - m.V[3 * i + k]);
    }
    disp[i] = sqrt(dd);
    if (disp[i] > dmax) { dmax = disp[i]; imax = i; }
  }
  int below = 0; /* median by counting */
  double med = 0;
  for (int t = 0; t < 60 && !med; t++) {
    double c = 0.001 * t * h0;
    below = 0;
    for (int i = 0; i < m.nv; i++) below += disp[i] <= c;
    if (below >= m.nv / 2) med = c;
  }
  free(disp);
  const double *pm = m.V + 3 * imax;
  int extremity = pm[1] < lo[1] + 0.1 * (hi[1] - lo[1]) || pm[0] < lo[0] + 0.15 * (hi[0] - lo[0]) ||
                  pm[0] > hi[0] - 0.15 * (hi[0] - lo[0]);
  CHECK_MSG(extremity && dmax > 2.5 * med, "largest move %.4f at vertex %d (%.3f %.3f %.3f), median %.4f", dmax, imax,
            pm[0], pm[1], pm[2], med);
  CHECK_MSG(hi1[0] - lo1[0] > 0.9 * (hi[0] - lo[0]) && hi1[1] - lo1[1] > 0.95 * (hi[1] - lo[1]), "extents shrank");
  check_remesh("smoothed FAUST tr_reg_000 -> 15000", &s, 15000, 2);
  ss_mesh_free(&m);
  ss_mesh_free(&s);
}

static unsigned long long rng = 88172645463325252ULL;
static double urand(void) {
  rng ^= rng << 13; rng ^= rng >> 7; rng ^= rng << 17;
  return (double)(rng >> 11) / 9007199254740992.0;
}

static void test_closest_vertices(void) {
  ss_mesh s = {0};
  ss_error e = {{0}};
  CHECK(ss_synth_icosphere(3, &s, &e) == SS_OK);
  for (int i = 0; i < s.nv; i++) s.V[3 * i] *= 3; /* anisotropic box */
  const int np = 3000;
  double *P = malloc(sizeof(double) * 3 * np);
  int *got = malloc(sizeof(int) * np);
  for (int i = 0; i < np; i++)
    for (int k = 0; k < 3; k++) P[3 * i + k] = (urand() * 2 - 1) * (i < np / 2 ? 1.2 : 8.0) * (k == 0 ? 3 : 1);
  for (int k = 0; k < 3; k++) P[k] = s.V[3 * 17 + k]; /* exactly on a vertex */
  CHECK(ss_closest_vertices(P, np, &s, got, &e) == SS_OK);
  int bad = 0;
  for (int i = 0; i < np; i++) {
    double best = INFINITY;
    int bi = -1;
    for (int j = 0; j < s.nv; j++) {
      double dx = s.V[3 * j] - P[3 * i], dy = s.V[3 * j + 1] - P[3 * i + 1], dz = s.V[3 * j + 2] - P[3 * i + 2];
      double dd = dx * dx + dy * dy + dz * dz;
      if (dd < best) { best = dd; bi = j; }
    }
    bad += got[i] != bi;
  }
  CHECK_MSG(bad == 0, "%d of %d differ from brute force", bad, np);
  CHECK(got[0] == 17);
  /* a single-vertex target and an empty query */
  ss_mesh one = {1, 0, s.V, NULL};
  CHECK(ss_closest_vertices(P, 5, &one, got, &e) == SS_OK && got[0] == 0 && got[4] == 0);
  CHECK(ss_closest_vertices(P, 0, &s, got, &e) == SS_OK);
  free(P);
  free(got);
  ss_mesh_free(&s);
}

int main(void) {
  test_cmcf_sphere();
  test_cmcf_protrusion();
  test_remesh_synthetic();
  test_closest_vertices();
  test_faust();
  TEST_MAIN_END();
}
