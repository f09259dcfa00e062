/* The split functional-map pipeline: base / extra probes built apart equal the virtual column list
 * built from the public WKS functions; a system assembled once and solved with extra blocks equals
 * ss_fmap_solve on the concatenated probes; ss_fmap_match equals the pieces called by hand. */
#include "specseg/fmap.h"
#include "specseg/geodesic.h"
#include "specseg/laplacian.h"
#include "specseg/mesh.h"
#include "specseg/synth.h"
#include "specseg/spectrum.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* OpenBLAS (cblas.h's complex.h would define I) */
void openblas_set_num_threads(int num_threads);
int openblas_get_num_threads(void);

static unsigned rng_state = 77u;
static double urand(void) {
  rng_state = rng_state * 1664525u + 1013904223u;
  return (rng_state >> 8) / 16777216.0;
}

static void sym_blocks(int k, int nd, double *D) {
  for (int d = 0; d < nd; d++)
    for (int a = 0; a < k; a++)
      for (int b = 0; b <= a; b++) D[(size_t)k * k * d + a + k * b] = D[(size_t)k * k * d + b + k * a] = urand() - 0.5;
}

static void pack(int k, int nd, const double *D, double *P) {
  size_t kk = (size_t)k * (k + 1) / 2;
  for (int d = 0; d < nd; d++)
    for (int b = 0; b < k; b++)
      for (int a = 0; a <= b; a++) P[kk * d + (size_t)b * (b + 1) / 2 + a] = D[(size_t)k * k * d + a + k * b];
}

/* system + extras == ss_fmap_solve on [base | √w · extras], with and without the extras' operators */
static void test_system_vs_solve(void) {
  const int kS = 7, kT = 6, p = 5, q = 3, m = kS * kT;
  double A[7 * 8], B[6 * 8], lS[7], lT[6], DS[8 * 49], DT[8 * 36];
  for (int i = 0; i < kS * (p + q); i++) A[i] = urand() - 0.5;
  for (int i = 0; i < kT * (p + q); i++) B[i] = urand() - 0.5;
  for (int i = 0; i < kS; i++) lS[i] = i * 1.3 + urand();
  for (int i = 0; i < kT; i++) lT[i] = i * 1.1 + urand();
  sym_blocks(kS, p + q, DS);
  sym_blocks(kT, p + q, DT);
  double PS[8 * 28], PT[8 * 21];
  pack(kS, p + q, DS, PS);
  pack(kT, p + q, DT, PT);
  const double wx = 0.37;
  for (int fix = 0; fix <= 1; fix++)
    for (int dcomm = 0; dcomm <= 1; dcomm++) {
      ss_fmap_weights w = {0.9, 0.05, 1.3, fix, 0.8, 0};
      ss_fmap_probes bS = {kS, p, p, A, PS, 0, NULL}, bT = {kT, p, p, B, PT, 0, NULL};
      ss_fmap_probes xS = {kS, q, dcomm ? q : 0, A + kS * p, PS + 28 * p, 0, NULL}, xT = {kT, q, dcomm ? q : 0, B + kT * p, PT + 21 * p, 0, NULL};
      ss_fmap_system *sys = NULL;
      double C1[42], C2[42], A2[7 * 8], B2[6 * 8], D2S[8 * 49], D2T[8 * 36];
      CHECK(ss_fmap_system_new(kS, kT, lS, lT, &bS, &bT, &w, &sys, NULL) == SS_OK);
      CHECK(ss_fmap_system_solve(sys, &xS, &xT, wx, dcomm, C1, NULL) == SS_OK);
      /* reference: extras' data columns scaled by √wx; their operators only with dcomm */
      memcpy(A2, A, sizeof A2);
      memcpy(B2, B, sizeof B2);
      for (int i = kS * p; i < kS * (p + q); i++) A2[i] *= sqrt(wx);
      for (int i = kT * p; i < kT * (p + q); i++) B2[i] *= sqrt(wx);
      memcpy(D2S, DS, sizeof D2S);
      memcpy(D2T, DT, sizeof D2T);
      CHECK(ss_fmap_solve(kS, kT, p + q, A2, B2, lS, lT, dcomm ? p + q : p, D2S, D2T, &w, C2, NULL) == SS_OK);
      double d = 0, s = 0;
      for (int i = 0; i < m; i++) d = fmax(d, fabs(C1[i] - C2[i])), s = fmax(s, fabs(C2[i]));
      CHECK_MSG(d <= 1e-10 * s, "fix %d dcomm %d: max |C_sys - C_solve| = %g (scale %g)", fix, dcomm, d, s);
      /* the base alone: no extras */
      CHECK(ss_fmap_system_solve(sys, NULL, NULL, 0.0, 0, C1, NULL) == SS_OK);
      CHECK(ss_fmap_solve(kS, kT, p, A, B, lS, lT, p, DS, DT, &w, C2, NULL) == SS_OK);
      d = 0;
      for (int i = 0; i < m; i++) d = fmax(d, fabs(C1[i] - C2[i]));
      CHECK_MSG(d <= 1e-10 * s, "fix %d: base alone differs by %g", fix, d);
      /* mismatched blocks are refused */
      ss_fmap_probes bad = xT;
      bad.p = q - 1;
      ss_error e;
      CHECK(ss_fmap_system_solve(sys, &xS, &bad, wx, dcomm, C1, &e) == SS_ERR_INVALID);
      CHECK(ss_fmap_system_solve(sys, &xS, &xT, -1.0, dcomm, C1, &e) == SS_ERR_INVALID);
      ss_fmap_system_free(sys);
    }
}

