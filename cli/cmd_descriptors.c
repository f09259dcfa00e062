/* specseg descriptors MESH --wks|--hks [-k K] [-n N] -o D.npy: per-vertex spectral descriptors. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static const char USAGE[] =
    "usage: specseg descriptors MESH --wks|--hks -o D.npy [-k K] [-n N]\n"
    "\n"
    "Per-vertex spectral descriptors from the K smallest Laplace-Beltrami eigenpairs (barycentric lumped\n"
    "masses), as an (vertices x N) float64 .npy, each column normalised to unit L2(M) norm. They are what\n"
    "'specseg match --descriptors DX.npy DY.npy' takes (or any features of your own with corresponding\n"
    "columns). Prints a summary line (on stderr when -o is -).\n"
    "\n"
    "  MESH                mesh file (OFF, OBJ, PLY, STL, glTF, ...); - reads standard input\n"
    "  --wks               wave kernel signature (Aubry et al. 2011): N log-spaced energies, sigma = 7\n"
    "                      energy spacings, as the WKS that 'specseg match' uses (its default K and N)\n"
    "  --hks               heat kernel signature (Sun et al. 2009): N log-spaced times from\n"
    "                      4 ln 10 / lambda_max to 4 ln 10 / lambda_1\n"
    "  -o FILE.npy         the descriptors (required); - writes the .npy to standard output\n"
    "  -k K                eigenpairs, 3 <= K < vertices (default 50)\n"
    "  -n N                energies / times, 1..10000 (default 100)\n";

static const char *const OPTS[] = {"--wks", "--hks", "-o=", "-k=", "-n=", NULL};

int cmd_descriptors(int argc, char **argv) {
  const char *path = NULL, *outp = NULL;
  int kind = 0, k = 50, nd = 100; /* kind: 1 WKS, 2 HKS */
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, OPTS);
  while (cli_next(&A)) {
    const char *v = A.val;
    if (A.pos) {
      if (path) return cli_bad(&A, "more than one mesh given ('%s', '%s')", path, A.pos);
      path = A.pos;
    } else if (cli_is(&A, "--wks") || cli_is(&A, "--hks")) {
      int kk = cli_is(&A, "--wks") ? 1 : 2;
      if (kind && kind != kk) return cli_bad(&A, "choose one of --wks and --hks");
      kind = kk;
    } else if (cli_is(&A, "-o")) {
      outp = v;
    } else if (cli_is(&A, "-k")) {
      if (cli_parse_int(v, 3, INT_MAX, &k)) return cli_bad(&A, "-k needs an integer >= 3, not '%s'", v);
    } else if (cli_is(&A, "-n")) {
      if (cli_parse_int(v, 1, 10000, &nd)) return cli_bad(&A, "-n needs an integer between 1 and 10000, not '%s'", v);
    }
  }
  if (A.rc >= 0) return A.rc;
  if (!path) return cli_bad(&A, "no mesh given");
  if (!kind) return cli_bad(&A, "choose --wks or --hks");
  if (!outp) return cli_bad(&A, "missing -o D.npy");
  if (!cli_is_std(outp) && !cli_is_npy(outp)) return cli_bad(&A, "-o: descriptors are written as .npy, not '%s'", outp);
  FILE *report = cli_is_std(outp) ? stderr : stdout;

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
  fprintf(report, "%s, %d %s from %d eigenpairs, %d vertices (%.2f s) -> %s\n", kind == 1 ? "WKS" : "HKS", nd,
          kind == 1 ? "energies" : "times", k, m.nv, ss_time() - t0, cli_out_name(outp));
  rc = fflush(report) ? cli_error("cannot write the summary") : SS_EXIT_OK;
out:
  free(evals), free(evecs), free(M), free(D);
  ss_mesh_free(&m);
  return rc;
}
