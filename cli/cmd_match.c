/* specseg match X Y [--landmarks LM.txt] [--probes std|asa|diff] [--k K] [--zoomout KMAX] [--no-refine]
 *                   [--zoomout-step S] [--zoomout-samples N] [--descr-k K] -o MAP.txt [--fmap C.npy]
 *                   [--pairs PAIRS.txt] [--timings] */
#include "cli.h"
#include "cli_shape.h"
#include "specseg/match.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char USAGE[] =
    "usage: specseg match X Y [--landmarks LM.txt] -o MAP.txt [--probes std|asa|diff]\n"
    "                     [--segment-profile indicator|tent|soft] [--k K] [--zoomout KMAX] [--fmap C.npy]\n"
    "                     [--no-refine] [--zoomout-step S] [--zoomout-samples N] [--descr-k K] [--orient W]\n"
    "                     [--hypotheses N] [--flip-by x|y|both] [--final-zoomout KMAX] [--no-polish] [--no-recheck]\n"
    "                     [--scale-fit] [--skip-tol T] [--min-coverage C]\n"
    "                     [--one-way]\n"
    "                     [--pairs PAIRS.txt] [--descriptors DX.npy DY.npy [--no-wks]] [--timings] [--json]\n"
    "\n"
    "Point-to-point map X -> Y by functional maps (paper section 6) with corresponding landmarks and\n"
    "the paired coherent segments as extra probe functions. The output is refined: ZoomOut up to KMAX\n"
    "eigenfunctions (on vertex samples of X, then once on every vertex) from the STD map and from the\n"
    "segment-aided one, keeping the map of lowest unsupervised energy (orthonormality of its\n"
    "functional map + preservation of the descriptors).\n"
    "Without --landmarks the segments are paired automatically (as 'specseg pair' prints them: WKS at the\n"
    "centres, centre-to-centre geodesics, and the orientation for left / right, which needs both meshes\n"
    "consistently oriented); 4 distinct pairing hypotheses (the best, its mirror, the next ones) are each\n"
    "mapped with their paired protrusion centres as landmarks, and so is one more candidate whose\n"
    "landmarks are X's protrusion centres and their images under the descriptors' own functional map (no\n"
    "segments: it survives segmentations too different to pair). When no map keeps orientation clearly,\n"
    "or a map that reverses it has the lower energy (below), each map that reverses it is also flipped\n"
    "through X's own left-right symmetry, then Y's, into more candidates. The map that is closest to an\n"
    "orientation-preserving isometry is kept (metric distortion + share of segments whose orientation\n"
    "the map reverses + the refinement's own energy of the map + how far its orientation score falls\n"
    "short of clear; a map that reverses the orientation of the whole only when none keeps it); when\n"
    "another hypothesis maps almost as well, the map kept does not keep orientation clearly or its own\n"
    "energy is high, a 'note:' line says so (the map may be wrong; --json: confident,\n"
    "hypothesis_margin and each hypothesis's energies).\n"
    "With --landmarks, each hypothesis's landmark-free map is also a candidate beside the landmarks' own\n"
    "map, when it keeps at least three quarters of them (within 0.1 geodesic / sqrt(area)); a note names\n"
    "the landmarks the map kept departs from.\n"
    "Prints a summary line (on stderr when an output goes to standard output).\n"
    "\n"
    "  X, Y                mesh files (OFF, OBJ, PLY, STL, glTF, ...), or prepared shapes (specseg\n"
    "                      prepare, .sss: the same map, without preparing them again); one input may\n"
    "                      be - (standard input)\n"
    "  --landmarks FILE    one landmark a line: 'i' (same vertex index on both shapes) or 'i j' (i on X,\n"
    "                      j on Y); without it, landmark-free (see above)\n"
    "  -o, --output FILE   the map: line i = vertex of Y that is the image of vertex i of X (required)\n"
    "  --probes P          std: WKS + landmarks (NO17); asa: + segment indicators; diff: + wave-filtered\n"
    "                      segment indicators (default diff)\n"
    "  --segment-profile S the segments' probe functions: indicator, tent (1 - d/R from the centre;\n"
    "                      default) or soft (soft Voronoi membership; better than tent from k = 60 on)\n"
    "  --k K               basis size, 3..10000 (default 50)\n"
    "  --zoomout KMAX      refinement (ZoomOut) up to KMAX >= K eigenfunctions (default 110)\n"
    "  --no-refine         the unrefined map of --probes at size K (with the library's descriptors, pairing\n"
    "                      safeguards and orientation term; specseg eval computes the paper's variants)\n"
    "  --hypotheses N      without --landmarks: pairing hypotheses mapped, 1..16 (default 4; 1: the\n"
    "                      pairing's answer alone), from each direction\n"
    "  --one-way           without --landmarks: X's own hypotheses only, not also Y's pairing search against\n"
    "                      X read the other way (fewer candidates, less time)\n"
    "  --flip-by x|y|both  whose own left-right symmetry turns a mirrored hypothesis round (default\n"
    "                      both: X's, then Y's)\n"
    "  --final-zoomout KMAX the map kept among the hypotheses, once chosen, refined further by ZoomOut\n"
    "                      from --zoomout's size up to KMAX, 0..10000 (default 150; 0: not)\n"    "  --no-polish         the map kept among the hypotheses is not then fitted to the surfaces (by default\n"
    "                      X is deformed as rigidly as possible onto Y and each vertex sent to the nearest\n"
    "                      vertex of Y facing the same way: specseg refine --polish-only)\n"
    "  --no-recheck        without --landmarks, a choice in doubt (not confident) is not rechecked (by\n"
    "                      default the map kept and the candidates within 0.05 of its energy are polished\n"
    "                      and compared again by their polished maps' distortion; a note names a change)\n"
    "  --scale-fit         without --landmarks or beside them: the hypotheses' distortion compares distances\n"
    "                      up to one scale fitted per map, within 0.5..2, instead of over sqrt(area) as\n"
    "                      they are: for bodies of different build, whose distances differ by a common\n"
    "                      factor that can hide a swapped limb (off by default: on one body in different\n"
    "                      poses it can prefer a map that pulls distances together)\n"
    "  --skip-tol T        without --landmarks: a candidate whose landmarks an earlier candidate's map\n"
    "                      already sends within T sqrt(area) of their partners is not mapped, 0..10^6\n"
    "                      (default 0: every one is; 0.05: about 0.8x the time, its own energy lost, so\n"
    "                      the choice and the confidence may change; --json: skipped_by)\n"
    "  --min-coverage C    the map is not confident when its distinct images make up less than C of the\n"
    "                      smaller shape's vertices, 0..1 (default 0.65; 0: not used; --json: coverage)\n"
    "  --zoomout-step S    ZoomOut's size increment, 1..10000 (default 5)\n"
    "  --zoomout-samples N ZoomOut's iterations on N samples of X, 0..10^9 (default 1000; 0 or at least\n"
    "                      X's vertex count: on every vertex, ZoomOut's plain loop)\n"
    "  --descr-k K         eigenpairs the descriptors are computed from (default 100; = K for the\n"
    "                      paper's construction)\n"
    "  --orient W          weight of the orientation-preserving term (Ren et al. 2018: the WKS probes'\n"
    "                      orientation operators, each mesh taken wound outward) (default 0.001; 0: the\n"
    "                      paper's Eq. (1) without it)\n"
    "  --fmap FILE         the functional map (functions on Y -> functions on X, K x K, in the bases of\n"
    "                      both shapes scaled to unit area) as .npy\n"
    "  --pairs FILE        the paired segment centres, 'x y' (input vertices) a line (with std: the\n"
    "                      segments are then computed and paired, though its map does not use them)\n"
    "  --descriptors DX.npy DY.npy\n"
    "                      your own per-vertex descriptors as extra probes: (vertices of X) x d and\n"
    "                      (vertices of Y) x d float64 arrays, column j of one corresponding to column j\n"
    "                      of the other (e.g. 'specseg descriptors --wks/--hks', or any features); used\n"
    "                      as they are (not sub-sampled), each normalised in L2, in the data and the\n"
    "                      commutativity terms beside the WKS and the landmarks\n"
    "  --no-wks            without the WKS: the descriptors given replace it\n"
    "  --timings           'timing: STAGE SECONDS' lines on stderr (segment, eigs: both shapes' added\n"
    "                      up, prepared side by side on two threads; total: the wall time)\n"
    "  --json              a JSON summary on standard output instead of the summary line (counts,\n"
    "                      timings, warnings, errors, output paths)\n"
    "One of the output files may be - (standard output).\n";

