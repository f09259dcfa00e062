/* specseg remesh MESH -o OUT [--faces N]: isotropic remeshing to about N triangles. */
#include <stdio.h>
#include <string.h>

#include "cli.h"

static const char USAGE[] =
    "usage: specseg remesh MESH -o OUT [--faces N] [--iterations K]\n"
    "\n"
    "Isotropic remeshing (split / collapse / flip / tangential relaxation / projection) of a closed\n"
    "manifold mesh to about N triangles. Prints on stderr: faces, % of triangles with min angle >= 30\n"
    "deg, % of vertices of valence 6, largest vertex distance to the input surface / input bbox\n"
    "diagonal, seconds.\n"
    "\n"
    "  MESH                mesh file (OFF, OBJ, PLY, STL, glTF, ...); - reads standard input\n"
    "  -o OUT              output mesh, .off or .ply (binary); - writes OFF to standard output\n"
    "  --faces N           target triangle count, >= 4 (default 15000)\n"
    "  --iterations K      remeshing rounds, 1..1000 (default 5)\n";

static const char *const OPTS[] = {"-o=", "--faces=", "--iterations=", NULL};

int cmd_remesh(int argc, char **argv) {
  const char *path = NULL, *outp = NULL;
  ss_remesh_options opt;
  ss_remesh_default_options(&opt);
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, OPTS);
  while (cli_next(&A)) {
    const char *v = A.val;
    if (A.pos) {
      if (path) return cli_bad(&A, "more than one mesh given ('%s', '%s')", path, A.pos);
      path = A.pos;
    } else if (cli_is(&A, "-o")) {
      outp = v;
    } else if (cli_is(&A, "--faces")) {
      if (cli_parse_int(v, 4, 100000000, &opt.target_faces)) return cli_bad(&A, "--faces wants an integer >= 4, got '%s'", v);
    } else if (cli_is(&A, "--iterations")) {
      if (cli_parse_int(v, 1, 1000, &opt.iterations)) return cli_bad(&A, "--iterations wants an integer in [1,1000], got '%s'", v);
    }
  }
  if (A.rc >= 0) return A.rc;
  if (!path) return cli_bad(&A, "no mesh given");
  if (!outp) return cli_bad(&A, "missing -o OUT");

  ss_error err = {{0}};
  ss_mesh m, r;
  if (cli_read_mesh(path, &m, &err)) return cli_error("%s", err.msg);
  double t0 = ss_time();
  if (ss_remesh(&m, &opt, &r, &err)) {
    ss_mesh_free(&m);
    return cli_error("%s: %s", cli_in_name(path), err.msg);
  }
  double t = ss_time() - t0;
  ss_remesh_quality q;
  ss_status st = ss_remesh_quality_measure(&r, &m, &q, &err);
  ss_mesh_free(&m);
  if (st) { ss_mesh_free(&r); return cli_error("%s", err.msg); }
  fprintf(stderr, "remesh: faces %d, min angle >= 30: %.1f%%, valence 6: %.1f%%, max deviation / bbox diag: %.2e, %.3f s\n",
          q.faces, 100 * q.frac_min_angle_30, 100 * q.frac_valence_6, q.max_deviation, t);
  st = cli_write_mesh(outp, &r, NULL, "off", &err);
  ss_mesh_free(&r);
  if (st) return cli_error("%s", err.msg);
  return SS_EXIT_OK;
}
