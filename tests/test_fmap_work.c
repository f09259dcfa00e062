/* The functional-map solver's shared buffers (fmap/fmap_work.h): systems assembled and solved in one
 * work give the very bits the public ss_fmap_system_new / ss_fmap_system_solve give, whatever the
 * work held before (a larger system's leftovers, a system of the same size, none), and a work too
 * small for a system leaves its solve to allocate. A whole match in a work with a ZoomOut plan made
 * beforehand (ssi_fmap_match_in) gives the bits of ss_fmap_match, and again with the same plan. */
#include "specseg/fmap.h"
#include "specseg/match.h"
#include "specseg/synth.h"
#include "fmap/fmap_work.h"
#include "fmap_random.h"
#include "testlib.h"

static unsigned rng = 7u;

/* one pair of size k: base probes, extra probes and eigenvalues */
typedef struct pair {
  int k;
  ss_fmap_probes bS, bT, xS, xT;
  double *eS, *eT;
  ss_fmap_weights w;
} pair;

static void pair_make(int k, pair *q) {
  memset(q, 0, sizeof *q);
  q->k = k;
  fr_random_probes(k, k + 4, 3, 1, &rng, &q->bS), fr_random_probes(k, k + 4, 3, 1, &rng, &q->bT);
  fr_random_probes(k, 5, 2, 0, &rng, &q->xS), fr_random_probes(k, 5, 2, 0, &rng, &q->xT);
  q->eS = malloc(sizeof(double) * k), q->eT = malloc(sizeof(double) * k);
  for (int i = 0; i < k; i++) q->eS[i] = 0.1 * i + 0.01 * fr_urand(&rng), q->eT[i] = 0.1 * i + 0.01 * fr_urand(&rng);
  q->eS[0] = q->eT[0] = 0;
  q->w = (ss_fmap_weights){1.0, 0.5, 0.1, 1, 1.0, 0.01};
}

static void pair_free(pair *q) {
  ss_fmap_probes_free(&q->bS), ss_fmap_probes_free(&q->bT), ss_fmap_probes_free(&q->xS), ss_fmap_probes_free(&q->xT);
  free(q->eS), free(q->eT);
}

/* the base solve and the solve with the extra block, through the public functions (work NULL) or
 * in the work: C0, C1 (k x k each) */
static int solve_both(const pair *q, ssi_fmap_work *work, double *C0, double *C1) {
  ss_error e;
  ss_fmap_system *s = NULL;
  int ok = work ? ssi_fmap_system_new_in(q->k, q->k, q->eS, q->eT, &q->bS, &q->bT, &q->w, work, &s, &e) == SS_OK
                : ss_fmap_system_new(q->k, q->k, q->eS, q->eT, &q->bS, &q->bT, &q->w, &s, &e) == SS_OK;
  if (ok)
    ok = work ? ssi_fmap_system_solve_in(s, NULL, NULL, 0, 0, work, C0, &e) == SS_OK &&
                    ssi_fmap_system_solve_in(s, &q->xS, &q->xT, 0.7, 1, work, C1, &e) == SS_OK
              : ss_fmap_system_solve(s, NULL, NULL, 0, 0, C0, &e) == SS_OK &&
                    ss_fmap_system_solve(s, &q->xS, &q->xT, 0.7, 1, C1, &e) == SS_OK;
  ss_fmap_system_free(s);
  return ok;
}

static int same_bits(const double *a, const double *b, int n) { return !memcmp(a, b, sizeof(double) * (size_t)n); }

/* two poses of the synthetic humanoid, WKS and the orientation term alone, ZoomOut 20 -> 60 on a
 * quarter of X's vertices: ss_fmap_match (its own plan) against ssi_fmap_match_in with one plan made
 * once (the match's descriptor candidates share it so) */
