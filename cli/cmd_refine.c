/* specseg refine X Y MAP.txt -o OUT.txt [--k K] [--zoomout KMAX] [--zoomout-step S]
 *                    [--zoomout-samples N] [--fmap C.npy] [--polish | --polish-only] [--json]:
 * ss_match_refine on a given map, ss_map_polish after it or alone. */
#include "cli.h"
#include "cli_shape.h"
#include "specseg/match.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char USAGE[] =
    "usage: specseg refine X Y MAP.txt -o OUT.txt [--k K] [--zoomout KMAX] [--zoomout-step S]\n"
    "                      [--zoomout-samples N] [--fmap C.npy] [--polish | --polish-only] [--json]\n"
    "\n"
    "A given point map X -> Y (another method's, or a rough one) through the refinement specseg match\n"
    "gives its own maps: the map's functional map on the first K eigenfunctions of both shapes (scaled\n"
    "to unit area), then ZoomOut up to KMAX (on vertex samples of X, then once on every vertex).\n"
    "ZoomOut mends what is local; a whole part mapped to the wrong place (a left-right swap) stays.\n"
    "Prints a summary line (on stderr when an output goes to standard output).\n"
    "\n"
    "  X, Y                mesh files (OFF, OBJ, PLY, STL, glTF, ...), or prepared shapes (specseg\n"
    "                      prepare, .sss: their eigenpairs are used); one input may be - (standard input)\n"
    "  MAP.txt             line i = vertex of Y that is the image of vertex i of X (0-based; .npy too)\n"
    "  -o, --output FILE   the refined map, same format (required)\n"
    "  --k K               the start's basis size, 1..10000 (default 50)\n"
    "  --zoomout KMAX      ZoomOut up to KMAX >= K eigenfunctions (default 110; = K: no ZoomOut, the map\n"
    "                      through its own K x K functional map)\n"
    "  --zoomout-step S    ZoomOut's size increment, 1..10000 (default 5)\n"
    "  --zoomout-samples N ZoomOut's iterations on N samples of X, 0..10^9 (default 1000; 0 or at least\n"
    "                      X's vertex count: on every vertex, ZoomOut's plain loop)\n"
    "  --fmap FILE         the final functional map (functions on Y -> functions on X, KMAX x KMAX) as .npy\n"
    "  --polish            then fit the map to the surfaces, as match's last step does: X deformed as rigidly\n"
    "                      as possible onto Y, each vertex sent to the nearest vertex of Y facing the same way\n"
    "  --polish-only       that step alone, on the map as given (no eigenpairs; --k, --zoomout* and --fmap unused)\n"
    "  --json              a JSON summary on standard output instead of the summary line\n"
    "One of the output files may be - (standard output).\n";

/* The prep of a shape argument with at least kev eigenpairs: a prepared shape's own (refused when it
 * is matched through a coarse proxy or has too few), else computed on the mesh into *own. */
static ss_status shape_prep(cli_shape *s, const char *name, int kev, ss_shape_prep *own, const ss_shape_prep **out,
                            ss_error *err) {
  if (s->prepared) {
    if (s->ps.has_proxy)
      return ss_fail(err, SS_ERR_INVALID, "%s is matched through a coarse proxy (above 100,000 vertices): refine the "
                     "mesh itself", name);
    if (s->ps.prep.kev < kev)
      return ss_fail(err, SS_ERR_INVALID, "%s was prepared with %d eigenpairs but this refinement needs %d: prepare it "
                     "with at least %d (specseg prepare --k)", name, s->ps.prep.kev, kev, kev);
    *out = &s->ps.prep;
    return SS_OK;
  }
  if (kev >= s->ps.mesh.nv)
    return ss_fail(err, SS_ERR_INVALID, "%s has %d vertices: too few for %d eigenpairs", name, s->ps.mesh.nv, kev);
  ss_error e = {{0}};
  ss_status st = ss_shape_prep_compute_spectral(&s->ps.mesh, kev, own, &e);
  if (!st) *out = own;
  else ss_fail(err, st, "%s: %s", name, e.msg + (strncmp(e.msg, "match: ", 7) ? 0 : 7)); /* the library's words, the file named */
  return st;
}