/* The probe cache (ss_fmap_probe_cache_compute) changes no number of the base probes: with an
 * entry for the call's options they are byte for byte those computed without it (WKS columns,
 * landmark operators from the triple products, orientation operators), also when the triple products
 * reach further than the call's basis; an entry of other options is not used. */
static void test_probe_cache(void) {
  /* byte for byte with one BLAS thread (the CLI's): OpenBLAS's threads split a product by its
   * columns, and the kernels' edge paths round differently, so the triple products for kt columns
   * and for kd < kt may differ in the last bit with several */
  const int blas = openblas_get_num_threads();
  openblas_set_num_threads(1);
  ss_mesh mesh;
  CHECK(ss_synth_icosphere(3, &mesh, NULL) == SS_OK);
  for (int i = 0; i < mesh.nv; i++) {
    double *v = mesh.V + 3 * i;
    v[0] *= 1.3 + 0.2 * v[1], v[2] *= 0.85;
  }
  const int n = mesh.nv, kev = 30, nl = 3;
  double *ev = malloc(sizeof(double) * kev), *phi = malloc(sizeof(double) * n * kev), *M = malloc(sizeof(double) * n);
  CHECK(ss_mesh_eigs(&mesh, kev, ev, phi, NULL) == SS_OK);
  CHECK(ss_mass_lumped(&mesh, SS_MASS_BARYCENTRIC, M, NULL) == SS_OK);
  int lm[3] = {7, 150, 420};
  ss_fmap_match_options o;
  ss_fmap_match_default_options(&o);
  o.k = 12, o.n_energies = 30, o.descr_step = 4, o.descr_k = 20, o.w_orient = 1e-3;
  const size_t kk = (size_t)o.k * (o.k + 1) / 2;
  ss_fmap_shape s = {&mesh, M, ev, phi, kev, NULL, 0, NULL, 0};
  for (int kt = 0; kt <= 26; kt += 26) {
    ss_fmap_probes ref = {0}, got = {0};
    ss_fmap_probe_cache c;
    s.cache = NULL, s.ncache = 0;
    CHECK(ss_fmap_base_probes(&s, nl, lm, &o, 1, &ref, NULL) == SS_OK);
    CHECK(ss_fmap_probe_cache_compute(&s, &o, 1, kt, &c, NULL) == SS_OK);
    CHECK(c.nwks == 8 && c.A && c.P && c.O && c.T && c.kt == (kt > 20 ? kt : 20));
    s.cache = &c, s.ncache = 1;
    CHECK(ss_fmap_base_probes(&s, nl, lm, &o, 1, &got, NULL) == SS_OK);
    CHECK(got.p == ref.p && got.nd == ref.nd && got.no == ref.no && ref.no == 8);
    CHECK_MSG(got.p == ref.p && !memcmp(got.A, ref.A, sizeof(double) * o.k * ref.p) &&
                  !memcmp(got.P, ref.P, sizeof(double) * kk * ref.nd) &&
                  !memcmp(got.O, ref.O, sizeof(double) * o.k * o.k * ref.no),
              "kt %d: cached base probes differ from the computed ones", kt);
    ss_fmap_probes_free(&got);
    /* other options: the entry is not used */
    ss_fmap_match_options o2 = o;
    o2.sigma_factor = 6.0;
    ss_fmap_probes r2 = {0}, g2 = {0};
    s.cache = NULL, s.ncache = 0;
    CHECK(ss_fmap_base_probes(&s, nl, lm, &o2, 1, &r2, NULL) == SS_OK);
    s.cache = &c, s.ncache = 1;
    CHECK(ss_fmap_base_probes(&s, nl, lm, &o2, 1, &g2, NULL) == SS_OK);
    CHECK(g2.p == r2.p && !memcmp(g2.A, r2.A, sizeof(double) * o.k * r2.p) && !memcmp(g2.P, r2.P, sizeof(double) * kk * r2.nd));
    CHECK(memcmp(g2.A, ref.A, sizeof(double) * o.k * 8)); /* the WKS of σ 6 are other functions */
    ss_fmap_probes_free(&r2), ss_fmap_probes_free(&g2), ss_fmap_probes_free(&ref);
    ss_fmap_probe_cache_free(&c);
  }
  /* more triple products than eigenpairs: refused */
  ss_fmap_probe_cache c;
  ss_error e;
  s.cache = NULL, s.ncache = 0;
  CHECK(ss_fmap_probe_cache_compute(&s, &o, 1, kev + 1, &c, &e) == SS_ERR_INVALID);
  free(ev), free(phi), free(M);
  ss_mesh_free(&mesh);
  openblas_set_num_threads(blas);
}

