#include "cli.h"

#include <cblas.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cli_error(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fputs("specseg: error: ", stderr);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  return SS_EXIT_FAIL;
}

int cli_usage(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fputs("specseg: usage: ", stderr);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  return SS_EXIT_USAGE;
}

void cli_warn(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fputs("specseg: warning: ", stderr);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
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
  const char *help;
} command;

static const command commands[] = {
    {"info", cmd_info, "MESH                      mesh statistics and checks"},
    {"eigs", cmd_eigs, "MESH -k K [--evecs F.npy]  Laplace-Beltrami eigenvalues"},
    {"demo", cmd_demo, "[-o DIR]                  the pipeline on built-in synthetic shapes"},
    {"smooth", cmd_smooth, "MESH -o OUT [--steps N] [--dt D]  conformalized mean curvature flow"},
    {"remesh", cmd_remesh, "MESH -o OUT [--faces N]   isotropic remeshing"},
    {"geodesic", cmd_geodesic, "MESH --source I [--source J ...] [--method exact|graph|edge] [--max-dist D] -o DIST.txt"},
    {"segment", cmd_segment, "MESH -o LABELS [--centers F] [--ply F] [--faces N] [--no-streamline] [--timings]"},
    {"match", cmd_match, "X Y --landmarks LM.txt [--probes std|asa|diff] [--k K] [--zoomout KMAX] -o MAP.txt [--fmap C.npy] [--pairs P.txt] [--timings]"},
    {"error", cmd_error, "MAP.txt Y [--gt GT.txt] [--sym SYM.txt] [-o E.txt]  geodesic error of a map"},
    {"eval", cmd_eval, "--data DIR --table1|--coherency|--timings|--figures OUTDIR [...] | merge CSV...  the paper's evaluation"},
    {"render", cmd_render, "MESH [MESH2 ...] -o OUT.png [--labels L | --scalar F | --map M --target Y | --error M --target Y]  pictures"},
};

static void print_help(FILE *f) {
  fprintf(f, "specseg — coherent spectral segmentation and functional-map matching\n\nusage: specseg COMMAND [ARGS]\n\n");
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    fprintf(f, "  %-9s %s\n", commands[i].name, commands[i].help);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    print_help(stderr);
    return SS_EXIT_USAGE;
  }
  if (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help") || !strcmp(argv[1], "help")) {
    print_help(stdout);
    return SS_EXIT_OK;
  }
  /* Our parallelism is OpenMP over shapes, pairs, queries and rows; OpenBLAS's own threads only
   * spin-wait beside it (FAUST match: 0.81 s wall / 1.04 s CPU with one BLAS thread, 0.92 s / 1.8 s
   * with two). OPENBLAS_NUM_THREADS in the environment still wins. */
  if (!getenv("OPENBLAS_NUM_THREADS")) openblas_set_num_threads(1);
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    if (!strcmp(argv[1], commands[i].name)) return commands[i].run(argc - 1, argv + 1);
  return cli_usage("unknown command '%s' (try 'specseg --help')", argv[1]);
}
