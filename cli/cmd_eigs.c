/* specseg eigs MESH -k K [--evecs FILE.npy] [--mass barycentric|voronoi] [--sigma S]
 * Prints the k smallest Laplace–Beltrami eigenvalues, one a line (%.17g). */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static const char USAGE[] =
    "usage: specseg eigs MESH... -k K [-o EVALS.txt] [--evecs FILE.npy] [--mass barycentric|voronoi] [--sigma S]\n"
    "                   [--jobs N] [--json]\n"
    "\n"
    "The K smallest eigenvalues of the Laplace-Beltrami problem W phi = lambda M phi (cotangent\n"
    "stiffness W, lumped mass M), one a line (%.17g) on standard output. Vertices without area get 0\n"
    "in every eigenvector (with a warning).\n"
    "\n"
    "  MESH                mesh file (OFF, OBJ, PLY, STL, glTF, ...); - reads standard input\n"
    "  -k K                number of eigenpairs, 1 <= K < vertices (required); K up to about half the\n"
    "                      vertices leaves the solver the room it needs\n"
    "  -o FILE             the eigenvalues to FILE (text, or .npy) instead of standard output; batch:\n"
    "                      OUTDIR (required), eigenvalues in OUTDIR/NAME.evals.txt\n"
    "  --evecs FILE.npy    also write the eigenvectors, a vertices x K float64 .npy (batch: a suffix,\n"
    "                      e.g. .evecs.npy)\n"
    "  --mass KIND         barycentric (default) or voronoi (mixed Voronoi areas)\n"
    "  --sigma S           shift: the K eigenvalues nearest S (default -1e-8)\n" CLI_BATCH_HELP;

typedef struct eigs_cfg {
  const char *evals, *evecs;
  int k;
  ss_mass_kind mass;
  ss_eigs_options opt;
} eigs_cfg;

/* Rows/columns of W for the vertices with keep[i] >= 0 (keep[i] = new index). */
static int restrict_matrix(const ss_sparse *W, const int *keep, int nkeep, ss_sparse *out) {
  memset(out, 0, sizeof *out);
  out->nrows = out->ncols = nkeep;
  out->colptr = malloc(sizeof(int) * ((size_t)nkeep + 1));
  out->rowind = malloc(sizeof(int) * ((size_t)W->colptr[W->ncols] + 1));
  out->val = malloc(sizeof(double) * ((size_t)W->colptr[W->ncols] + 1));
  if (!out->colptr || !out->rowind || !out->val) return -1;
  int q = 0;
  for (int j = 0; j < W->ncols; j++) {
    if (keep[j] < 0) continue;
    out->colptr[keep[j]] = q;
    for (int p = W->colptr[j]; p < W->colptr[j + 1]; p++)
      if (keep[W->rowind[p]] >= 0) {
        out->rowind[q] = keep[W->rowind[p]];
        out->val[q++] = W->val[p];
      }
  }
  out->colptr[nkeep] = q;
  return 0;
}

