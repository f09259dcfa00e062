/* specseg smooth MESH -o OUT [--steps N] [--dt D] [--bbox]: conformalized mean curvature flow. */
#include <stdio.h>
#include <string.h>

#include "cli.h"

static const char USAGE[] =
    "usage: specseg smooth MESH -o OUT [--steps N] [--dt D] [--bbox]\n"
    "\n"
    "Conformalized mean curvature flow (Kazhdan et al. 2012): N steps of (M_t + D W0) X' = M_t X with\n"
    "the shape centred and scaled to unit area before each step. The result keeps the connectivity,\n"
    "the input's area and centroid.\n"
    "\n"
    "  MESH                mesh file (OFF, OBJ, PLY, STL, glTF, ...); - reads standard input\n"
    "  -o OUT              output mesh, .off or .ply (binary); - writes OFF to standard output\n"
    "  --steps N           flow steps, 0..100000 (default 12)\n"
    "  --dt D              time step, > 0 (default 2.2e-5; 1e-5 with --bbox)\n"
    "  --bbox              scale to unit bounding-box diagonal instead of unit area, as the authors'\n"
    "                      code does\n";

static const char *const OPTS[] = {"-o=", "--steps=", "--dt=", "--bbox", NULL};

int cmd_smooth(int argc, char **argv) {
  const char *path = NULL, *outp = NULL;
  ss_cmcf_options opt;
  ss_cmcf_default_options(&opt);
  int dt_given = 0;
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, OPTS);
  while (cli_next(&A)) {
    const char *v = A.val;
    if (A.pos) {
      if (path) return cli_bad(&A, "more than one mesh given ('%s', '%s')", path, A.pos);
      path = A.pos;
    } else if (cli_is(&A, "-o")) {
      outp = v;
    } else if (cli_is(&A, "--steps")) {
      if (cli_parse_int(v, 0, 100000, &opt.steps)) return cli_bad(&A, "--steps wants an integer in [0,100000], got '%s'", v);
    } else if (cli_is(&A, "--dt")) {
      if (cli_parse_double(v, &opt.dt) || !(opt.dt > 0) || opt.dt > 1e6) return cli_bad(&A, "--dt wants a positive number, got '%s'", v);
      dt_given = 1;
    } else if (cli_is(&A, "--bbox")) {
      opt.normalization = SS_CMCF_UNIT_BBOX;
    }
  }
  if (A.rc >= 0) return A.rc;
  if (!path) return cli_bad(&A, "no mesh given");
  if (!outp) return cli_bad(&A, "missing -o OUT");
  if (opt.normalization == SS_CMCF_UNIT_BBOX && !dt_given) opt.dt = 1e-5;

  ss_error err = {{0}};
  ss_mesh m, s;
  if (cli_read_mesh(path, &m, &err)) return cli_error("%s", err.msg);
  if (ss_cmcf_smooth(&m, &opt, &s, &err)) {
    ss_mesh_free(&m);
    return cli_error("%s: %s", cli_in_name(path), err.msg);
  }
  ss_mesh_free(&m);
  ss_status st = cli_write_mesh(outp, &s, NULL, "off", &err);
  ss_mesh_free(&s);
  if (st) return cli_error("%s", err.msg);
  return SS_EXIT_OK;
}
