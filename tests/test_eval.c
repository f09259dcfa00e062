/* Evaluation framework: PRNG, pairing policies, FPS, symmetry map, results CSV / shard merge, and the
 * evaluation's matching adapter against the library's ss_match_prepared. */
#include "testlib.h"

#include "eval/eval_internal.h"
#include "specseg/eval.h"
#include "specseg/io.h"
#include "specseg/match.h"
#include "specseg/mesh.h"
#include "specseg/synth.h"

#include <stdint.h>
#include <unistd.h>

static void test_rng(void) {
  ss_rng a, b;
  ss_rng_seed(&a, 0);
  /* splitmix64's published first output for seed 0 */
  CHECK(ss_rng_next(&a) == 0xE220A8397B1DCDAFull);
  ss_rng_seed(&a, 12345);
  ss_rng_seed(&b, 12345);
  int same = 1;
  for (int i = 0; i < 1000; i++) same &= ss_rng_next(&a) == ss_rng_next(&b);
  CHECK(same);
  ss_rng_seed(&a, 7);
  int hist[10] = {0}, inrange = 1;
  for (int i = 0; i < 100000; i++) {
    int v = ss_rng_below(&a, 10);
    inrange &= v >= 0 && v < 10;
    if (v >= 0 && v < 10) hist[v]++;
  }
  CHECK(inrange);
  for (int v = 0; v < 10; v++) CHECK_MSG(hist[v] > 9500 && hist[v] < 10500, "bucket %d: %d", v, hist[v]);
  CHECK(ss_rng_below(&a, 1) == 0);
}

static void test_pairs(void) {
  int x[300], y[300], x2[300], y2[300];
  for (int p = 0; p < 3; p++) {
    CHECK(ss_eval_pairs((ss_pair_policy)p, 10, 10, 100, 42, x, y, NULL) == SS_OK);
    CHECK(ss_eval_pairs((ss_pair_policy)p, 10, 10, 100, 42, x2, y2, NULL) == SS_OK);
    int valid = 1, distinct = 1, same = 1;
    for (int i = 0; i < 100; i++) {
      valid &= x[i] >= 0 && x[i] < 100 && y[i] >= 0 && y[i] < 100 && x[i] != y[i];
      if (p == SS_POLICY_SUBJ) valid &= x[i] / 10 == y[i] / 10;
      if (p == SS_POLICY_POSE) valid &= x[i] % 10 == y[i] % 10;
      for (int j = 0; j < i; j++) distinct &= !(x[i] == x[j] && y[i] == y[j]);
      same &= x[i] == x2[i] && y[i] == y2[i];
    }
    CHECK_MSG(valid, "policy %s", ss_pair_policy_name(p));
    CHECK_MSG(distinct, "policy %s repeats a pair", ss_pair_policy_name(p));
    CHECK(same);
    CHECK(ss_eval_pairs((ss_pair_policy)p, 10, 10, 100, 43, x2, y2, NULL) == SS_OK);
    int differ = 0;
    for (int i = 0; i < 100; i++) differ += x[i] != x2[i] || y[i] != y2[i];
    CHECK(differ > 50);
  }
  /* subj allows 10 · 10 · 9 = 900 ordered pairs */
  CHECK(ss_eval_pairs(SS_POLICY_SUBJ, 10, 10, 900, 1, NULL, NULL, NULL) == SS_ERR_INVALID);
  int *bx = malloc(sizeof(int) * 900), *by = malloc(sizeof(int) * 900);
  CHECK(ss_eval_pairs(SS_POLICY_SUBJ, 10, 10, 900, 1, bx, by, NULL) == SS_OK);
  CHECK(ss_eval_pairs(SS_POLICY_SUBJ, 10, 10, 901, 1, bx, by, NULL) == SS_ERR_INVALID);
  free(bx), free(by);
  CHECK(ss_eval_pairs((ss_pair_policy)5, 10, 10, 1, 1, x, y, NULL) == SS_ERR_INVALID);
}

