/* Large meshes (issue 14, item 2): CPU seconds and peak RSS of whole `specseg segment` and
 * `specseg match` runs on FAUST tr_reg_000 / tr_reg_001 midpoint-subdivided L times (L = 0: 6,890
 * vertices; 1: 27.6k; 2: 110k; 3: 441k; 4: 1.76M).
 *
 *   bench_large [--data DIR] [--dir TMPDIR] [--levels 2,3,4] [--ops segment,match] [--reps N]
 *               [--bin SPECSEG] [--match-args "ARGS"] [--write-only]
 *
 * The subdivided meshes are written to TMPDIR (default /tmp/specseg_large; never into the
 * repository) the first time and reused. Each run is a child process (the CLI, exec'd); its user +
 * system CPU time and peak RSS come from wait4(), medians over --reps runs (default 1: the large
 * runs are long, and one at a time on a shared machine). `segment` also prints the segment count.
 * `match` is the CLI's default (landmark-free, refined) unless --match-args says otherwise
 * (e.g. "--no-refine"). Without the FAUST data it prints SKIP and exits 0. */
#define _DEFAULT_SOURCE
#include "specseg/io.h"
#include "specseg/mesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef SS_DATA_DIR_DEFAULT
#define SS_DATA_DIR_DEFAULT "../shared/data"
#endif
#ifndef SS_CLI_DEFAULT
#define SS_CLI_DEFAULT "./specseg"
#endif

static int cmp_d(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, cmp_d);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static int file_exists(const char *p) {
  struct stat s;
  return stat(p, &s) == 0 && s.st_size > 0;
}

/* tr_reg_NNN subdivided `level` times, written to dir once. */
static int ensure_mesh(const char *data, const char *dir, int shape, int level, char *path, size_t n) {
  snprintf(path, n, "%s/tr_reg_%03d_s%d.off", dir, shape, level);
  if (file_exists(path)) return 0;
  char src[1024];
  snprintf(src, sizeof src, "%s/faust/tr_reg_%03d.off", data, shape);
  ss_error e = {0};
  ss_mesh m = {0};
  if (ss_read_mesh(src, &m, &e)) {
    fprintf(stderr, "bench_large: %s\n", e.msg);
    return -1;
  }
  for (int l = 0; l < level; l++) {
    ss_mesh s = {0};
    if (ss_mesh_subdivide(&m, &s, &e)) {
      fprintf(stderr, "bench_large: subdivide: %s\n", e.msg);
      ss_mesh_free(&m);
      return -1;
    }
    ss_mesh_free(&m);
    m = s;
  }
  ss_status st = ss_write_mesh(path, &m, NULL, &e);
  ss_mesh_free(&m);
  if (st) {
    fprintf(stderr, "bench_large: %s\n", e.msg);
    return -1;
  }
  return 0;
}

/* Runs argv (NULL-terminated) with stdout/stderr to `log`; CPU seconds (user + sys) and peak RSS
 * (MB) of the child. Returns its exit status (-1: could not run). */
