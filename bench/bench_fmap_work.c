/* The functional-map solver's buffers shared across a match's systems (fmap/fmap_work.h) against
 * fresh ones for each system (the public ss_fmap_system_new / ss_fmap_system_solve), as a library
 * user's process sees them: the allocator's own settings (the CLI raises glibc's mmap threshold; a
 * program or the Python package does not).
 *   bench_fmap_work [--k K] [--systems S] [--rounds R]
 * Each round assembles S systems of k² unknowns (a landmark-free match: ~14 at k = 50) and solves
 * each twice (base, then with an extra block), once each way, interleaved; prints the medians of CPU
 * time and page faults and their ratio, and checks that both ways give the same bits. Probes are
 * random (the cost depends on the sizes alone): 110 descriptors with operators, 2 orientation
 * operators, 16 extra probes, as a match's at k = 50. */
#include "specseg/fmap.h"
#include "fmap/fmap_work.h"
#include "../tests/fmap_random.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

static unsigned rng = 11u;

static double cpu_now(void) { return (double)clock() / CLOCKS_PER_SEC; }
static long faults_now(void) {
  struct rusage u;
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}
static int cmp_d(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}
static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, cmp_d);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int main(int argc, char **argv) {
  int k = 50, ns = 14, rounds = 3;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!strcmp(argv[i], "--k")) k = atoi(argv[i + 1]);
    else if (!strcmp(argv[i], "--systems")) ns = atoi(argv[i + 1]);
    else if (!strcmp(argv[i], "--rounds")) rounds = atoi(argv[i + 1]);
    else { fprintf(stderr, "bench_fmap_work: unknown option %s\n", argv[i]); return 2; }
  }
  if (k < 3 || k > 200 || ns < 1 || rounds < 1 || rounds > 50) { fprintf(stderr, "bench_fmap_work: bad sizes\n"); return 2; }
  ss_fmap_probes bS, bT, xS, xT;
  fr_random_probes(k, 110, 110, 2, &rng, &bS), fr_random_probes(k, 110, 110, 2, &rng, &bT);
  fr_random_probes(k, 16, 16, 0, &rng, &xS), fr_random_probes(k, 16, 16, 0, &rng, &xT);
  double *eS = malloc(sizeof(double) * k), *eT = malloc(sizeof(double) * k);
  for (int i = 0; i < k; i++) eS[i] = 0.1 * i + 0.01 * fr_urand(&rng), eT[i] = 0.1 * i + 0.01 * fr_urand(&rng);
  eS[0] = eT[0] = 0;
  const ss_fmap_weights w = {1.0, 1e-3, 1e-2, 1, 1.0, 1e-3};
  const size_t kk = (size_t)k * k;
  double *C[2] = {malloc(sizeof(double) * kk * 2 * ns), malloc(sizeof(double) * kk * 2 * ns)};
  double *cpu[2] = {malloc(sizeof(double) * rounds), malloc(sizeof(double) * rounds)};
  double *flt[2] = {malloc(sizeof(double) * rounds), malloc(sizeof(double) * rounds)};
  int same = 1;
  ss_error e;
  printf("%d systems of %d unknowns a round (base + extra-block solves), %d rounds, interleaved\n", ns, k * k, rounds);
  for (int r = 0; r < rounds; r++)
    for (int way = 0; way < 2; way++) { /* 0: fresh buffers (public API), 1: one work */
      ssi_fmap_work work = {0};
      const double t0 = cpu_now();
      const long f0 = faults_now();
      for (int s = 0; s < ns; s++) {
        ss_fmap_system *sys = NULL;
        double *c0 = C[way] + kk * 2 * s, *c1 = c0 + kk;
        ss_status st = way ? ssi_fmap_system_new_in(k, k, eS, eT, &bS, &bT, &w, &work, &sys, &e)
                           : ss_fmap_system_new(k, k, eS, eT, &bS, &bT, &w, &sys, &e);
        if (!st) st = way ? ssi_fmap_system_solve_in(sys, NULL, NULL, 0, 0, &work, c0, &e) : ss_fmap_system_solve(sys, NULL, NULL, 0, 0, c0, &e);
        if (!st) st = way ? ssi_fmap_system_solve_in(sys, &xS, &xT, 1.0, 1, &work, c1, &e) : ss_fmap_system_solve(sys, &xS, &xT, 1.0, 1, c1, &e);
        ss_fmap_system_free(sys);
        if (st) { fprintf(stderr, "bench_fmap_work: %s\n", e.msg); return 1; }
      }
      ssi_fmap_work_free(&work);
      cpu[way][r] = cpu_now() - t0, flt[way][r] = (double)(faults_now() - f0);
      printf("round %d %-14s %.3f s CPU, %.0f page faults\n", r, way ? "one work" : "fresh buffers", cpu[way][r], flt[way][r]);
    }
  same = !memcmp(C[0], C[1], sizeof(double) * kk * 2 * ns);
  const double c0 = median(cpu[0], rounds), c1 = median(cpu[1], rounds), f0 = median(flt[0], rounds), f1 = median(flt[1], rounds);
  printf("fresh buffers (reference): %.3f s CPU, %.0f page faults (median)\n", c0, f0);
  printf("one work:                  %.3f s CPU, %.0f page faults (median)\n", c1, f1);
  printf("ratio (CPU, reference / one work): %.2f; the same solutions to the bit: %s\n", c0 / c1, same ? "yes" : "NO");
  ss_fmap_probes_free(&bS), ss_fmap_probes_free(&bT), ss_fmap_probes_free(&xS), ss_fmap_probes_free(&xT);
  free(eS), free(eT), free(C[0]), free(C[1]), free(cpu[0]), free(cpu[1]), free(flt[0]), free(flt[1]);
  return same ? 0 : 1;
}
