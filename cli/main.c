#include "cli.h"
#include "cli_shape.h"

#include <cblas.h>
#include <errno.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <math.h>
#include <stdarg.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <dlfcn.h>
#include <string.h>

int cli_error(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  cli_diag("error", fmt, ap);
  va_end(ap);
  return SS_EXIT_FAIL;
}

int cli_usage(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  cli_diag("usage", fmt, ap);
  va_end(ap);
  return SS_EXIT_USAGE;
}

void cli_warn(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  cli_diag("warning", fmt, ap);
  va_end(ap);
}

int cli_parse_int(const char *s, long lo, long hi, int *out) {
  if (!s || !*s) return -1;
  char *end;
  errno = 0;
  long v = strtol(s, &end, 10);
  if (errno || *end || v < lo || v > hi) return -1;
  *out = (int)v;
  return 0;
}

int cli_parse_double(const char *s, double *out) {
  if (!s || !*s) return -1;
  char *end;
  errno = 0;
  double v = strtod(s, &end);
  if (errno || *end || isnan(v)) return -1;
  *out = v;
  return 0;
}

typedef struct {
  const char *name;
  int (*run)(int, char **);
  const char *what;
} command;

static const command commands[] = {
    {"info", cmd_info, "mesh statistics and checks"},
    {"eigs", cmd_eigs, "Laplace-Beltrami eigenvalues (and eigenvectors as .npy)"},
    {"descriptors", cmd_descriptors, "WKS / HKS per-vertex descriptors as .npy (for match --descriptors)"},
    {"demo", cmd_demo, "the pipeline on built-in synthetic shapes, no data needed"},
    {"smooth", cmd_smooth, "conformalized mean curvature flow"},
    {"remesh", cmd_remesh, "isotropic remeshing"},
    {"geodesic", cmd_geodesic, "geodesic distances from source vertices"},
    {"segment", cmd_segment, "coherent spectral segmentation"},
    {"prepare", cmd_prepare, "prepare a shape once for many matches (a .sss file match / segment take)"},
    {"match", cmd_match, "point-to-point map between two shapes (functional maps)"},
    {"refine", cmd_refine, "refine a given point map (another method's) as match refines its own (ZoomOut)"},
    {"pair", cmd_pair, "landmark-free pairing of two shapes' segments, with its confidence"},
    {"error", cmd_error, "geodesic error of a map"},
    {"eval", cmd_eval, "the paper's evaluation (Table 1, coherency, timings, figures); eval merge"},
    {"render", cmd_render, "pictures of segmentations, fields, maps and map errors (PNG)"},
};
enum { NCOMMANDS = sizeof commands / sizeof commands[0] };

static void print_help(FILE *f) {
  fprintf(f, "specseg %s — coherent spectral segmentation and functional-map matching\n\n"
             "usage: specseg COMMAND [ARGS]\n\ncommands:\n",
          ss_version());
  for (int i = 0; i < NCOMMANDS; i++) fprintf(f, "  %-11s %s\n", commands[i].name, commands[i].what);
  fprintf(f, "  %-11s %s\n  %-11s %s\n\n", "help", "this list; help COMMAND: the command's usage and options", "version",
          "the version (also --version)");
  fprintf(f, "specseg COMMAND --help (or -h) prints the command's usage and options. Options that take a\n"
             "value accept --opt VALUE and --opt=VALUE; '-' as a file name is standard input or output.\n"
             "Exit codes: 0 ok, 1 input or computation error, 2 usage error.\n");
}

static const command *find_command(const char *name) {
  for (int i = 0; i < NCOMMANDS; i++)
    if (!strcmp(name, commands[i].name)) return &commands[i];
  return NULL;
}

static int run(int argc, char **argv) {
  if (argc < 2) {
    print_help(stderr);
    return SS_EXIT_USAGE;
  }
  const char *a = argv[1];
  if (!strcmp(a, "-h") || !strcmp(a, "--help") || !strcmp(a, "help")) {
    if (argc == 2) {
      print_help(stdout);
      return fflush(stdout) ? cli_error("cannot write to standard output") : SS_EXIT_OK;
    }
    if (argc > 3) return cli_usage("help takes one command name (try 'specseg help')");
    const command *c = find_command(argv[2]);
    if (!c) return cli_usage("unknown command '%s' (try 'specseg help')", argv[2]);
    char help[] = "--help";
    char *av[3] = {argv[2], help, NULL};
    return c->run(2, av); /* the command prints its own usage text */
  }
  if (!strcmp(a, "--version") || !strcmp(a, "version")) {
    if (argc > 2) return cli_usage("%s takes no arguments", a);
    printf("specseg %s\n", ss_version());
    return fflush(stdout) ? cli_error("cannot write to standard output") : SS_EXIT_OK;
  }
  /* Our parallelism is OpenMP over shapes, pairs, queries and rows; OpenBLAS's own threads only
   * spin-wait beside it (FAUST match: 0.81 s wall / 1.04 s CPU with one BLAS thread, 0.92 s / 1.8 s
   * with two). OPENBLAS_NUM_THREADS in the environment still wins. Its thread pool was started when
   * the library loaded (one thread per core) and keeps polling with sched_yield, and every unmap
   * then interrupts its core: stopping it (OpenBLAS's own fork-time shutdown, looked up so that
   * another BLAS is no problem) took a prepared FAUST match from 0.23 s wall / 0.18 s system time
   * to 0.17 s / 0.05 s. */
  if (!getenv("OPENBLAS_NUM_THREADS")) {
    openblas_set_num_threads(1);
    int (*stop_pool)(void) = NULL;
    *(void **)&stop_pool = dlsym(RTLD_DEFAULT, "blas_thread_shutdown_"); /* (POSIX's idiom for a function) */
    if (stop_pool) stop_pool();
  }
#ifdef __GLIBC__
  /* Blocks up to 64 MB come from the heap and freed memory up to 128 MB stays there: glibc would give
   * every such block fresh pages (mmap), whose first touch costs ~10x a write on the machines we
   * measured (FAUST match: 2.82 -> 2.63 s CPU, system time 0.23 -> 0.10 s, peak memory 134 -> 154
   * MB, measured before the library kept a match's 50 MB functional-map systems in one work itself,
   * fmap/fmap_work.h). MALLOC_MMAP_THRESHOLD_ / MALLOC_TRIM_THRESHOLD_ in the environment still win. */
  if (!getenv("MALLOC_MMAP_THRESHOLD_")) mallopt(M_MMAP_THRESHOLD, 64 << 20);
  if (!getenv("MALLOC_TRIM_THRESHOLD_")) mallopt(M_TRIM_THRESHOLD, 128 << 20);
#endif
  const command *c = find_command(a);
  if (c) return c->run(argc - 1, argv + 1);
  return cli_usage("unknown command '%s' (try 'specseg help')", a);
}

int main(int argc, char **argv) {
  /* past a file size limit (ulimit -f) a write fails with EFBIG and is reported, its temporary
   * removed, instead of the signal killing the program with a temporary file left behind */
  signal(SIGXFSZ, SIG_IGN);
  int rc = run(argc, argv);
  /* every command's stdout, checked once more at the end: a report or a JSON summary that did not
   * reach its destination (a full disk, /dev/full, a closed pipe) is a failure, not exit 0 */
  if ((ferror(stdout) || fflush(stdout)) && rc == SS_EXIT_OK) rc = cli_error("cannot write to standard output");
  cli_io_cleanup();
  return rc;
}