int cmd_refine(int argc, char **argv) {
  const char *xp = NULL, *yp = NULL, *mapp = NULL, *outp = NULL, *fmapp = NULL;
  int json = 0, polish = 0, polish_only = 0;
  ss_match_options o;
  ss_match_default_options(&o);
  const cli_opt opts[] = {CLI_OPT_POS("X", &xp, NULL),
                          CLI_OPT_POS("Y", &yp, NULL),
                          CLI_OPT_POS("MAP.txt", &mapp, "too many arguments ('%s')"),
                          CLI_OPT_STR("-o|--output", &outp),
                          CLI_OPT_STR("--fmap", &fmapp),
                          CLI_OPT_INT("--k", &o.fmap.k, 1, 10000, NULL),
                          CLI_OPT_INT("--zoomout", &o.fmap.zoomout_kmax, 1, 10000, NULL),
                          CLI_OPT_INT("--zoomout-step", &o.fmap.zoomout_step, 1, 10000, NULL),
                          CLI_OPT_INT("--zoomout-samples", &o.fmap.zoomout_samples, 0, 1000000000, NULL),
                          CLI_OPT_FLAG("--polish", &polish, 1),
                          CLI_OPT_FLAG("--polish-only", &polish_only, 1),
                          CLI_OPT_FLAG("--json", &json, 1),
                          CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, opts);
  int rc = cli_parse(&A);
  if (rc >= 0) return rc;
  if (!xp || !yp || !mapp) return cli_bad(&A, "needs two shapes X and Y and the map MAP.txt");
  if (!outp) return cli_bad(&A, "missing -o OUT.txt");
  if (polish && polish_only) return cli_bad(&A, "--polish and --polish-only: choose one");
  if (polish_only && fmapp) return cli_bad(&A, "--fmap needs the spectral refinement, which --polish-only skips");
  if (o.fmap.zoomout_kmax < o.fmap.k) return cli_bad(&A, "--zoomout %d is below --k %d", o.fmap.zoomout_kmax, o.fmap.k);
  const char *ins[3] = {xp, yp, mapp}, *outs[2] = {outp, fmapp};
  if (cli_count_std(ins, 3) > 1) return cli_bad(&A, "only one input can come from standard input ('-')");
  if (cli_check_outputs(&A, outs, 2, ins, 3) >= 0) return A.rc;
  const int to_stdout = cli_count_std(outs, 2);
  if (to_stdout > 1) return cli_bad(&A, "only one output can go to standard output ('-')");
  if (to_stdout && json) return cli_bad(&A, "--json and an output to '-' both want standard output");
  FILE *report = to_stdout ? stderr : stdout;
  const char *xn = cli_in_name(xp), *yn = cli_in_name(yp), *mn = cli_in_name(mapp);
  cli_job J;
  cli_job_begin(&J, NULL);
  cli_job_str(&J, "x", xn), cli_job_str(&J, "y", yn), cli_job_str(&J, "map", mn);

  ss_error err = {{0}};
  cli_shape SX = {0}, SY = {0};
  ss_shape_prep ownX = {0}, ownY = {0};
  const ss_shape_prep *PX = NULL, *PY = NULL;
  int *map = NULL, *lines = NULL, n = 0;
  double *C = NULL;
  const int kz = o.fmap.zoomout_kmax;
  double t0 = ss_time();
  rc = SS_EXIT_OK;
  if (cli_read_ints_lines(mapp, &map, &lines, &n, &err) || cli_read_shape(xp, &SX, &err) || cli_read_shape(yp, &SY, &err)) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  /* the map's length and entries, named by file and line, before the eigenpairs */
  if (n != SX.ps.mesh.nv) {
    rc = cli_error("%s: %d lines, but X (%s) has %d vertices: a map has one line per vertex of X", mn, n, xn, SX.ps.mesh.nv);
    goto done;
  }
  for (int i = 0; i < n; i++)
    if (map[i] < 0 || map[i] >= SY.ps.mesh.nv) {
      rc = cli_error("%s:%d: vertex %d is not on the target (%s has vertices 0..%d): a map's i-th entry is the vertex of "
                     "Y that vertex i of X goes to; is %s the map's target?",
                     mn, lines[i], map[i], yn, SY.ps.mesh.nv - 1, yn);
      goto done;
    }
  if (!polish_only && (shape_prep(&SX, xn, kz, &ownX, &PX, &err) || shape_prep(&SY, yn, kz, &ownY, &PY, &err))) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  double t1 = ss_time();
  if (fmapp && !(C = malloc(sizeof(double) * (size_t)kz * kz))) { /* only for --fmap */
    rc = cli_error("out of memory");
    goto done;
  }
  if (!polish_only && ss_match_refine(PX, PY, map, &o, map, C, &err)) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  const double t_refine = ss_time() - t1;
  if ((polish || polish_only) && ss_map_polish(&SX.ps.mesh, &SY.ps.mesh, map, NULL, map, &err)) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  const double t_polish = ss_time() - t1 - t_refine;
  if (cli_write_ints(outp, map, n, &err) || (fmapp && cli_write_npy(fmapp, C, kz, kz, &err))) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  cli_job_output(&J, outp, NULL), cli_job_extra(&J, fmapp);
  cli_job_int(&J, "vertices_x", SX.ps.mesh.nv), cli_job_int(&J, "vertices_y", SY.ps.mesh.nv);
  if (!polish_only) cli_job_int(&J, "k", o.fmap.k), cli_job_int(&J, "zoomout", kz);
  cli_job_int(&J, "polished", polish || polish_only);
  cli_job_num(&J, "t_prepare", t1 - t0), cli_job_num(&J, "t_refine", t_refine), cli_job_num(&J, "t_polish", t_polish);
  if (!json && polish_only)
    fprintf(report, "%d -> %d vertices, polished on the surfaces -> %s\n", SX.ps.mesh.nv, SY.ps.mesh.nv,
            cli_out_name(outp));
  else if (!json)
    fprintf(report, "%d -> %d vertices, refined: k %d%s%d%s -> %s\n", SX.ps.mesh.nv, SY.ps.mesh.nv, o.fmap.k,
            kz > o.fmap.k ? ", ZoomOut to " : ", no ZoomOut, k ", kz, polish ? ", polished on the surfaces" : "",
            cli_out_name(outp));
done:
  ss_shape_prep_free(&ownX), ss_shape_prep_free(&ownY);
  cli_shape_free(&SX), cli_shape_free(&SY);
  free(map), free(lines), free(C);
  return cli_job_end(&J, "refine", rc, json);
}