/* A system too ill-conditioned for the single-precision Cholesky with refinement (condition ~1e13:
 * the data term has rank k_T, the Laplacian term weighs 1e-13) still gets a backward-stable
 * solution: the double factorisation takes over. */
static void test_ill_conditioned(void) {
  enum { kS = 4, kT = 4, m = kS * kT };
  double A[kS], B[kT], lS[kS], lT[kT], C[m];
  for (int i = 0; i < kS; i++) A[i] = urand() + 0.5, lS[i] = 1.0 + i;
  for (int i = 0; i < kT; i++) B[i] = urand() - 0.5, lT[i] = 1.3 + i;
  ss_fmap_weights w = {1.0, 1e-13, 0, 0, 0, 0};
  ss_fmap_probes S = {kS, 1, 0, A, NULL, 0, NULL}, T = {kT, 1, 0, B, NULL, 0, NULL};
  ss_fmap_system *sys = NULL;
  CHECK(ss_fmap_system_new(kS, kT, lS, lT, &S, &T, &w, &sys, NULL) == SS_OK);
  CHECK(ss_fmap_system_solve(sys, NULL, NULL, 0.0, 0, C, NULL) == SS_OK);
  ss_fmap_system_free(sys);
  /* N x − b with N = A Aᵀ ⊗ I + w_l diag((λ_T,r − λ_S,c)²), b = vec(B Aᵀ) */
  double worst = 0, nn = 0, xn = 0;
  for (int c = 0; c < kS; c++)
    for (int r = 0; r < kT; r++) {
      double d = lT[r] - lS[c], v = w.w_lap * d * d * C[r + kT * c] - B[r] * A[c];
      for (int c2 = 0; c2 < kS; c2++) v += A[c] * A[c2] * C[r + kT * c2];
      worst = fmax(worst, fabs(v));
      xn = fmax(xn, fabs(C[r + kT * c]));
    }
  for (int c = 0; c < kS; c++) nn += A[c] * A[c];
  CHECK_MSG(worst <= 1e-13 * nn * xn, "ill-conditioned system: residual %g (|N| %g, |x| %g)", worst, nn, xn);
}

