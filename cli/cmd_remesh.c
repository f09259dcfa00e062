/* specseg remesh MESH -o OUT [--faces N]: isotropic remeshing to about N triangles. */
#include <stdio.h>
#include <string.h>

#include "cli.h"

static const char USAGE[] =
    "usage: specseg remesh MESH... -o OUT [--faces N] [--iterations K] [--jobs N] [--json]\n"
    "\n"
    "Isotropic remeshing (split / collapse / flip / tangential relaxation / projection) of a closed\n"
    "manifold mesh to about N triangles. Prints on stderr: faces, % of triangles with min angle >= 30\n"
    "deg, % of vertices of valence 6, largest vertex distance to the input surface / input bbox\n"
    "diagonal, seconds.\n"
    "\n"
    "  MESH                mesh file (OFF, OBJ, PLY, STL, glTF, ...); - reads standard input\n"
    "  -o OUT              output mesh, .off, .ply (binary) or .obj; - writes OFF to standard output;\n"
    "                      batch: OUTDIR, meshes in OUTDIR/NAME.off\n"
    "  --faces N           target triangle count, 4..2000000 (default 15000)\n"
    "  --iterations K      remeshing rounds, 1..1000 (default 5)\n" CLI_BATCH_HELP;

typedef struct remesh_cfg {
  const char *out;
  ss_remesh_options opt;
} remesh_cfg;

static int remesh_job(cli_job *j, void *vcfg) {
  const remesh_cfg *c = vcfg;
  const char *path = j->input, *outp = cli_job_output(j, c->out, ".off");
  ss_error err = {{0}};
  ss_mesh m, r;
  if (cli_read_mesh(path, &m, &err)) return cli_error("%s", err.msg);
  double t0 = ss_time();
  if (ss_remesh(&m, &c->opt, &r, &err)) {
    ss_mesh_free(&m);
    return cli_error("%s: %s", cli_in_name(path), err.msg);
  }
  double t = ss_time() - t0;
  ss_remesh_quality q;
  ss_status st = ss_remesh_quality_measure(&r, &m, &q, &err);
  ss_mesh_free(&m);
  if (st) { ss_mesh_free(&r); return cli_error("%s", err.msg); }
  /* stderr, as always; in a batch the report (prefixed by the mesh) */
  fprintf(j->b && j->b->batch ? cli_job_report(j, 0) : stderr,
          "remesh: faces %d, min angle >= 30: %.1f%%, valence 6: %.1f%%, max deviation / bbox diag: %.2e, %.3f s\n",
          q.faces, 100 * q.frac_min_angle_30, 100 * q.frac_valence_6, q.max_deviation, t);
  cli_job_int(j, "faces", q.faces);
  cli_job_int(j, "vertices", r.nv);
  cli_job_num(j, "min_angle_30", q.frac_min_angle_30);
  cli_job_num(j, "valence_6", q.frac_valence_6);
  cli_job_num(j, "max_deviation", q.max_deviation);
  cli_job_num(j, "t_remesh", t);
  st = cli_write_mesh(outp, &r, NULL, "off", &err);
  ss_mesh_free(&r);
  if (st) return cli_error("%s", err.msg);
  return SS_EXIT_OK;
}

int cmd_remesh(int argc, char **argv) {
  remesh_cfg c;
  memset(&c, 0, sizeof c);
  ss_remesh_default_options(&c.opt);
  cli_batch B;
  cli_batch_init(&B, "remesh");
  const cli_opt opts[] = {
      CLI_BATCH_OPTIONS(&B),
      CLI_OPT_STR("-o", &c.out),
      CLI_OPT_INT("--faces", &c.opt.target_faces, 4, SS_REMESH_MAX_FACES,
                  "--faces wants an integer in [4, " CLI_STRINGIFY(SS_REMESH_MAX_FACES) "], got '%s'"),
      CLI_OPT_INT("--iterations", &c.opt.iterations, 1, 1000, "--iterations wants an integer in [1,1000], got '%s'"),
      CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, opts);
  int rc = cli_parse(&A);
  if (rc < 0 && B.nin == 0) rc = cli_bad(&A, "no mesh given");
  if (rc < 0) rc = cli_batch_setup(&B, &A, c.out, 1, ".off", NULL, 0);
  if (rc < 0 && !c.out) rc = cli_bad(&A, "missing -o OUT");
  if (rc < 0 && !B.batch && B.json && cli_is_std(c.out)) rc = cli_bad(&A, "--json and -o - both want standard output");
  return cli_batch_finish(&B, rc, remesh_job, &c);
}
