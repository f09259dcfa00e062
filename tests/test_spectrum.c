/* Laplace–Beltrami spectrum: known spectra (sphere, flat rectangle), accuracy bounds, components,
 * argument errors, and FAUST when the data folder is there. */
#include "specseg/io.h"
#include "specseg/laplacian.h"
#include "specseg/mesh.h"
#include "specseg/synth.h"
#include "specseg/spectrum.h"
#include "testlib.h"
#include "linalg/cholmod_wrap.h"

#include <omp.h>

/* OpenBLAS (cblas.h's complex.h would define I) */
void openblas_set_num_threads(int num_threads);
int openblas_get_num_threads(void);

#define PI 3.14159265358979323846

/* W and barycentric M of a mesh. */
static int operators(const ss_mesh *m, ss_sparse *W, double **M) {
  *M = malloc(sizeof(double) * (size_t)m->nv);
  if (ss_cotan_stiffness(m, W, NULL) != SS_OK) return -1;
  if (ss_mass_lumped(m, SS_MASS_BARYCENTRIC, *M, NULL) != SS_OK) return -1;
  return 0;
}

/* Rectangle [0,a]x[0,b] as an nx x ny grid, diagonals alternating (no preferred direction). */
static void rect_grid(double a, double b, int nx, int ny, ss_mesh *m) {
  ss_mesh_alloc(m, nx * ny, 2 * (nx - 1) * (ny - 1), NULL);
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++) {
      double *p = m->V + 3 * (j * nx + i);
      p[0] = a * i / (nx - 1);
      p[1] = b * j / (ny - 1);
      p[2] = 0;
    }
  int k = 0;
  for (int j = 0; j + 1 < ny; j++)
    for (int i = 0; i + 1 < nx; i++) {
      int v0 = j * nx + i, v1 = v0 + 1, v2 = v0 + nx, v3 = v2 + 1;
      int t[6];
      if ((i + j) % 2 == 0) { int u[6] = {v0, v1, v3, v0, v3, v2}; memcpy(t, u, sizeof t); }
      else { int u[6] = {v0, v1, v2, v1, v3, v2}; memcpy(t, u, sizeof t); }
      memcpy(m->F + 3 * k, t, sizeof t);
      k += 2;
    }
}

/* Residual and M-orthonormality bounds of the issue, for one solve. */
static void check_accuracy(const ss_sparse *W, const double *M, int k, const double *ev, const double *X,
                           const char *what) {
  double res = -1, orth = -1;
  CHECK(ss_eigs_check(W, M, k, ev, X, &res, &orth, NULL) == SS_OK);
  CHECK_MSG(res >= 0 && res <= 1e-8, "%s: max relative residual %g", what, res);
  CHECK_MSG(orth >= 0 && orth <= 1e-9, "%s: max |PhiT M Phi - I| %g", what, orth);
  for (int i = 1; i < k; i++) CHECK_MSG(ev[i] >= ev[i - 1], "%s: eigenvalues not ascending at %d", what, i);
  printf("%s: k=%d max rel residual %.3g, orthonormality error %.3g\n", what, k, res, orth);
}