/* A data weight near DBL_MAX overflows the normal equations (the diagonal infinite, the solution 0,
 * once returned with status OK): an error now, not a zero functional map that the point map would
 * turn into a meaningless map. */
static void test_overflow(void) {
  enum { kS = 4, kT = 4, m = kS * kT };
  double A[kS] = {1.6, 1.9, 2.2, 1.7}, B[kT] = {0.1, -0.3, 0.2, 0.4}, lS[kS], lT[kT], C[m];
  for (int i = 0; i < kS; i++) lS[i] = 1.0 + i, lT[i] = 1.3 + i;
  ss_fmap_weights w = {1e308, 1.0, 0, 0, 0, 0};
  ss_fmap_probes S = {kS, 1, 0, A, NULL, 0, NULL}, T = {kT, 1, 0, B, NULL, 0, NULL};
  ss_fmap_system *sys = NULL;
  ss_error e = {{0}};
  ss_status st = ss_fmap_system_new(kS, kT, lS, lT, &S, &T, &w, &sys, &e);
  if (st == SS_OK) st = ss_fmap_system_solve(sys, NULL, NULL, 0.0, 0, C, &e);
  ss_fmap_system_free(sys);
  CHECK_MSG(st == SS_ERR_NUMERIC && e.msg[0], "data weight 1e308: status %d (%s)", (int)st, e.msg);
  /* the same system at weight 1: a finite, non-zero functional map */
  w.w_descr = 1.0;
  CHECK(ss_fmap_system_new(kS, kT, lS, lT, &S, &T, &w, &sys, &e) == SS_OK);
  CHECK(ss_fmap_system_solve(sys, NULL, NULL, 0.0, 0, C, &e) == SS_OK);
  ss_fmap_system_free(sys);
  double mx = 0;
  for (int i = 0; i < m; i++) mx = fmax(mx, fabs(C[i]));
  CHECK(isfinite(mx) && mx > 0);
}

/* base + extra probes == the virtual column list from ss_wks / ss_wks_landmarks / ss_wks_filter,
 * every step-th column kept, normalised, projected */
