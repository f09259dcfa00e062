/* Functional-map matching on FAUST (BEST landmarks, ground truth = identity): accuracy and speed of
 * STD (and ZoomOut) over random pairs.
 *   bench_fmap [--data DIR] [--pairs N] [--seed S] [--k K] [--energies E] [--step S]
 *              [--wdescr W] [--wlap W] [--wdcomm W] [--nofix] [--zoomout KMAX] [--euclid]
 * Errors: mean over x of d_Y(Π(x), x) / √area(Y), exact geodesics (ss_geodesic_pairs), or Euclidean
 * with --euclid. Eigenpairs are cached in /tmp/ss_fmap_cache (they do not depend on the options). */
#include "specseg/fmap.h"
#include "specseg/geodesic.h"
#include "specseg/io.h"
#include "specseg/laplacian.h"
#include "specseg/spectrum.h"

#include <cblas.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#ifndef SS_DATA_DIR_DEFAULT
#define SS_DATA_DIR_DEFAULT "../shared/data"
#endif

typedef struct shape {
  ss_mesh m;
  double *M, *ev, *phi;
  int kev;
  ss_geodesic_mesh *gm;
  ss_geodesic_landmarks *lm; /* built by the first error batch with enough far pairs */
} shape;

static int load_shape(const char *dir, int id, int kev, shape *s) {
  char path[4096];
  snprintf(path, sizeof path, "%s/faust/tr_reg_%03d.off", dir, id);
  ss_error e;
  if (ss_read_mesh(path, &s->m, &e)) { fprintf(stderr, "%s\n", e.msg); return 1; }
  int n = s->m.nv;
  s->kev = kev;
  s->M = malloc(sizeof(double) * n);
  s->ev = malloc(sizeof(double) * kev);
  s->phi = malloc(sizeof(double) * (size_t)n * kev);
  s->gm = NULL;
  ss_mass_lumped(&s->m, SS_MASS_BARYCENTRIC, s->M, NULL);
  mkdir("/tmp/ss_fmap_cache", 0755);
  snprintf(path, sizeof path, "/tmp/ss_fmap_cache/faust_%03d_k%d.bin", id, kev);
  FILE *f = fopen(path, "rb");
  if (f) {
    int ok = fread(s->ev, sizeof(double), kev, f) == (size_t)kev &&
             fread(s->phi, sizeof(double), (size_t)n * kev, f) == (size_t)n * kev;
    fclose(f);
    if (ok) return 0;
  }
  if (ss_mesh_eigs(&s->m, kev, s->ev, s->phi, &e)) { fprintf(stderr, "eigs: %s\n", e.msg); return 1; }
  f = fopen(path, "wb");
  if (f) {
    fwrite(s->ev, sizeof(double), kev, f);
    fwrite(s->phi, sizeof(double), (size_t)n * kev, f);
    fclose(f);
  }
  return 0;
}

static double euclid_error(const ss_mesh *Y, const int *map, int nX) {
  double s = 0;
  for (int i = 0; i < nX; i++) {
    const double *a = Y->V + 3 * i, *b = Y->V + 3 * map[i];
    s += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
  }
  return s / nX / sqrt(ss_mesh_area(Y));
}

static double geo_error(shape *Y, const int *map, int nX) {
  ss_error e;
  if (!Y->gm && ss_geodesic_mesh_build(&Y->m, &Y->gm, &e)) { fprintf(stderr, "geodesic: %s\n", e.msg); return NAN; }
  int *gt = malloc(sizeof(int) * nX);
  double *d = malloc(sizeof(double) * nX);
  for (int i = 0; i < nX; i++) gt[i] = i;
  double s = NAN;
  if (!ss_geodesic_pairs(Y->gm, &Y->lm, map, gt, nX, d, &e)) {
    s = 0;
    for (int i = 0; i < nX; i++) s += d[i];
    s /= nX * sqrt(ss_mesh_area(&Y->m));
  } else fprintf(stderr, "geodesic: %s\n", e.msg);
  free(gt);
  free(d);
  return s;
}