static void test_fps(void) {
  ss_mesh m = {0};
  CHECK(ss_synth_icosphere(2, &m, NULL) == SS_OK);
  /* squash it so that distances are not all tied */
  for (int i = 0; i < m.nv; i++) m.V[3 * i + 1] *= 0.6, m.V[3 * i + 2] *= 1.3;
  ss_geodesic_mesh *gm = NULL;
  CHECK(ss_geodesic_mesh_build(&m, &gm, NULL) == SS_OK);
  int n = m.nv, K = 6, pts[6];
  double *all = malloc(sizeof(double) * (size_t)n * n), *md = malloc(sizeof(double) * n);
  int *src = malloc(sizeof(int) * n);
  for (int i = 0; i < n; i++) src[i] = i;
  CHECK(ss_geodesic_fields(gm, src, n, 0, all, NULL) == SS_OK);
  CHECK(ss_fps(gm, 5, K, pts, md, NULL) == SS_OK);
  /* brute force: the same greedy rule on the full distance matrix */
  int bf[6] = {5};
  for (int j = 1; j < K; j++) {
    int best = -1;
    double bd = -1;
    for (int v = 0; v < n; v++) {
      double s = INFINITY;
      for (int i = 0; i < j; i++) s = fmin(s, all[v + (size_t)n * bf[i]]);
      if (s > bd) bd = s, best = v;
    }
    bf[j] = best;
  }
  for (int j = 0; j < K; j++) CHECK_MSG(pts[j] == bf[j], "point %d: %d vs brute force %d", j, pts[j], bf[j]);
  /* p1 is the farthest vertex from the seed; mindist is the min over the chosen points' fields */
  double far = 0;
  for (int v = 0; v < n; v++) far = fmax(far, all[v + (size_t)n * 5]);
  CHECK_NEAR(all[pts[1] + (size_t)n * 5], far, 1e-12);
  double maxerr = 0;
  for (int v = 0; v < n; v++) {
    double s = INFINITY;
    for (int j = 0; j < K; j++) s = fmin(s, all[v + (size_t)n * pts[j]]);
    maxerr = fmax(maxerr, fabs(s - md[v]));
  }
  CHECK(maxerr < 1e-12);
  CHECK(ss_fps(gm, -1, 3, pts, NULL, NULL) == SS_ERR_INVALID);
  ss_geodesic_mesh_free(gm);
  free(all), free(md), free(src);
  ss_mesh_free(&m);
}

static void test_symmetry(void) {
  /* the icosphere is mirror-symmetric under x → −x vertex for vertex; stretch it so that the
   * mirror plane is the only one */
  ss_mesh m = {0};
  CHECK(ss_synth_icosphere(2, &m, NULL) == SS_OK);
  for (int i = 0; i < m.nv; i++) m.V[3 * i + 0] *= 0.8, m.V[3 * i + 1] *= 1.6, m.V[3 * i + 2] *= 1.1;
  int n = m.nv, *mir = malloc(sizeof(int) * n), *sym = malloc(sizeof(int) * n);
  for (int i = 0; i < n; i++) {
    mir[i] = -1;
    for (int j = 0; j < n; j++)
      if (fabs(m.V[3 * j] + m.V[3 * i]) < 1e-9 && fabs(m.V[3 * j + 1] - m.V[3 * i + 1]) < 1e-9 &&
          fabs(m.V[3 * j + 2] - m.V[3 * i + 2]) < 1e-9)
        mir[i] = j;
  }
  int ok = 1;
  for (int i = 0; i < n; i++) ok &= mir[i] >= 0;
  CHECK(ok);
  /* landmarks: two off-plane pairs (listed both ways, as FAUST's hands and feet) and one on it */
  int a = -1, b = -1, c = -1;
  for (int i = 0; i < n && (a < 0 || b < 0 || c < 0); i++) {
    if (a < 0 && m.V[3 * i] > 0.3 && m.V[3 * i + 1] > 0.5) a = i;
    else if (b < 0 && m.V[3 * i] > 0.3 && m.V[3 * i + 1] < -0.5) b = i;
    else if (c < 0 && mir[i] == i && m.V[3 * i + 1] > 1.0) c = i;
  }
  CHECK(a >= 0 && b >= 0 && c >= 0);
  int lm[5] = {c, a, b, mir[b], mir[a]}, lmm[5] = {c, mir[a], mir[b], b, a};
  ss_symmetry_stats st;
  CHECK(ss_symmetry_map(&m, 5, lm, lmm, sym, &st, NULL) == SS_OK);
  int inv = 1, exact = 1;
  for (int i = 0; i < n; i++) inv &= sym[sym[i]] == i, exact &= sym[i] == mir[i];
  CHECK(inv);
  CHECK(exact);
  CHECK_NEAR(st.involution, 1.0, 0);
  CHECK_NEAR(fabs(st.normal[0]), 1.0, 1e-9);
  /* all landmarks on the plane: no left-right direction */
  int on[1] = {c};
  CHECK(ss_symmetry_map(&m, 1, on, on, sym, NULL, NULL) == SS_ERR_INVALID);
  free(mir), free(sym);
  ss_mesh_free(&m);
}