static void test_probes_split(void) {
  ss_mesh mesh;
  CHECK(ss_synth_icosphere(3, &mesh, NULL) == SS_OK);
  for (int i = 0; i < mesh.nv; i++) { /* break the symmetry: distinct eigenvalues */
    double *v = mesh.V + 3 * i;
    v[0] *= 1.4 + 0.2 * v[1], v[2] *= 0.8;
  }
  const int n = mesh.nv, k = 20, ne = 30, step = 4, nl = 3, nx = 2;
  double *ev = malloc(sizeof(double) * k), *phi = malloc(sizeof(double) * n * k), *M = malloc(sizeof(double) * n);
  CHECK(ss_mesh_eigs(&mesh, k, ev, phi, NULL) == SS_OK);
  CHECK(ss_mass_lumped(&mesh, SS_MASS_BARYCENTRIC, M, NULL) == SS_OK);
  int lm[3] = {5, 100, 400};
  double *X = malloc(sizeof(double) * n * nx);
  for (int i = 0; i < n; i++) X[i] = mesh.V[3 * i] > 0, X[i + n] = mesh.V[3 * i + 2] > 0.3;
  ss_fmap_match_options o;
  ss_fmap_match_default_options(&o);
  o.k = k, o.n_energies = ne, o.descr_step = step;
  ss_fmap_shape s = {&mesh, M, ev, phi, k, NULL, 0, NULL, 0};
  ss_fmap_probes base, wave, raw;
  CHECK(ss_fmap_base_probes(&s, nl, lm, &o, 1, &base, NULL) == SS_OK);
  CHECK(ss_fmap_extra_probes(&s, nl, nx, X, SS_PROBE_WAVE, &o, 1, &wave, NULL) == SS_OK);
  CHECK(ss_fmap_extra_probes(&s, nl, nx, X, SS_PROBE_RAW, &o, 0, &raw, NULL) == SS_OK);
  /* the virtual list, column by column */
  int nall = ne * (1 + nl + nx);
  double *L = malloc(sizeof(double) * (size_t)n * nall);
  CHECK(ss_wks(n, k, ev, phi, M, ne, 7.0, L, NULL) == SS_OK);
  CHECK(ss_wks_landmarks(n, k, ev, phi, M, ne, 7.0, nl, lm, L + (size_t)n * ne, NULL) == SS_OK);
  CHECK(ss_wks_filter(n, k, ev, phi, M, ne, 7.0, nx, X, L + (size_t)n * ne * (1 + nl), NULL) == SS_OK);
  int nb = (ne * (1 + nl) + step - 1) / step, nw = 0;
  for (int c = nb * step; c < nall; c += step) nw++;
  CHECK(base.p == nb && wave.p == nw && raw.p == nx && base.nd == nb && wave.nd == nw && raw.nd == 0);
  double *a = malloc(sizeof(double) * k), dmax = 0, pmax = 0, area = 0;
  double *P = malloc(sizeof(double) * (size_t)k * (k + 1) / 2);
  for (int i = 0; i < n; i++) area += M[i]; /* the probes' operators are those at unit area: x sqrt(area) */
  for (int c = 0, col = 0; c < nall && base.p == nb && wave.p == nw; c += step, col++) {
    const ss_fmap_probes *pr = col < nb ? &base : &wave;
    int j = col < nb ? col : col - nb;
    CHECK(ss_fmap_project(n, k, phi, M, 1, L + (size_t)n * c, a, NULL) == SS_OK);
    CHECK(ss_fmap_mult_operators_packed(n, k, phi, M, 1, L + (size_t)n * c, P, NULL) == SS_OK);
    for (int i = 0; i < k; i++) dmax = fmax(dmax, fabs(a[i] - pr->A[i + (size_t)k * j]));
    for (int i = 0; i < k * (k + 1) / 2; i++) pmax = fmax(pmax, fabs(P[i] * sqrt(area) - pr->P[i + (size_t)k * (k + 1) / 2 * j]));
  }
  CHECK_MSG(dmax < 1e-10 && pmax < 1e-10, "split probes differ from the virtual list: %g, %g", dmax, pmax);
  /* raw extras: normalised indicator coefficients */
  for (int j = 0; j < nx; j++) {
    double nrm = 0;
    for (int i = 0; i < n; i++) nrm += M[i] * X[i + (size_t)n * j] * X[i + (size_t)n * j];
    CHECK(ss_fmap_project(n, k, phi, M, 1, X + (size_t)n * j, a, NULL) == SS_OK);
    double d = 0;
    for (int i = 0; i < k; i++) d = fmax(d, fabs(a[i] / sqrt(nrm) - raw.A[i + (size_t)k * j]));
    CHECK_NEAR(d, 0, 1e-12);
  }
  /* bad input */
  ss_error e;
  int badlm[3] = {5, n, 2};
  ss_fmap_probes t;
  CHECK(ss_fmap_base_probes(&s, nl, badlm, &o, 1, &t, &e) == SS_ERR_INVALID);
  o.k = k + 1;
  CHECK(ss_fmap_base_probes(&s, nl, lm, &o, 1, &t, &e) == SS_ERR_INVALID);
  ss_fmap_probes_free(&base), ss_fmap_probes_free(&wave), ss_fmap_probes_free(&raw);
  free(ev), free(phi), free(M), free(X), free(L), free(a), free(P);
  ss_mesh_free(&mesh);
}