static void test_sphere(void) {
#if defined(__SANITIZE_ADDRESS__)
  const int level = 4;
#else
  const int level = 5;
#endif
  ss_mesh m;
  CHECK(ss_synth_icosphere(level, &m, NULL) == SS_OK);
  ss_sparse W;
  double *M;
  CHECK(operators(&m, &W, &M) == 0);
  int k = 30;
  double *ev = malloc(sizeof(double) * k), *X = malloc(sizeof(double) * (size_t)m.nv * k);
  double t0 = ss_time();
  ss_error e;
  CHECK_MSG(ss_eigs(&W, M, k, NULL, ev, X, &e) == SS_OK, "%s", e.msg);
  printf("sphere level %d (%d vertices): k=%d in %.3f s\n", level, m.nv, k, ss_time() - t0);
  /* l(l+1) with multiplicity 2l+1: 0 | 2 2 2 | 6 x5 | 12 x7 (first 16) */
  int idx = 0;
  for (int l = 0; l <= 3; l++)
    for (int q = 0; q < 2 * l + 1; q++, idx++) {
      double exact = l * (l + 1);
      if (l == 0) CHECK_MSG(fabs(ev[idx]) < 1e-8, "lambda_0 = %g", ev[idx]);
      else CHECK_MSG(fabs(ev[idx] - exact) <= 0.01 * exact, "lambda_%d = %.6f vs %g", idx, ev[idx], exact);
    }
  /* next cluster (l = 4, 20) is separate from l = 3 */
  CHECK_NEAR(ev[16], 20.0, 0.2);
  check_accuracy(&W, M, k, ev, X, "sphere");

  /* same problem with an explicit generous Krylov space must agree */
  ss_eigs_options o;
  ss_eigs_default_options(&o);
  o.ncv = 80;
  double *ev2 = malloc(sizeof(double) * k);
  CHECK(ss_eigs(&W, M, k, &o, ev2, NULL, NULL) == SS_OK);
  double worst = 0;
  for (int i = 0; i < k; i++) worst = fmax(worst, fabs(ev2[i] - ev[i]) / (1 + ev[i]));
  CHECK_MSG(worst < 1e-9, "ncv=80 vs default differ by %g", worst);

  /* interior shift (indefinite LDLᵀ): the 5 eigenvalues nearest 5 are the l = 2 cluster (6) */
  {
    ss_eigs_options oi;
    ss_eigs_default_options(&oi);
    oi.sigma = 5;
    double evi[5], *Xi = malloc(sizeof(double) * (size_t)m.nv * 5);
    CHECK_MSG(ss_eigs(&W, M, 5, &oi, evi, Xi, &e) == SS_OK, "%s", e.msg);
    for (int i = 0; i < 5; i++) CHECK_MSG(fabs(evi[i] - ev[4 + i]) < 1e-9 * ev[4 + i], "sigma=5: %.12g vs %.12g", evi[i], ev[4 + i]);
    check_accuracy(&W, M, 5, evi, Xi, "sphere (sigma = 5)");
    free(Xi);
  }

  /* invalid arguments */
  CHECK(ss_eigs(&W, M, 0, NULL, ev, X, NULL) == SS_ERR_INVALID);
  CHECK(ss_eigs(&W, M, m.nv, NULL, ev, NULL, NULL) == SS_ERR_INVALID);
  CHECK(ss_eigs(&W, M, -3, NULL, ev, NULL, NULL) == SS_ERR_INVALID);
  o.ncv = 5;
  CHECK(ss_eigs(&W, M, 10, &o, ev, NULL, NULL) == SS_ERR_INVALID);
  ss_eigs_default_options(&o);
  o.tol = -1;
  CHECK(ss_eigs(&W, M, 10, &o, ev, NULL, NULL) == SS_ERR_INVALID);
  double keep = M[7];
  M[7] = 0;
  CHECK(ss_eigs(&W, M, 10, NULL, ev, NULL, &e) == SS_ERR_INVALID);
  CHECK(strstr(e.msg, "mass") != NULL);
  M[7] = NAN;
  CHECK(ss_eigs(&W, M, 10, NULL, ev, NULL, NULL) == SS_ERR_INVALID);
  M[7] = keep;
  /* a shift exactly at the (exact) zero eigenvalue of a 2x2 Laplacian: singular */
  {
    int cp[3] = {0, 2, 4}, ri[4] = {0, 1, 0, 1};
    double vals[4] = {1, -1, -1, 1}, m2[2] = {1, 1};
    ss_sparse S2 = {2, 2, cp, ri, vals};
    ss_eigs_options o2;
    ss_eigs_default_options(&o2);
    o2.sigma = 2; /* exactly the non-zero eigenvalue */
    ss_status s2 = ss_eigs(&S2, m2, 1, &o2, ev, NULL, &e);
    CHECK_MSG(s2 == SS_ERR_NUMERIC, "status %d (%s)", s2, e.msg);
  }
  free(ev); free(ev2); free(X); free(M);
  ss_sparse_free(&W);
  ss_mesh_free(&m);
}

