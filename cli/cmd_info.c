/* specseg info MESH: mesh statistics and checks, one "key: value" a line. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"

static const char USAGE[] =
    "usage: specseg info MESH... [-o OUT] [--jobs N] [--json]\n"
    "\n"
    "Mesh statistics and checks, one 'key: value' a line: vertices, faces, area, components, boundary\n"
    "loops, manifoldness, bounding-box diagonal, whether the faces are consistently oriented (and\n"
    "orientable), the counts of defects (boundary and non-manifold edges, non-manifold vertices,\n"
    "degenerate and duplicate faces, unreferenced and non-finite vertices, misoriented edges, faces the\n"
    "pipeline would re-orient), the Euler characteristic and, for a closed manifold, the genus.\n"
    "\n"
    "  MESH                mesh file (OFF, OBJ, PLY, STL, glTF, ...); - reads standard input (format from\n"
    "                      the content); several meshes or folders: one block per mesh, its lines\n"
    "                      prefixed 'MESH: '\n"
    "  -o OUT              write the lines to OUT instead of standard output (batch: OUTDIR/NAME.info.txt)\n"
    CLI_BATCH_HELP;

static int info_job(cli_job *j, void *cfg) {
  (void)cfg;
  const char *path = j->input;
  ss_error err = {{0}};
  ss_mesh m;
  if (cli_read_mesh(path, &m, &err)) return cli_error("%s", err.msg);
  ss_mesh_report r;
  if (ss_mesh_check(&m, &r, &err)) {
    ss_mesh_free(&m);
    return cli_error("%s: %s", cli_in_name(path), err.msg);
  }
  ss_mesh_free(&m);
  const char *outp = cli_job_output(j, *(const char *const *)cfg, ".info.txt");
  FILE *f = outp ? cli_open_out(outp) : cli_job_report(j, 0);
  if (!f) return cli_error("%s: cannot open: %s", outp, strerror(errno));
  static const char *const YN[2] = {"no", "yes"};
  const struct { const char *key; long v; } ints[] = {
      {"vertices", r.vertices}, {"faces", r.faces}, {"components", r.components}, {"boundary_loops", r.boundary_loops},
      {"boundary_edges", r.boundary_edges}, {"nonmanifold_edges", r.nonmanifold_edges},
      {"nonmanifold_vertices", r.nonmanifold_vertices}, {"degenerate_faces", r.degenerate_faces},
      {"duplicate_faces", r.duplicate_faces}, {"unreferenced_vertices", r.unreferenced_vertices},
      {"nonfinite_vertices", r.nonfinite_vertices}, {"misoriented_edges", r.misoriented_edges},
      {"reorient_faces", r.reorient_faces}, {"euler_characteristic", r.euler_characteristic}};
  /* areas beyond the double range (coordinates ~1e155 and up, or ~1e-155 and down) */
  if (r.nonfinite_vertices == 0 && (isinf(r.area) || (r.area == 0 && r.faces > r.degenerate_faces)))
    cli_warn("%s: the area %s a double (bounding-box diagonal %.3g); the other commands accept coordinates up to "
             "1e70 and extents down to 1e-70: scale the mesh",
             cli_in_name(path), r.area > 0 ? "overflows" : "underflows", r.bbox_diagonal);
  fprintf(f, "vertices: %d\n", r.vertices);
  fprintf(f, "faces: %d\n", r.faces);
  fprintf(f, "area: %.10g\n", r.area);
  fprintf(f, "components: %d\n", r.components);
  fprintf(f, "boundary_loops: %d\n", r.boundary_loops);
  fprintf(f, "manifold: %s\n", YN[!!r.manifold]);
  fprintf(f, "oriented: %s\n", YN[!!r.oriented]);
  fprintf(f, "orientable: %s\n", YN[!!r.orientable]);
  fprintf(f, "bbox_diagonal: %.10g\n", r.bbox_diagonal);
  fprintf(f, "boundary_edges: %d\n", r.boundary_edges);
  fprintf(f, "nonmanifold_edges: %d\n", r.nonmanifold_edges);
  fprintf(f, "nonmanifold_vertices: %d\n", r.nonmanifold_vertices);
  fprintf(f, "degenerate_faces: %d\n", r.degenerate_faces);
  fprintf(f, "duplicate_faces: %d\n", r.duplicate_faces);
  fprintf(f, "unreferenced_vertices: %d\n", r.unreferenced_vertices);
  fprintf(f, "nonfinite_vertices: %d\n", r.nonfinite_vertices);
  fprintf(f, "misoriented_edges: %d\n", r.misoriented_edges);
  fprintf(f, "reorient_faces: %d\n", r.reorient_faces);
  fprintf(f, "euler_characteristic: %d\n", r.euler_characteristic);
  /* genus is only defined for a closed manifold: chi = sum over components of (2 - 2 g_i) */
  int closed = r.manifold && r.boundary_edges == 0 && r.degenerate_faces == 0 && r.duplicate_faces == 0;
  int genus = (2 * r.components - r.euler_characteristic) / 2;
  if (closed) fprintf(f, "genus: %d\n", genus);
  for (size_t i = 0; i < sizeof ints / sizeof ints[0]; i++) cli_job_int(j, ints[i].key, ints[i].v);
  cli_job_num(j, "area", r.area);
  cli_job_num(j, "bbox_diagonal", r.bbox_diagonal);
  cli_job_int(j, "manifold", !!r.manifold);
  cli_job_int(j, "oriented", !!r.oriented);
  cli_job_int(j, "orientable", !!r.orientable);
  if (closed) cli_job_int(j, "genus", genus);
  if (outp) {
    if (cli_close_out(f)) return cli_error("%s: write error", cli_out_name(outp));
  } else if (fflush(f) != 0) {
    return cli_error("cannot write to standard output");
  }
  return SS_EXIT_OK;
}

int cmd_info(int argc, char **argv) {
  const char *outp = NULL;
  cli_batch B;
  cli_batch_init(&B, "info");
  const cli_opt opts[] = {CLI_BATCH_OPTIONS(&B), CLI_OPT_STR("-o", &outp), CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, opts);
  int rc = cli_parse(&A);
  if (rc < 0) rc = cli_batch_setup(&B, &A, outp, 0, ".info.txt", NULL, 0);
  if (rc < 0 && B.json && cli_is_std(outp)) rc = cli_bad(&A, "--json and -o - both want standard output");
  return cli_batch_finish(&B, rc, info_job, &outp);
}
