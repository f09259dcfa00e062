/* Orientation operators (ss_fmap_orientation_operators) and their term in the functional-map system:
 * the algebraic per-face formula equals the geometric one (gradients, normals, area-weighted vertex
 * averages, lumped masses); on the unit sphere ⟨n × ∇z, ∇x⟩ = y, so ∫ y ⟨n × ∇z, ∇x⟩ = 4π/3; flipping
 * every face negates the operators; the assembled system with the orientation term has the least-
 * squares solution of the stacked residuals. */
#include "specseg/fmap.h"
#include "specseg/mesh.h"
#include "specseg/spectrum.h"
#include "specseg/laplacian.h"
#include "specseg/synth.h"
#include "testlib.h"

#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static void cross(const double *a, const double *b, double *c) {
  c[0] = a[1] * b[2] - a[2] * b[1], c[1] = a[2] * b[0] - a[0] * b[2], c[2] = a[0] * b[1] - a[1] * b[0];
}
static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* per-vertex test functions: 1, x, y, z, xy, yz, x² − z², then F: z, x + y², xyz */
static void functions(const ss_mesh *m, int k, double *phi, int p, double *F) {
  for (int v = 0; v < m->nv; v++) {
    const double x = m->V[3 * v], y = m->V[3 * v + 1], z = m->V[3 * v + 2];
    const double b[7] = {1, x, y, z, x * y, y * z, x * x - z * z}, f[3] = {z, x + y * y, x * y * z};
    for (int i = 0; i < k; i++) phi[v + (size_t)m->nv * i] = b[i];
    for (int i = 0; i < p; i++) F[v + (size_t)m->nv * i] = f[i];
  }
}

/* O by the geometry: ∇ per face from the hat functions, ⟨n × ∇f, ∇g⟩ per face, averaged to the
 * vertices with weights area/3, integrated with the lumped masses */
static void geometric(const ss_mesh *m, int k, const double *phi, const double *f, double *O) {
  const int n = m->nv;
  double *Mv = calloc((size_t)n, sizeof(double)), *g = calloc((size_t)n * k, sizeof(double));
  for (int t = 0; t < m->nf; t++) {
    const int *v = m->F + 3 * t;
    const double *p0 = m->V + 3 * v[0], *p1 = m->V + 3 * v[1], *p2 = m->V + 3 * v[2];
    double e1[3], e2[3], nn[3];
    for (int c = 0; c < 3; c++) e1[c] = p1[c] - p0[c], e2[c] = p2[c] - p0[c];
    cross(e1, e2, nn);
    const double A2 = sqrt(dot3(nn, nn)), A = A2 / 2;
    for (int c = 0; c < 3; c++) nn[c] /= A2;
    /* ∇h_a = n × (p_c − p_b) / (2A) for (a, b, c) cyclic */
    double gh[3][3];
    for (int a = 0; a < 3; a++) {
      const double *pb = m->V + 3 * v[(a + 1) % 3], *pc = m->V + 3 * v[(a + 2) % 3];
      double e[3] = {pc[0] - pb[0], pc[1] - pb[1], pc[2] - pb[2]};
      cross(nn, e, gh[a]);
      for (int c = 0; c < 3; c++) gh[a][c] /= A2;
    }
    double gf[3] = {0, 0, 0}, r[3];
    for (int a = 0; a < 3; a++)
      for (int c = 0; c < 3; c++) gf[c] += f[v[a]] * gh[a][c];
    cross(nn, gf, r);
    for (int j = 0; j < k; j++) {
      double gg[3] = {0, 0, 0};
      for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++) gg[c] += phi[v[a] + (size_t)n * j] * gh[a][c];
      const double q = dot3(r, gg);
      for (int a = 0; a < 3; a++) g[v[a] + (size_t)n * j] += A / 3 * q;
    }
    for (int a = 0; a < 3; a++) Mv[v[a]] += A / 3;
  }
  for (int i = 0; i < k; i++)
    for (int j = 0; j < k; j++) {
      double s = 0;
      for (int v = 0; v < n; v++) s += Mv[v] * phi[v + (size_t)n * i] * (g[v + (size_t)n * j] / Mv[v]);
      O[i + (size_t)k * j] = s;
    }
  free(Mv), free(g);
}