/* Two disjoint spheres of different radii: two zero eigenvalues with locally constant vectors. */
static void test_two_components(void) {
  ss_mesh a, b, m;
  CHECK(ss_synth_icosphere(3, &a, NULL) == SS_OK);
  CHECK(ss_synth_icosphere(2, &b, NULL) == SS_OK);
  ss_mesh_alloc(&m, a.nv + b.nv, a.nf + b.nf, NULL);
  memcpy(m.V, a.V, sizeof(double) * 3 * a.nv);
  for (int i = 0; i < b.nv; i++)
    for (int d = 0; d < 3; d++) m.V[3 * (a.nv + i) + d] = 1.5 * b.V[3 * i + d] + (d == 0 ? 5.0 : 0.0);
  memcpy(m.F, a.F, sizeof(int) * 3 * a.nf);
  for (int i = 0; i < 3 * b.nf; i++) m.F[3 * a.nf + i] = b.F[i] + a.nv;
  ss_sparse W;
  double *M;
  CHECK(operators(&m, &W, &M) == 0);
  int k = 8;
  double ev[8], *X = malloc(sizeof(double) * (size_t)m.nv * k);
  ss_error e;
  CHECK_MSG(ss_eigs(&W, M, k, NULL, ev, X, &e) == SS_OK, "%s", e.msg);
  CHECK_MSG(fabs(ev[0]) < 1e-8 && fabs(ev[1]) < 1e-8, "zero eigenvalues %g %g", ev[0], ev[1]);
  /* the third is the first non-zero one of the larger sphere: 2/1.5^2 */
  CHECK_MSG(ev[2] > 0.5, "third eigenvalue %g should be clearly positive", ev[2]);
  CHECK_NEAR(ev[2], 2.0 / 2.25, 0.03);
  /* φ0, φ1 are constant on each component */
  for (int j = 0; j < 2; j++) {
    const double *x = X + (size_t)m.nv * j;
    double spread_a = 0, spread_b = 0;
    for (int i = 1; i < a.nv; i++) spread_a = fmax(spread_a, fabs(x[i] - x[0]));
    for (int i = a.nv + 1; i < m.nv; i++) spread_b = fmax(spread_b, fabs(x[i] - x[a.nv]));
    CHECK_MSG(spread_a < 1e-6 && spread_b < 1e-6, "null vector %d not piecewise constant (%g, %g)", j, spread_a,
              spread_b);
  }
  check_accuracy(&W, M, k, ev, X, "two spheres");
  /* k = number of components: only the exact null pairs, no factorisation needed */
  double ev2[2];
  CHECK(ss_eigs(&W, M, 2, NULL, ev2, X, NULL) == SS_OK);
  CHECK(fabs(ev2[0]) < 1e-8 && fabs(ev2[1]) < 1e-8);
  check_accuracy(&W, M, 2, ev2, X, "two spheres, k = 2");
  free(X); free(M);
  ss_sparse_free(&W);
  ss_mesh_free(&a); ss_mesh_free(&b); ss_mesh_free(&m);
}

/* Neumann eigenvalues of [0,a]x[0,b]: π²((p/a)² + (q/b)²). */
static int cmp_double(const void *x, const void *y) {
  double a = *(const double *)x, b = *(const double *)y;
  return (a > b) - (a < b);
}

static void test_rectangle(void) {
  const double a = 2.0, b = 1.0;
  ss_mesh m;
  rect_grid(a, b, 81, 41, &m);
  ss_sparse W;
  double *M;
  CHECK(operators(&m, &W, &M) == 0);
  int k = 8;
  double ev[8], *X = malloc(sizeof(double) * (size_t)m.nv * k);
  ss_error e;
  CHECK_MSG(ss_eigs(&W, M, k, NULL, ev, X, &e) == SS_OK, "%s", e.msg);
  double exact[64];
  int ne = 0;
  for (int p = 0; p < 8; p++)
    for (int q = 0; q < 8; q++) exact[ne++] = PI * PI * ((p / a) * (p / a) + (q / b) * (q / b));
  qsort(exact, (size_t)ne, sizeof(double), cmp_double);
  CHECK_MSG(fabs(ev[0]) < 1e-8, "lambda_0 = %g", ev[0]);
  for (int i = 1; i < k; i++)
    CHECK_MSG(fabs(ev[i] - exact[i]) <= 0.01 * exact[i], "rectangle lambda_%d = %.6f vs %.6f", i, ev[i], exact[i]);
  check_accuracy(&W, M, k, ev, X, "rectangle");
  free(X); free(M);
  ss_sparse_free(&W);
  ss_mesh_free(&m);
}

static int cmp_ll(const void *x, const void *y) {
  long long a = *(const long long *)x, b = *(const long long *)y;
  return (a > b) - (a < b);
}