/* the hypotheses of a landmark-free match as a JSON array (non-finite numbers as null) */
static const char *hypotheses_json(const ss_autopair_info *a, char *buf, size_t size) {
  size_t n = 0;
  n += (size_t)snprintf(buf + n, size - n, "[");
  for (int h = 0; h < a->hypotheses && h < SS_MAX_HYPOTHESES && n < size; h++) {
    const double v[9] = {a->hyp_energy[h],       a->hyp_distortion[h],      a->hyp_reversed[h],
                         a->hyp_orientation[h],  a->hyp_orientation_min[h], a->hyp_pair_energy[h],
                         a->hyp_map_energy[h],   a->hyp_differ[h],          a->hyp_scale[h]};
    static const char *const key[9] = {"energy",      "distortion", "reversed", "orientation", "orientation_min",
                                       "pair_energy", "map_energy", "differ",   "scale"};
    n += (size_t)snprintf(buf + n, size - n, "%s{", h ? ", " : "");
    for (int k = 0; k < 9 && n < size; k++) {
      if (isfinite(v[k])) n += (size_t)snprintf(buf + n, size - n, "%s\"%s\": %.17g", k ? ", " : "", key[k], v[k]);
      else n += (size_t)snprintf(buf + n, size - n, "%s\"%s\": null", k ? ", " : "", key[k]);
    }
    if (n < size && a->hyp_from_y[h]) n += (size_t)snprintf(buf + n, size - n, ", \"from\": \"Y\"");
    if (n < size && a->hyp_skipped_by[h] >= 0)
      n += (size_t)snprintf(buf + n, size - n, ", \"skipped_by\": %d", a->hyp_skipped_by[h]);
    if (n < size && a->hyp_flip_of[h] >= 0)
      n += (size_t)snprintf(buf + n, size - n, ", \"flip_of\": %d, \"flip_by\": \"%s\"", a->hyp_flip_of[h],
                            a->hyp_flip_by_y[h] ? "Y" : "X");
    if (n < size) n += (size_t)snprintf(buf + n, size - n, "}");
  }
  if (n < size) snprintf(buf + n, size - n, "]");
  return buf;
}

