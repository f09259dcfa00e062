/* specseg remesh MESH -o OUT [--faces N]: isotropic remeshing to about N triangles. */
#include <stdio.h>
#include <string.h>

#include "cli.h"

static const char *usage = "specseg remesh MESH -o OUT [--faces N] [--iterations K]";

int cmd_remesh(int argc, char **argv) {
  const char *path = NULL, *outp = NULL;
  ss_remesh_options opt;
  ss_remesh_default_options(&opt);
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
      printf("usage: %s\n"
             "Isotropic remeshing (split / collapse / flip / tangential relaxation / projection) of a\n"
             "closed manifold mesh to about N triangles (default %d) in K rounds (default %d).\n"
             "Prints on stderr: faces, %% of triangles with min angle >= 30 deg, %% of vertices of\n"
             "valence 6, largest vertex distance to the input surface / input bbox diagonal, seconds.\n",
             usage, opt.target_faces, opt.iterations);
      return SS_EXIT_OK;
    }
    if (!strcmp(a, "-o") || !strcmp(a, "--faces") || !strcmp(a, "--iterations")) {
      if (i + 1 >= argc) return cli_usage("%s: %s needs a value", usage, a);
      const char *v = argv[++i];
      if (!strcmp(a, "-o")) outp = v;
      else if (!strcmp(a, "--faces")) {
        if (cli_parse_int(v, 4, 100000000, &opt.target_faces)) return cli_usage("%s: --faces wants an integer >= 4, got '%s'", usage, v);
      } else if (cli_parse_int(v, 1, 1000, &opt.iterations)) {
        return cli_usage("%s: --iterations wants an integer in [1,1000], got '%s'", usage, v);
      }
      continue;
    }
    if (a[0] == '-' && a[1] != '\0') return cli_usage("%s: unknown option '%s'", usage, a);
    if (path) return cli_usage("%s: more than one mesh given", usage);
    path = a;
  }
  if (!path || !outp) return cli_usage("%s", usage);

  ss_error err = {{0}};
  ss_mesh m, r;
  if (ss_read_mesh(path, &m, &err)) return cli_error("%s", err.msg);
  double t0 = ss_time();
  if (ss_remesh(&m, &opt, &r, &err)) {
    ss_mesh_free(&m);
    return cli_error("%s: %s", path, err.msg);
  }
  double t = ss_time() - t0;
  ss_remesh_quality q;
  ss_status st = ss_remesh_quality_measure(&r, &m, &q, &err);
  ss_mesh_free(&m);
  if (st) { ss_mesh_free(&r); return cli_error("%s", err.msg); }
  fprintf(stderr, "remesh: faces %d, min angle >= 30: %.1f%%, valence 6: %.1f%%, max deviation / bbox diag: %.2e, %.3f s\n",
          q.faces, 100 * q.frac_min_angle_30, 100 * q.frac_valence_6, q.max_deviation, t);
  st = ss_write_mesh(outp, &r, NULL, &err);
  ss_mesh_free(&r);
  if (st) return cli_error("%s", err.msg);
  return SS_EXIT_OK;
}
