/* specseg info MESH: mesh statistics and checks, one "key: value" a line. */
#include <stdio.h>
#include <string.h>

#include "cli.h"

static const char USAGE[] =
    "usage: specseg info MESH\n"
    "\n"
    "Mesh statistics and checks, one 'key: value' a line: vertices, faces, area, components, boundary\n"
    "loops, manifoldness, bounding-box diagonal, whether the faces are consistently oriented (and\n"
    "orientable), the counts of defects (boundary and non-manifold edges, non-manifold vertices,\n"
    "degenerate and duplicate faces, unreferenced and non-finite vertices, misoriented edges, faces the\n"
    "pipeline would re-orient), the Euler characteristic and, for a closed manifold, the genus.\n"
    "\n"
    "  MESH                mesh file (OFF, OBJ, PLY, STL, glTF, ...); - reads standard input (format from\n"
    "                      the content)\n";

static const char *const OPTS[] = {NULL};

int cmd_info(int argc, char **argv) {
  const char *path = NULL;
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, OPTS);
  while (cli_next(&A)) {
    if (path) return cli_bad(&A, "more than one mesh given ('%s', '%s')", path, A.pos);
    path = A.pos;
  }
  if (A.rc >= 0) return A.rc;
  if (!path) return cli_bad(&A, "no mesh given");

  ss_error err = {{0}};
  ss_mesh m;
  if (cli_read_mesh(path, &m, &err)) return cli_error("%s", err.msg);
  ss_mesh_report r;
  if (ss_mesh_check(&m, &r, &err)) {
    ss_mesh_free(&m);
    return cli_error("%s: %s", cli_in_name(path), err.msg);
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