/* descr_k: 0 and k are the same construction bit for bit; descr_k = kd > k gives the probes of the
 * kd-basis construction truncated to the first k coefficients (the same functions, projected on
 * fewer eigenfunctions), for the base and the wave-filtered extras alike */
static void test_descr_k(void) {
  ss_mesh mesh;
  CHECK(ss_synth_icosphere(3, &mesh, NULL) == SS_OK);
  for (int i = 0; i < mesh.nv; i++) {
    double *v = mesh.V + 3 * i;
    v[0] *= 1.4 + 0.2 * v[1], v[2] *= 0.8;
  }
  const int n = mesh.nv, k = 12, kd = 30, ne = 30, step = 4, nl = 3, nx = 2;
  double *ev = malloc(sizeof(double) * kd), *phi = malloc(sizeof(double) * n * kd), *M = malloc(sizeof(double) * n);
  CHECK(ss_mesh_eigs(&mesh, kd, ev, phi, NULL) == SS_OK);
  CHECK(ss_mass_lumped(&mesh, SS_MASS_BARYCENTRIC, M, NULL) == SS_OK);
  int lm[3] = {5, 100, 400};
  double *X = malloc(sizeof(double) * n * nx);
  for (int i = 0; i < n; i++) X[i] = mesh.V[3 * i] > 0, X[i + n] = mesh.V[3 * i + 2] > 0.3;
  ss_fmap_match_options o;
  ss_fmap_match_default_options(&o);
  o.k = k, o.n_energies = ne, o.descr_step = step;
  ss_fmap_shape s = {&mesh, M, ev, phi, kd, NULL, 0, NULL, 0};
  ss_fmap_probes b0, bk, w0, wk, bd, wd, bbig, wbig;
  CHECK(o.descr_k == 0);
  CHECK(ss_fmap_base_probes(&s, nl, lm, &o, 1, &b0, NULL) == SS_OK);
  CHECK(ss_fmap_extra_probes(&s, nl, nx, X, SS_PROBE_WAVE, &o, 1, &w0, NULL) == SS_OK);
  o.descr_k = k;
  CHECK(ss_fmap_base_probes(&s, nl, lm, &o, 1, &bk, NULL) == SS_OK);
  CHECK(ss_fmap_extra_probes(&s, nl, nx, X, SS_PROBE_WAVE, &o, 1, &wk, NULL) == SS_OK);
  const size_t kk = (size_t)k * (k + 1) / 2;
  CHECK(b0.p == bk.p && w0.p == wk.p);
  CHECK(!memcmp(b0.A, bk.A, sizeof(double) * k * b0.p) && !memcmp(b0.P, bk.P, sizeof(double) * kk * b0.p));
  CHECK(!memcmp(w0.A, wk.A, sizeof(double) * k * w0.p) && !memcmp(w0.P, wk.P, sizeof(double) * kk * w0.p));
  o.descr_k = kd;
  CHECK(ss_fmap_base_probes(&s, nl, lm, &o, 1, &bd, NULL) == SS_OK);
  CHECK(ss_fmap_extra_probes(&s, nl, nx, X, SS_PROBE_WAVE, &o, 1, &wd, NULL) == SS_OK);
  o.descr_k = 0, o.k = kd;
  CHECK(ss_fmap_base_probes(&s, nl, lm, &o, 1, &bbig, NULL) == SS_OK);
  CHECK(ss_fmap_extra_probes(&s, nl, nx, X, SS_PROBE_WAVE, &o, 1, &wbig, NULL) == SS_OK);
  CHECK(bd.k == k && bd.p == bbig.p && wd.p == wbig.p);
  double da = 0, dp = 0, ddiff = 0;
  for (int t = 0; t < 2; t++) {
    const ss_fmap_probes *a = t ? &wd : &bd, *b = t ? &wbig : &bbig, *c = t ? &w0 : &b0;
    for (int j = 0; j < a->p && a->p == b->p; j++) {
      for (int i = 0; i < k; i++) {
        da = fmax(da, fabs(a->A[i + (size_t)k * j] - b->A[i + (size_t)kd * j]));
        ddiff = fmax(ddiff, fabs(a->A[i + (size_t)k * j] - c->A[i + (size_t)k * j]));
      }
      for (size_t i = 0; i < kk; i++) dp = fmax(dp, fabs(a->P[i + kk * j] - b->P[i + (size_t)kd * (kd + 1) / 2 * j]));
    }
  }
  CHECK_MSG(da < 1e-12 && dp < 1e-12, "descr_k %d probes are not the k %d probes truncated: %g %g", kd, kd, da, dp);
  CHECK_MSG(ddiff > 1e-3, "descr_k %d probes equal the k-basis ones (%g): the option has no effect", kd, ddiff);
  /* descr_k below k, or more than the shape has, is refused */
  ss_error e;
  ss_fmap_probes t;
  o.k = k, o.descr_k = k - 1;
  CHECK(ss_fmap_base_probes(&s, nl, lm, &o, 1, &t, &e) == SS_ERR_INVALID);
  o.descr_k = kd + 1;
  CHECK(ss_fmap_base_probes(&s, nl, lm, &o, 1, &t, &e) == SS_ERR_INVALID);
  ss_fmap_probes *all[] = {&b0, &bk, &w0, &wk, &bd, &wd, &bbig, &wbig};
  for (int i = 0; i < 8; i++) ss_fmap_probes_free(all[i]);
  free(ev), free(phi), free(M), free(X);
  ss_mesh_free(&mesh);
}