/* Subdivision keeps the surface: vertex/face counts, area, and the sphere spectrum stays close. */
static void test_subdivide(void) {
  ss_mesh a, s;
  CHECK(ss_synth_icosphere(2, &a, NULL) == SS_OK);
  CHECK(ss_mesh_subdivide(&a, &s, NULL) == SS_OK);
  CHECK(s.nv == a.nv + 3 * a.nf / 2); /* closed mesh: E = 3F/2 */
  CHECK(s.nf == 4 * a.nf);
  CHECK_NEAR(ss_mesh_area(&s), ss_mesh_area(&a), 1e-12 * ss_mesh_area(&a));
  /* closed and consistently oriented: every directed edge once, and its reverse once */
  size_t ne = 3 * (size_t)s.nf;
  long long *keys = malloc(sizeof(long long) * ne);
  for (int f = 0; f < s.nf; f++)
    for (int c = 0; c < 3; c++) {
      long long u = s.F[3 * f + c], v = s.F[3 * f + (c + 1) % 3];
      keys[3 * f + c] = (u << 32) | v;
    }
  qsort(keys, ne, sizeof(long long), cmp_ll);
  int dup = 0, unmatched = 0;
  for (size_t i = 0; i < ne; i++) {
    if (i && keys[i] == keys[i - 1]) dup++;
    long long rev = ((keys[i] & 0xffffffffLL) << 32) | (keys[i] >> 32);
    if (!bsearch(&rev, keys, ne, sizeof(long long), cmp_ll)) unmatched++;
  }
  CHECK(dup == 0 && unmatched == 0);
  free(keys);
  /* ss_mesh_eigs on the subdivided (flat-faceted, so slightly off) sphere: 0 then the l = 1 triple */
  double ev4[4];
  CHECK(ss_mesh_eigs(&s, 4, ev4, NULL, NULL) == SS_OK);
  CHECK(fabs(ev4[0]) < 1e-8);
  for (int i = 1; i < 4; i++) CHECK_MSG(fabs(ev4[i] - 2.0) < 0.1, "subdivided sphere lambda_%d = %g", i, ev4[i]);
  CHECK(ss_mesh_eigs(&s, s.nv, ev4, NULL, NULL) == SS_ERR_INVALID);
  ss_mesh_free(&s);
  int bad[3] = {0, 1, 100000};
  ss_mesh b = {a.nv, 1, a.V, bad};
  CHECK(ss_mesh_subdivide(&b, &s, NULL) == SS_ERR_INVALID);
  ss_mesh_free(&a);
}

/* Block Lanczos (SS_EIGS_BLOCK) or partial reorthogonalisation (SS_EIGS_PRO) against ARPACK: same
 * eigenvalues, same accuracy, the same eigenspaces (eigenvectors up to sign, within a multiple
 * eigenvalue up to a rotation), and which one AUTO picks. */