static void test_geometric_and_analytic(void) {
  ss_mesh m = {0};
  ss_error e = {{0}};
  CHECK_MSG(ss_synth_icosphere(4, &m, &e) == SS_OK, "%s", e.msg);
  const int n = m.nv, k = 7, p = 3;
  double *phi = malloc(sizeof(double) * (size_t)n * k), *F = malloc(sizeof(double) * (size_t)n * p);
  double *O = malloc(sizeof(double) * k * k * p), *R = malloc(sizeof(double) * k * k);
  functions(&m, k, phi, p, F);
  CHECK_MSG(ss_fmap_orientation_operators(&m, k, phi, p, F, O, &e) == SS_OK, "%s", e.msg);
  /* the same as the geometric construction, up to one sign for all */
  double sign = 0, worst = 0, scale = 0;
  for (int q = 0; q < p; q++) {
    geometric(&m, k, phi, F + (size_t)n * q, R);
    for (int i = 0; i < k * k; i++) {
      scale = fmax(scale, fabs(R[i]));
      if (sign == 0 && fabs(R[i]) > 1e-3) sign = O[(size_t)k * k * q + i] / R[i] > 0 ? 1 : -1;
    }
    for (int i = 0; i < k * k; i++) worst = fmax(worst, fabs(O[(size_t)k * k * q + i] - sign * R[i]));
  }
  CHECK_MSG(sign != 0 && worst < 1e-12 * scale, "algebraic vs geometric operators: %g (scale %g)", worst, scale);
  /* ∫ y ⟨n × ∇z, ∇x⟩ dA = ∫ y² dA = 4π/3 on the unit sphere; ∫ x ⟨n × ∇z, ∇x⟩ = ∫ xy = 0 */
  const double v = fabs(O[2 + (size_t)k * 1]), want = 4 * M_PI / 3;
  CHECK_MSG(fabs(v - want) < 0.01 * want, "sphere: %g, want 4pi/3 = %g", v, want);
  CHECK_MSG(fabs(O[1 + (size_t)k * 1]) < 1e-3, "sphere: int x <n x grad z, grad x> = %g, want 0", O[1 + (size_t)k * 1]);
  /* the constant function has no gradient: its column is zero */
  double c0 = 0;
  for (int q = 0; q < p; q++)
    for (int i = 0; i < k; i++) c0 = fmax(c0, fabs(O[(size_t)k * k * q + i]));
  CHECK_MSG(c0 < 1e-12 * scale, "constant basis function: %g", c0);
  /* every face flipped: every operator negated, exactly */
  double *O2 = malloc(sizeof(double) * k * k * p);
  for (int t = 0; t < m.nf; t++) {
    int tmp = m.F[3 * t + 1];
    m.F[3 * t + 1] = m.F[3 * t + 2], m.F[3 * t + 2] = tmp;
  }
  CHECK(ss_fmap_orientation_operators(&m, k, phi, p, F, O2, &e) == SS_OK);
  double flip = 0;
  for (int i = 0; i < k * k * p; i++) flip = fmax(flip, fabs(O2[i] + O[i]));
  CHECK_MSG(flip < 1e-12 * scale, "flipped winding: operators not negated (%g)", flip);
  /* bad input */
  CHECK(ss_fmap_orientation_operators(NULL, k, phi, p, F, O, &e) == SS_ERR_INVALID);
  CHECK(ss_fmap_orientation_operators(&m, 0, phi, p, F, O, &e) == SS_ERR_INVALID);
  m.F[4] = n;
  CHECK(ss_fmap_orientation_operators(&m, k, phi, p, F, O, &e) == SS_ERR_INVALID);
  free(phi), free(F), free(O), free(R), free(O2);
  ss_mesh_free(&m);
}

static unsigned rng_state = 1234u;
static double urand(void) {
  rng_state = rng_state * 1664525u + 1013904223u;
  return (rng_state >> 8) / 16777216.0 - 0.5;
}

/* The system with every term — data, Laplacian commutativity, multiplication operators, orientation
 * operators, and an extra probe block with or without its operators — solves the least-squares
 * problem of the stacked residuals (C: k_T x k_S; x = vec(C), index r + k_T·c):
 *   √w_d (C A − B), √w_l (λ_T,r − λ_S,c) C[r, c], √w_c (C D_S − D_T C), √w_o (C O_S − O_T C),
 *   √(w_d·w_x) (C A_x − B_x) [, √w_c (C D_Sx − D_Tx C)]
 * checked against dense least squares (LAPACK dgels). */
static void add_commutator_rows(int kS, int kT, double wt, const double *XS, const double *XT, double *K, int rows, int *row) {
  for (int c = 0; c < kS; c++)
    for (int r = 0; r < kT; r++, (*row)++) { /* (C X_S − X_T C)[r, c] */
      for (int c2 = 0; c2 < kS; c2++) K[*row + (size_t)rows * (r + kT * c2)] += sqrt(wt) * XS[c2 + kS * c];
      for (int r2 = 0; r2 < kT; r2++) K[*row + (size_t)rows * (r2 + kT * c)] -= sqrt(wt) * XT[r + kT * r2];
    }
}

