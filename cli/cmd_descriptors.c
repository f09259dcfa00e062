/* specseg descriptors MESH --wks|--hks [-k K] [-n N] -o D.npy: per-vertex spectral descriptors. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static const char USAGE[] =
    "usage: specseg descriptors MESH... --wks|--hks -o D.npy [-k K] [-n N] [--jobs N] [--json]\n"
    "\n"
    "Per-vertex spectral descriptors from the K smallest Laplace-Beltrami eigenpairs (barycentric lumped\n"
    "masses), as an (vertices x N) float64 .npy, each column normalised to unit L2(M) norm. They are what\n"
    "'specseg match --descriptors DX.npy DY.npy' takes (or any features of your own with corresponding\n"
    "columns). Prints a summary line (on stderr when -o is -).\n"
    "\n"
    "  MESH                mesh file (OFF, OBJ, PLY, STL, glTF, ...); - reads standard input\n"
    "  --wks               wave kernel signature (Aubry et al. 2011): N log-spaced energies, sigma = 7\n"
    "                      energy spacings, as the WKS that 'specseg match' uses (its default --descr-k\n"
    "                      and N)\n"
    "  --hks               heat kernel signature (Sun et al. 2009): N log-spaced times from\n"
    "                      4 ln 10 / lambda_max to 4 ln 10 / lambda_1\n"
    "  -o FILE.npy         the descriptors (required); - writes the .npy to standard output; batch:\n"
    "                      OUTDIR, descriptors in OUTDIR/NAME.wks.npy or NAME.hks.npy\n"
    "  -k K                eigenpairs, 3 <= K < vertices (default 100: match's default --descr-k)\n"
    "  -n N                energies / times, 1..10000 (default 100)\n" CLI_BATCH_HELP;

typedef struct descr_cfg {
  const char *out;
  int kind, k, n; /* kind: 1 WKS, 2 HKS */
} descr_cfg;

static int descriptors_job(cli_job *j, void *vcfg) {
  const descr_cfg *c = vcfg;
  const int kind = c->kind, k = c->k, nd = c->n;
  const char *path = j->input, *outp = cli_job_output(j, c->out, kind == 1 ? ".wks.npy" : ".hks.npy");
  FILE *report = cli_job_report(j, cli_is_std(outp));
  ss_error err = {{0}};
  ss_mesh m = {0};
  if (cli_read_mesh(path, &m, &err)) return cli_error("%s", err.msg);
  const char *name = cli_in_name(path);
  int rc = SS_EXIT_FAIL;
  double *evals = NULL, *evecs = NULL, *M = NULL, *D = NULL;
  if (k >= m.nv) {
    rc = cli_error("%s: -k %d must be smaller than the number of vertices (%d)", name, k, m.nv);
    goto out;
  }
  evals = malloc(sizeof(double) * (size_t)k);
  evecs = malloc(sizeof(double) * (size_t)m.nv * (size_t)k);
  M = malloc(sizeof(double) * (size_t)m.nv);
  D = malloc(sizeof(double) * (size_t)m.nv * (size_t)nd);
  if (!evals || !evecs || !M || !D) {
    cli_error("out of memory");
    goto out;
  }
  double t0 = ss_time();
  if (ss_mesh_eigs(&m, k, evals, evecs, &err) || ss_mass_lumped(&m, SS_MASS_BARYCENTRIC, M, &err) ||
      (kind == 1 ? ss_wks(m.nv, k, evals, evecs, M, nd, 7.0, D, &err) : ss_hks(m.nv, k, evals, evecs, M, nd, D, &err))) {
    cli_error("%s: %s", name, err.msg);
    goto out;
  }
  if (cli_write_npy(outp, D, m.nv, nd, &err)) {
    cli_error("%s", err.msg);
    goto out;
  }
  double t = ss_time() - t0;
  fprintf(report, "%s, %d %s from %d eigenpairs, %d vertices (%.2f s) -> %s\n", kind == 1 ? "WKS" : "HKS", nd,
          kind == 1 ? "energies" : "times", k, m.nv, t, cli_out_name(outp));
  cli_job_str(j, "descriptor", kind == 1 ? "wks" : "hks");
  cli_job_int(j, "vertices", m.nv);
  cli_job_int(j, "columns", nd);
  cli_job_int(j, "k", k);
  cli_job_num(j, "t_compute", t);
  rc = fflush(report) ? cli_error("cannot write the summary") : SS_EXIT_OK;
out:
  free(evals), free(evecs), free(M), free(D);
  ss_mesh_free(&m);
  return rc;
}

int cmd_descriptors(int argc, char **argv) {
  descr_cfg c = {NULL, 0, 100, 100};
  cli_batch B;
  cli_batch_init(&B, "descriptors");
  const cli_opt opts[] = {CLI_BATCH_OPTIONS(&B),
                          CLI_OPT_FLAG1("--wks", &c.kind, 1, "choose one of --wks and --hks"),
                          CLI_OPT_FLAG1("--hks", &c.kind, 2, "choose one of --wks and --hks"),
                          CLI_OPT_STR("-o", &c.out),
                          CLI_OPT_INT("-k", &c.k, 3, INT_MAX, "-k needs an integer >= 3, not '%s'"),
                          CLI_OPT_INT("-n", &c.n, 1, 10000, NULL),
                          CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, opts);
  int rc = cli_parse(&A);
  if (rc < 0 && B.nin == 0) rc = cli_bad(&A, "no mesh given");
  if (rc < 0 && !c.kind) rc = cli_bad(&A, "choose --wks or --hks");
  if (rc < 0) rc = cli_batch_setup(&B, &A, c.out, 1, c.kind == 1 ? ".wks.npy" : ".hks.npy", NULL, 0);
  if (rc < 0 && !c.out) rc = cli_bad(&A, "missing -o D.npy");
  if (rc < 0 && !B.batch && !cli_is_std(c.out) && !cli_is_npy(c.out))
    rc = cli_bad(&A, "-o: descriptors are written as .npy, not '%s'", c.out);
  if (rc < 0 && B.batch && B.suffix && !cli_is_npy(B.suffix))
    rc = cli_bad(&A, "--suffix: descriptors are written as .npy, not '%s'", B.suffix);
  if (rc < 0 && !B.batch && B.json && cli_is_std(c.out)) rc = cli_bad(&A, "--json and -o - both want standard output");
  return cli_batch_finish(&B, rc, descriptors_job, &c);
}
