/* specseg geodesic MESH --source I [--source J ...] [--method exact|graph|edge] [--max-dist D] -o F:
 * distance from every vertex to the nearest source, one value a line (%.17g, unreached "inf"). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static const char *usage =
    "specseg geodesic MESH --source I [--source J ...] [--method exact|graph|edge] [--max-dist D] -o DIST.txt";

static int write_field(const char *path, const double *d, int n) {
  FILE *f = strcmp(path, "-") ? fopen(path, "w") : stdout;
  if (!f) return -1;
  for (int i = 0; i < n; i++) {
    if (isinf(d[i])) fputs("inf\n", f);
    else fprintf(f, "%.17g\n", d[i]);
  }
  int bad = ferror(f);
  if (f != stdout) bad |= fclose(f);
  else bad |= fflush(f);
  return bad ? -1 : 0;
}

int cmd_geodesic(int argc, char **argv) {
  const char *path = NULL, *out = NULL;
  int *src = NULL, ns = 0;
  ss_geodesic_method method = SS_GEODESIC_EXACT;
  double maxd = INFINITY;
  int rc = SS_EXIT_OK;
  src = malloc(sizeof(int) * (size_t)(argc > 0 ? argc : 1));
  if (!src) return cli_error("out of memory");
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
      printf("usage: %s\nExact polyhedral geodesic distance (VTP window propagation), or Dijkstra on the NPP22\n"
             "graph (graph) or on the mesh edges (edge), from every vertex to the nearest source vertex\n"
             "(0-based indices). With --max-dist, vertices farther than D are written as inf.\n",
             usage);
      free(src);
      return SS_EXIT_OK;
    }
    int has_val = i + 1 < argc;
    if (!strcmp(a, "--source") || !strcmp(a, "-s")) {
      if (!has_val || cli_parse_int(argv[i + 1], 0, 2147483647L, &src[ns]))
        { rc = cli_usage("%s: --source needs a vertex index >= 0", usage); goto done; }
      ns++; i++;
    } else if (!strcmp(a, "--method")) {
      if (!has_val) { rc = cli_usage("%s: --method needs a value", usage); goto done; }
      const char *m = argv[++i];
      if (!strcmp(m, "exact")) method = SS_GEODESIC_EXACT;
      else if (!strcmp(m, "graph")) method = SS_GEODESIC_GRAPH;
      else if (!strcmp(m, "edge")) method = SS_GEODESIC_EDGE;
      else { rc = cli_usage("%s: unknown method '%s' (exact, graph or edge)", usage, m); goto done; }
    } else if (!strcmp(a, "--max-dist")) {
      if (!has_val || cli_parse_double(argv[i + 1], &maxd) || !(maxd > 0))
        { rc = cli_usage("%s: --max-dist needs a positive number", usage); goto done; }
      i++;
    } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
      if (!has_val) { rc = cli_usage("%s: -o needs a file name", usage); goto done; }
      out = argv[++i];
    } else if (a[0] == '-' && a[1] != '\0') {
      rc = cli_usage("%s: unknown option '%s'", usage, a); goto done;
    } else {
      if (path) { rc = cli_usage("%s: more than one mesh given", usage); goto done; }
      path = a;
    }
  }
  if (!path || ns == 0 || !out) { rc = cli_usage("%s", usage); goto done; }

  ss_error err = {{0}};
  ss_mesh m;
  if (ss_read_mesh(path, &m, &err)) { rc = cli_error("%s", err.msg); goto done; }
  for (int i = 0; i < ns; i++)
    if (src[i] >= m.nv) {
      rc = cli_error("%s: source vertex %d out of range (mesh has %d vertices)", path, src[i], m.nv);
      ss_mesh_free(&m);
      goto done;
    }
  if (method == SS_GEODESIC_EXACT) {
    ss_mesh_report rep;
    if (!ss_mesh_check(&m, &rep, NULL) && !rep.oriented && rep.orientable)
      cli_warn("%s: faces are not consistently oriented (%d misoriented edges); %d faces re-oriented internally",
               path, rep.misoriented_edges, rep.reorient_faces);
  }
  double *d = malloc(sizeof(double) * (size_t)(m.nv > 0 ? m.nv : 1));
  if (!d) { ss_mesh_free(&m); rc = cli_error("out of memory"); goto done; }
  if (ss_geodesic_distances(&m, method, src, ns, maxd, d, &err)) rc = cli_error("%s: %s", path, err.msg);
  else if (write_field(out, d, m.nv)) rc = cli_error("cannot write '%s'", out);
  free(d);
  ss_mesh_free(&m);
done:
  free(src);
  return rc;
}