static ss_eval_row fake_row(ss_rng *r, int p, int l, int mth, int x, int y) {
  ss_eval_row w;
  memset(&w, 0, sizeof w);
  w.policy = p, w.landmarks = l, w.method = mth, w.x = x, w.y = y;
  w.error = (double)(ss_rng_next(r) >> 11) / 9007199254740992.0 * 0.1;
  w.error_sym = w.error * (double)(ss_rng_next(r) >> 11) / 9007199254740992.0;
  w.segments_x = 8, w.segments_y = 7 + (int)(ss_rng_next(r) % 3), w.paired = 7;
  w.seconds = 0.25;
  w.samples = 126;
  return w;
}

static void write_csv(const char *path, const ss_eval_row *r, int n, int truncate_last) {
  FILE *f = fopen(path, "wb");
  fprintf(f, "%s\n", ss_eval_csv_header());
  char line[512];
  for (int i = 0; i < n; i++) {
    ss_eval_csv_format_row(&r[i], line, sizeof line);
    if (truncate_last && i == n - 1) line[strlen(line) / 2] = 0, fputs(line, f);
    else fprintf(f, "%s\n", line);
  }
  fclose(f);
}

static void test_csv_and_merge(void) {
  ss_rng r;
  ss_rng_seed(&r, 99);
  int n = 0, x[20], y[20];
  ss_eval_row rows[3 * 3 * 3 * 20];
  for (int p = 0; p < 3; p++) {
    ss_eval_pairs((ss_pair_policy)p, 10, 10, 20, 5, x, y, NULL);
    for (int i = 0; i < 20; i++)
      for (int l = 0; l < 3; l++)
        for (int mth = 0; mth < 3; mth++) rows[n++] = fake_row(&r, p, l, mth, x[i], y[i]);
  }
  char dir[] = "/tmp/ss_test_eval_XXXXXX", path[256];
  CHECK(mkdtemp(dir) != NULL);
  /* round trip is exact (%.17g) */
  snprintf(path, sizeof path, "%s/all.csv", dir);
  write_csv(path, rows, n, 0);
  ss_eval_row *back = NULL;
  int nb = 0;
  CHECK(ss_eval_csv_read(path, &back, &nb, NULL) == SS_OK);
  CHECK(nb == n);
  int same = nb == n;
  for (int i = 0; same && i < n; i++)
    same = back[i].error == rows[i].error && back[i].error_sym == rows[i].error_sym && back[i].x == rows[i].x &&
           back[i].y == rows[i].y && back[i].method == rows[i].method && back[i].paired == rows[i].paired;
  CHECK(same);
  ss_table1 whole, merged;
  CHECK(ss_table1_aggregate(rows, n, &whole, NULL) == SS_OK);
  CHECK(whole.count[0][0] == 20 && whole.count[9][2] == 20 && whole.count[8][1] == 20);
  /* 3 shards written in scrambled order, one of them with a duplicated row (a resumed run): the
   * merged table is bit-identical to the single run's */
  ss_eval_row *all = malloc(sizeof rows + sizeof rows[0]);
  int na = 0;
  for (int s = 2; s >= 0; s--) {
    ss_eval_row shard[sizeof rows / sizeof rows[0]];
    int ns = 0;
    for (int i = n - 1; i >= 0; i--)
      if ((i * 7 + 3) % 3 == s) shard[ns++] = rows[i];
    if (s == 1) shard[ns++] = shard[0];
    snprintf(path, sizeof path, "%s/shard%d.csv", dir, s);
    write_csv(path, shard, ns, 0);
    ss_eval_row *rb;
    int nrb;
    CHECK(ss_eval_csv_read(path, &rb, &nrb, NULL) == SS_OK);
    memcpy(all + na, rb, sizeof *rb * (size_t)nrb);
    na += nrb;
    free(rb);
  }
  CHECK(na == n + 1);
  CHECK(ss_table1_aggregate(all, na, &merged, NULL) == SS_OK);
  CHECK(memcmp(&whole, &merged, sizeof whole) == 0);
  CHECK(ss_eval_rows_canonical(all, &na, NULL) == SS_OK);
  CHECK(na == n);
  /* a conflicting duplicate is an error */
  all[na] = all[0];
  all[na].error += 1e-9;
  na++;
  CHECK(ss_eval_rows_canonical(all, &na, NULL) == SS_ERR_INVALID);
  /* an interrupted run's partial last line is dropped; garbage elsewhere is an error */
  snprintf(path, sizeof path, "%s/partial.csv", dir);
  write_csv(path, rows, 10, 1);
  free(back);
  CHECK(ss_eval_csv_read(path, &back, &nb, NULL) == SS_OK);
  CHECK(nb == 9);
  free(back);
  FILE *f = fopen(path, "wb");
  fprintf(f, "%s\nrandom,best,std,1,2,x,0.1,8,8,8,0.1,10\nrandom,best,std,1,3,0.1,0.1,8,8,8,0.1,10\n", ss_eval_csv_header());
  fclose(f);
  CHECK(ss_eval_csv_read(path, &back, &nb, NULL) == SS_ERR_PARSE);
  f = fopen(path, "wb");
  fprintf(f, "policy,x,y\n");
  fclose(f);
  CHECK(ss_eval_csv_read(path, &back, &nb, NULL) == SS_ERR_PARSE);
  snprintf(path, sizeof path, "%s/missing.csv", dir);
  CHECK(ss_eval_csv_read(path, &back, &nb, NULL) == SS_ERR_IO);
  free(all);
  const char *names[] = {"all.csv", "shard0.csv", "shard1.csv", "shard2.csv", "partial.csv"};
  for (int i = 0; i < 5; i++) {
    snprintf(path, sizeof path, "%s/%s", dir, names[i]);
    remove(path);
  }
  rmdir(dir);
}