static int run(char **argv, const char *log, double *cpu, double *rss_mb) {
  fflush(stdout); /* or the child's copy of the buffer is printed twice */
  pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    FILE *f = freopen(log, "w", stdout);
    if (f) dup2(fileno(stdout), 2);
    execv(argv[0], argv);
    _exit(127);
  }
  int status = 0;
  struct rusage ru;
  if (wait4(pid, &status, 0, &ru) < 0) return -1;
  *cpu = (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec + (double)ru.ru_stime.tv_sec +
         1e-6 * (double)ru.ru_stime.tv_usec;
  *rss_mb = (double)ru.ru_maxrss / 1024.0;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static int count_segments(const char *labels) {
  FILE *f = fopen(labels, "r");
  if (!f) return -1;
  int x, mx = -1;
  while (fscanf(f, "%d", &x) == 1)
    if (x > mx) mx = x;
  fclose(f);
  return mx + 1;
}

int main(int argc, char **argv) {
  const char *data = getenv("SS_DATA_DIR") ? getenv("SS_DATA_DIR") : SS_DATA_DIR_DEFAULT;
  const char *dir = "/tmp/specseg_large", *bin = SS_CLI_DEFAULT, *levels = "2,3,4", *ops = "segment,match";
  const char *match_args = "";
  int reps = 1, write_only = 0;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--data") && i + 1 < argc) data = argv[++i];
    else if (!strcmp(argv[i], "--dir") && i + 1 < argc) dir = argv[++i];
    else if (!strcmp(argv[i], "--levels") && i + 1 < argc) levels = argv[++i];
    else if (!strcmp(argv[i], "--ops") && i + 1 < argc) ops = argv[++i];
    else if (!strcmp(argv[i], "--reps") && i + 1 < argc) reps = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--bin") && i + 1 < argc) bin = argv[++i];
    else if (!strcmp(argv[i], "--match-args") && i + 1 < argc) match_args = argv[++i];
    else if (!strcmp(argv[i], "--write-only")) write_only = 1;
    else {
      fprintf(stderr,
              "usage: bench_large [--data DIR] [--dir TMPDIR] [--levels 2,3,4] [--ops segment,match] [--reps N]\n"
              "                   [--bin SPECSEG] [--match-args \"ARGS\"] [--write-only]\n");
      return 2;
    }
  }
  if (reps < 1 || reps > 99) reps = 1;
  char probe[1024];
  snprintf(probe, sizeof probe, "%s/faust/tr_reg_000.off", data);
  if (!file_exists(probe)) {
    printf("SKIP: %s not found\n", probe);
    return 0;
  }
  mkdir(dir, 0755);
  const int do_seg = strstr(ops, "segment") != NULL, do_match = strstr(ops, "match") != NULL;
  printf("%-8s %5s %9s %9s %9s %s\n", "op", "level", "vertices", "cpu_s", "rss_MB", "notes");
  for (const char *p = levels; *p;) {
    int level = (int)strtol(p, (char **)&p, 10);
    if (*p == ',') p++;
    if (level < 0 || level > 5) continue;
    char X[1100], Y[1100];
    if (ensure_mesh(data, dir, 0, level, X, sizeof X)) return 1;
    if (do_match && ensure_mesh(data, dir, 1, level, Y, sizeof Y)) return 1;
    if (write_only) {
      printf("wrote %s%s%s\n", X, do_match ? " " : "", do_match ? Y : "");
      continue;
    }
    ss_mesh m = {0};
    ss_error e = {0};
    int nv = 0;
    if (!ss_read_mesh(X, &m, &e)) nv = m.nv;
    ss_mesh_free(&m);
    for (int op = 0; op < 2; op++) {
      if ((op == 0 && !do_seg) || (op == 1 && !do_match)) continue;
      double cpu[99], rss[99];
      char out[1200], log[1200], note[1400] = "";
      snprintf(out, sizeof out, "%s/%s_s%d.txt", dir, op ? "map" : "labels", level);
      snprintf(log, sizeof log, "%s/%s_s%d.log", dir, op ? "match" : "segment", level);
      int ok = 1;
      for (int r = 0; r < reps && ok; r++) {
        char *av[32];
        int n = 0;
        av[n++] = (char *)bin;
        av[n++] = op ? "match" : "segment";
        av[n++] = X;
        if (op) av[n++] = Y;
        av[n++] = "-o";
        av[n++] = out;
        char extra[512];
        snprintf(extra, sizeof extra, "%s", op ? match_args : "");
        for (char *t = strtok(extra, " "); t && n < 30; t = strtok(NULL, " ")) av[n++] = t;
        av[n] = NULL;
        int rc = run(av, log, &cpu[r], &rss[r]);
        if (rc != 0) {
          snprintf(note, sizeof note, "FAILED (exit %d, see %s)", rc, log);
          ok = 0;
        }
      }
      if (ok && op == 0) snprintf(note, sizeof note, "%d segments", count_segments(out));
      printf("%-8s %5d %9d %9.2f %9.0f %s\n", op ? "match" : "segment", level, nv, ok ? median(cpu, reps) : NAN,
             ok ? median(rss, reps) : NAN, note);
      fflush(stdout);
    }
  }
  return 0;
}