static void test_planned_match(void) {
  ss_error e = {{0}};
  ss_mesh X = {0}, Y = {0};
  ss_shape_prep pX = {0}, pY = {0};
  const int kev = 60;
  if (ss_synth_humanoid(0, &X, &e) || ss_synth_humanoid(5, &Y, &e) || ss_shape_prep_compute_spectral(&X, kev, &pX, &e) ||
      ss_shape_prep_compute_spectral(&Y, kev, &pY, &e)) {
    CHECK_MSG(0, "%s", e.msg);
    return;
  }
  ss_fmap_match_options o;
  ss_fmap_match_default_options(&o);
  o.k = 20, o.zoomout_kmax = kev, o.zoomout_step = 5, o.zoomout_samples = X.nv / 4, o.w_orient = 0.001;
  const ss_fmap_shape sX = {&X, pX.M, pX.evals, pX.evecs, kev, NULL, 0, NULL, 0},
                      sY = {&Y, pY.M, pY.evals, pY.evecs, kev, NULL, 0, NULL, 0};
  const int n = X.nv, kk = kev * kev;
  int *m0 = malloc(sizeof(int) * n), *m1 = malloc(sizeof(int) * n);
  double *C0 = malloc(sizeof(double) * kk), *C1 = malloc(sizeof(double) * kk);
  CHECK(ss_fmap_match(&sX, &sY, 0, NULL, NULL, 0, NULL, NULL, SS_PROBE_RAW, &o, m0, C0, &e) == SS_OK);
  ssi_zoomout_plan plan;
  CHECK(ssi_zoomout_plan_new(&Y, pY.M, pY.evecs, &X, pX.M, o.zoomout_samples, o.zoomout_kmax, &plan, &e) == SS_OK);
  CHECK(plan.n_S == Y.nv && plan.sub_T); /* sampled, so the plan is what is shared */
  ssi_fmap_work work = {0};
  for (int round = 0; round < 2; round++) { /* the plan is read, never changed */
    memset(m1, 0xff, sizeof(int) * n);
    CHECK(ssi_fmap_match_in(&sX, &sY, 0, NULL, NULL, 0, NULL, NULL, SS_PROBE_RAW, &o, &work, &plan, m1, C1, &e) == SS_OK);
    CHECK_MSG(!memcmp(m0, m1, sizeof(int) * n) && same_bits(C0, C1, kk), "round %d: the planned match differs", round);
  }
  int fixed = 0; /* and it is a map worth comparing: the poses share their vertex order */
  for (int i = 0; i < n; i++) fixed += m0[i] == i;
  printf("planned match: %d of %d vertices on themselves\n", fixed, n);
  CHECK(fixed > n / 10);
  ssi_zoomout_plan_free(&plan);
  ssi_fmap_work_free(&work);
  free(m0), free(m1), free(C0), free(C1);
  ss_shape_prep_free(&pX), ss_shape_prep_free(&pY);
  ss_mesh_free(&X), ss_mesh_free(&Y);
}

int main(void) {
  test_planned_match();
  /* sizes in the order one work sees them: first, smaller (a larger one's leftovers), larger (the
   * work grows), the same again (its own leftovers) */
  const int ks[] = {10, 6, 12, 12};
  ssi_fmap_work work = {0};
  for (int t = 0; t < 4; t++) {
    pair q;
    pair_make(ks[t], &q);
    const int n = ks[t] * ks[t];
    double *C0 = malloc(sizeof(double) * n), *C1 = malloc(sizeof(double) * n);
    double *W0 = malloc(sizeof(double) * n), *W1 = malloc(sizeof(double) * n);
    CHECK(solve_both(&q, NULL, C0, C1));
    CHECK(solve_both(&q, &work, W0, W1));
    CHECK_MSG(same_bits(C0, W0, n) && same_bits(C1, W1, n), "k %d: the work's solutions differ", ks[t]);
    CHECK(work.m == (size_t)(t < 2 ? 100 : 144)); /* grown once, to the largest system */
    int moved = 0; /* the extra block counts (else the two solves would test one path) */
    for (int i = 0; i < n; i++) moved |= C0[i] != C1[i];
    CHECK(moved);
    free(C0), free(C1), free(W0), free(W1);
    pair_free(&q);
  }
  /* a work too small for the system: the solve allocates its own copies, the same answer */
  {
    pair q;
    pair_make(9, &q);
    ssi_fmap_work small = {0};
    pair p6;
    pair_make(6, &p6);
    double *C6 = malloc(sizeof(double) * 36), *D6 = malloc(sizeof(double) * 36);
    CHECK(solve_both(&p6, &small, C6, D6) && small.m == 36);
    ss_error e;
    ss_fmap_system *s = NULL;
    double *C = malloc(sizeof(double) * 81), *W = malloc(sizeof(double) * 81);
    CHECK(ss_fmap_system_new(9, 9, q.eS, q.eT, &q.bS, &q.bT, &q.w, &s, &e) == SS_OK);
    CHECK(ss_fmap_system_solve(s, &q.xS, &q.xT, 0.7, 1, C, &e) == SS_OK);
    CHECK(ssi_fmap_system_solve_in(s, &q.xS, &q.xT, 0.7, 1, &small, W, &e) == SS_OK);
    CHECK(same_bits(C, W, 81) && small.m == 36);
    ss_fmap_system_free(s);
    ssi_fmap_work_free(&small);
    CHECK(small.m == 0 && !small.N && !small.own && !small.F);
    free(C), free(W), free(C6), free(D6);
    pair_free(&q), pair_free(&p6);
  }
  ssi_fmap_work_free(&work);
  ssi_fmap_work_free(NULL);
  TEST_MAIN_END();
}
