/* Landmark-free pairing of the segments (issue 16) on FAUST: accuracy of ss_pair_centres_auto against
 * the ground truth (identity), up to the left-right mirror and with it, its confidence and CPU, and
 * optionally the landmark-free ss_match_prepared map error.
 *   bench_autopair [--data DIR] [--cache DIR] [--split tune|held|all] [--pairs N] [--seed S]
 *                  [--all-pairs] [--list X,Y;X,Y;...] [--wd W] [--wg W] [--radius R] [--energies E] [--exact-max N]
 *                  [--ok K] [--odk K] (orientation test's basis / descriptor eigenpairs)
 *                  [--recheck M] [--rk K] [--rz K] [--rs N] [--rkeep F] (the second test: below margin M,
 *                  basis K, ZoomOut to K on N samples, or the fraction F of the centres as landmarks) [--keep F] (the test's landmarks: the fraction F of the
 *                  centres farthest from the others)
 *                  [--alt N GAP MARGIN] [--alt-min S] (near-ties: up to N pairings within GAP of the
 *                  best, replacing it when their score is >= S and beats the best's pair by MARGIN)
 *                  [--match N] [--verbose] [--dump DIR]
 *                  [--gtrho]  the orientation test on the ground-truth pairing and its mirror
 *                  [--variant K KEEP] (repeatable) the test with basis K and orient_keep KEEP on the
 *                  ground-truth pairing and its mirror: right by the whole-shape scores / the median rule
 *                  [--self]   the orientation test of the first 5 shapes with themselves
 *   bench_autopair --tosca [--tosca-class NAME] [--verbose]
 *                  each TOSCA class: its first shape against the others with the same vertex count
 * Pairs: --pairs N random ordered pairs of distinct shapes of the split (the LCG of bench_match from
 * --seed), or --all-pairs (every ordered pair of the split). A pair (cx, cy) is right when vertex cx
 * of X (GT = identity) lies in segment cy of Y; "up to the mirror" when it is right after FAUST's
 * left-right symmetry map (ss_symmetry_map of tr_reg_000 with the BEST landmarks) of every centre.
 * Shapes are prepared once (segmentation + 120 eigenpairs) and cached in --cache (default
 * /tmp/specseg_autopair_cache). --match N: the first N pairs also through ss_match_prepared without
 * landmarks (the default refined output), mean exact geodesic error / sqrt(area). CPU: process CPU. */
#include "specseg/eval.h"
#include "specseg/fmap.h"
#include "specseg/io.h"
#include "specseg/match.h"
#include "match/autopair_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#ifndef SS_DATA_DIR_DEFAULT
#define SS_DATA_DIR_DEFAULT "../shared/data"
#endif
#define KEV 120

