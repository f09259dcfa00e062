/* Benchmark: k = 100 smallest Laplace–Beltrami eigenpairs, specseg (ARPACK + CHOLMOD) against
 * scipy.sparse.linalg.eigsh(W, k=100, M=M, sigma=-1e-8) on the very same W and M, run side by side
 * (interleaved repetitions, so load changes on a shared machine hit both alike).
 *
 *   bench_eigs [--data DIR] [--out DIR] [--python PY] [--script bench_eigs_scipy.py] [--reps R]
 *              [--k K] [--levels L]   (L = 0,1,2: largest subdivision level of FAUST tr_reg_000 to run)
 *
 * Cases: FAUST tr_reg_000 (6,890 vertices) and the same shape subdivided twice (1->4 midpoint,
 * ~110k vertices). Prints per case: both median times, the ratio, and the accuracy of both. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "specseg/specseg.h"
#include "specseg/synth.h"

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

/* One run of the SciPy script; returns its eigsh time or -1. Echoes its other lines. */
static double run_scipy(const char *python, const char *script, const char *prefix, int k, int verbose) {
  char cmd[8192];
  snprintf(cmd, sizeof cmd, "'%s' '%s' '%s' %d 1", python, script, prefix, k);
  FILE *p = popen(cmd, "r");
  if (!p) return -1;
  char line[1024];
  double t = -1;
  while (fgets(line, sizeof line, p)) {
    if (!strncmp(line, "scipy_seconds ", 14)) t = atof(line + 14);
    else if (verbose) printf("  %s", line);
  }
  if (pclose(p) != 0) return -1;
  return t;
}

static int run_case(const char *name, const ss_mesh *m, const char *outdir, const char *python, const char *script,
                    int reps, int k) {
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
  double *tours = malloc(sizeof(double) * (size_t)reps), *tsci = malloc(sizeof(double) * (size_t)reps);
  int nsci = 0;
  for (int r = 0; r < reps; r++) {
    double t0 = ss_time();
    if (ss_eigs(&W, M, k, NULL, ev, X, &e) != SS_OK) {
      fprintf(stderr, "bench_eigs: %s: ss_eigs failed: %s\n", name, e.msg);
      return 1;
    }
    tours[r] = ss_time() - t0;
    double ts = run_scipy(python, script, prefix, k, r == 0);
    if (ts > 0) tsci[nsci++] = ts;
    printf("  run %d: specseg %.3f s, scipy %.3f s\n", r + 1, tours[r], ts);
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
  if (nsci && ss_read_npy(path, &sv, &sr, &sc, &e) == SS_OK && sr * sc == k) {
    double worst = 0;
    for (int i = 0; i < k; i++) worst = fmax(worst, fabs(sv[i] - ev[i]) / (1 + fabs(ev[i])));
    printf("  max |lambda_specseg - lambda_scipy| / (1 + |lambda|) = %.3e\n", worst);
  }
  free(sv);
  double to = median(tours, reps);
  if (nsci) {
    double tsm = median(tsci, nsci);
    printf("RESULT %s n=%d k=%d specseg %.3f s  scipy %.3f s  ratio %.2fx\n", name, m->nv, k, to, tsm, tsm / to);
  } else {
    printf("RESULT %s n=%d k=%d specseg %.3f s  scipy: not run (python3 with scipy missing?)\n", name, m->nv, k, to);
  }
  fflush(stdout);
  free(ev); free(X); free(tours); free(tsci); free(M);
  ss_sparse_free(&W);
  return 0;
}

int main(int argc, char **argv) {
  const char *data = getenv("SS_DATA_DIR") ? getenv("SS_DATA_DIR") : SS_DATA_DIR_DEFAULT;
  const char *out = "/tmp", *python = "python3", *script = "scripts/bench_eigs_scipy.py";
  int reps = 3, k = 100, levels = 2;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!strcmp(argv[i], "--data")) data = argv[i + 1];
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
    rc = run_case(name, &m, out, python, script, reps, k);
  }
  ss_mesh_free(&m);
  return rc;
}