int main(int argc, char **argv) {
  const char *dir = SS_DATA_DIR_DEFAULT;
  int npairs = 30, euclid = 0, nnbench = 0;
  const char *symout = NULL;
  int *sym = NULL;
  unsigned seed = 7;
  ss_fmap_match_options o;
  ss_fmap_match_default_options(&o);
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : "0";
    if (!strcmp(a, "--data")) dir = v, i++;
    else if (!strcmp(a, "--pairs")) npairs = atoi(v), i++;
    else if (!strcmp(a, "--seed")) seed = (unsigned)atoi(v), i++;
    else if (!strcmp(a, "--k")) o.k = atoi(v), i++;
    else if (!strcmp(a, "--energies")) o.n_energies = atoi(v), i++;
    else if (!strcmp(a, "--step")) o.descr_step = atoi(v), i++;
    else if (!strcmp(a, "--sigma")) o.sigma_factor = atof(v), i++;
    else if (!strcmp(a, "--wdescr")) o.w_descr = atof(v), i++;
    else if (!strcmp(a, "--wlap")) o.w_lap = atof(v), i++;
    else if (!strcmp(a, "--wdcomm")) o.w_dcomm = atof(v), i++;
    else if (!strcmp(a, "--zoomout")) o.zoomout_kmax = atoi(v), i++;
    else if (!strcmp(a, "--nofix")) o.fix_constant = 0;
    else if (!strcmp(a, "--euclid")) euclid = 1;
    else if (!strcmp(a, "--nnbench")) nnbench = 1;
    else if (!strcmp(a, "--sym-out")) symout = v, i++;
    else { fprintf(stderr, "unknown option %s\n", a); return 2; }
  }
  int lm[5];
  {
    char path[4096];
    snprintf(path, sizeof path, "%s/faust/landmarks_best.txt", dir);
    int *l, nl;
    ss_error e;
    if (ss_read_ints(path, &l, &nl, &e) || nl != 5) { fprintf(stderr, "landmarks: %s\n", e.msg); return 1; }
    memcpy(lm, l, sizeof lm);
    free(l);
  }
  int kev = o.zoomout_kmax > o.k ? o.zoomout_kmax : o.k;
  kev = kev < 100 ? 100 : kev; /* one cache for every setting up to ZoomOut 100 */
  shape *S = calloc(100, sizeof(shape));
  int *loaded = calloc(100, sizeof(int));
  if (symout) {
    /* FAUST's left-right symmetry map, derived from the shapes: tr_reg_000 matched to itself with
     * the BEST landmarks mirrored (head, R hand, R foot, L foot, L hand), ZoomOut 50 -> 100. All
     * FAUST shapes share the template's vertex order, so one map serves every shape. */
    if (load_shape(dir, 0, kev, &S[0])) return 1;
    loaded[0] = 1;
    int n = S[0].m.nv, lmsw[5] = {lm[0], lm[4], lm[3], lm[2], lm[1]};
    sym = malloc(sizeof(int) * n);
    ss_fmap_shape s0 = {&S[0].m, S[0].M, S[0].ev, S[0].phi, S[0].kev, NULL, 0, NULL, 0};
    ss_fmap_match_options os = o;
    os.zoomout_kmax = 100;
    ss_error e;
    if (ss_fmap_match(&s0, &s0, 5, lm, lmsw, 0, NULL, NULL, SS_PROBE_RAW, &os, sym, NULL, &e)) {
      fprintf(stderr, "symmetry: %s\n", e.msg);
      return 1;
    }
    int inv = 0, fixed = 0;
    int *ss2 = malloc(sizeof(int) * n);
    for (int x = 0; x < n; x++) {
      ss2[x] = sym[sym[x]];
      inv += ss2[x] == x;
      fixed += sym[x] == x;
    }
    double einv = 0;
    ss_map_geodesic_error(&S[0].m, n, ss2, NULL, NULL, NULL, &einv, NULL);
    printf("symmetry map: sym(sym(x)) = x on %d of %d vertices, mean geodesic |sym∘sym - id| %.4f, "
           "%d fixed points\n", inv, n, einv, fixed);
    ss_write_ints(symout, sym, n, NULL);
    free(ss2);
  }
  unsigned r = seed;
  double se = 0, st = 0, tmax = 0, ssum = 0;
  int *map = NULL;
  for (int p = 0; p < npairs; p++) {
    int a, b;
    do {
      r = r * 1664525u + 1013904223u; a = (r >> 8) % 100;
      r = r * 1664525u + 1013904223u; b = (r >> 8) % 100;
    } while (a == b);
    int ids[2] = {a, b};
    for (int q = 0; q < 2; q++)
      if (!loaded[ids[q]]) {
        if (load_shape(dir, ids[q], kev, &S[ids[q]])) return 1;
        loaded[ids[q]] = 1;
      }
    shape *X = &S[a], *Y = &S[b];
    map = realloc(map, sizeof(int) * X->m.nv);
    ss_fmap_shape sx = {&X->m, X->M, X->ev, X->phi, X->kev, NULL, 0, NULL, 0}, sy = {&Y->m, Y->M, Y->ev, Y->phi, Y->kev, NULL, 0, NULL, 0};
    ss_error e;
    double t0 = ss_time();
    if (ss_fmap_match(&sx, &sy, 5, lm, lm, 0, NULL, NULL, SS_PROBE_RAW, &o, map, NULL, &e)) {
      fprintf(stderr, "match: %s\n", e.msg);
      return 1;
    }
    double t = ss_time() - t0;
    if (nnbench && p == 0) { /* nearest-neighbour engines on this pair's embeddings, same process */
      int *m1 = malloc(sizeof(int) * X->m.nv), *m2 = malloc(sizeof(int) * X->m.nv);
      double *Cz = malloc(sizeof(double) * 100 * 100), *E = malloc(sizeof(double) * Y->m.nv * 100);
      for (int kk = 50; kk <= 100; kk += 50) {
        ss_fmap_match_options oz = o;
        oz.k = 50;
        oz.zoomout_kmax = kk > 50 ? kk : 0;
        ss_fmap_match(&sx, &sy, 5, lm, lm, 0, NULL, NULL, SS_PROBE_RAW, &oz, m1, Cz, NULL);
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, Y->m.nv, kk, kk, 1.0, Y->phi, Y->m.nv, Cz, kk, 0.0, E,
                    Y->m.nv);
        double w0 = ss_time(), c0 = (double)clock() / CLOCKS_PER_SEC;
        ss_nn_brute(Y->m.nv, X->m.nv, kk, E, Y->m.nv, X->phi, X->m.nv, m1, NULL, NULL);
        double w1 = ss_time(), c1 = (double)clock() / CLOCKS_PER_SEC;
        ss_nn_exact(Y->m.nv, X->m.nv, kk, E, Y->m.nv, X->phi, X->m.nv, m2, NULL, NULL);
        double w2 = ss_time(), c2 = (double)clock() / CLOCKS_PER_SEC;
        int same = 0;
        for (int i = 0; i < X->m.nv; i++) same += m1[i] == m2[i];
        printf("nn k=%d: brute %.3f s wall %.3f s cpu, clustered %.3f s wall %.3f s cpu, ratio(cpu) %.1f, agree %d/%d\n",
               kk, w1 - w0, c1 - c0, w2 - w1, c2 - c1, (c1 - c0) / (c2 - c1), same, X->m.nv);
      }
      free(m1);
      free(m2);
      free(Cz);
      free(E);
    }
    double err = euclid ? euclid_error(&Y->m, map, X->m.nv) : geo_error(Y, map, X->m.nv), esym = NAN;
    if (sym) ss_map_geodesic_error(&Y->m, X->m.nv, map, NULL, sym, NULL, &esym, NULL);
    ssum += esym;
    printf("pair %2d: %3d -> %3d  error %.4f  sym %.4f  time %.3f s\n", p, a, b, err, esym, t);
    fflush(stdout);
    se += err;
    st += t;
    tmax = fmax(tmax, t);
  }
  printf("MEAN %s error %.4f over %d pairs; match time mean %.3f s, max %.3f s (k %d, E %d, step %d, w %g/%g/%g, "
         "fix %d, zoomout %d)\n",
         euclid ? "euclidean" : "geodesic", se / npairs, npairs, st / npairs, tmax, o.k, o.n_energies, o.descr_step,
         o.w_descr, o.w_lap, o.w_dcomm, o.fix_constant, o.zoomout_kmax);
  if (sym) printf("MEAN symmetric geodesic error %.4f\n", ssum / npairs);
  free(sym);
  for (int i = 0; i < 100; i++)
    if (loaded[i]) {
      ss_mesh_free(&S[i].m);
      free(S[i].M); free(S[i].ev); free(S[i].phi);
      if (S[i].gm) ss_geodesic_mesh_free(S[i].gm);
      ss_geodesic_landmarks_free(S[i].lm);
    }
  free(S);
  free(loaded);
  free(map);
  return 0;
}
