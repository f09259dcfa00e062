/* specseg error MAP.txt Y [--gt GT.txt] [--sym SYM.txt] [--x MESH] [-o ERRORS.txt] [--json]: geodesic
 * error of a map. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_shape.h"

static const char USAGE[] =
    "usage: specseg error MAP.txt Y [--gt GT.txt] [--sym SYM.txt] [--x MESH] [-o ERRORS.txt] [--json]\n"
    "\n"
    "Mean over the vertices x of X of d_Y(MAP(x), GT(x)) / sqrt(area(Y)) with exact geodesics, printed as\n"
    "'mean_error: E' (on stderr when -o is -).\n"
    "\n"
    "  MAP.txt             line i = vertex of Y that is the image of vertex i of X\n"
    "  Y                   the target mesh (OFF, OBJ, PLY, STL, glTF, ..., or a prepared shape .sss)\n"
    "  --gt GT.txt         the ground-truth map, same format (default: the identity)\n"
    "  --x MESH            the source mesh X (or its .sss): the map must have one line per vertex of X\n"
    "                      (always checked: one line per line of GT, or per vertex of Y for the identity)\n"
    "  --sym SYM.txt       a left-right symmetry map of X (line i = mirror of vertex i): the error of x is\n"
    "                      the smaller of the errors to GT(x) and GT(mirror of x), the paper's symmetric\n"
    "                      variant\n"
    "  -o FILE             the per-vertex errors, one a line; - writes them to standard output\n"
    "  --json              a JSON summary on standard output instead of 'mean_error: E' (the mean, the\n"
    "                      median and largest error, counts, seconds, output paths, errors)\n"
    "One of the input files may be - (standard input).\n";

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The vertex count of a mesh or prepared shape; -1 after reporting why not. */
static int vertex_count(const char *path, ss_mesh *keep) {
  cli_shape s;
  ss_error err = {{0}};
  if (cli_read_shape(path, &s, &err)) {
    cli_error("%s", err.msg);
    return -1;
  }
  int nv = s.ps.mesh.nv;
  if (keep) *keep = s.ps.mesh, memset(&s.ps.mesh, 0, sizeof s.ps.mesh); /* the mesh taken over */
  cli_shape_free(&s);
  return nv;
}