static int eigs_job(cli_job *j, void *vcfg) {
  const eigs_cfg *c = vcfg;
  const char *mesh_path = j->input;
  const char *evals_path = cli_job_output(j, c->evals, ".evals.txt"), *evecs_path = cli_job_extra(j, c->evecs);
  const int k = c->k;
  const ss_mass_kind mass = c->mass;
  ss_error err;
  ss_mesh m = {0};
  if (cli_read_mesh(mesh_path, &m, &err) != SS_OK) return cli_error("%s", err.msg);
  if (k >= m.nv) {
    int nv = m.nv;
    ss_mesh_free(&m);
    return cli_usage("eigs: %s: -k %d must be smaller than the number of vertices (%d)", cli_in_name(mesh_path), k, nv);
  }

  int rc = SS_EXIT_FAIL;
  ss_sparse W = {0}, Wk = {0};
  double *M = malloc(sizeof(double) * (size_t)m.nv), *Mk = NULL, *evals = NULL, *X = NULL, *Xk = NULL;
  int *keep = malloc(sizeof(int) * (size_t)m.nv);
  if (!M || !keep) { cli_error("out of memory"); goto out; }
  if (ss_cotan_stiffness(&m, &W, &err) || ss_mass_lumped(&m, mass, M, &err)) {
    cli_error("%s: %s", cli_in_name(mesh_path), err.msg);
    goto out;
  }
  /* Vertices with no area (unreferenced, or only in degenerate faces) have no W entries either:
   * solve on the others and report 0 for them, rather than refusing the mesh. */
  int nkeep = 0;
  for (int i = 0; i < m.nv; i++) keep[i] = M[i] > 0 ? nkeep++ : -1;
  const ss_sparse *Wuse = &W;
  const double *Muse = M;
  if (nkeep < m.nv) {
    for (int v = 0; v < m.nv; v++)
      if (keep[v] < 0)
        for (int p = W.colptr[v]; p < W.colptr[v + 1]; p++)
          if (W.val[p] != 0 && W.val[p] == W.val[p]) {
            cli_error("%s: vertex %d has zero area but non-zero stiffness", cli_in_name(mesh_path), v);
            goto out;
          }
    if (k >= nkeep) {
      cli_error("%s: only %d vertices have positive area; -k %d is too large", cli_in_name(mesh_path), nkeep, k);
      goto out;
    }
    cli_warn("%s: %d vertices have zero area (unreferenced or only in degenerate faces); their eigenvector "
             "entries are 0",
             cli_in_name(mesh_path), m.nv - nkeep);
    Mk = malloc(sizeof(double) * (size_t)nkeep);
    if (!Mk || restrict_matrix(&W, keep, nkeep, &Wk)) { cli_error("out of memory"); goto out; }
    for (int i = 0; i < m.nv; i++)
      if (keep[i] >= 0) Mk[keep[i]] = M[i];
    Wuse = &Wk;
    Muse = Mk;
  }
  evals = malloc(sizeof(double) * (size_t)k);
  Xk = malloc(sizeof(double) * (size_t)nkeep * (size_t)k);
  if (!evals || !Xk) { cli_error("out of memory for %d eigenvectors", k); goto out; }
  if (ss_eigs(Wuse, Muse, k, &c->opt, evals, Xk, &err) != SS_OK) {
    cli_error("%s: %s", cli_in_name(mesh_path), err.msg);
    goto out;
  }
  if (evecs_path) {
    const double *out = Xk;
    if (nkeep < m.nv) {
      X = calloc((size_t)m.nv * (size_t)k, sizeof(double));
      if (!X) { cli_error("out of memory"); goto out; }
      for (size_t col = 0; col < (size_t)k; col++)
        for (int i = 0; i < m.nv; i++)
          if (keep[i] >= 0) X[(size_t)i + (size_t)m.nv * col] = Xk[(size_t)keep[i] + (size_t)nkeep * col];
      out = X;
    }
    if (cli_write_npy(evecs_path, out, m.nv, k, &err) != SS_OK) {
      cli_error("%s", err.msg);
      goto out;
    }
  }
  if (evals_path) { /* a file (text or .npy by extension), or - */
    if (cli_write_doubles(evals_path, evals, k, &err)) { cli_error("%s", err.msg); goto out; }
  } else {
    for (int i = 0; i < k; i++) printf("%.17g\n", evals[i]);
    if (fflush(stdout) != 0) { cli_error("cannot write to standard output"); goto out; }
  }
  cli_job_int(j, "vertices", m.nv);
  cli_job_int(j, "k", k);
  cli_job_num(j, "lambda_1", k > 1 ? evals[1] : evals[0]);
  cli_job_num(j, "lambda_max", evals[k - 1]);
  if (evals_path && j->b && j->b->batch)
    fprintf(cli_job_report(j, 0), "%d eigenvalues, %g .. %g -> %s\n", k, evals[0], evals[k - 1], evals_path);
  rc = SS_EXIT_OK;
out:
  ss_sparse_free(&W);
  ss_sparse_free(&Wk);
  free(M); free(Mk); free(keep); free(evals); free(X); free(Xk);
  ss_mesh_free(&m);
  return rc;
}

int cmd_eigs(int argc, char **argv) {
  eigs_cfg c;
  memset(&c, 0, sizeof c);
  c.k = -1;
  c.mass = SS_MASS_BARYCENTRIC;
  ss_eigs_default_options(&c.opt);
  cli_batch B;
  cli_batch_init(&B, "eigs");
  static const int MASS[] = {SS_MASS_BARYCENTRIC, SS_MASS_VORONOI};
  const cli_opt opts[] = {
      CLI_BATCH_OPTIONS(&B),
      CLI_OPT_INT("-k", &c.k, 1, INT_MAX, "-k needs a positive integer, not '%s'"),
      CLI_OPT_STR("-o", &c.evals),
      CLI_OPT_STR("--evecs", &c.evecs),
      CLI_OPT_CHOICE("--mass", CLI_ENUM(&c.mass), "barycentric|voronoi", MASS,
                     "--mass must be barycentric or voronoi, not '%s'"),
      CLI_OPT_DOUBLE("--sigma", &c.opt.sigma, -1e308, 1e308, CLI_OPEN_LO | CLI_OPEN_HI,
                     "--sigma needs a finite number, not '%s'"),
      CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, opts);
  int rc = cli_parse(&A);
  if (rc < 0 && B.nin == 0) rc = cli_bad(&A, "no mesh given");
  if (rc < 0 && c.k < 0) rc = cli_bad(&A, "-k K is required");
  const char *extras[1] = {c.evecs};
  if (rc < 0) rc = cli_batch_setup(&B, &A, c.evals, 1, ".evals.txt", extras, 1);
  if (rc < 0 && !B.batch && cli_is_std(c.evecs))
    rc = cli_bad(&A, "--evecs -: standard output carries the eigenvalues; give a file name");
  if (rc < 0 && !B.batch && B.json && (!c.evals || cli_is_std(c.evals)))
    rc = cli_bad(&A, "--json wants standard output: write the eigenvalues with -o FILE");
  return cli_batch_finish(&B, rc, eigs_job, &c);
}
