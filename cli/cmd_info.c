/* specseg info MESH: mesh statistics and checks, one "key: value" a line. */
#include <stdio.h>
#include <string.h>

#include "cli.h"

static const char *usage = "specseg info MESH   (OFF, OBJ or PLY)";

int cmd_info(int argc, char **argv) {
  const char *path = NULL;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) {
      printf("usage: %s\nPrints vertices, faces, area, components, boundary loops, manifoldness, bounding-box\n"
             "diagonal, whether the faces are consistently oriented (and orientable), the counts of\n"
             "defects (non-manifold edges/vertices, degenerate, duplicate faces, unreferenced and\n"
             "non-finite vertices, misoriented edges, faces the pipeline would re-orient), Euler\n"
             "characteristic and genus.\n",
             usage);
      return SS_EXIT_OK;
    }
    if (argv[i][0] == '-' && argv[i][1] != '\0') return cli_usage("%s: unknown option '%s'", usage, argv[i]);
    if (path) return cli_usage("%s: more than one mesh given", usage);
    path = argv[i];
  }
  if (!path) return cli_usage("%s", usage);

  ss_error err = {{0}};
  ss_mesh m;
  if (ss_read_mesh(path, &m, &err)) return cli_error("%s", err.msg);
  ss_mesh_report r;
  if (ss_mesh_check(&m, &r, &err)) {
    ss_mesh_free(&m);
    return cli_error("%s: %s", path, err.msg);
  }
  ss_mesh_free(&m);
  printf("vertices: %d\n", r.vertices);
  printf("faces: %d\n", r.faces);
  printf("area: %.10g\n", r.area);
  printf("components: %d\n", r.components);
  printf("boundary_loops: %d\n", r.boundary_loops);
  printf("manifold: %s\n", r.manifold ? "yes" : "no");
  printf("oriented: %s\n", r.oriented ? "yes" : "no");
  printf("orientable: %s\n", r.orientable ? "yes" : "no");
  printf("bbox_diagonal: %.10g\n", r.bbox_diagonal);
  printf("boundary_edges: %d\n", r.boundary_edges);
  printf("nonmanifold_edges: %d\n", r.nonmanifold_edges);
  printf("nonmanifold_vertices: %d\n", r.nonmanifold_vertices);
  printf("degenerate_faces: %d\n", r.degenerate_faces);
  printf("duplicate_faces: %d\n", r.duplicate_faces);
  printf("unreferenced_vertices: %d\n", r.unreferenced_vertices);
  printf("nonfinite_vertices: %d\n", r.nonfinite_vertices);
  printf("misoriented_edges: %d\n", r.misoriented_edges);
  printf("reorient_faces: %d\n", r.reorient_faces);
  printf("euler_characteristic: %d\n", r.euler_characteristic);
  /* genus is only defined for a closed manifold: chi = sum over components of (2 - 2 g_i) */
  if (r.manifold && r.boundary_edges == 0 && r.degenerate_faces == 0 && r.duplicate_faces == 0)
    printf("genus: %d\n", (2 * r.components - r.euler_characteristic) / 2);
  if (fflush(stdout) != 0) return cli_error("cannot write to standard output");
  return SS_EXIT_OK;
}
