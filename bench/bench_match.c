/* Matching with segments as probes on FAUST (paper §6, BEST landmarks, ground truth = identity):
 * mean geodesic error of STD, ASA, DIFF and DIFF + ZoomOut over random pairs, and the time of the
 * whole ss_match (both meshes read from files, streamlining and pairing included) and of ZoomOut.
 *   bench_match [--data DIR] [--pairs N] [--seed S] [--k K] [--zoomout KMAX] [--energies E]
 *               [--step S] [--wdescr W] [--wlap W] [--wdcomm W] [--no-timing] [--verbose]
 *               [--zo-pairs N] [--timed-pairs N]   (ZoomOut / whole-match timing on the first N pairs only)
 * Errors: mean over x of d_Y(Π(x), x) / √area(Y), exact geodesics (ss_map_geodesic_error).
 * Accuracy runs reuse one ss_shape_prep per shape (segmentation + 100 eigenpairs); the timed run
 * is a separate, complete ss_match per pair (DIFF, no ZoomOut). */
#include "specseg/fmap.h"
#include "specseg/io.h"
#include "specseg/match.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifndef SS_DATA_DIR_DEFAULT
#define SS_DATA_DIR_DEFAULT "../shared/data"
#endif

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}
static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof(double), cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

typedef struct slot {
  ss_mesh m;
  ss_shape_prep prep;
  int loaded;
} slot;

static int load(const char *dir, int id, const ss_match_options *o, int kev, slot *s) {
  if (s->loaded) return 0;
  char path[4096];
  snprintf(path, sizeof path, "%s/faust/tr_reg_%03d.off", dir, id);
  ss_error e;
  if (ss_read_mesh(path, &s->m, &e) || ss_shape_prep_compute(&s->m, &o->seg, kev, &s->prep, &e)) {
    fprintf(stderr, "shape %d: %s\n", id, e.msg);
    return 1;
  }
  s->loaded = 1;
  return 0;
}