static void compare_methods(const ss_mesh *m, int k, const char *what, int method) {
  ss_sparse W;
  double *M;
  CHECK(operators(m, &W, &M) == 0);
  size_t n = (size_t)m->nv;
  double *ea = malloc(sizeof(double) * k), *eb = malloc(sizeof(double) * k);
  double *Xa = malloc(sizeof(double) * n * k), *Xb = malloc(sizeof(double) * n * k);
  ss_eigs_options o;
  ss_eigs_stats st;
  ss_eigs_default_options(&o);
  o.stats = &st;
  o.method = SS_EIGS_ARPACK;
  ss_error e;
  CHECK_MSG(ss_eigs(&W, M, k, &o, ea, Xa, &e) == SS_OK, "%s", e.msg);
  CHECK(st.method == SS_EIGS_ARPACK);
  o.method = method;
  double t0 = ss_time();
  CHECK_MSG(ss_eigs(&W, M, k, &o, eb, Xb, &e) == SS_OK, "%s", e.msg);
  CHECK_MSG(st.method == method, "%s: method %d ran, not %d", what, st.method, method);
  printf("%s (%d vertices): %s k=%d in %.3f s, block %d, %d restarts, %d solves, %d recovered\n", what, m->nv,
         method == SS_EIGS_BLOCK ? "block Lanczos" : "partial reorthogonalisation", k, ss_time() - t0, st.block,
         st.restarts, st.operator_applications, st.recovered);
  check_accuracy(&W, M, k, eb, Xb, what);
  /* block: the same bits with one thread and with two (fixed row chunks summed in a fixed order) */
  if (method == SS_EIGS_BLOCK) {
    int blas = openblas_get_num_threads(), omp = omp_get_max_threads();
    double *e1 = malloc(sizeof(double) * k), *e2 = malloc(sizeof(double) * k);
    double *X1 = malloc(sizeof(double) * n * k), *X2 = malloc(sizeof(double) * n * k);
    openblas_set_num_threads(1);
    omp_set_num_threads(1);
    CHECK(ss_eigs(&W, M, k, &o, e1, X1, NULL) == SS_OK);
    omp_set_num_threads(2);
    CHECK(ss_eigs(&W, M, k, &o, e2, X2, NULL) == SS_OK);
    CHECK_MSG(!memcmp(e1, e2, sizeof(double) * k) && !memcmp(X1, X2, sizeof(double) * n * k),
              "%s: block Lanczos differs between 1 and 2 threads", what);
    omp_set_num_threads(omp);
    openblas_set_num_threads(blas);
    free(e1); free(e2); free(X1); free(X2);
  }
  double worst = 0;
  for (int i = 0; i < k; i++) worst = fmax(worst, fabs(eb[i] - ea[i]) / (1 + fabs(ea[i])));
  CHECK_MSG(worst < 1e-10, "%s: eigenvalues differ by %g", what, worst);
  /* eigenspaces: for each cluster of equal eigenvalues (inside the k), ‖Φ_Aᵀ M Φ_B‖_F² = its size */
  for (int i = 0; i < k;) {
    int j = i + 1;
    while (j < k && fabs(ea[j] - ea[i]) <= 1e-8 * (1 + fabs(ea[i]))) j++;
    if (j == k) break; /* the last cluster may continue past k: its kept parts may differ */
    double f2 = 0;
    for (int a = i; a < j; a++)
      for (int b = i; b < j; b++) {
        double d = 0;
        for (size_t r = 0; r < n; r++) d += Xa[r + n * a] * M[r] * Xb[r + n * b];
        f2 += d * d;
      }
    CHECK_MSG(fabs(f2 - (j - i)) < 1e-8, "%s: eigenspace of lambda_%d (x%d) differs: %g", what, i, j - i, f2);
    i = j;
  }
  free(ea); free(eb); free(Xa); free(Xb); free(M);
  ss_sparse_free(&W);
}

