/* specseg error MAP.txt Y [--gt GT.txt] [--sym SYM.txt] [-o ERRORS.txt]: geodesic error of a map. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static const char *usage = "specseg error MAP.txt Y [--gt GT.txt] [--sym SYM.txt] [-o ERRORS.txt]";

int cmd_error(int argc, char **argv) {
  const char *mapf = NULL, *yf = NULL, *gtf = NULL, *symf = NULL, *outf = NULL;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
      printf("usage: %s\nMean over the vertices x of X of d_Y(MAP(x), GT(x)) / sqrt(area(Y)), exact geodesics.\n"
             "MAP.txt: line i = vertex of Y that is the image of vertex i of X. GT.txt: same format\n"
             "(default: the identity). SYM.txt: a left-right symmetry map of X (line i = mirror of vertex i);\n"
             "with it the error of x is the smaller of the errors to GT(x) and GT(mirror of x), the paper's\n"
             "symmetric variant. -o: the per-vertex errors, one a line.\n",
             usage);
      return SS_EXIT_OK;
    }
    if (!strcmp(a, "--gt") || !strcmp(a, "--sym") || !strcmp(a, "-o")) {
      if (i + 1 >= argc) return cli_usage("%s: %s needs a file", usage, a);
      const char **dst = !strcmp(a, "--gt") ? &gtf : !strcmp(a, "--sym") ? &symf : &outf;
      *dst = argv[++i];
      continue;
    }
    if (a[0] == '-' && a[1] != '\0') return cli_usage("%s: unknown option '%s'", usage, a);
    if (!mapf) mapf = a;
    else if (!yf) yf = a;
    else return cli_usage("%s: too many arguments", usage);
  }
  if (!mapf || !yf) return cli_usage("%s", usage);

  ss_error err = {{0}};
  int *map = NULL, *gt = NULL, *sym = NULL, n = 0, ngt = 0, nsym = 0, rc = SS_EXIT_OK;
  double *e = NULL, mean = 0;
  ss_mesh Y = {0};
  if (ss_read_ints(mapf, &map, &n, &err)) { rc = cli_error("%s", err.msg); goto done; }
  if (n < 1) { rc = cli_error("%s: empty map", mapf); goto done; }
  if (gtf) {
    if (ss_read_ints(gtf, &gt, &ngt, &err)) { rc = cli_error("%s", err.msg); goto done; }
    if (ngt != n) { rc = cli_error("%s: %d lines, the map has %d", gtf, ngt, n); goto done; }
  }
  if (symf) {
    if (ss_read_ints(symf, &sym, &nsym, &err)) { rc = cli_error("%s", err.msg); goto done; }
    if (nsym != n) { rc = cli_error("%s: %d lines, the map has %d", symf, nsym, n); goto done; }
  }
  if (ss_read_mesh(yf, &Y, &err)) { rc = cli_error("%s", err.msg); goto done; }
  if (!gt && n > Y.nv) { rc = cli_error("identity ground truth: the map has %d vertices, %s only %d", n, yf, Y.nv); goto done; }
  if (!(e = malloc(sizeof(double) * n))) { rc = cli_error("out of memory"); goto done; }
  if (ss_map_geodesic_error(&Y, n, map, gt, sym, e, &mean, &err)) { rc = cli_error("%s", err.msg); goto done; }
  if (outf && ss_write_doubles(outf, e, n, &err)) { rc = cli_error("%s", err.msg); goto done; }
  printf("mean_error: %.6f\n", mean);
  if (fflush(stdout) != 0) rc = cli_error("cannot write to standard output");
done:
  free(map);
  free(gt);
  free(sym);
  free(e);
  ss_mesh_free(&Y);
  return rc;
}
