/* Benchmark: streamlining on FAUST (paper §4.1): CMCF smoothing and isotropic remeshing to 15k
 * triangles of every tr_reg_XXX.off, with the remesh quality bounds of issue 3.
 *
 *   bench_streamline [--data DIR] [--count N]
 *
 * Prints median wall and CPU times of CMCF, remesh and Ψ, and the worst quality over the shapes
 * (fraction of triangles with min angle >= 30°, fraction of valence-6 vertices, face-count error,
 * max deviation / bbox diagonal, topology). For reference: CGAL's isotropic remeshing to ~15k takes
 * 170–230 ms on this machine (paper-notes), the paper reports CMCF 0.14 s and remeshing 0.84 s on
 * an M1 Pro. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "specseg/specseg.h"
#include "specseg/synth.h"

#ifndef SS_DATA_DIR_DEFAULT
#define SS_DATA_DIR_DEFAULT "../shared/data"
#endif

static double cpu_time(void) {
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v, int n) {
  if (n == 0) return NAN;
  qsort(v, (size_t)n, sizeof(double), cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int main(int argc, char **argv) {
  const char *data = SS_DATA_DIR_DEFAULT;
  int count = 100;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--data") && i + 1 < argc) data = argv[++i];
    else if (!strcmp(argv[i], "--count") && i + 1 < argc) count = atoi(argv[++i]);
    else { fprintf(stderr, "usage: bench_streamline [--data DIR] [--count N]\n"); return 2; }
  }
  if (count < 1) count = 1;
  double *w[3], *c[3];
  for (int k = 0; k < 3; k++) { w[k] = malloc(sizeof(double) * count); c[k] = malloc(sizeof(double) * count); }
  double worst_ang = 1, worst_val = 1, worst_face = 0, worst_dev = 0;
  int n = 0, bad_topo = 0, failures = 0;
  ss_remesh_options ro;
  ss_remesh_default_options(&ro);
  for (int i = 0; i < count; i++) {
    char path[4096];
    snprintf(path, sizeof path, "%s/faust/tr_reg_%03d.off", data, i);
    ss_mesh m, s, r;
    ss_error e = {{0}};
    if (ss_read_mesh(path, &m, &e) != SS_OK) { if (i == 0) { fprintf(stderr, "%s\n", e.msg); return 1; } break; }
    double w0 = ss_time(), c0 = cpu_time();
    if (ss_cmcf_smooth(&m, NULL, &s, &e)) { fprintf(stderr, "%s: %s\n", path, e.msg); failures++; ss_mesh_free(&m); continue; }
    double w1 = ss_time(), c1 = cpu_time();
    if (ss_remesh(&s, &ro, &r, &e)) { fprintf(stderr, "%s: %s\n", path, e.msg); failures++; ss_mesh_free(&m); ss_mesh_free(&s); continue; }
    double w2 = ss_time(), c2 = cpu_time();
    int *psi = malloc(sizeof(int) * (size_t)s.nv);
    ss_closest_vertices(s.V, s.nv, &r, psi, &e);
    double w3 = ss_time(), c3 = cpu_time();
    free(psi);
    w[0][n] = w1 - w0; w[1][n] = w2 - w1; w[2][n] = w3 - w2;
    c[0][n] = c1 - c0; c[1][n] = c2 - c1; c[2][n] = c3 - c2;
    ss_remesh_quality q;
    ss_mesh_report in_rep, out_rep;
    if (ss_remesh_quality_measure(&r, &s, &q, &e) == SS_OK && ss_mesh_check(&s, &in_rep, &e) == SS_OK &&
        ss_mesh_check(&r, &out_rep, &e) == SS_OK) {
      worst_ang = fmin(worst_ang, q.frac_min_angle_30);
      worst_val = fmin(worst_val, q.frac_valence_6);
      worst_face = fmax(worst_face, fabs(q.faces / (double)ro.target_faces - 1));
      worst_dev = fmax(worst_dev, q.max_deviation);
      if (!out_rep.manifold || out_rep.boundary_edges || out_rep.components != in_rep.components ||
          out_rep.euler_characteristic != in_rep.euler_characteristic)
        bad_topo++;
    }
    n++;
    ss_mesh_free(&m); ss_mesh_free(&s); ss_mesh_free(&r);
  }
  printf("FAUST shapes: %d (failures %d)\n", n, failures);
  printf("median wall  : cmcf %.1f ms  remesh %.1f ms  psi %.2f ms\n", 1e3 * median(w[0], n), 1e3 * median(w[1], n), 1e3 * median(w[2], n));
  printf("median cpu   : cmcf %.1f ms  remesh %.1f ms  psi %.2f ms\n", 1e3 * median(c[0], n), 1e3 * median(c[1], n), 1e3 * median(c[2], n));
  printf("worst quality: min angle >= 30: %.2f%% (need >= 90)  valence 6: %.1f%% (need >= 70)  face error %.2f%% (need <= 5)\n",
         100 * worst_ang, 100 * worst_val, 100 * worst_face);
  printf("               max deviation / bbox diag %.1e (need <= 5e-3)  topology changed on %d shapes\n", worst_dev, bad_topo);
  for (int k = 0; k < 3; k++) { free(w[k]); free(c[k]); }
  return failures || bad_topo;
}