static void test_block(void) {
  ss_mesh m;
  /* sphere: multiplicities 2l+1 up to 13 inside k = 40, more than the block of 8 */
  CHECK(ss_synth_icosphere(4, &m, NULL) == SS_OK);
  compare_methods(&m, 40, "sphere", SS_EIGS_BLOCK);
  compare_methods(&m, 40, "sphere", SS_EIGS_PRO); /* multiplicities: the completeness check recovers them */
  /* a Krylov size just above k (ncv = k + 10): the block method used to keep all but one block at each
   * restart and gave up after 1,000 restarts (0 of 39 pairs); it now keeps room for 4 blocks */
  {
    ss_sparse W;
    double *M, ea[40], eb[40];
    CHECK(operators(&m, &W, &M) == 0);
    ss_eigs_options o;
    ss_eigs_stats st;
    ss_eigs_default_options(&o);
    o.method = SS_EIGS_ARPACK;
    ss_error e;
    CHECK_MSG(ss_eigs(&W, M, 40, &o, ea, NULL, &e) == SS_OK, "%s", e.msg);
    o.method = SS_EIGS_BLOCK;
    o.ncv = 50;
    o.stats = &st;
    CHECK_MSG(ss_eigs(&W, M, 40, &o, eb, NULL, &e) == SS_OK, "block, ncv 50: %s", e.msg);
    CHECK_MSG(st.restarts <= 100, "block, ncv 50: %d restarts", st.restarts);
    double worst = 0;
    for (int i = 0; i < 40; i++) worst = fmax(worst, fabs(eb[i] - ea[i]) / (1 + fabs(ea[i])));
    CHECK_MSG(worst < 1e-10, "block, ncv 50: eigenvalues differ by %g", worst);
    free(M);
    ss_sparse_free(&W);
  }
  ss_mesh_free(&m);
  /* two components: two exact null pairs deflated */
  {
    ss_mesh a, b;
    CHECK(ss_synth_icosphere(3, &a, NULL) == SS_OK);
    CHECK(ss_synth_icosphere(3, &b, NULL) == SS_OK);
    ss_mesh_alloc(&m, a.nv + b.nv, a.nf + b.nf, NULL);
    memcpy(m.V, a.V, sizeof(double) * 3 * a.nv);
    for (int i = 0; i < b.nv; i++)
      for (int d = 0; d < 3; d++) m.V[3 * (a.nv + i) + d] = 0.7 * b.V[3 * i + d] + (d == 0 ? 5.0 : 0.0);
    memcpy(m.F, a.F, sizeof(int) * 3 * a.nf);
    for (int i = 0; i < 3 * b.nf; i++) m.F[3 * a.nf + i] = b.F[i] + a.nv;
    compare_methods(&m, 30, "two spheres", SS_EIGS_BLOCK);
    compare_methods(&m, 30, "two spheres", SS_EIGS_PRO);
    ss_mesh_free(&m);
    ss_mesh_free(&a);
    ss_mesh_free(&b);
  }
  /* a rectangle (simple eigenvalues), k = 100: partial reorthogonalisation against ARPACK */
  {
    rect_grid(1.3, 1.0, 71, 57, &m);
    compare_methods(&m, 100, "rectangle", SS_EIGS_PRO);
    ss_mesh_free(&m);
  }
  /* AUTO: partial reorthogonalisation below SS_EIGS_BLOCK_MIN_N vertices or 32 pairs, the block
   * method above */
  {
    rect_grid(1.3, 1.0, 131, 121, &m); /* 15,851 vertices */
    CHECK(m.nv >= SS_EIGS_BLOCK_MIN_N);
    ss_sparse W;
    double *M;
    CHECK(operators(&m, &W, &M) == 0);
    double ev[40];
    ss_eigs_options o;
    ss_eigs_stats st;
    ss_eigs_default_options(&o);
    o.stats = &st;
    CHECK(ss_eigs(&W, M, 40, &o, ev, NULL, NULL) == SS_OK);
    CHECK_MSG(st.method == SS_EIGS_BLOCK, "AUTO ran method %d at n = %d, k = 40", st.method, m.nv);
    CHECK(ss_eigs(&W, M, 20, &o, ev, NULL, NULL) == SS_OK);
    CHECK_MSG(st.method == SS_EIGS_PRO, "AUTO ran method %d at k = 20", st.method);
    /* interior shift: the block method needs σ <= 0, ARPACK runs */
    o.method = SS_EIGS_BLOCK;
    o.sigma = 30;
    CHECK(ss_eigs(&W, M, 5, &o, ev, NULL, NULL) == SS_OK);
    CHECK(st.method == SS_EIGS_ARPACK);
    o.method = SS_EIGS_PRO; /* the same for partial reorthogonalisation */
    CHECK(ss_eigs(&W, M, 5, &o, ev, NULL, NULL) == SS_OK);
    CHECK(st.method == SS_EIGS_ARPACK);
    o.sigma = -1e-8;
    o.method = 7;
    CHECK(ss_eigs(&W, M, 5, &o, ev, NULL, NULL) == SS_ERR_INVALID);
    o.method = SS_EIGS_BLOCK;
    o.block = -1;
    CHECK(ss_eigs(&W, M, 5, &o, ev, NULL, NULL) == SS_ERR_INVALID);
    /* Sylvester's inertia from a supernodal factor (a simplicial LDLᵀ in its ordering) = from the
     * simplicial one */
    o.method = SS_EIGS_AUTO;
    o.block = 0;
    CHECK(ss_eigs(&W, M, 5, &o, ev, NULL, NULL) == SS_OK);
    ssi_chol *cs = NULL, *cp = NULL;
    CHECK(ssi_chol_factor(&W, 1.0, M, &cs, NULL) == SS_OK);
    CHECK(ssi_chol_factor_super(&W, 1.0, M, &cp, NULL) == SS_OK);
    int ns = -1, np = -2;
    double tau = ev[4] * 1.001;
    CHECK(ssi_chol_inertia(cs, &W, -tau, M, &ns, NULL) == SS_OK);
    CHECK(ssi_chol_inertia(cp, &W, -tau, M, &np, NULL) == SS_OK);
    int below = 0;
    for (int i = 0; i < 5; i++) below += ev[i] < tau;
    CHECK_MSG(ns == below && np == below, "inertia below 1.001 lambda_4: simplicial %d, supernodal %d, %d expected",
              ns, np, below);
    /* multi-column solves through any workspace slot and in any grouping give the same columns */
    size_t nn = (size_t)m.nv;
    double *B = malloc(sizeof(double) * nn * 9), *X1 = malloc(sizeof(double) * nn * 9), *X2 = malloc(sizeof(double) * nn * 9);
    for (size_t i = 0; i < nn * 9; i++) B[i] = sin(0.37 * (double)i);
    CHECK(ssi_chol_solve(cp, B, X1, 9, NULL) == SS_OK);
    CHECK(ssi_chol_solve_slot(cp, 3, B, X2, 4, NULL) == SS_OK);
    CHECK(ssi_chol_solve_slot(cp, 1, B + nn * 4, X2 + nn * 4, 5, NULL) == SS_OK);
    CHECK(ssi_chol_solve_slot(cp, SSI_CHOL_SLOTS, B, X2, 1, NULL) == SS_ERR_INVALID);
    double dx = 0, xm = 0;
    for (size_t i = 0; i < nn * 9; i++) { dx = fmax(dx, fabs(X1[i] - X2[i])); xm = fmax(xm, fabs(X1[i])); }
    CHECK_MSG(dx <= 1e-12 * xm, "solve through other slots differs by %g", dx);
    CHECK(ssi_chol_solve_slot(cs, 2, B, X2, 9, NULL) == SS_OK);
    dx = 0;
    for (size_t i = 0; i < nn * 9; i++) dx = fmax(dx, fabs(X1[i] - X2[i]));
    CHECK_MSG(dx <= 1e-9 * xm, "simplicial and supernodal solves differ by %g", dx);
    /* a supernodal LLᵀ refuses an indefinite matrix */
    ssi_chol *ci = NULL;
    CHECK(ssi_chol_factor_super(&W, -ev[4], M, &ci, NULL) == SS_ERR_NUMERIC);
    free(B); free(X1); free(X2);
    ssi_chol_free(cs);
    ssi_chol_free(cp);
    free(M);
    ss_sparse_free(&W);
    ss_mesh_free(&m);
  }
}