static void add_data_rows(int kS, int kT, int p, double wt, const double *A, const double *B, double *K, double *rhs, int rows,
                          int *row) {
  for (int j = 0; j < p; j++)
    for (int r = 0; r < kT; r++, (*row)++) { /* (C A)[r, j] = Σ_c C[r, c] A[c, j] */
      for (int c = 0; c < kS; c++) K[*row + (size_t)rows * (r + kT * c)] = sqrt(wt) * A[c + kS * j];
      rhs[*row] = sqrt(wt) * B[r + kT * j];
    }
}

static void sym_random(int k, int nd, double *D, double *P) {
  for (int i = 0; i < nd; i++)
    for (int b = 0; b < k; b++)
      for (int a = 0; a <= b; a++)
        D[(size_t)k * k * i + a + k * b] = D[(size_t)k * k * i + b + k * a] =
            P[(size_t)k * (k + 1) / 2 * i + (size_t)b * (b + 1) / 2 + a] = urand();
}

static void test_system(void) {
  enum { kS = 6, kT = 5, p = 4, no = 3, nd = 2, q = 2, m = kS * kT };
  double A[kS * p], B[kT * p], OS[no * kS * kS], OT[no * kT * kT], lS[kS], lT[kT];
  double DS[(nd + q) * kS * kS], DT[(nd + q) * kT * kT], PS[(nd + q) * kS * (kS + 1) / 2], PT[(nd + q) * kT * (kT + 1) / 2];
  double AX[kS * q], BX[kT * q];
  for (int i = 0; i < kS * p; i++) A[i] = urand();
  for (int i = 0; i < kT * p; i++) B[i] = urand();
  for (int i = 0; i < kS * q; i++) AX[i] = urand();
  for (int i = 0; i < kT * q; i++) BX[i] = urand();
  for (int i = 0; i < no * kS * kS; i++) OS[i] = urand();
  for (int i = 0; i < no * kT * kT; i++) OT[i] = urand();
  for (int i = 0; i < kS; i++) lS[i] = 0.9 * i + urand();
  for (int i = 0; i < kT; i++) lT[i] = 1.1 * i + urand();
  sym_random(kS, nd + q, DS, PS);
  sym_random(kT, nd + q, DT, PT);
  for (int variant = 0; variant < 4; variant++) {
    /* 0: data + orientation only (no operators, no Laplacian); 1: every base term; 2: + extras;
     * 3: + extras with their operators */
    const double wd = 0.7, wo = 1.9, wl = variant ? 0.05 : 0, wc = variant ? 1.3 : 0, wx = 0.45;
    const int ndv = variant ? nd : 0, extras = variant >= 2, xops = variant == 3;
    ss_fmap_probes S = {kS, p, ndv, A, PS, no, OS}, T = {kT, p, ndv, B, PT, no, OT};
    ss_fmap_probes XS = {kS, q, xops ? q : 0, AX, PS + nd * kS * (kS + 1) / 2, 0, NULL};
    ss_fmap_probes XT = {kT, q, xops ? q : 0, BX, PT + nd * kT * (kT + 1) / 2, 0, NULL};
    ss_fmap_weights w = {wd, wl, wc, 0, 0, wo};
    ss_fmap_system *sys = NULL;
    ss_error e = {{0}};
    double C[m];
    CHECK_MSG(ss_fmap_system_new(kS, kT, lS, lT, &S, &T, &w, &sys, &e) == SS_OK, "%s", e.msg);
    CHECK_MSG(ss_fmap_system_solve(sys, extras ? &XS : NULL, extras ? &XT : NULL, wx, xops, C, &e) == SS_OK, "%s", e.msg);
    ss_fmap_system_free(sys);
    const int rows = kT * p + m + nd * m + no * m + kT * q + q * m;
    double *K = calloc((size_t)rows * m, sizeof(double)), *rhs = calloc((size_t)rows, sizeof(double));
    int row = 0;
    add_data_rows(kS, kT, p, wd, A, B, K, rhs, rows, &row);
    for (int c = 0; c < kS; c++)
      for (int r = 0; r < kT; r++, row++) K[row + (size_t)rows * (r + kT * c)] = sqrt(wl) * (lT[r] - lS[c]);
    for (int i = 0; i < ndv; i++) add_commutator_rows(kS, kT, wc, DS + i * kS * kS, DT + i * kT * kT, K, rows, &row);
    for (int i = 0; i < no; i++) add_commutator_rows(kS, kT, wo, OS + i * kS * kS, OT + i * kT * kT, K, rows, &row);
    if (extras) add_data_rows(kS, kT, q, wd * wx, AX, BX, K, rhs, rows, &row);
    for (int i = 0; i < (xops ? q : 0); i++)
      add_commutator_rows(kS, kT, wc, DS + (nd + i) * kS * kS, DT + (nd + i) * kT * kT, K, rows, &row);
    CHECK(LAPACKE_dgels(LAPACK_COL_MAJOR, 'N', rows, m, 1, K, rows, rhs, rows) == 0);
    double worst = 0, scale = 0;
    for (int i = 0; i < m; i++) worst = fmax(worst, fabs(C[i] - rhs[i])), scale = fmax(scale, fabs(rhs[i]));
    CHECK_MSG(worst < 1e-9 * scale, "variant %d: system vs least squares: %g (scale %g)", variant, worst, scale);
    free(K), free(rhs);
  }
  /* mismatched operator counts are refused */
  ss_fmap_probes S = {kS, p, 0, A, NULL, no, OS}, T = {kT, p, 0, B, NULL, no - 1, OT};
  ss_fmap_weights w = {0.7, 0, 0, 0, 0, 1.9};
  ss_fmap_system *sys = NULL;
  ss_error e;
  CHECK(ss_fmap_system_new(kS, kT, lS, lT, &S, &T, &w, &sys, &e) == SS_ERR_INVALID && sys == NULL);
}