/* The evaluation's matching adapter (cached landmark fields + pairing + ss_fmap_match) must give
 * exactly the map of the library's ss_match_prepared, on two poses of the synthetic humanoid. */
static void test_adapter(void) {
  ev_context ctx;
  memset(&ctx, 0, sizeof ctx);
  ss_match_paper_options(&ctx.mopt);
  ctx.mopt.fmap.k = 20;
  ctx.mopt.fmap.n_energies = 30;
  ctx.kev = 20;
  ev_shape X, Y;
  memset(&X, 0, sizeof X);
  memset(&Y, 0, sizeof Y);
  ss_error e;
  if (ss_synth_humanoid(0, &X.mesh, &e) || ss_synth_humanoid(1, &Y.mesh, &e)) {
    CHECK_MSG(0, "humanoid: %s", e.msg);
    return;
  }
  int n = X.mesh.nv;
  /* landmarks: FPS-spread input vertices (same on both: ground truth is the identity) */
  for (int i = 0; i < EV_NL; i++) ctx.best[i] = (int)((long)n * (2 * i + 1) / (2 * EV_NL)), ctx.gt[i] = (i * 997) % n;
  ss_status s1 = ev_shape_prepare(&X, &ctx, &e);
  CHECK_MSG(s1 == SS_OK, "%s", e.msg);
  ss_status s2 = s1 ? s1 : ev_shape_prepare(&Y, &ctx, &e);
  CHECK_MSG(s2 == SS_OK, "%s", e.msg);
  if (!s1 && !s2) {
    CHECK(X.fps[0] == 0 && Y.fps[0] == 0);
    int *m1 = malloc(sizeof(int) * n);
    /* (landmark set, method): BEST with ASA, the shapes' own FPS landmarks with STD and DIFF */
    static const int cases[3][2] = {{SS_LM_BEST, SS_METHOD_ASA}, {SS_LM_FPS, SS_METHOD_STD}, {SS_LM_FPS, SS_METHOD_DIFF}};
    for (int c = 0; c < 3; c++) {
        int lmset = cases[c][0], mth = cases[c][1];
        int paired = -1;
        CHECK(ev_match(&ctx, &X, &Y, lmset, mth, m1, &paired, &e) == SS_OK);
        ss_match_options mo = ctx.mopt;
        mo.probes = (ss_probe_set)mth;
        mo.std_pairs = 1; /* eval reports the unit's pairing on its STD rows too */
        ss_match_result res;
        CHECK(ss_match_prepared(&X.prep, &Y.prep, EV_NL, ev_landmarks(&ctx, &X, lmset), ev_landmarks(&ctx, &Y, lmset), &mo,
                                &res, &e) == SS_OK);
        int diff = 0;
        for (int i = 0; i < n; i++) diff += m1[i] != res.map[i];
        CHECK_MSG(diff == 0, "set %d method %d: %d vertices differ", lmset, mth, diff);
        CHECK(paired == res.pairs.n);
        ss_match_result_free(&res);
      }
    /* all three methods at once (shared pairing and normal equations), with the shapes' cached base
     * probes: the same maps as one method at a time */
    int *mm = malloc(sizeof(int) * SS_EVAL_NMETHODS * (size_t)n), *maps[SS_EVAL_NMETHODS];
    for (int mth = 0; mth < SS_EVAL_NMETHODS; mth++) maps[mth] = mm + (size_t)n * mth;
    CHECK(ev_shape_probes(&X, &ctx, 7, &e) == SS_OK && ev_shape_probes(&Y, &ctx, 7, &e) == SS_OK);
    CHECK(X.base[SS_LM_FPS].p > 0 && Y.base[SS_LM_BEST].nd == Y.base[SS_LM_BEST].p);
    double cpu[SS_EVAL_NMETHODS];
    int paired[SS_EVAL_NMETHODS] = {-1, -1, -1, -1};
    CHECK(ev_match_methods(&ctx, &X, &Y, SS_LM_FPS, 7, maps, cpu, paired, &e) == SS_OK);
    for (int mth = 0; mth < 3; mth++) {
      int p2 = -1, diff = 0;
      CHECK(ev_match(&ctx, &X, &Y, SS_LM_FPS, mth, m1, &p2, &e) == SS_OK);
      for (int i = 0; i < n; i++) diff += m1[i] != maps[mth][i];
      CHECK_MSG(diff == 0 && p2 == paired[mth], "method %d: %d vertices differ between joint and single runs", mth, diff);
      CHECK(cpu[mth] > 0);
    }
    /* the refined method (not prepared: an error), then with its eigenpairs: ss_match_prepared with the
     * default options on them (pairing from the work meshes, not the cached fields), and with the
     * paper's methods in one call: the same maps */
    CHECK(ev_match(&ctx, &X, &Y, SS_LM_BEST, SS_METHOD_REFINED, m1, NULL, &e) == SS_ERR_INVALID);
    ss_match_default_options(&ctx.ropt);
    ctx.ropt.autopair.hyp_landmarks = 0; /* as Table 1 sets it: the refined rows are the landmarks' map */
    ctx.ropt.fmap.k = 20, ctx.ropt.fmap.n_energies = 30, ctx.ropt.fmap.descr_k = 30, ctx.ropt.fmap.zoomout_kmax = 30;
    ctx.kref = 30;
    CHECK(ev_shape_refined(&X, &ctx, &e) == SS_OK && ev_shape_refined(&Y, &ctx, &e) == SS_OK);
    CHECK(X.rprep.kev == 30 && X.rprep.M == X.prep.M && X.prep.kev == 20);
    for (int set = 0; set < 2; set++) {
      int lmset = set ? SS_LM_FPS : SS_LM_BEST, p2 = -1, diff = 0;
      CHECK(ev_match(&ctx, &X, &Y, lmset, SS_METHOD_REFINED, m1, &p2, &e) == SS_OK);
      ss_match_result res;
      CHECK(ss_match_prepared(&X.rprep, &Y.rprep, EV_NL, ev_landmarks(&ctx, &X, lmset), ev_landmarks(&ctx, &Y, lmset),
                              &ctx.ropt, &res, &e) == SS_OK);
      for (int i = 0; i < n; i++) diff += m1[i] != res.map[i];
      CHECK_MSG(diff == 0 && p2 == res.pairs.n, "refined, set %d: %d vertices differ from ss_match_prepared", lmset, diff);
      CHECK(res.refine_choice >= 0);
      ss_match_result_free(&res);
      CHECK(ev_match_methods(&ctx, &X, &Y, lmset, 15, maps, cpu, paired, &e) == SS_OK);
      diff = 0;
      for (int i = 0; i < n; i++) diff += m1[i] != maps[SS_METHOD_REFINED][i];
      CHECK(diff == 0 && paired[SS_METHOD_REFINED] == p2 && cpu[SS_METHOD_REFINED] > 0);
      CHECK(ev_match(&ctx, &X, &Y, lmset, SS_METHOD_STD, m1, NULL, &e) == SS_OK);
      diff = 0;
      for (int i = 0; i < n; i++) diff += m1[i] != maps[SS_METHOD_STD][i];
      CHECK(diff == 0);
    }
    /* batched exact errors == the library's per-map error (sym: an arbitrary vertex map) */
    int *sym = malloc(sizeof(int) * (size_t)n);
    for (int i = 0; i < n; i++) sym[i] = n - 1 - i;
    ss_geodesic_mesh *gm = NULL;
    double sum[3], sum_sym[3];
    CHECK(ss_geodesic_mesh_build(&Y.mesh, &gm, &e) == SS_OK);
    CHECK(ev_batch_errors(gm, n, sym, NULL, 3, (const int *const *)maps, sum, sum_sym, &e) == SS_OK);
    for (int mth = 0; mth < 3; mth++) {
      double mean, mean_sym, scale = sqrt(ss_mesh_area(&Y.mesh));
      CHECK(ss_map_geodesic_error(&Y.mesh, n, maps[mth], NULL, NULL, NULL, &mean, &e) == SS_OK);
      CHECK(ss_map_geodesic_error(&Y.mesh, n, maps[mth], NULL, sym, NULL, &mean_sym, &e) == SS_OK);
      CHECK_NEAR(sum[mth] / n / scale, mean, 1e-12 * mean);
      CHECK_NEAR(sum_sym[mth] / n / scale, mean_sym, 1e-12 * mean);
      CHECK(sum_sym[mth] <= sum[mth] * (1 + 1e-12));
    }
    ss_geodesic_mesh_free(gm);
    free(sym);
    free(mm);
    free(m1);
  }
  ev_shape_free(&X);
  ev_shape_free(&Y);
}