int main(int argc, char **argv) {
  const char *dir = SS_DATA_DIR_DEFAULT;
  int npairs = 30, timing = 1, verbose = 0, zo_pairs = 1 << 30, timed_pairs = 1 << 30;
  unsigned seed = 7;
  ss_match_options o;
  ss_match_default_options(&o);
  o.fmap.zoomout_kmax = 100;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : "0";
    if (!strcmp(a, "--data")) dir = v, i++;
    else if (!strcmp(a, "--pairs")) npairs = atoi(v), i++;
    else if (!strcmp(a, "--seed")) seed = (unsigned)atoi(v), i++;
    else if (!strcmp(a, "--k")) o.fmap.k = atoi(v), i++;
    else if (!strcmp(a, "--zoomout")) o.fmap.zoomout_kmax = atoi(v), i++;
    else if (!strcmp(a, "--energies")) o.fmap.n_energies = atoi(v), i++;
    else if (!strcmp(a, "--step")) o.fmap.descr_step = atoi(v), i++;
    else if (!strcmp(a, "--wdescr")) o.fmap.w_descr = atof(v), i++;
    else if (!strcmp(a, "--wlap")) o.fmap.w_lap = atof(v), i++;
    else if (!strcmp(a, "--wdcomm")) o.fmap.w_dcomm = atof(v), i++;
    else if (!strcmp(a, "--no-timing")) timing = 0;
    else if (!strcmp(a, "--zo-pairs")) zo_pairs = atoi(v), i++;
    else if (!strcmp(a, "--timed-pairs")) timed_pairs = atoi(v), i++;
    else if (!strcmp(a, "--verbose")) verbose = 1;
    else { fprintf(stderr, "unknown option %s\n", a); return 2; }
  }
  if (npairs < 1 || o.fmap.k < 3 || (o.fmap.zoomout_kmax && o.fmap.zoomout_kmax < o.fmap.k)) {
    fprintf(stderr, "bad options\n");
    return 2;
  }
  int *lm = NULL, nl = 0;
  {
    char path[4096];
    snprintf(path, sizeof path, "%s/faust/landmarks_best.txt", dir);
    ss_error e;
    if (ss_read_ints(path, &lm, &nl, &e)) {
      fprintf(stderr, "landmarks: %s\n", e.msg);
      return 1;
    }
  }
  int kev = o.fmap.zoomout_kmax > o.fmap.k ? o.fmap.zoomout_kmax : o.fmap.k;
  slot *S = calloc(100, sizeof(slot));
  double sum[4] = {0}, *tmatch = calloc((size_t)npairs, sizeof(double)), *tzoom = calloc((size_t)npairs, sizeof(double));
  double *cmatch = calloc((size_t)npairs, sizeof(double));
  double *tpair = calloc((size_t)npairs, sizeof(double)), *tfmap = calloc((size_t)npairs, sizeof(double));
  int better = 0, npaired = 0, nzo = 0, ntimed = 0;
  double sum_diff_zo = 0;
  const char *names[4] = {"STD", "ASA", "DIFF", "DIFF+ZO"};
  printf("FAUST, %d pairs (seed %u), %d BEST landmarks, k %d, ZoomOut %d, energies %d step %d, weights %g %g %g\n",
         npairs, seed, nl, o.fmap.k, o.fmap.zoomout_kmax, o.fmap.n_energies, o.fmap.descr_step, o.fmap.w_descr,
         o.fmap.w_lap, o.fmap.w_dcomm);
  unsigned r = seed;
  for (int p = 0; p < npairs; p++) {
    int a, b;
    do {
      r = r * 1664525u + 1013904223u;
      a = (r >> 8) % 100;
      r = r * 1664525u + 1013904223u;
      b = (r >> 8) % 100;
    } while (a == b);
    if (load(dir, a, &o, kev, &S[a]) || load(dir, b, &o, kev, &S[b])) return 1;
    double err4[4];
    ss_error e;
    for (int v = 0; v < 4; v++) {
      ss_match_options ov = o;
      ov.probes = v == 0 ? SS_PROBES_STD : v == 1 ? SS_PROBES_ASA : SS_PROBES_DIFF;
      if (v < 3) ov.fmap.zoomout_kmax = 0;
      if (v == 3 && (o.fmap.zoomout_kmax <= o.fmap.k || p >= zo_pairs)) { err4[3] = NAN; continue; }
      ss_match_result res;
      if (ss_match_prepared(&S[a].prep, &S[b].prep, nl, lm, lm, &ov, &res, &e) ||
          ss_map_geodesic_error(&S[b].m, res.nX, res.map, NULL, NULL, NULL, &err4[v], &e)) {
        fprintf(stderr, "pair %d-%d %s: %s\n", a, b, names[v], e.msg);
        return 1;
      }
      if (v == 3) tzoom[p] = res.t_zoomout;
      if (v == 2) {
        npaired = res.pairs.n;
        tpair[p] = res.t_pair;
        tfmap[p] = res.t_fmap;
      }
      ss_match_result_free(&res);
    }
    for (int v = 0; v < 3; v++) sum[v] += err4[v];
    if (!isnan(err4[3])) sum[3] += err4[3], sum_diff_zo += err4[2], nzo++;
    better += err4[2] < err4[0];
    if (timing && p < timed_pairs) { /* the whole pipeline from the files, nothing cached */
      char pa[4096], pb[4096];
      snprintf(pa, sizeof pa, "%s/faust/tr_reg_%03d.off", dir, a);
      snprintf(pb, sizeof pb, "%s/faust/tr_reg_%03d.off", dir, b);
      ss_match_options ot = o;
      ot.probes = SS_PROBES_DIFF;
      ot.fmap.zoomout_kmax = 0;
      double t0 = ss_time(), c0 = (double)clock() / CLOCKS_PER_SEC;
      ss_mesh X = {0}, Y = {0};
      ss_match_result res;
      if (ss_read_mesh(pa, &X, &e) || ss_read_mesh(pb, &Y, &e) || ss_match(&X, &Y, nl, lm, lm, &ot, &res, &e)) {
        fprintf(stderr, "timed pair %d-%d: %s\n", a, b, e.msg);
        return 1;
      }
      tmatch[ntimed] = ss_time() - t0;
      cmatch[ntimed++] = (double)clock() / CLOCKS_PER_SEC - c0;
      if (verbose)
        fprintf(stderr, "  timed: segment %.3f eigs %.3f pair %.3f fmap %.3f total %.3f\n", res.t_segment, res.t_eigs,
                res.t_pair, res.t_fmap, tmatch[ntimed - 1]);
      ss_match_result_free(&res);
      ss_mesh_free(&X);
      ss_mesh_free(&Y);
    }
    printf("pair %2d: %3d -> %3d  segs %2d/%2d paired %2d  STD %.4f ASA %.4f DIFF %.4f DIFF+ZO %.4f  match %.3f s "
           "zoomout %.3f s\n",
           p, a, b, S[a].prep.seg.m, S[b].prep.seg.m, npaired, err4[0], err4[1], err4[2], err4[3],
           timing && p < timed_pairs ? tmatch[ntimed - 1] : 0.0, tzoom[p]);
    fflush(stdout);
  }
  printf("mean error over %d pairs:", npairs);
  for (int v = 0; v < 3; v++) printf("  %s %.4f", names[v], sum[v] / npairs);
  if (nzo) printf("\nover the first %d pairs: DIFF %.4f, DIFF+ZoomOut %.4f", nzo, sum_diff_zo / nzo, sum[3] / nzo);
  printf("\nDIFF/STD %.3f (goal <= 0.8), ASA/STD %.3f (goal <= 1); DIFF better than STD on %d of %d pairs\n",
         sum[2] / sum[0], sum[1] / sum[0], better, npairs);
  printf("reference: pyFM STD 0.046, pyFM ZoomOut 0.030; paper STD 0.027, DIFF 0.020\n");
  printf("median pairing %.3f s, fmap (k %d) %.3f s\n", median(tpair, npairs), o.fmap.k, median(tfmap, npairs));
  if (timing && ntimed) printf("median whole ss_match (files in, DIFF) over %d pairs %.3f s wall, %.3f s CPU (goal <= 1 s; pyFM ~10 s)\n", ntimed, median(tmatch, ntimed), median(cmatch, ntimed));
  if (nzo) printf("median ZoomOut %d -> %d: %.3f s (goal < 3 s; pyFM ~58 s)\n", o.fmap.k, o.fmap.zoomout_kmax,
         median(tzoom, nzo));
  for (int i = 0; i < 100; i++)
    if (S[i].loaded) ss_shape_prep_free(&S[i].prep), ss_mesh_free(&S[i].m);
  free(S), free(lm), free(tmatch), free(tzoom), free(tpair), free(tfmap), free(cmatch);
  return 0;
}