static void test_faust(void) {
  const char *dir = tl_data_dir();
  if (!dir) {
    SKIP("no data folder: FAUST k=100 check");
    return;
  }
  char path[4096];
  snprintf(path, sizeof path, "%s/faust/tr_reg_000.off", dir);
  ss_mesh m;
  ss_error e;
  if (ss_read_off(path, &m, &e) != SS_OK) {
    CHECK_MSG(0, "%s", e.msg);
    return;
  }
  ss_sparse W;
  double *M;
  CHECK(operators(&m, &W, &M) == 0);
  int k = 100;
  double *ev = malloc(sizeof(double) * k), *X = malloc(sizeof(double) * (size_t)m.nv * k);
  double t0 = ss_time();
  ss_eigs_options o;
  ss_eigs_stats st;
  ss_eigs_default_options(&o);
  o.stats = &st;
  CHECK_MSG(ss_eigs(&W, M, k, &o, ev, X, &e) == SS_OK, "%s", e.msg);
  /* FAUST's pairs come from partial reorthogonalisation (segmentation and matching results depend
   * on the eigenvectors: they must be ARPACK's eigenspaces, checked below) */
  CHECK_MSG(st.method == SS_EIGS_PRO, "AUTO ran method %d on FAUST", st.method);
  printf("FAUST tr_reg_000 (%d vertices): k=100 in %.3f s\n", m.nv, ss_time() - t0);
  CHECK_MSG(fabs(ev[0]) < 1e-8, "lambda_0 = %g", ev[0]);
  CHECK(ev[1] > 1e-3);
  check_accuracy(&W, M, k, ev, X, "FAUST");
  free(ev); free(X); free(M);
  ss_sparse_free(&W);
  compare_methods(&m, k, "FAUST tr_reg_000", SS_EIGS_PRO);
  ss_mesh_free(&m);
}

int main(void) {
  test_sphere();
  test_two_components();
  test_rectangle();
  test_subdivide();
  test_block();
  test_faust();
  TEST_MAIN_END();
}
