/* specseg smooth MESH -o OUT [--steps N] [--dt D] [--bbox]: conformalized mean curvature flow. */
#include <stdio.h>
#include <string.h>

#include "cli.h"

static const char USAGE[] =
    "usage: specseg smooth MESH... -o OUT [--steps N] [--dt D] [--bbox] [--jobs N] [--json]\n"
    "\n"
    "Conformalized mean curvature flow (Kazhdan et al. 2012): N steps of (M_t + D W0) X' = M_t X with\n"
    "the shape centred and scaled to unit area before each step. The result keeps the connectivity,\n"
    "the input's area and centroid.\n"
    "\n"
    "  MESH                mesh file (OFF, OBJ, PLY, STL, glTF, ...); - reads standard input\n"
    "  -o OUT              output mesh, .off, .ply (binary) or .obj; - writes OFF to standard output;\n"
    "                      batch: OUTDIR, meshes in OUTDIR/NAME.off\n"
    "  --steps N           flow steps, 0..100000 (default 12)\n"
    "  --dt D              time step in (0, 1e6] (default 2.2e-5; 1e-5 with --bbox)\n"
    "  --bbox              scale to unit bounding-box diagonal instead of unit area, as the authors'\n"
    "                      code does\n" CLI_BATCH_HELP;

typedef struct smooth_cfg {
  const char *out;
  ss_cmcf_options opt;
} smooth_cfg;

static int smooth_job(cli_job *j, void *vcfg) {
  const smooth_cfg *c = vcfg;
  const char *path = j->input, *outp = cli_job_output(j, c->out, ".off");
  ss_error err = {{0}};
  ss_mesh m, s;
  double t0 = ss_time();
  if (cli_read_mesh(path, &m, &err)) return cli_error("%s", err.msg);
  if (ss_cmcf_smooth(&m, &c->opt, &s, &err)) {
    ss_mesh_free(&m);
    return cli_error("%s: %s", cli_in_name(path), err.msg);
  }
  cli_job_int(j, "vertices", m.nv);
  cli_job_int(j, "faces", m.nf);
  cli_job_int(j, "steps", c->opt.steps);
  ss_mesh_free(&m);
  ss_status st = cli_write_mesh(outp, &s, NULL, "off", &err);
  ss_mesh_free(&s);
  if (st) return cli_error("%s", err.msg);
  if (j->b && j->b->batch) fprintf(cli_job_report(j, 0), "%d steps (%.2f s) -> %s\n", c->opt.steps, ss_time() - t0, outp);
  return SS_EXIT_OK;
}

int cmd_smooth(int argc, char **argv) {
  smooth_cfg c;
  memset(&c, 0, sizeof c);
  ss_cmcf_default_options(&c.opt);
  double dt = 0; /* given: > 0 */
  cli_batch B;
  cli_batch_init(&B, "smooth");
  const cli_opt opts[] = {CLI_BATCH_OPTIONS(&B),
                    CLI_OPT_STR("-o", &c.out),
                    CLI_OPT_INT("--steps", &c.opt.steps, 0, 100000, "--steps wants an integer in [0,100000], got '%s'"),
                    CLI_OPT_DOUBLE("--dt", &dt, 0, 1e6, CLI_OPEN_LO, "--dt wants a time step in (0, 1e6], got '%s'"),
                    CLI_OPT_FLAG("--bbox", CLI_ENUM(&c.opt.normalization), SS_CMCF_UNIT_BBOX),
                    CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, opts);
  int rc = cli_parse(&A);
  if (rc < 0 && B.nin == 0) rc = cli_bad(&A, "no mesh given");
  if (rc < 0) rc = cli_batch_setup(&B, &A, c.out, 1, ".off", NULL, 0);
  if (rc < 0 && !c.out) rc = cli_bad(&A, "missing -o OUT");
  if (rc < 0 && !B.batch && B.json && cli_is_std(c.out)) rc = cli_bad(&A, "--json and -o - both want standard output");
  if (dt > 0) c.opt.dt = dt;
  else if (c.opt.normalization == SS_CMCF_UNIT_BBOX) c.opt.dt = 1e-5;
  return cli_batch_finish(&B, rc, smooth_job, &c);
}
