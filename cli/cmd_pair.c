/* specseg pair X Y [-o PAIRS.txt] [--timings]: the landmark-free pairing of the segments. */
#include "cli.h"
#include "specseg/match.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char USAGE[] =
    "usage: specseg pair X Y [-o PAIRS.txt] [--timings]\n"
    "\n"
    "Pairs the coherent segments of X and Y without landmarks and prints the pairing with per-pair\n"
    "scores and its confidence (what 'specseg match X Y' without --landmarks uses). The segments are\n"
    "paired intrinsically (WKS at the segment centres, centre-to-centre exact geodesic distances; exact\n"
    "search up to 10 centres), then left and right are told apart by the orientation of the maps of the\n"
    "two mirror candidates (segment by segment: the median segment decides), which needs consistently\n"
    "oriented meshes (faces wound inconsistently are taken in their component's majority orientation;\n"
    "an open surface of ~zero volume is warned about). A pairing below the confidence thresholds says\n"
    "so ('NOT confident'): give landmarks then.\n"
    "\n"
    "  X, Y                OFF, OBJ or PLY files; one of the inputs may be - (standard input)\n"
    "  -o, --output FILE   the paired centres, 'x y' (input vertices of X and Y) a line: a landmark file\n"
    "                      for 'specseg match --landmarks'\n"
    "  --timings           'timing: STAGE SECONDS' lines on stderr (pairing: CPU seconds)\n"
    "One output may be - (standard output); the report then goes to stderr.\n";

int cmd_pair(int argc, char **argv) {
  const char *xp = NULL, *yp = NULL, *outp = NULL;
  int timings = 0;
  const cli_opt opts[] = {CLI_OPT_POS("X", &xp, NULL), CLI_OPT_POS("Y", &yp, NULL), CLI_OPT_STR("-o|--output", &outp),
                          CLI_OPT_FLAG("--timings", &timings, 1), CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, opts);
  int rc = cli_parse(&A);
  if (rc >= 0) return rc;
  if (!xp || !yp) return cli_bad(&A, "needs two meshes X and Y");
  const char *ins[2] = {xp, yp};
  if (cli_count_std(ins, 2) > 1) return cli_bad(&A, "only one input can come from standard input ('-')");
  const char *outs[1] = {outp};
  if (cli_check_outputs(&A, outs, 1, ins, 2) >= 0) return A.rc;
  FILE *report = outp && cli_is_std(outp) ? stderr : stdout;
  const char *xn = cli_in_name(xp), *yn = cli_in_name(yp);

  ss_error err = {{0}};
  ss_mesh X = {0}, Y = {0};
  ss_shape_prep pX = {0}, pY = {0};
  ss_centre_signature sX = {0}, sY = {0};
  ss_segment_pairs pr = {0};
  ss_autopair_info info;
  ss_match_options mo;
  ss_match_default_options(&mo);
  rc = SS_EXIT_OK;
  double t0 = ss_time();
  if (cli_read_mesh(xp, &X, &err) || cli_read_mesh(yp, &Y, &err)) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  for (int s = 0; s < 2; s++) {
    ss_mesh_report rep;
    if (!ss_mesh_check(s ? &Y : &X, &rep, NULL) && !rep.oriented && rep.orientable)
      cli_warn("%s: faces not consistently oriented (%d reversed internally: the left / right decision takes each "
               "component's majority orientation as outward-consistent)",
               s ? yn : xn, rep.reorient_faces);

  }
  double t1 = ss_time();
  int kev = mo.autopair.descr_k > mo.autopair.orient_k ? mo.autopair.descr_k : mo.autopair.orient_k;
  if (kev >= X.nv || kev >= Y.nv) kev = (X.nv < Y.nv ? X.nv : Y.nv) - 1;
  if (ss_shape_prep_compute(&X, &mo.seg, kev, &pX, &err) || ss_shape_prep_compute(&Y, &mo.seg, kev, &pY, &err)) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  double t2 = ss_time();
  if (ss_centre_signature_compute(&pX, &mo.autopair, &sX, &err) || ss_centre_signature_compute(&pY, &mo.autopair, &sY, &err)) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  double t3 = ss_time();
  if (ss_pair_centres_auto(&sX, &sY, &mo.autopair, &pr, &info, &err)) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  double t4 = ss_time();
  for (int s = 0; s < 2; s++) {
    double vr = (s ? &sY : &sX)->volume_ratio;
    if (vr > -1e-3 && vr < 1e-3)
      cli_warn("%s: signed volume ~0 (%.2g of area^1.5): an open surface whose outward side is unknown; the left / "
               "right decision is not reliable",
               s ? yn : xn, vr);
  }
  if (outp) {
    FILE *f = cli_open_out(outp);
    if (!f) {
      rc = cli_error("%s: %s", outp, strerror(errno));
      goto done;
    }
    for (int p = 0; p < pr.n; p++) fprintf(f, "%d %d\n", pX.seg.centers[pr.sx[p]], pY.seg.centers[pr.sy[p]]);
    if (cli_close_out(f)) {
      rc = cli_error("%s: write error", cli_out_name(outp));
      goto done;
    }
  }
  fprintf(report, "%s: %d segments, %s: %d segments, %d paired (%s search)\n", xn, pr.nx, yn, pr.ny, pr.n,
          info.exact ? "exact" : "relaxed");
  fprintf(report, "%5s %5s %5s %9s %9s %10s\n", "pair", "seg_x", "seg_y", "centre_x", "centre_y", "energy");
  for (int p = 0; p < pr.n; p++)
    fprintf(report, "%5d %5d %5d %9d %9d %10.3g\n", p, pr.sx[p], pr.sy[p], pX.seg.centers[pr.sx[p]],
            pY.seg.centers[pr.sy[p]], pr.energy[p]);
  fprintf(report, "energy %.4g, mirror candidate %.4g, best other pairing %.4g: gap %.3f (min %.3f)\n", info.energy,
          info.energy_mirror, info.energy_other, info.gap, mo.autopair.min_gap);
  fprintf(report, "orientation score %.3f, mirror candidate %.3f; median segment margin %.3f (min %.3f)\n", info.mirror,
          info.mirror_other, info.mirror_margin, mo.autopair.min_mirror);
  if (info.polished > 0)
    fprintf(report, "oriented polish: %d move%s lowered the energy (orientation score kept within %.2g)\n", info.polished,
            info.polished > 1 ? "s" : "", mo.autopair.polish_orient_tol);
  if (info.alternatives > 0)
    fprintf(report, "near-tie pairings tested: %d%s\n", info.alternatives,
            info.alternative ? "; one replaced the search's best (its map preserves orientation clearly better)" : "");
  fprintf(report, "%s\n", info.confident ? "confident" : "NOT confident: a segment pair or left / right may be wrong");
  if (timings) {
    fprintf(stderr, "timing: read %.6f\n", t1 - t0);
    fprintf(stderr, "timing: prepare %.6f\n", t2 - t1);
    fprintf(stderr, "timing: signatures %.6f\n", t3 - t2);
    fprintf(stderr, "timing: pair %.6f\n", t4 - t3);
    fprintf(stderr, "timing: pair_cpu %.6f\n", info.cpu);
  }
done:
  ss_segment_pairs_free(&pr);
  ss_centre_signature_free(&sX);
  ss_centre_signature_free(&sY);
  ss_shape_prep_free(&pX);
  ss_shape_prep_free(&pY);
  ss_mesh_free(&X);
  ss_mesh_free(&Y);
  return rc;
}
