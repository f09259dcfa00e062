/* specseg smooth MESH -o OUT [--steps N] [--dt D] [--bbox]: conformalized mean curvature flow. */
#include <stdio.h>
#include <string.h>

#include "cli.h"

static const char *usage = "specseg smooth MESH -o OUT [--steps N] [--dt D] [--bbox]";

int cmd_smooth(int argc, char **argv) {
  const char *path = NULL, *outp = NULL;
  ss_cmcf_options opt;
  ss_cmcf_default_options(&opt);
  int dt_given = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
      printf("usage: %s\n"
             "Conformalized mean curvature flow (Kazhdan et al. 2012): N steps (default %d) of\n"
             "(M_t + D W0) X' = M_t X with the shape centred and scaled to unit area before each step\n"
             "(D default %g). --bbox scales to unit bounding-box diagonal instead, as the authors' code\n"
             "does (D default 1e-5 then). The result keeps the connectivity, the input's area and centroid.\n",
             usage, opt.steps, opt.dt);
      return SS_EXIT_OK;
    }
    if (!strcmp(a, "-o") || !strcmp(a, "--steps") || !strcmp(a, "--dt")) {
      if (i + 1 >= argc) return cli_usage("%s: %s needs a value", usage, a);
      const char *v = argv[++i];
      if (!strcmp(a, "-o")) outp = v;
      else if (!strcmp(a, "--steps")) {
        if (cli_parse_int(v, 0, 100000, &opt.steps)) return cli_usage("%s: --steps wants an integer in [0,100000], got '%s'", usage, v);
      } else {
        if (cli_parse_double(v, &opt.dt) || !(opt.dt > 0) || opt.dt > 1e6) return cli_usage("%s: --dt wants a positive number, got '%s'", usage, v);
        dt_given = 1;
      }
      continue;
    }
    if (!strcmp(a, "--bbox")) { opt.normalization = SS_CMCF_UNIT_BBOX; continue; }
    if (a[0] == '-' && a[1] != '\0') return cli_usage("%s: unknown option '%s'", usage, a);
    if (path) return cli_usage("%s: more than one mesh given", usage);
    path = a;
  }
  if (!path || !outp) return cli_usage("%s", usage);
  if (opt.normalization == SS_CMCF_UNIT_BBOX && !dt_given) opt.dt = 1e-5;

  ss_error err = {{0}};
  ss_mesh m, s;
  if (ss_read_mesh(path, &m, &err)) return cli_error("%s", err.msg);
  if (ss_cmcf_smooth(&m, &opt, &s, &err)) {
    ss_mesh_free(&m);
    return cli_error("%s: %s", path, err.msg);
  }
  ss_mesh_free(&m);
  ss_status st = ss_write_mesh(outp, &s, NULL, &err);
  ss_mesh_free(&s);
  if (st) return cli_error("%s", err.msg);
  return SS_EXIT_OK;
}
