/* The caller's own descriptors as probes (ss_fmap_shape.descr, ss_fmap_match_options.no_wks,
 * ss_match_options.ndescr): appended to the base probes as they are (normalised in L²(M)), the WKS
 * given as one's own descriptors with no_wks reproduces the default map, mismatched or non-finite
 * descriptors and an empty probe set are refused; ss_match passes them through. */
#include "specseg/fmap.h"
#include "specseg/laplacian.h"
#include "specseg/match.h"
#include "specseg/spectrum.h"
#include "specseg/synth.h"
#include "testlib.h"

int main(void) {
  ss_error e;
  ss_mesh X = {0}, Y = {0};
  if (ss_synth_humanoid(0, &X, &e) || ss_synth_humanoid(ss_synth_humanoid_pose_count() > 2 ? 2 : 1, &Y, &e)) {
    SKIP("humanoid: %s", e.msg);
    TEST_MAIN_END();
  }
  const int n = X.nv, kev = 20;
  double *evX = malloc(sizeof(double) * kev), *phX = malloc(sizeof(double) * (size_t)n * kev);
  double *evY = malloc(sizeof(double) * kev), *phY = malloc(sizeof(double) * (size_t)n * kev);
  double *MX = malloc(sizeof(double) * n), *MY = malloc(sizeof(double) * n);
  CHECK(ss_mesh_eigs(&X, kev, evX, phX, &e) == SS_OK && ss_mesh_eigs(&Y, kev, evY, phY, &e) == SS_OK);
  CHECK(ss_mass_lumped(&X, SS_MASS_BARYCENTRIC, MX, &e) == SS_OK && ss_mass_lumped(&Y, SS_MASS_BARYCENTRIC, MY, &e) == SS_OK);
  int lm[5] = {0, 0, 0, 0, 0};
  for (int i = 0; i < n; i++) {
    const double *p = X.V + 3 * i;
    if (p[0] > X.V[3 * lm[0]]) lm[0] = i;
    if (p[0] < X.V[3 * lm[1]]) lm[1] = i;
    if (p[1] > X.V[3 * lm[2] + 1]) lm[2] = i;
    if (p[1] < X.V[3 * lm[3] + 1]) lm[3] = i;
    if (p[2] > X.V[3 * lm[4] + 2]) lm[4] = i;
  }
  ss_fmap_match_options o;
  ss_fmap_match_default_options(&o);
  o.k = kev, o.n_energies = 50;
  CHECK(o.no_wks == 0);
  ss_fmap_shape sX = {&X, MX, evX, phX, kev, NULL, 0, NULL, 0}, sY = {&Y, MY, evY, phY, kev, NULL, 0, NULL, 0};

  /* 1. base probes with three descriptors (the coordinates): the default columns, then the three */
  double *D = malloc(sizeof(double) * (size_t)n * 3);
  for (int c = 0; c < 3; c++)
    for (int x = 0; x < n; x++) D[x + (size_t)n * c] = X.V[3 * x + c] + 2.0; /* shifted: not orthogonal to 1 */
  ss_fmap_probes b0 = {0}, b1 = {0};
  CHECK(ss_fmap_base_probes(&sX, 5, lm, &o, 1, &b0, &e) == SS_OK);
  ss_fmap_shape sD = sX;
  sD.descr = D, sD.ndescr = 3;
  CHECK(ss_fmap_base_probes(&sD, 5, lm, &o, 1, &b1, &e) == SS_OK);
  CHECK_MSG(b1.p == b0.p + 3 && b1.nd == b1.p, "p %d vs %d", b1.p, b0.p);
  if (b1.p == b0.p + 3) {
    /* (equal up to the rounding of a wider dgemm) */
    const size_t np = (size_t)kev * (kev + 1) / 2;
    double da = 0, dp = 0;
    for (size_t i = 0; i < (size_t)kev * b0.p; i++) da = fmax(da, fabs(b1.A[i] - b0.A[i]));
    for (size_t i = 0; i < np * b0.p; i++) dp = fmax(dp, fabs(b1.P[i] - b0.P[i]));
    CHECK_MSG(da < 1e-13 && dp < 1e-13, "the default columns moved: %g %g", da, dp);
    double *Dn = malloc(sizeof(double) * (size_t)n * 3), *A = malloc(sizeof(double) * kev * 3), worst = 0;
    for (int c = 0; c < 3; c++) {
      double s = 0;
      for (int x = 0; x < n; x++) s += MX[x] * D[x + (size_t)n * c] * D[x + (size_t)n * c];
      for (int x = 0; x < n; x++) Dn[x + (size_t)n * c] = D[x + (size_t)n * c] / sqrt(s);
    }
    CHECK(ss_fmap_project(n, kev, phX, MX, 3, Dn, A, &e) == SS_OK);
    for (int i = 0; i < kev * 3; i++) worst = fmax(worst, fabs(A[i] - b1.A[(size_t)kev * b0.p + i]));
    CHECK_MSG(worst < 1e-12, "the descriptors' coefficients differ by %g", worst);
    free(Dn), free(A);
  }
  ss_fmap_probes_free(&b0), ss_fmap_probes_free(&b1);

  /* 2. the kept WKS columns given as one's own descriptors, with no_wks: the same map, C up to rounding */
  const int ne = o.n_energies, step = o.descr_step, nd = (ne + step - 1) / step;
  double *WX = malloc(sizeof(double) * (size_t)n * ne), *WY = malloc(sizeof(double) * (size_t)n * ne);
  double *DX = malloc(sizeof(double) * (size_t)n * nd), *DY = malloc(sizeof(double) * (size_t)n * nd);
  CHECK(ss_wks(n, kev, evX, phX, MX, ne, o.sigma_factor, WX, &e) == SS_OK);
  CHECK(ss_wks(n, kev, evY, phY, MY, ne, o.sigma_factor, WY, &e) == SS_OK);
  for (int j = 0; j < nd; j++) {
    memcpy(DX + (size_t)n * j, WX + (size_t)n * j * step, sizeof(double) * n);
    memcpy(DY + (size_t)n * j, WY + (size_t)n * j * step, sizeof(double) * n);
  }
  int *map0 = malloc(sizeof(int) * n), *map1 = malloc(sizeof(int) * n);
  double *C0 = malloc(sizeof(double) * kev * kev), *C1 = malloc(sizeof(double) * kev * kev);
  CHECK(ss_fmap_match(&sX, &sY, 5, lm, lm, 0, NULL, NULL, SS_PROBE_RAW, &o, map0, C0, &e) == SS_OK);
  ss_fmap_shape uX = sX, uY = sY;
  uX.descr = DX, uY.descr = DY, uX.ndescr = uY.ndescr = nd;
  ss_fmap_match_options on = o;
  on.no_wks = 1;
  CHECK(ss_fmap_match(&uX, &uY, 5, lm, lm, 0, NULL, NULL, SS_PROBE_RAW, &on, map1, C1, &e) == SS_OK);
  int same = 0;
  double dc = 0;
  for (int i = 0; i < n; i++) same += map0[i] == map1[i];
  for (int i = 0; i < kev * kev; i++) dc = fmax(dc, fabs(C0[i] - C1[i]));
  CHECK_MSG(same == n && dc < 1e-8, "WKS as own descriptors: %d of %d equal, max |dC| %g", same, n, dc);
  /* without no_wks the WKS enters twice: a different (but valid) problem */
  CHECK(ss_fmap_match(&uX, &uY, 5, lm, lm, 0, NULL, NULL, SS_PROBE_RAW, &o, map1, C1, &e) == SS_OK);
  dc = 0;
  for (int i = 0; i < kev * kev; i++) dc = fmax(dc, fabs(C0[i] - C1[i]));
  CHECK_MSG(dc > 1e-6, "descriptors beside the WKS change C (%g)", dc);

  /* 3. refusals */
  uY.ndescr = nd - 1;
  CHECK(ss_fmap_match(&uX, &uY, 5, lm, lm, 0, NULL, NULL, SS_PROBE_RAW, &o, map1, NULL, &e) == SS_ERR_INVALID &&
        strstr(e.msg, "descriptors"));
  uY.ndescr = nd;
  double keep = DX[7];
  DX[7] = NAN;
  CHECK(ss_fmap_match(&uX, &uY, 5, lm, lm, 0, NULL, NULL, SS_PROBE_RAW, &o, map1, NULL, &e) == SS_ERR_INVALID &&
        strstr(e.msg, "not finite"));
  DX[7] = keep;
  ss_fmap_probes b2 = {0};
  CHECK(ss_fmap_base_probes(&sX, 0, NULL, &on, 0, &b2, &e) == SS_ERR_INVALID && strstr(e.msg, "no WKS"));
  uX.descr = NULL;
  CHECK(ss_fmap_base_probes(&uX, 5, lm, &o, 0, &b2, &e) == SS_ERR_INVALID);

  /* 4. ss_match passes them on: WKS as descriptors + no_wks = the default pipeline's map (STD) */
  ss_match_options mo;
  ss_match_default_options(&mo);
  CHECK(mo.ndescr == 0 && !mo.descrX && !mo.descrY);
  mo.probes = SS_PROBES_STD, mo.fmap.k = kev, mo.fmap.n_energies = ne;
  mo.fmap.descr_k = 0; /* the WKS from the first k = kev eigenpairs, as DX / DY (the default takes 100) */
  ss_match_result r0 = {0}, r1 = {0};
  CHECK(ss_match(&X, &Y, 5, lm, lm, &mo, &r0, &e) == SS_OK);
  /* ss_match computes its own eigenpairs (k = kev): recompute the WKS from the same solver as above */
  mo.ndescr = nd, mo.descrX = DX, mo.descrY = DY, mo.fmap.no_wks = 1;
  CHECK(ss_match(&X, &Y, 5, lm, lm, &mo, &r1, &e) == SS_OK);
  same = 0;
  for (int i = 0; r0.map && r1.map && i < n; i++) same += r0.map[i] == r1.map[i];
  CHECK_MSG(same >= n * 0.999, "ss_match with the WKS as descriptors: %d of %d equal", same, n);
  mo.descrY = NULL;
  ss_match_result r2 = {0};
  CHECK(ss_match(&X, &Y, 5, lm, lm, &mo, &r2, &e) == SS_ERR_INVALID);
  ss_match_result_free(&r0), ss_match_result_free(&r1), ss_match_result_free(&r2);

  free(evX), free(phX), free(evY), free(phY), free(MX), free(MY), free(D), free(WX), free(WY), free(DX), free(DY);
  free(map0), free(map1), free(C0), free(C1);
  ss_mesh_free(&X), ss_mesh_free(&Y);
  TEST_MAIN_END();
}
