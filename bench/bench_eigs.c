/* Benchmark: k = 100 smallest Laplace–Beltrami eigenpairs, specseg (ARPACK or block Lanczos on
 * CHOLMOD, whichever ss_eigs picks) against scipy.sparse.linalg.eigsh(W, k=100, M=M, sigma=-1e-8) on
 * the very same W and M, side by side: repetitions interleaved (ours, SciPy, ours, SciPy, ... for
 * each thread count), so load changes on a shared machine hit both alike. Timed in CPU seconds
 * (this process's for ours, SciPy's own time.process_time() around eigsh), which load does not
 * inflate the way it does wall-clock; wall seconds are printed too.
 *
 *   bench_eigs [--data DIR] [--out DIR] [--python PY] [--script bench_eigs_scipy.py] [--reps R]
 *              [--k K] [--levels L] [--threads 1,2] [--arpack]
 *   (L = 0,1,2: largest subdivision level of FAUST tr_reg_000 to run; --arpack also times ss_eigs
 *    forced to ARPACK, the method below SS_EIGS_BLOCK_MIN_N vertices)
 *
 * Cases: FAUST tr_reg_000 (6,890 vertices) and the same shape subdivided twice (1->4 midpoint,
 * 110,210 vertices). Threads: ours runs T OpenMP threads with OpenBLAS single-threaded (as the
 * specseg program does), SciPy runs with OMP_NUM_THREADS = OPENBLAS_NUM_THREADS = T. Prints per case
 * and thread count the medians, the ratios SciPy / specseg, and the accuracy of both. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "specseg/specseg.h"
#include "specseg/synth.h"

/* OpenBLAS (not through cblas.h, whose complex.h defines I) */
void openblas_set_num_threads(int num_threads);

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
  qsort(v, (size_t)n, sizeof(double), cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* W as three n x 1 triplet arrays, M as n x 1. */
static int export_matrices(const char *prefix, const ss_sparse *W, const double *M) {
  size_t nnz = (size_t)W->colptr[W->ncols];
  double *I = malloc(sizeof(double) * nnz), *J = malloc(sizeof(double) * nnz);
  if (!I || !J) return -1;
  for (int j = 0; j < W->ncols; j++)
    for (int p = W->colptr[j]; p < W->colptr[j + 1]; p++) {
      I[p] = W->rowind[p];
      J[p] = j;
    }
  char path[4200];
  ss_error e;
  int bad = 0;
  snprintf(path, sizeof path, "%s_I.npy", prefix);
  bad |= ss_write_npy(path, I, (int)nnz, 1, &e) != SS_OK;
  snprintf(path, sizeof path, "%s_J.npy", prefix);
  bad |= ss_write_npy(path, J, (int)nnz, 1, &e) != SS_OK;
  snprintf(path, sizeof path, "%s_X.npy", prefix);
  bad |= ss_write_npy(path, W->val, (int)nnz, 1, &e) != SS_OK;
  snprintf(path, sizeof path, "%s_M.npy", prefix);
  bad |= ss_write_npy(path, M, W->ncols, 1, &e) != SS_OK;
  if (bad) fprintf(stderr, "bench_eigs: export failed: %s\n", e.msg);
  free(I);
  free(J);
  return bad ? -1 : 0;
}

/* One run of the SciPy script with T threads; its eigsh wall and CPU seconds (-1 on failure). Echoes
 * its other lines when verbose. */
static int run_scipy(const char *python, const char *script, const char *prefix, int k, int threads, int verbose,
                     double *wall, double *cpu) {
  char cmd[8400];
  snprintf(cmd, sizeof cmd, "OMP_NUM_THREADS=%d OPENBLAS_NUM_THREADS=%d '%s' '%s' '%s' %d 1", threads, threads, python,
           script, prefix, k);
  FILE *p = popen(cmd, "r");
  if (!p) return -1;
  char line[1024];
  *wall = *cpu = -1;
  while (fgets(line, sizeof line, p)) {
    if (!strncmp(line, "scipy_seconds ", 14)) *wall = atof(line + 14);
    else if (!strncmp(line, "scipy_cpu_seconds ", 18)) *cpu = atof(line + 18);
    else if (verbose) printf("  %s", line);
  }
  if (pclose(p) != 0) return -1;
  return *wall > 0 && *cpu > 0 ? 0 : -1;
}

typedef struct {
  double *w, *c;
  int n;
} samples;

static int ours(const ss_sparse *W, const double *M, int k, int method, double *ev, double *X, samples *s,
                ss_eigs_stats *stats, ss_error *e) {
  ss_eigs_options o;
  ss_eigs_default_options(&o);
  o.method = method;
  o.stats = stats;
  double w0 = ss_time(), c0 = cpu_time();
  if (ss_eigs(W, M, k, &o, ev, X, e) != SS_OK) return -1;
  s->c[s->n] = cpu_time() - c0;
  s->w[s->n++] = ss_time() - w0;
  return 0;
}

static const char *method_name(int m) {
  return m == SS_EIGS_BLOCK ? "block Lanczos" : m == SS_EIGS_ARPACK ? "ARPACK" : m == SS_EIGS_PRO ? "partial-reorth Lanczos" : "-";
}

static int run_case(const char *name, const ss_mesh *m, const char *outdir, const char *python, const char *script,
                    int reps, int k, const int *threads, int nthreads, int with_arpack) {
  ss_error e;
  ss_sparse W;
  double *M = malloc(sizeof(double) * (size_t)m->nv);
  if (!M || ss_cotan_stiffness(m, &W, &e) || ss_mass_lumped(m, SS_MASS_BARYCENTRIC, M, &e)) {
    fprintf(stderr, "bench_eigs: %s: operators failed\n", name);
    return 1;
  }
  char prefix[4096];
  snprintf(prefix, sizeof prefix, "%s/%s", outdir, name);
  if (export_matrices(prefix, &W, M)) return 1;
  printf("== %s: %d vertices, nnz(W) = %d, k = %d\n", name, m->nv, W.colptr[W.ncols], k);
  fflush(stdout);
  double *ev = malloc(sizeof(double) * (size_t)k), *X = malloc(sizeof(double) * (size_t)m->nv * (size_t)k);
  samples S[3]; /* ours (AUTO), ours (ARPACK), SciPy */
  for (int q = 0; q < 3; q++) {
    S[q].w = malloc(sizeof(double) * (size_t)reps);
    S[q].c = malloc(sizeof(double) * (size_t)reps);
  }
  int sci_ok = 1;
  for (int t = 0; t < nthreads; t++) {
    int T = threads[t];
    omp_set_num_threads(T);
    openblas_set_num_threads(1);
    for (int q = 0; q < 3; q++) S[q].n = 0;
    ss_eigs_stats st = {0}, sta = {0};
    for (int r = 0; r < reps; r++) {
      if (ours(&W, M, k, SS_EIGS_AUTO, ev, X, &S[0], &st, &e)) {
        fprintf(stderr, "bench_eigs: %s: ss_eigs failed: %s\n", name, e.msg);
        return 1;
      }
      double sw = -1, sc = -1;
      if (sci_ok && run_scipy(python, script, prefix, k, T, r == 0 && t == 0, &sw, &sc) == 0) {
        S[2].w[S[2].n] = sw;
        S[2].c[S[2].n++] = sc;
      } else {
        sci_ok = 0;
      }
      if (with_arpack && st.method != SS_EIGS_ARPACK) {
        double *ea = malloc(sizeof(double) * (size_t)k);
        if (ours(&W, M, k, SS_EIGS_ARPACK, ea, NULL, &S[1], &sta, &e)) {
          fprintf(stderr, "bench_eigs: %s: ss_eigs (ARPACK) failed: %s\n", name, e.msg);
          return 1;
        }
        free(ea);
      }
      printf("  %d thread%s, run %d: specseg %.3f s CPU (%.3f wall)", T, T > 1 ? "s" : "", r + 1, S[0].c[r], S[0].w[r]);
      if (S[1].n > r) printf(", ARPACK path %.3f s CPU (%.3f wall)", S[1].c[r], S[1].w[r]);
      if (S[2].n > r) printf(", scipy %.3f s CPU (%.3f wall)", S[2].c[r], S[2].w[r]);
      printf("\n");
      fflush(stdout);
    }
    double oc = median(S[0].c, S[0].n), ow = median(S[0].w, S[0].n);
    printf("RESULT %s n=%d k=%d threads=%d specseg (%s) %.3f s CPU, %.3f s wall", name, m->nv, k, T,
           method_name(st.method), oc, ow);
    if (S[2].n) {
      double sc = median(S[2].c, S[2].n), sw = median(S[2].w, S[2].n);
      printf("  scipy %.3f s CPU, %.3f s wall  ratio scipy/specseg %.2fx CPU, %.2fx wall", sc, sw, sc / oc, sw / ow);
    } else {
      printf("  scipy: not run (python3 with scipy missing?)");
    }
    printf("\n");
    if (S[1].n) {
      double ac = median(S[1].c, S[1].n), aw = median(S[1].w, S[1].n);
      printf("RESULT %s n=%d k=%d threads=%d specseg ARPACK path %.3f s CPU, %.3f s wall (AUTO is %.2fx faster in CPU)",
             name, m->nv, k, T, ac, aw, ac / oc);
      if (S[2].n) printf("  ratio scipy/ARPACK path %.2fx CPU", median(S[2].c, S[2].n) / ac);
      printf("\n");
    }
    fflush(stdout);
  }
  double res = 0, orth = 0;
  ss_eigs_check(&W, M, k, ev, X, &res, &orth, &e);
  printf("  specseg_max_rel_residual %.3e\n  specseg_max_orth_error %.3e\n", res, orth);
  /* same eigenvalues as SciPy? */
  char path[4200];
  snprintf(path, sizeof path, "%s_scipy_evals.npy", prefix);
  double *sv = NULL;
  int sr = 0, sc = 0;
  if (sci_ok && ss_read_npy(path, &sv, &sr, &sc, &e) == SS_OK && sr * sc == k) {
    double worst = 0;
    for (int i = 0; i < k; i++) worst = fmax(worst, fabs(sv[i] - ev[i]) / (1 + fabs(ev[i])));
    printf("  max |lambda_specseg - lambda_scipy| / (1 + |lambda|) = %.3e\n", worst);
  }
  free(sv);
  fflush(stdout);
  for (int q = 0; q < 3; q++) { free(S[q].w); free(S[q].c); }
  free(ev); free(X); free(M);
  ss_sparse_free(&W);
  return 0;
}

int main(int argc, char **argv) {
  const char *data = getenv("SS_DATA_DIR") ? getenv("SS_DATA_DIR") : SS_DATA_DIR_DEFAULT;
  const char *out = "/tmp", *python = "python3", *script = "scripts/bench_eigs_scipy.py";
  int reps = 3, k = 100, levels = 2, with_arpack = 0;
  int threads[8] = {1, 2}, nthreads = 2;
  for (int i = 1; i < argc; i += 2) {
    if (!strcmp(argv[i], "--arpack")) {
      with_arpack = 1;
      i--;
      continue;
    }
    if (i + 1 >= argc) {
      fprintf(stderr, "bench_eigs: %s needs a value\n", argv[i]);
      return 2;
    }
    if (!strcmp(argv[i], "--threads")) {
      nthreads = 0;
      for (char *p = argv[i + 1]; *p && nthreads < 8;) {
        threads[nthreads] = (int)strtol(p, &p, 10);
        if (threads[nthreads] < 1) {
          fprintf(stderr, "bench_eigs: bad --threads %s\n", argv[i + 1]);
          return 2;
        }
        nthreads++;
        if (*p == ',') p++;
      }
    } else if (!strcmp(argv[i], "--data")) data = argv[i + 1];
    else if (!strcmp(argv[i], "--out")) out = argv[i + 1];
    else if (!strcmp(argv[i], "--python")) python = argv[i + 1];
    else if (!strcmp(argv[i], "--script")) script = argv[i + 1];
    else if (!strcmp(argv[i], "--reps")) reps = atoi(argv[i + 1]);
    else if (!strcmp(argv[i], "--k")) k = atoi(argv[i + 1]);
    else if (!strcmp(argv[i], "--levels")) levels = atoi(argv[i + 1]);
    else {
      fprintf(stderr, "bench_eigs: unknown option %s\n", argv[i]);
      return 2;
    }
  }
  if (reps < 1) reps = 1;
  char path[4096];
  snprintf(path, sizeof path, "%s/faust/tr_reg_000.off", data);
  ss_mesh m;
  ss_error e;
  if (ss_read_mesh(path, &m, &e) != SS_OK) {
    fprintf(stderr, "bench_eigs: %s\n", e.msg);
    return 1;
  }
  int rc = 0;
  for (int level = 0; level <= levels && !rc; level++) {
    if (level > 0) {
      ss_mesh s;
      if (ss_mesh_subdivide(&m, &s, &e) != SS_OK) {
        fprintf(stderr, "bench_eigs: %s\n", e.msg);
        return 1;
      }
      ss_mesh_free(&m);
      m = s;
    }
    if (level == 1 && levels == 2) continue; /* the ~27k mesh only as a step towards ~110k */
    char name[64];
    snprintf(name, sizeof name, level ? "tr_reg_000_sub%d" : "tr_reg_000", level);
    rc = run_case(name, &m, out, python, script, reps, k, threads, nthreads, with_arpack);
  }
  ss_mesh_free(&m);
  return rc;
}