int cmd_match(int argc, char **argv) {
  const char *xp = NULL, *yp = NULL, *lmp = NULL, *outp = NULL, *fmapp = NULL, *pairsp = NULL, *dxp = NULL, *dyp = NULL;
  int timings = 0, json = 0, no_recheck = 0;
  ss_match_options o;
  ss_match_default_options(&o);
  o.probes = SS_PROBES_DIFF;
  static const int PROBES[] = {SS_PROBES_STD, SS_PROBES_ASA, SS_PROBES_DIFF}, FLIP_SIDES[] = {0, 1, 2};
  static const int PROFILE[] = {SS_PROFILE_INDICATOR, SS_PROFILE_TENT, SS_PROFILE_SOFT};
  const cli_opt opts[] = {
      CLI_OPT_POS("X", &xp, NULL),
      CLI_OPT_POS("Y", &yp, NULL),
      CLI_OPT_STR("--landmarks", &lmp),
      CLI_OPT_STR("-o|--output", &outp),
      CLI_OPT_STR("--fmap", &fmapp),
      CLI_OPT_STR("--pairs", &pairsp),
      CLI_OPT_CHOICE("--probes", CLI_ENUM(&o.probes), "std|asa|diff", PROBES, "--probes takes std, asa or diff, not '%s'"),
      CLI_OPT_CHOICE("--segment-profile", CLI_ENUM(&o.segment_profile), "indicator|tent|soft", PROFILE,
                     "--segment-profile takes indicator, tent or soft, not '%s'"),
      CLI_OPT_INT("--k", &o.fmap.k, 3, 10000, NULL),
      CLI_OPT_INT("--zoomout", &o.fmap.zoomout_kmax, 3, 10000, NULL),
      CLI_OPT_FLAG("--no-refine", CLI_ENUM(&o.refine), SS_REFINE_NONE),
      CLI_OPT_INT("--descr-k", &o.fmap.descr_k, 3, 10000, NULL),
      CLI_OPT_INT("--zoomout-step", &o.fmap.zoomout_step, 1, 10000, NULL),
      CLI_OPT_INT("--zoomout-samples", &o.fmap.zoomout_samples, 0, 1000000000, NULL),
      CLI_OPT_DOUBLE("--orient", &o.fmap.w_orient, 0, 1e6, 0, "--orient needs a weight between 0 and 1e6, not '%s'"),
      CLI_OPT_FLAG("--timings", &timings, 1),
      CLI_OPT_STR2("--descriptors", &dxp, &dyp),
      CLI_OPT_FLAG("--no-wks", &o.fmap.no_wks, 1),
      CLI_OPT_FLAG("--json", &json, 1),
      CLI_OPT_FLAG("--one-way", &o.autopair.hyp_reverse, 0),
      CLI_OPT_INT("--hypotheses", &o.autopair.hypotheses, 1, SS_MAX_HYPOTHESES, NULL),
      CLI_OPT_INT("--final-zoomout", &o.autopair.hyp_final_kmax, 0, 10000, NULL),
      CLI_OPT_FLAG("--no-polish", &o.autopair.hyp_final_polish, 0),
      CLI_OPT_FLAG("--no-recheck", &no_recheck, 1),
      CLI_OPT_FLAG("--scale-fit", &o.autopair.hyp_fit_scale, 1),
      CLI_OPT_DOUBLE("--skip-tol", &o.autopair.hyp_skip_tol, 0, 1e6, 0, "--skip-tol needs a value between 0 and 1e6, not '%s'"),
      CLI_OPT_DOUBLE("--min-coverage", &o.autopair.hyp_min_coverage, 0, 1, 0, "--min-coverage needs a value between 0 and 1, not '%s'"),
      CLI_OPT_CHOICE("--flip-by", &o.autopair.hyp_flip_side, "x|y|both", FLIP_SIDES,
                     "--flip-by takes x, y or both, not '%s'"),
      CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, opts);
  int rc = cli_parse(&A);
  if (rc >= 0) return rc;
  if (!xp || !yp) return cli_bad(&A, "needs two meshes X and Y");
  if (!outp) return cli_bad(&A, "missing -o MAP.txt");
  if (o.fmap.zoomout_kmax && o.fmap.zoomout_kmax < o.fmap.k)
    return cli_bad(&A, "--zoomout %d is below --k %d", o.fmap.zoomout_kmax, o.fmap.k);
  if (o.fmap.descr_k < o.fmap.k) o.fmap.descr_k = o.fmap.k; /* a larger --k takes the descriptors along */
  if (o.fmap.no_wks && !dxp) return cli_bad(&A, "--no-wks needs --descriptors DX.npy DY.npy (they replace the WKS)");
  if (no_recheck) o.autopair.hyp_recheck_window = 0;
  o.std_pairs = pairsp != NULL; /* the pairs file is written for every probe set */
  const char *ins[5] = {xp, yp, lmp ? lmp : "", dxp ? dxp : "", dyp ? dyp : ""}, *outs[3] = {outp, fmapp, pairsp};
  if (cli_count_std(ins, 5) > 1) return cli_bad(&A, "only one input can come from standard input ('-')");
  if (cli_check_outputs(&A, outs, 3, ins, 5) >= 0) return A.rc;
  int to_stdout = cli_count_std(outs, 3);
  if (to_stdout > 1) return cli_bad(&A, "only one output can go to standard output ('-')");
  if (to_stdout && json) return cli_bad(&A, "--json and an output to '-' both want standard output");
  FILE *report = to_stdout ? stderr : stdout;
  const char *xn = cli_in_name(xp), *yn = cli_in_name(yp), *lmn = lmp ? cli_in_name(lmp) : "";
  cli_job J;
  cli_job_begin(&J, NULL);
  cli_job_str(&J, "x", xn);
  cli_job_str(&J, "y", yn);
  if (lmp) cli_job_str(&J, "landmarks_file", lmn);

  ss_error err = {{0}};
  cli_shape SX = {0}, SY = {0}; /* a mesh, or a prepared shape (then matched as such) */
  const ss_mesh *const X = &SX.ps.mesh, *const Y = &SY.ps.mesh;
  ss_match_result res = {0};
  int *lx = NULL, *ly = NULL, *lline = NULL, nl = 0;
  rc = SS_EXIT_OK;
  double *DX = NULL, *DY = NULL;
  double t0 = ss_time();
  /* LM.txt: "i" or "i j" lines; their line numbers for the range checks below */
  if (lmp && cli_read_landmarks(lmp, &lx, &ly, &lline, &nl, NULL, &err))
    return cli_job_end(&J, "match", cli_error("%s", err.msg), json);
  if (cli_read_shape(xp, &SX, &err) || cli_read_shape(yp, &SY, &err)) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  double t_read = ss_time() - t0;
  for (int i = 0; i < nl; i++) { /* clear messages before the expensive part */
    if (lx[i] >= X->nv) {
      rc = cli_error("%s:%d: landmark vertex %d not on X (%s has %d vertices)", lmn, lline[i], lx[i], xn, X->nv);
      goto done;
    }
    if (ly[i] >= Y->nv) {
      rc = cli_error("%s:%d: landmark vertex %d not on Y (%s has %d vertices)", lmn, lline[i], ly[i], yn, Y->nv);
      goto done;
    }
  }
  { /* too many, a vertex with two partners (both lines named), an exact repeat (said) */
    int la, lb;
    if (ss_landmarks_check(nl, lx, ly, &la, &lb, &err)) {
      if (la < 0) rc = cli_error("%s: %s", lmn, err.msg + (strncmp(err.msg, "match: ", 7) ? 0 : 7));
      else {
        const int on_y = lx[la] != lx[lb]; /* the shared vertex is on Y */
        rc = cli_error("%s:%d and %s:%d: vertex %d of %s has two partners on %s (%d and %d)", lmn, lline[la], lmn,
                       lline[lb], on_y ? ly[la] : lx[la], on_y ? "Y" : "X", on_y ? "X" : "Y", on_y ? lx[la] : ly[la],
                       on_y ? lx[lb] : ly[lb]);
      }
      goto done;
    }
    if (la >= 0) cli_warn("%s:%d repeats %s:%d (the same landmark twice)", lmn, lline[lb], lmn, lline[la]);
  }
  if (dxp) { /* (nX x d) and (nY x d), corresponding columns */
    int rx, cx, ry, cy;
    if (cli_read_matrix(dxp, &DX, &rx, &cx, &err) || cli_read_matrix(dyp, &DY, &ry, &cy, &err)) {
      rc = cli_error("%s", err.msg);
      goto done;
    }
    if (rx != X->nv || ry != Y->nv) {
      rc = cli_error("%s: %d rows, but %s has %d vertices", cli_in_name(rx != X->nv ? dxp : dyp), rx != X->nv ? rx : ry,
                     rx != X->nv ? xn : yn, rx != X->nv ? X->nv : Y->nv);
      goto done;
    }
    if (cx != cy) {
      rc = cli_error("--descriptors: %s has %d columns, %s %d (they must correspond)", cli_in_name(dxp), cx, cli_in_name(dyp), cy);
      goto done;
    }
    o.ndescr = cx, o.descrX = DX, o.descrY = DY;
  }
  /* what the pipeline repairs internally (a prepared shape's were said by specseg prepare); STD with
   * landmarks segments nothing */
  const int segmented = ss_match_segments(&o, nl);
  if (!SX.prepared) cli_warn_repairs(X, xn, segmented, segmented && !o.seg.no_streamline, nl == 0);
  if (!SY.prepared) cli_warn_repairs(Y, yn, segmented, segmented && !o.seg.no_streamline, nl == 0);
  char dropped[1024];
  if (SX.prepared || SY.prepared ? cli_match_shapes(&SX, &SY, nl, lx, ly, &o, &res, dropped, sizeof dropped, &err)
                                 : ss_match_warn(X, Y, nl, lx, ly, &o, &res, dropped, sizeof dropped, &err)) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  if (dropped[0]) cli_warn("%s -> %s: %s", xn, yn, dropped); /* components without landmarks */
  double t1 = ss_time();
  if (cli_write_ints(outp, res.map, res.nX, &err) ||
      (fmapp && cli_write_npy(fmapp, res.C, res.kc, res.kc, &err))) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  if (pairsp) {
    FILE *f = cli_open_out(pairsp);
    if (!f) {
      rc = cli_error("%s: %s", pairsp, strerror(errno));
      goto done;
    }
    for (int p = 0; p < res.pairs.n; p++) fprintf(f, "%d %d\n", res.centerX[p], res.centerY[p]);
    if (cli_close_out(f)) {
      rc = cli_error("%s: write error", cli_out_name(pairsp));
      goto done;
    }
  }
  double t_write = ss_time() - t1;
  if (timings) {
    fprintf(stderr, "timing: read %.6f\n", t_read);
    fprintf(stderr, "timing: segment %.6f\n", res.t_segment);
    fprintf(stderr, "timing: eigs %.6f\n", res.t_eigs);
    fprintf(stderr, "timing: pair %.6f\n", res.t_pair);
    fprintf(stderr, "timing: fmap %.6f\n", res.t_fmap);
    fprintf(stderr, "timing: zoomout %.6f\n", res.t_zoomout);
    fprintf(stderr, "timing: write %.6f\n", t_write);
    fprintf(stderr, "timing: total %.6f\n", ss_time() - t0);
  }
  char dnote[64] = "";
  if (o.ndescr) snprintf(dnote, sizeof dnote, ", %d own descriptors%s", o.ndescr, o.fmap.no_wks ? " (no WKS)" : "");
  const char *pn = o.probes == SS_PROBES_STD ? "std" : o.probes == SS_PROBES_ASA ? "asa" : "diff";
  const int std_only = !ss_match_segments(&o, nl); /* nothing segmented */
  static const char *choice[4] = {"STD", "STD + ZoomOut", "segment-aided", "segment-aided + ZoomOut"};
  if (res.autopair.used && !json)
    fprintf(report, "landmark-free pairing (%s search): energy %.4g, mirror candidate %.4g, next other %.4g (gap %.3f), "
            "orientation %.3f vs mirror %.3f%s\n", res.autopair.exact ? "exact" : "relaxed", res.autopair.energy,
            res.autopair.energy_mirror, res.autopair.energy_other, res.autopair.gap, res.autopair.mirror,
            res.autopair.mirror_other, res.autopair.pairing_confident ? ", confident" : ", NOT confident");
  if (!json && res.autopair.hypotheses > 1) {
    const ss_autopair_info *a = &res.autopair;
    const int h = a->hypothesis;
    char what[64] = "";
    if (h == a->hyp_descriptor) snprintf(what, sizeof what, " (the descriptors' own)");
    else if (a->hyp_flip_of[h] >= 0)
      snprintf(what, sizeof what, " (the flip of #%d by %s's symmetry)", a->hyp_flip_of[h], a->hyp_flip_by_y[h] ? "Y" : "X");
    else if (a->hyp_from_y[h]) snprintf(what, sizeof what, " (from Y's side)");
    int skipped = 0;
    for (int c = 0; c < a->hypotheses && c < SS_MAX_HYPOTHESES; c++) skipped += a->hyp_skipped_by[c] >= 0;
    char skip[64] = ""; /* candidates whose landmarks an earlier map already kept (hyp_skip_tol) */
    if (skipped) snprintf(skip, sizeof skip, " (%d more skipped)", skipped);
    fprintf(report, "hypotheses: %d mapped%s, #%d%s kept (energy %.4g: distortion %.4g, %.0f%% of the segments "
            "reversed, map energy %.4g, orientation %.3f; margin %.3g)%s\n", a->hypotheses - skipped, skip, h, what,
            a->hyp_energy[h],
            a->hyp_distortion[h], 100 * a->hyp_reversed[h], a->hyp_map_energy[h], a->hyp_orientation[h], a->hyp_margin,
            a->confident ? ", confident" : ", NOT confident");
  }
  const char *refined = res.refine_choice >= 0 ? choice[res.refine_choice] : o.refine == SS_REFINE_ZOOMOUT ? "ZoomOut" : "";
  const int kz = o.refine != SS_REFINE_NONE && o.fmap.zoomout_kmax > o.fmap.k ? o.fmap.zoomout_kmax : 0;
  cli_job_output(&J, outp, NULL), cli_job_extra(&J, fmapp), cli_job_extra(&J, pairsp);
  cli_job_int(&J, "vertices_x", X->nv), cli_job_int(&J, "vertices_y", Y->nv), cli_job_int(&J, "landmarks", res.autopair.used ? res.autopair.hyp_landmarks : nl);
  cli_job_int(&J, "landmark_free", res.autopair.used);
  char hbuf[SS_MAX_HYPOTHESES * 512]; /* 9 keys of up to ~45 characters, the flip and side keys */
  if (res.autopair.used || res.autopair.hypotheses > 1) { /* landmark-free, or hypotheses beside landmarks */
    cli_job_int(&J, "confident", res.autopair.confident);
    if (res.autopair.used) cli_job_int(&J, "pairing_confident", res.autopair.pairing_confident);
    if (res.autopair.hypotheses > 1) cli_job_num(&J, "hypothesis_margin", res.autopair.hyp_margin);
    cli_job_num(&J, "coverage", res.autopair.coverage);
    cli_job_int(&J, "hypothesis", res.autopair.hypothesis);
    cli_job_int(&J, "descriptor_candidate", res.autopair.hyp_descriptor);
    cli_job_json(&J, "hypotheses", hypotheses_json(&res.autopair, hbuf, sizeof hbuf));
  }
  cli_job_int(&J, "segments_x", res.pairs.nx), cli_job_int(&J, "segments_y", res.pairs.ny);
  cli_job_int(&J, "paired", res.pairs.n), cli_job_str(&J, "probes", pn), cli_job_int(&J, "k", o.fmap.k);
  cli_job_int(&J, "zoomout", kz);
  if (res.autopair.used) cli_job_int(&J, "final_zoomout", res.autopair.hyp_final_k);
  cli_job_int(&J, "polished", res.autopair.hyp_final_polished);
  if (res.autopair.used) {
    cli_job_int(&J, "rechecked", res.autopair.hyp_rechecked);
    cli_job_int(&J, "recheck_from", res.autopair.hyp_recheck_from);
  }
  if (o.refine != SS_REFINE_NONE) cli_job_str(&J, "refined", refined);
  if (res.notes[0]) cli_job_str(&J, "notes", res.notes);
  cli_job_int(&J, "descriptors", o.ndescr), cli_job_int(&J, "wks", !o.fmap.no_wks);
  cli_job_num(&J, "t_read", t_read), cli_job_num(&J, "t_segment", res.t_segment), cli_job_num(&J, "t_eigs", res.t_eigs);
  cli_job_num(&J, "t_pair", res.t_pair), cli_job_num(&J, "t_fmap", res.t_fmap), cli_job_num(&J, "t_zoomout", res.t_zoomout);
  cli_job_num(&J, "t_write", t_write);
  if (!json) {
    char segs[64] = "no segments (std)";
    if (!std_only)
      snprintf(segs, sizeof segs, "%d of %d/%d segments paired", res.pairs.n, res.pairs.nx, res.pairs.ny);
    fprintf(report, "%d -> %d vertices, %d landmarks%s, %s, probes %s, k %d%s%s%s%s -> %s\n", X->nv, Y->nv,
            res.autopair.used ? res.autopair.hyp_landmarks : nl,
            res.autopair.used ? " (paired protrusion centres)" : "", segs, pn, o.fmap.k,
            o.refine == SS_REFINE_NONE ? "" : ", refined: ", refined, res.autopair.hyp_final_polished ? ", polished" : "",
            dnote, cli_out_name(outp));
    if (res.notes[0]) fprintf(report, "note: %s\n", res.notes);
  }
done:
  ss_match_result_free(&res);
  cli_shape_free(&SX);
  cli_shape_free(&SY);
  free(lx);
  free(ly);
  free(lline);
  free(DX);
  free(DY);
  return cli_job_end(&J, "match", rc, json);
}