int cmd_error(int argc, char **argv) {
  const char *mapf = NULL, *yf = NULL, *gtf = NULL, *symf = NULL, *outf = NULL, *xf = NULL;
  int json = 0;
  const cli_opt opts[] = {CLI_OPT_POS("MAP.txt", &mapf, NULL), CLI_OPT_POS("Y", &yf, "too many arguments ('%s')"),
                          CLI_OPT_STR("--gt", &gtf),   CLI_OPT_STR("--sym", &symf),
                          CLI_OPT_STR("--x", &xf),     CLI_OPT_STR("-o", &outf),
                          CLI_OPT_FLAG("--json", &json, 1), CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, opts);
  int rc = cli_parse(&A);
  if (rc >= 0) return rc;
  if (!mapf || !yf) return cli_bad(&A, "needs MAP.txt and Y");
  const char *ins[5] = {mapf, yf, gtf, symf, xf};
  if (cli_count_std(ins, 5) > 1) return cli_bad(&A, "only one input can come from standard input ('-')");
  const char *outs[1] = {outf};
  if (cli_check_outputs(&A, outs, 1, ins, 5) >= 0) return A.rc;
  if (json && cli_is_std(outf)) return cli_bad(&A, "--json and -o - both want standard output");
  FILE *report = cli_is_std(outf) ? stderr : stdout;
  cli_job J;
  cli_job_begin(&J, NULL);
  cli_job_str(&J, "map", cli_in_name(mapf));
  cli_job_str(&J, "y", cli_in_name(yf));
  if (gtf) cli_job_str(&J, "gt", cli_in_name(gtf));
  if (symf) cli_job_str(&J, "sym", cli_in_name(symf));

  ss_error err = {{0}};
  int *map = NULL, *gt = NULL, *sym = NULL, n = 0, ngt = 0, nsym = 0;
  rc = SS_EXIT_OK;
  int *lmap = NULL, *lgt = NULL, *lsym = NULL; /* line numbers, for the range checks */
  double *e = NULL, mean = 0;
  ss_mesh Y = {0};
  if (cli_read_ints_lines(mapf, &map, &lmap, &n, &err)) { rc = cli_error("%s", err.msg); goto done; }
  if (n < 1) { rc = cli_error("%s: empty map", cli_in_name(mapf)); goto done; }
  if (gtf) {
    if (cli_read_ints_lines(gtf, &gt, &lgt, &ngt, &err)) { rc = cli_error("%s", err.msg); goto done; }
    if (ngt != n) { rc = cli_error("%s: %d lines, the map has %d", cli_in_name(gtf), ngt, n); goto done; }
  }
  if (symf) {
    if (cli_read_ints_lines(symf, &sym, &lsym, &nsym, &err)) { rc = cli_error("%s", err.msg); goto done; }
    if (nsym != n) { rc = cli_error("%s: %d lines, the map has %d", cli_in_name(symf), nsym, n); goto done; }
  }
  if (vertex_count(yf, &Y) < 0) { rc = SS_EXIT_FAIL; goto done; }
  /* entries out of range, named by file and line: maps and GT hold vertices of Y, SYM vertices of X */
  for (int f = 0; f < 3; f++) {
    const int *v = f == 0 ? map : f == 1 ? gt : sym, *ln = f == 0 ? lmap : f == 1 ? lgt : lsym;
    const char *name = cli_in_name(f == 0 ? mapf : f == 1 ? gtf : symf);
    int hi = f == 2 ? n : Y.nv;
    for (int i = 0; v && i < n; i++)
      if (v[i] < 0 || v[i] >= hi) {
        if (f == 2)
          rc = cli_error("%s:%d: vertex %d is not a vertex of X (the map has %d entries, so X has vertices 0..%d): a "
                         "symmetry map's i-th entry is the mirror of vertex i of X",
                         name, ln[i], v[i], n, n - 1);
        else
          rc = cli_error("%s:%d: vertex %d is not on the target (%s has vertices 0..%d): a map's i-th entry is the vertex "
                         "of Y that vertex i of X goes to; is %s the map's target?",
                         name, ln[i], v[i], cli_in_name(yf), Y.nv - 1, cli_in_name(yf));
        goto done;
      }
  }
  /* a map cut short (or too long) scores as well as a whole one: its length is checked against
   * the ground truth's (above), X's and, for the identity, Y's vertex count */
  if (xf) {
    int nx = vertex_count(xf, NULL);
    if (nx < 0) { rc = SS_EXIT_FAIL; goto done; }
    if (nx != n) {
      rc = cli_error("%s: %d lines, but X (%s) has %d vertices: a map has one line per vertex of X", cli_in_name(mapf), n,
                     cli_in_name(xf), nx);
      goto done;
    }
  }
  if (!gt && n != Y.nv) {
    rc = cli_error("%s: %d lines, but %s has %d vertices: the identity ground truth needs one line per vertex of Y "
                   "(give --gt for shapes of different vertex orders)",
                   cli_in_name(mapf), n, cli_in_name(yf), Y.nv);
    goto done;
  }
  if (!(e = malloc(sizeof(double) * n))) { rc = cli_error("out of memory"); goto done; }
  if (ss_map_geodesic_error(&Y, n, map, gt, sym, e, &mean, &err)) { rc = cli_error("%s", err.msg); goto done; }
  if (outf && cli_write_doubles(outf, e, n, &err)) { rc = cli_error("%s", err.msg); goto done; }
  cli_job_output(&J, outf, NULL);
  cli_job_int(&J, "vertices", n);
  cli_job_num(&J, "mean_error", mean);
  {
    double *sorted = malloc(sizeof(double) * n);
    if (sorted) {
      memcpy(sorted, e, sizeof(double) * n);
      qsort(sorted, (size_t)n, sizeof(double), cmp_double);
      cli_job_num(&J, "median_error", n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]));
      cli_job_num(&J, "max_error", sorted[n - 1]);
      free(sorted);
    }
  }
  if (!json) {
    fprintf(report, "mean_error: %.6f\n", mean);
    if (fflush(report) != 0) rc = cli_error("cannot write to standard output");
  }
done:
  free(lmap), free(lgt), free(lsym);
  free(map);
  free(gt);
  free(sym);
  free(e);
  ss_mesh_free(&Y);
  return cli_job_end(&J, "error", rc, json);
}