/* The landmark-free table: every method (the refined one too) gets its column; the pairing
 * fractions count only rows that carry a pairing (the refined rows carry -1). */
static void test_none_table(void) {
  ss_eval_row rows[3 * 4 * 4];
  int n = 0;
  for (int p = 0; p < 3; p++)
    for (int i = 0; i < 4; i++)
      for (int mth = 0; mth < SS_EVAL_NMETHODS; mth++) {
        ss_eval_row *r = &rows[n++];
        memset(r, 0, sizeof *r);
        r->policy = (ss_pair_policy)p, r->landmarks = SS_LM_NONE, r->method = (ss_eval_method)mth;
        r->x = i, r->y = i + 10, r->error = 0.01 * (mth + 1) + 0.001 * i, r->error_sym = r->error;
        r->samples = 10, r->segments_x = r->segments_y = r->paired = 8;
        r->pairing = mth == SS_METHOD_REFINED ? -1 : (i == 0 ? 0 : i == 1 ? 1 : 2);
      }
  ss_table1_none t;
  CHECK(ss_table1_none_aggregate(rows, n, &t, NULL) == SS_OK);
  for (int p = 0; p < 3; p++) {
    CHECK(t.count[p][SS_METHOD_REFINED] == 4);
    CHECK(fabs(t.mean[p][SS_METHOD_REFINED] - (0.04 + 0.0015)) < 1e-12);
    CHECK(fabs(t.all_right[p] - 0.5) < 1e-12 && fabs(t.mirror_right[p] - 0.75) < 1e-12);
    CHECK(t.pairs[p] == 4);
  }
  CHECK(t.count[3][SS_METHOD_REFINED] == 4 && t.count[3][SS_METHOD_STD] == 4);
  /* refined rows alone: the errors, and no pairing fraction */
  int m = 0;
  for (int i = 0; i < n; i++)
    if (rows[i].method == SS_METHOD_REFINED) rows[m++] = rows[i];
  CHECK(ss_table1_none_aggregate(rows, m, &t, NULL) == SS_OK);
  CHECK(t.count[0][SS_METHOD_REFINED] == 4 && t.count[0][SS_METHOD_STD] == 0);
  CHECK(isnan(t.all_right[0]) && isnan(t.mirror_right[0]));
}

int main(void) {
  test_rng();
  test_pairs();
  test_fps();
  test_symmetry();
  test_csv_and_merge();
  test_none_table();
  test_adapter();
  TEST_MAIN_END();
}
