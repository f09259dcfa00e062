/* specseg geodesic MESH --source I [--source J ...] [--method exact|graph|edge] [--max-dist D] -o F:
 * distance from every vertex to the nearest source, one value a line (%.17g, unreached "inf"). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static const char USAGE[] =
    "usage: specseg geodesic MESH --source I [--source J ...] [--method exact|graph|edge] [--max-dist D]\n"
    "                        -o DIST.txt\n"
    "\n"
    "Distance from every vertex to the nearest source vertex, one value a line (%.17g; unreached or\n"
    "farther than D: inf).\n"
    "\n"
    "  MESH                mesh file (OFF, OBJ, PLY, STL, glTF, ...); - reads standard input\n"
    "  -s, --source I      source vertex (0-based); repeat for several sources (at least one)\n"
    "  --method M          exact: polyhedral geodesics, VTP window propagation (default); graph:\n"
    "                      Dijkstra on the NPP22 graph; edge: Dijkstra on the mesh edges\n"
    "  --max-dist D        stop at distance D > 0 (default: no limit)\n"
    "  -o, --output FILE   the distances (required), text or .npy by extension; - writes them to standard\n"
    "                      output\n";

/* the mesh: one positional argument */
static int take_mesh(cli_args *A, const cli_opt *o, const char *arg) {
  const char **path = o->dest;
  if (*path) return cli_bad(A, "more than one mesh given ('%s', '%s')", *path, arg);
  *path = arg;
  return -1;
}

int cmd_geodesic(int argc, char **argv) {
  const char *path = NULL, *out = NULL;
  int *src = NULL, ns = 0;
  ss_geodesic_method method = SS_GEODESIC_EXACT;
  double maxd = INFINITY;
  int rc = SS_EXIT_OK;
  src = malloc(sizeof(int) * (size_t)(argc > 0 ? argc : 1));
  if (!src) return cli_error("out of memory");
  static const int METHOD[] = {SS_GEODESIC_EXACT, SS_GEODESIC_GRAPH, SS_GEODESIC_EDGE};
  const cli_opt opts[] = {
      CLI_OPT_POS_FN("MESH", take_mesh, &path),
      CLI_OPT_INTS("-s|--source", src, &ns, 0, 2147483647L, "--source needs a vertex index >= 0, not '%s'"),
      CLI_OPT_CHOICE("--method", CLI_ENUM(&method), "exact|graph|edge", METHOD, "unknown method '%s' (exact, graph or edge)"),
      CLI_OPT_DOUBLE("--max-dist", &maxd, 0, INFINITY, CLI_OPEN_LO, "--max-dist needs a positive number, not '%s'"),
      CLI_OPT_STR("-o|--output", &out),
      CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, opts);
  if ((rc = cli_parse(&A)) >= 0) goto done;
  rc = SS_EXIT_OK;
  if (!path) { rc = cli_bad(&A, "no mesh given"); goto done; }
  {
    const char *ins[1] = {path}, *outs[1] = {out};
    if (cli_check_outputs(&A, outs, 1, ins, 1) >= 0) { rc = A.rc; goto done; }
  }
  if (ns == 0) { rc = cli_bad(&A, "no --source given"); goto done; }
  if (!out) { rc = cli_bad(&A, "missing -o DIST.txt"); goto done; }

  ss_error err = {{0}};
  ss_mesh m;
  if (cli_read_mesh(path, &m, &err)) { rc = cli_error("%s", err.msg); goto done; }
  for (int i = 0; i < ns; i++)
    if (src[i] >= m.nv) {
      rc = cli_error("%s: source vertex %d out of range (mesh has %d vertices)", cli_in_name(path), src[i], m.nv);
      ss_mesh_free(&m);
      goto done;
    }
  if (method == SS_GEODESIC_EXACT) {
    ss_mesh_report rep;
    if (!ss_mesh_check(&m, &rep, NULL) && !rep.oriented && rep.orientable)
      cli_warn("%s: faces are not consistently oriented (%d misoriented edges); %d faces re-oriented internally",
               cli_in_name(path), rep.misoriented_edges, rep.reorient_faces);
  }
  double *d = malloc(sizeof(double) * (size_t)(m.nv > 0 ? m.nv : 1));
  if (!d) { ss_mesh_free(&m); rc = cli_error("out of memory"); goto done; }
  if (ss_geodesic_distances(&m, method, src, ns, maxd, d, &err)) rc = cli_error("%s: %s", cli_in_name(path), err.msg);
  else if (cli_write_doubles(out, d, m.nv, &err)) rc = cli_error("%s", err.msg);
  free(d);
  ss_mesh_free(&m);
done:
  free(src);
  return rc;
}