static double cpu_now(void) {
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

typedef struct shape {
  ss_mesh m;
  ss_shape_prep prep;
  ss_centre_signature sig;
  int loaded;
  double t_sig;
} shape;

#define RD(p, c) (fread((p), sizeof *(p), (size_t)(c), f) == (size_t)(c))
#define WR(p, c) ((void)fwrite((p), sizeof *(p), (size_t)(c), f))

static int cache_load(const char *path, shape *s) {
  FILE *f = fopen(path, "rb");
  if (!f) return 0;
  ss_shape_prep *p = &s->prep;
  int nv, kev, m, wn;
  int ok = RD(&nv, 1) && RD(&kev, 1) && RD(&m, 1) && RD(&wn, 1) && nv == s->m.nv && kev == KEV && m > 0 && m < nv;
  if (ok) {
    p->evals = malloc(sizeof(double) * kev);
    p->evecs = malloc(sizeof(double) * (size_t)nv * kev);
    p->M = malloc(sizeof(double) * nv);
    p->seg.labels = malloc(sizeof(int) * nv);
    p->seg.centers = malloc(sizeof(int) * m);
    p->seg.psi = malloc(sizeof(int) * nv);
    p->seg.work_dist = malloc(sizeof(double) * wn);
    ok = RD(p->evals, kev) && RD(p->evecs, (size_t)nv * kev) && RD(p->M, nv) && RD(p->seg.labels, nv) &&
         RD(p->seg.centers, m) && RD(p->seg.psi, nv) && RD(p->seg.work_dist, wn);
  }
  fclose(f);
  if (!ok) return 0;
  p->mesh = &s->m;
  p->kev = kev;
  p->seg.nv = nv;
  p->seg.m = m;
  p->area = 0;
  for (int i = 0; i < nv; i++) p->area += p->M[i];
  return 1;
}

static void cache_store(const char *path, const shape *s) {
  FILE *f = fopen(path, "wb");
  if (!f) return;
  const ss_shape_prep *p = &s->prep;
  int nv = s->m.nv, m = p->seg.m, wn = p->seg.work.nv;
  WR(&nv, 1), WR(&p->kev, 1), WR(&m, 1), WR(&wn, 1), WR(p->evals, p->kev), WR(p->evecs, (size_t)nv * p->kev), WR(p->M, nv);
  WR(p->seg.labels, nv), WR(p->seg.centers, m), WR(p->seg.psi, nv), WR(p->seg.work_dist, wn);
  fclose(f);
}

static int load(const char *dir, const char *cache, int id, const ss_autopair_options *ao, shape *s) {
  if (s->loaded) return 0;
  char path[4096];
  snprintf(path, sizeof path, "%s/faust/tr_reg_%03d.off", dir, id);
  ss_error e;
  if (ss_read_mesh(path, &s->m, &e)) { fprintf(stderr, "%s\n", e.msg); return 1; }
  snprintf(path, sizeof path, "%s/faust_%03d_k%d.bin", cache, id, KEV);
  if (!cache_load(path, s)) {
    ss_shape_prep_free(&s->prep);
    if (ss_shape_prep_compute(&s->m, NULL, KEV, &s->prep, &e)) { fprintf(stderr, "shape %d: %s\n", id, e.msg); return 1; }
    cache_store(path, s);
  }
  double c0 = cpu_now();
  if (ss_centre_signature_compute(&s->prep, ao, &s->sig, &e)) { fprintf(stderr, "shape %d: %s\n", id, e.msg); return 1; }
  s->t_sig = cpu_now() - c0;
  s->loaded = 1;
  return 0;
}

static void next_pair(unsigned *r, int lo, int n, int *a, int *b) {
  do {
    *r = *r * 1664525u + 1013904223u;
    *a = lo + (int)((*r >> 8) % (unsigned)n);
    *r = *r * 1664525u + 1013904223u;
    *b = lo + (int)((*r >> 8) % (unsigned)n);
  } while (*a == *b);
}

int main(int argc, char **argv) {
  setvbuf(stdout, NULL, _IOLBF, 0);
  const char *tosca_class = NULL, *data = SS_DATA_DIR_DEFAULT, *cache = "/tmp/specseg_autopair_cache", *split = "tune", *dump = NULL;
  int fv_k[8], nfv = 0, fv_ok[8] = {0}, fv_okm[8] = {0}, fv_n = 0;
  double fv_keep[8], fv_cpu[8] = {0};
  const char *list = NULL;
  int tosca = 0, selftest = 0, npairs = 20, allpairs = 0, verbose = 0, nmatch = 0, gtrho = 0, n_gt = 0, n_gtok = 0;
  double gt_margin = 0;
  unsigned seed = 1;
  ss_autopair_options ao;
  ss_autopair_default_options(&ao);
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(a, "--data") && v) data = v, i++;
    else if (!strcmp(a, "--cache") && v) cache = v, i++;
    else if (!strcmp(a, "--split") && v) split = v, i++;
    else if (!strcmp(a, "--pairs") && v) npairs = atoi(v), i++;
    else if (!strcmp(a, "--seed") && v) seed = (unsigned)atoi(v), i++;
    else if (!strcmp(a, "--all-pairs")) allpairs = 1;
    else if (!strcmp(a, "--list") && v) list = v, i++;
    else if (!strcmp(a, "--wd") && v) ao.w_descr = atof(v), i++;
    else if (!strcmp(a, "--wg") && v) ao.w_geo = atof(v), i++;
    else if (!strcmp(a, "--gtrho")) gtrho = 1;
    else if (!strcmp(a, "--variant") && v && i + 2 < argc && nfv < 8) fv_k[nfv] = atoi(v), fv_keep[nfv++] = atof(argv[i + 2]), i += 2;
    else if (!strcmp(a, "--self")) selftest = 1;
    else if (!strcmp(a, "--tosca")) tosca = 1;
    else if (!strcmp(a, "--tosca-class") && v) tosca = 1, tosca_class = v, i++;
    else if (!strcmp(a, "--radius") && v) ao.descr_radius = atof(v), i++;
    else if (!strcmp(a, "--energies") && v) ao.n_energies = atoi(v), i++;
    else if (!strcmp(a, "--ok") && v) ao.orient_k = atoi(v), i++;
    else if (!strcmp(a, "--odk") && v) ao.orient_descr_k = atoi(v), i++;
    else if (!strcmp(a, "--recheck") && v) ao.recheck_margin = atof(v), i++;
    else if (!strcmp(a, "--keep") && v) ao.orient_keep = atof(v), i++;
    else if (!strcmp(a, "--rkeep") && v) ao.recheck_keep = atof(v), i++;
    else if (!strcmp(a, "--alt-min") && v) ao.alt_min_score = atof(v), i++;
    else if (!strcmp(a, "--alt") && v && i + 3 < argc)
      ao.alt_max = atoi(v), ao.alt_gap = atof(argv[i + 2]), ao.alt_margin = atof(argv[i + 3]), i += 3;
    else if (!strcmp(a, "--rk") && v) ao.recheck_k = atoi(v), i++;
    else if (!strcmp(a, "--rz") && v) ao.recheck_zoomout = atoi(v), i++;
    else if (!strcmp(a, "--rs") && v) ao.recheck_samples = atoi(v), i++;
    else if (!strcmp(a, "--exact-max") && v) ao.exact_max = atoi(v), i++;
    else if (!strcmp(a, "--match") && v) nmatch = atoi(v), i++;
    else if (!strcmp(a, "--dump") && v) dump = v, i++;
    else if (!strcmp(a, "--verbose")) verbose = 1;
    else { fprintf(stderr, "bench_autopair: bad argument %s (see the source's header)\n", a); return 2; }
  }
  if (tosca) { /* each class: its first shape against every other of the same vertex count (GT = identity) */
    static const char *classes[] = {"cat", "centaur", "david", "dog", "horse", "michael", "victoria", "wolf"};
    static const int counts[] = {11, 6, 14, 11, 18, 20, 26, 3};
    for (int c = 0; c < 8; c++) {
      if (tosca_class && strcmp(tosca_class, classes[c])) continue;
      shape X0 = {0};
      int have0 = 0, np = 0, nright = 0, nconf = 0, nconfw = 0, nsame = 0;
      double cpu = 0;
      char segs[512] = "";
      for (int i = 0; i < counts[c] + 12; i++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/tosca/%s%d.off", data, classes[c], i);
        FILE *t = fopen(path, "r");
        if (!t) continue;
        fclose(t);
        shape Y = {0};
        ss_error e2;
        if (ss_read_mesh(path, &Y.m, &e2) || ss_shape_prep_compute(&Y.m, NULL, KEV, &Y.prep, &e2) ||
            ss_centre_signature_compute(&Y.prep, &ao, &Y.sig, &e2)) {
          printf("%s: %s\n", path, e2.msg);
          continue;
        }
        size_t L = strlen(segs);
        snprintf(segs + L, sizeof segs - L, " %d", Y.sig.m);
        if (!have0) { /* the copy's prep and signature must point at the copy, not at the loop's Y */
          X0 = Y, have0 = 1;
          X0.prep.mesh = &X0.m, X0.sig.prep = &X0.prep;
          continue;
        }
        if (Y.m.nv == X0.m.nv) {
          ss_segment_pairs pr;
          ss_autopair_info info;
          if (!ss_pair_centres_auto(&X0.sig, &Y.sig, &ao, &pr, &info, &e2)) {
            int right = 0;
            for (int p = 0; p < pr.n; p++) right += Y.prep.seg.labels[X0.prep.seg.centers[pr.sx[p]]] == pr.sy[p];
            np++, nsame += X0.sig.m == Y.sig.m, nright += right == pr.n && X0.sig.m == Y.sig.m;
            nconf += info.confident, nconfw += info.confident && !(right == pr.n && X0.sig.m == Y.sig.m);
            cpu += info.cpu;
            if (verbose) printf("  %s%d: m %d/%d right %d/%d gap %.3f margin %.3f %s\n", classes[c], i, X0.sig.m, Y.sig.m, right, pr.n, info.gap, (info.mirror - info.mirror_other) / 2, info.confident ? "confident" : "");
            ss_segment_pairs_free(&pr);
          }
        }
        ss_centre_signature_free(&Y.sig), ss_shape_prep_free(&Y.prep), ss_mesh_free(&Y.m);
      }
      printf("tosca %s: segments%s; %d pairs with the first shape (same vertex count), %d with equal segment counts: "
             "all right %d, confident %d (wrong among them %d), search CPU mean %.3f s\n",
             classes[c], segs, np, nsame, nright, nconf, nconfw, np ? cpu / np : 0);
      fflush(stdout);
      if (have0) ss_centre_signature_free(&X0.sig), ss_shape_prep_free(&X0.prep), ss_mesh_free(&X0.m);
    }
    return 0;
  }
  int lo = 0, n = 100;
  if (!strcmp(split, "tune")) lo = 0, n = 50;
  else if (!strcmp(split, "held")) lo = 50, n = 50;
  else if (strcmp(split, "all")) { fprintf(stderr, "bad split\n"); return 2; }
  mkdir(cache, 0755);
  shape *S = calloc(100, sizeof(shape));
  int *px, *py, np;
  if (allpairs) {
    np = n * (n - 1);
    px = malloc(sizeof(int) * np), py = malloc(sizeof(int) * np);
    int q = 0;
    for (int a = lo; a < lo + n; a++)
      for (int b = lo; b < lo + n; b++)
        if (a != b) px[q] = a, py[q++] = b;
  } else if (list) { /* "x,y;x,y;..." */
    np = 1;
    for (const char *c = list; *c; c++) np += *c == ';';
    px = malloc(sizeof(int) * np), py = malloc(sizeof(int) * np);
    const char *c = list;
    for (int q = 0; q < np; q++) {
      if (sscanf(c, "%d,%d", &px[q], &py[q]) != 2 || px[q] < 0 || px[q] > 99 || py[q] < 0 || py[q] > 99) {
        fprintf(stderr, "bad --list\n");
        return 2;
      }
      c = strchr(c, ';');
      c = c ? c + 1 : "";
    }
  } else {
    np = npairs;
    px = malloc(sizeof(int) * np), py = malloc(sizeof(int) * np);
    unsigned r = seed;
    for (int q = 0; q < np; q++) next_pair(&r, lo, n, &px[q], &py[q]);
  }
  /* the symmetry map of tr_reg_000 (FAUST shares connectivity) */
  ss_mesh m0 = {0};
  ss_error e;
  char path[4096];
  int *lm = NULL, nl = 0;
  snprintf(path, sizeof path, "%s/faust/tr_reg_000.off", data);
  if (ss_read_mesh(path, &m0, &e)) { fprintf(stderr, "%s\n", e.msg); return 1; }
  snprintf(path, sizeof path, "%s/faust/landmarks_best.txt", data);
  if (ss_read_ints(path, &lm, &nl, &e) || nl != 5) { fprintf(stderr, "landmarks: %s\n", e.msg); return 1; }
  int mir[5] = {lm[0], lm[4], lm[3], lm[2], lm[1]}, *sym = malloc(sizeof(int) * m0.nv);
  if (ss_symmetry_map(&m0, 5, lm, mir, sym, NULL, &e)) { fprintf(stderr, "%s\n", e.msg); return 1; }
  if (selftest) {
    for (int a = lo; a < lo + 5; a++) {
      if (load(data, cache, a, &ao, &S[a])) return 1;
      int g[64], gm[64], m = S[a].sig.m;
      for (int c = 0; c < m; c++) g[c] = c, gm[c] = S[a].prep.seg.labels[sym[S[a].prep.seg.centers[c]]];
      double r1 = NAN, r2 = NAN;
      ssi_autopair_orient_score(&S[a].sig, &S[a].sig, g, &ao, &r1, &e);
      ssi_autopair_orient_score(&S[a].sig, &S[a].sig, gm, &ao, &r2, &e);
      printf("self %d: identity score %.3f, mirror score %.3f, volume ratio %.4f\n", a, r1, r2, S[a].sig.volume_ratio);
    }
    return 0;
  }
  int n_right = 0, n_mirror = 0, n_conf = 0, n_conf_wrong = 0, n_done = 0, n_unequal = 0, n_rechecked = 0, n_alt = 0, n_altc = 0;
  double cpu_sum = 0, cpu_max = 0, err_sum = 0, sig_sum = 0;
  int nerr = 0, nsig = 0;
  for (int q = 0; q < np; q++) {
    int a = px[q], b = py[q];
    if (!S[a].loaded) {
      if (load(data, cache, a, &ao, &S[a])) return 1;
      sig_sum += S[a].t_sig, nsig++;
    }
    if (!S[b].loaded) {
      if (load(data, cache, b, &ao, &S[b])) return 1;
      sig_sum += S[b].t_sig, nsig++;
    }
    ss_segment_pairs pr;
    ss_autopair_info info;
    if (ss_pair_centres_auto(&S[a].sig, &S[b].sig, &ao, &pr, &info, &e)) { fprintf(stderr, "%s\n", e.msg); return 1; }
    int right = 0, mright = 0;
    for (int p = 0; p < pr.n; p++) {
      int cx = S[a].prep.seg.centers[pr.sx[p]];
      right += S[b].prep.seg.labels[cx] == pr.sy[p];
      mright += S[b].prep.seg.labels[sym[cx]] == pr.sy[p];
    }
    int all = right == pr.n, allm = mright == pr.n;
    if (gtrho && S[a].sig.m == S[b].sig.m) { /* the orientation test on the ground truth and its mirror */
      int g[64], gm[64];
      for (int c = 0; c < S[a].sig.m && c < 64; c++) {
        g[c] = S[b].prep.seg.labels[S[a].prep.seg.centers[c]];
        gm[c] = S[b].prep.seg.labels[sym[S[a].prep.seg.centers[c]]];
      }
      double rg = NAN, rm = NAN;
      ssi_autopair_orient_score(&S[a].sig, &S[b].sig, g, &ao, &rg, &e);
      ssi_autopair_orient_score(&S[a].sig, &S[b].sig, gm, &ao, &rm, &e);
      if (verbose) printf("   GT score %.3f  GT-mirror score %.3f\n", rg, rm);
      n_gt++, n_gtok += rg > rm, gt_margin += (rg - rm) / 2;
    }
    if (nfv && S[a].sig.m == S[b].sig.m) { /* variants of the test on the ground truth and its mirror */
      int g[64], gm[64], mm = S[a].sig.m;
      for (int c = 0; c < mm && c < 64; c++) {
        g[c] = S[b].prep.seg.labels[S[a].prep.seg.centers[c]];
        gm[c] = S[b].prep.seg.labels[sym[S[a].prep.seg.centers[c]]];
      }
      printf("   fv %d->%d:", a, b);
      for (int t = 0; t < nfv; t++) {
        double r1 = 0, r2 = 0, med = 0, c0 = cpu_now();
        if (ssi_orient_pair(&S[a].sig, &S[b].sig, g, gm, fv_k[t], ao.orient_descr_k, fv_keep[t], &r1, &r2, &med, &e)) { fprintf(stderr, "%s\n", e.msg); return 1; }
        fv_cpu[t] += cpu_now() - c0;
        fv_ok[t] += r1 > r2, fv_okm[t] += med > 0;
        printf(" [%.3f %.3f %.3f]", r1, r2, med);
      }
      printf("\n");
      fv_n++;
    }
    n_right += all;
    n_mirror += all || allm;
    n_conf += info.confident;
    n_rechecked += info.rechecked;
    n_alt += info.alternatives > 0, n_altc += info.alternative;
    n_conf_wrong += info.confident && !all;
    n_unequal += S[a].sig.m != S[b].sig.m;
    n_done++;
    cpu_sum += info.cpu;
    cpu_max = info.cpu > cpu_max ? info.cpu : cpu_max;
    double merr = NAN;
    if (q < nmatch) {
      ss_match_options mo;
      ss_match_default_options(&mo);
      mo.autopair = ao;
      ss_match_result res;
      if (ss_match_prepared(&S[a].prep, &S[b].prep, 0, NULL, NULL, &mo, &res, &e)) { fprintf(stderr, "%s\n", e.msg); return 1; }
      if (ss_map_geodesic_error(&S[b].m, S[a].m.nv, res.map, NULL, NULL, NULL, &merr, &e)) return 1;
      err_sum += merr, nerr++;
      if (verbose && res.notes[0]) printf("   notes: %s\n", res.notes);
      ss_match_result_free(&res);
    }
    if (verbose)
      printf("%3d -> %3d  m %d/%d  right %d/%d mirror-right %d  E %.4g mirror %.4g other %.4g  gap %.3f rho %.3f "
             "rho_m %.3f margin %.3f conf %d  %s %.4f s  err %.4f  first %.3f %.3f rechecked %d alt %d/%d\n",
             a, b, S[a].sig.m, S[b].sig.m, right, pr.n, mright, info.energy, info.energy_mirror, info.energy_other, info.gap,
             info.mirror, info.mirror_other, info.mirror_margin, info.confident, info.exact ? "exact" : "relaxed", info.cpu, merr,
             info.mirror_first, info.mirror_other_first, info.rechecked, info.alternative, info.alternatives);
    ss_segment_pairs_free(&pr);
  }
  int nsig_ok = 0, nsig_all = 0;
  for (int q = 0; q < 100; q++) {
    if (!S[q].loaded) continue;
    int ok = 1;
    for (int c = 0; c < S[q].sig.m; c++) ok &= S[q].prep.seg.labels[sym[S[q].prep.seg.centers[c]]] == S[q].sig.sigma[c];
    nsig_ok += ok, nsig_all++;
    if (verbose && !ok) {
      printf("shape %d sigma (score %.3f):", q, S[q].sig.sigma_score);
      for (int c = 0; c < S[q].sig.m; c++) printf(" %d/%d", S[q].sig.sigma[c], S[q].prep.seg.labels[sym[S[q].prep.seg.centers[c]]]);
      printf("\n");
    }
  }
  printf("symmetry of the centres right on %d of %d shapes\n", nsig_ok, nsig_all);
  printf("split %s seed %u pairs %d (%d with unequal counts) wd %g wg %g ok %d radius %g: all right %d (%.1f%%), up to "
         "mirror %d (%.1f%%), confident %d (wrong among them %d); search CPU mean %.4f s max %.4f s; signature CPU "
         "mean %.3f s",
         split, seed, n_done, n_unequal, ao.w_descr, ao.w_geo, ao.orient_k, ao.descr_radius, n_right,
         100.0 * n_right / n_done, n_mirror, 100.0 * n_mirror / n_done, n_conf, n_conf_wrong, cpu_sum / n_done, cpu_max,
         nsig ? sig_sum / nsig : 0);
  if (ao.recheck_margin > 0) printf("; second test (margin < %g, k %d, ZoomOut %d on %d samples) on %d pairs", ao.recheck_margin, ao.recheck_k, ao.recheck_zoomout, ao.recheck_samples, n_rechecked);
  if (ao.alt_max > 0) printf("; near-ties (up to %d within %g, margin %g) tested on %d pairs, chosen on %d", ao.alt_max, ao.alt_gap, ao.alt_margin, n_alt, n_altc);
  if (n_gt) printf("; orientation test on the ground-truth pairing right on %d of %d (mean margin %.3f)", n_gtok, n_gt, gt_margin / n_gt);
  for (int t = 0; t < nfv; t++)
    printf("; variant k %d keep %g on the ground truth vs its mirror: right by the whole-shape scores on %d, by the "
           "median rule on %d, of %d (CPU %.3f s)", fv_k[t], fv_keep[t], fv_ok[t], fv_okm[t], fv_n, fv_cpu[t] / fv_n);
  if (nerr) printf("; landmark-free map error mean %.4f over %d pairs", err_sum / nerr, nerr);
  printf("\n");
  if (dump) {
    mkdir(dump, 0755);
    for (int s = 0; s < 100; s++) {
      if (!S[s].loaded) continue;
      snprintf(path, sizeof path, "%s/sig_%03d.bin", dump, s);
      FILE *f = fopen(path, "wb");
      const ss_centre_signature *g = &S[s].sig;
      WR(&g->m, 1), WR(&g->nd, 1), WR(g->centers, g->m), WR(g->descr, (size_t)g->m * g->nd), WR(g->D, g->m * g->m);
      int lab[64];
      for (int c = 0; c < 64 && c < g->m; c++) lab[c] = 0;
      (void)lab;
      fclose(f);
    }
    snprintf(path, sizeof path, "%s/labels.bin", dump);
    FILE *f = fopen(path, "wb");
    for (int s = 0; s < 100; s++)
      if (S[s].loaded) WR(&s, 1), WR(S[s].prep.seg.labels, S[s].m.nv);
    fclose(f);
    snprintf(path, sizeof path, "%s/sym.bin", dump);
    f = fopen(path, "wb");
    WR(sym, m0.nv);
    fclose(f);
  }
  return 0;
}