/* The pipeline's operators (ss_fmap_base_probes with w_orient) are those of the outward orientation:
 * a mesh wound inward, or with every third face reversed, gives the same operators bit for bit; the
 * term off gives none. */
static void test_probes_outward(void) {
  ss_mesh m = {0};
  ss_error e = {{0}};
  CHECK_MSG(ss_synth_icosphere(3, &m, &e) == SS_OK, "%s", e.msg);
  for (int v = 0; v < m.nv; v++) m.V[3 * v] *= 1.0 + 0.3 * m.V[3 * v + 1]; /* no symmetry to hide a sign */
  const int n = m.nv, kev = 14;
  double *ev = malloc(sizeof(double) * kev), *phi = malloc(sizeof(double) * (size_t)n * kev), *M = malloc(sizeof(double) * n);
  CHECK_MSG(ss_mesh_eigs(&m, kev, ev, phi, &e) == SS_OK, "%s", e.msg);
  CHECK(ss_mass_lumped(&m, SS_MASS_BARYCENTRIC, M, &e) == SS_OK);
  ss_fmap_match_options o;
  ss_fmap_match_default_options(&o);
  o.k = 12, o.n_energies = 20, o.descr_step = 4, o.w_orient = 1.0;
  int lm[2] = {0, 7};
  ss_fmap_shape s = {&m, M, ev, phi, kev, NULL, 0, NULL, 0};
  ss_fmap_probes ref = {0}, got = {0};
  CHECK_MSG(ss_fmap_base_probes(&s, 2, lm, &o, 1, &ref, &e) == SS_OK, "%s", e.msg);
  CHECK(ref.no == 5 && ref.O != NULL);
  double mag = 0;
  for (int i = 0; ref.O && i < o.k * o.k * ref.no; i++) mag = fmax(mag, fabs(ref.O[i]));
  CHECK_MSG(mag > 1e-3, "orientation operators vanish (%g)", mag);
  for (int variant = 0; variant < 2; variant++) {
    for (int t = 0; t < m.nf; t++)
      if (variant == 0 || t % 3 == 0) { /* 0: every face (inward), 1: every third face back again */
        int tmp = m.F[3 * t + 1];
        m.F[3 * t + 1] = m.F[3 * t + 2], m.F[3 * t + 2] = tmp;
      }
    CHECK_MSG(ss_fmap_base_probes(&s, 2, lm, &o, 1, &got, &e) == SS_OK, "%s", e.msg);
    CHECK_MSG(got.no == ref.no && ref.O && got.O && !memcmp(got.O, ref.O, sizeof(double) * o.k * o.k * ref.no),
              "winding variant %d: other orientation operators", variant);
    ss_fmap_probes_free(&got);
  }
  o.w_orient = 0;
  CHECK(ss_fmap_base_probes(&s, 2, lm, &o, 1, &got, &e) == SS_OK && got.no == 0 && got.O == NULL);
  ss_fmap_probes_free(&got), ss_fmap_probes_free(&ref);
  free(ev), free(phi), free(M);
  ss_mesh_free(&m);
}

int main(void) {
  test_probes_outward();
  test_geometric_and_analytic();
  test_system();
  TEST_MAIN_END();
}