/* NULLs and bad sizes are reported, never dereferenced */
static void test_bad_input(void) {
  ss_error e;
  double C[4];
  int map[4];
  ss_fmap_system *sys = (ss_fmap_system *)1;
  CHECK(ss_fmap_system_solve(NULL, NULL, NULL, 0, 0, C, &e) == SS_ERR_INVALID);
  CHECK(ss_fmap_system_new(2, 2, C, C, NULL, NULL, NULL, &sys, &e) == SS_ERR_INVALID && sys == NULL);
  ss_fmap_probes a = {2, 1, 0, C, NULL, 0, NULL}, b = {3, 1, 0, C, NULL, 0, NULL};
  ss_fmap_weights w = {1, 0, 0, 0, 0, 0};
  CHECK(ss_fmap_system_new(2, 2, C, C, &a, &b, &w, &sys, &e) == SS_ERR_INVALID && sys == NULL);
  CHECK(ss_fmap_system_new(100000, 100000, C, C, &a, &a, &w, &sys, &e) == SS_ERR_INVALID);
  CHECK(ss_fmap_match_finish(NULL, NULL, NULL, C, map, NULL, &e) == SS_ERR_INVALID);
  CHECK(ss_fmap_pair_weights(NULL, NULL, NULL, &w, &e) == SS_ERR_INVALID);
  ss_fmap_probes out;
  CHECK(ss_fmap_base_probes(NULL, 0, NULL, NULL, 0, &out, &e) == SS_ERR_INVALID);
  CHECK(ss_fmap_extra_probes(NULL, 0, 0, NULL, SS_PROBE_RAW, NULL, 0, &out, &e) == SS_ERR_INVALID);
  CHECK(ss_geodesic_lower_bound(NULL, NULL, 0, 1) == 0.0);
}

int main(void) {
  test_bad_input();
  test_system_vs_solve();
  test_ill_conditioned();
  test_overflow();
  test_probe_cache();
  test_probes_split();
  test_descr_k();
  TEST_MAIN_END();
}
