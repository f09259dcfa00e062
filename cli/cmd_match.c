/* specseg match X Y --landmarks LM.txt [--probes std|asa|diff] [--k K] [--zoomout KMAX] [--no-refine]
 *                   [--descr-k K] -o MAP.txt [--fmap C.npy] [--pairs PAIRS.txt] [--timings] */
#include "cli.h"
#include "specseg/match.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *USAGE = "specseg match X Y --landmarks LM.txt [--probes std|asa|diff] "
                           "[--segment-profile indicator|tent|soft] [--k K] [--zoomout KMAX] [--no-refine] [--descr-k K] -o MAP.txt [--fmap C.npy] [--pairs PAIRS.txt] [--timings]";

int cmd_match(int argc, char **argv) {
  const char *xp = NULL, *yp = NULL, *lmp = NULL, *outp = NULL, *fmapp = NULL, *pairsp = NULL;
  int timings = 0;
  ss_match_options o;
  ss_match_default_options(&o);
  o.probes = SS_PROBES_DIFF;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    int has_next = i + 1 < argc;
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
      printf("usage: %s\n\n"
             "Point-to-point map X -> Y by functional maps (paper §6) with corresponding landmarks and the\n"
             "paired coherent segments as extra probe functions. LM.txt: one landmark a line, 'i' (same\n"
             "vertex index on both shapes) or 'i j' (i on X, j on Y). --probes: std (WKS + landmarks,\n"
             "NO17), asa (+ segment indicators), diff (+ wave-filtered segment indicators; default).\n"
             "--segment-profile: the segments' probe functions, indicator, tent (1 - d/R from the centre;\n"
             "default) or soft (soft Voronoi membership; better than tent from k = 60 on).\n"
             "--k: basis size (default 50). The output is refined: ZoomOut up to KMAX eigenfunctions (--zoomout,\n"
             "default 120) from the STD map and from the segment-aided one, keeping the map of lowest\n"
             "unsupervised energy (orthonormality of its functional map + preservation of the descriptors).\n"
             "--no-refine: the unrefined map of\n"
             "--probes at size k (the paper's variants). --descr-k: eigenpairs the descriptors are computed\n"
             "from (default 100; = k for the paper's construction).\n"
             "MAP.txt: line i = vertex of Y that is the image of vertex i of X. --fmap: the functional map\n"
             "(functions on Y -> functions on X, k x k) as .npy. --pairs: the paired segment centres, 'x y'\n"
             "(input vertices) per line. --timings: 'timing: STAGE SECONDS' lines on stderr.\n",
             USAGE);
      return SS_EXIT_OK;
    }
    if (!strcmp(a, "--landmarks") || !strcmp(a, "-o") || !strcmp(a, "--output") || !strcmp(a, "--fmap") ||
        !strcmp(a, "--pairs")) {
      if (!has_next) return cli_usage("%s: %s needs a file", USAGE, a);
      const char *v = argv[++i];
      if (!strcmp(a, "--landmarks")) lmp = v;
      else if (!strcmp(a, "--fmap")) fmapp = v;
      else if (!strcmp(a, "--pairs")) pairsp = v;
      else outp = v;
    } else if (!strcmp(a, "--probes")) {
      const char *v = has_next ? argv[++i] : "";
      if (!strcmp(v, "std")) o.probes = SS_PROBES_STD;
      else if (!strcmp(v, "asa")) o.probes = SS_PROBES_ASA;
      else if (!strcmp(v, "diff")) o.probes = SS_PROBES_DIFF;
      else return cli_usage("%s: --probes takes std, asa or diff", USAGE);
    } else if (!strcmp(a, "--segment-profile")) {
      const char *v = has_next ? argv[++i] : "";
      if (!strcmp(v, "indicator")) o.segment_profile = SS_PROFILE_INDICATOR;
      else if (!strcmp(v, "tent")) o.segment_profile = SS_PROFILE_TENT;
      else if (!strcmp(v, "soft")) o.segment_profile = SS_PROFILE_SOFT;
      else return cli_usage("%s: --segment-profile takes indicator, tent or soft", USAGE);
    } else if (!strcmp(a, "--k")) {
      if (!has_next || cli_parse_int(argv[++i], 3, 10000, &o.fmap.k))
        return cli_usage("%s: --k needs an integer between 3 and 10000", USAGE);
    } else if (!strcmp(a, "--zoomout")) {
      if (!has_next || cli_parse_int(argv[++i], 3, 10000, &o.fmap.zoomout_kmax))
        return cli_usage("%s: --zoomout needs an integer between 3 and 10000", USAGE);
    } else if (!strcmp(a, "--no-refine")) {
      o.refine = SS_REFINE_NONE;
    } else if (!strcmp(a, "--descr-k")) {
      if (!has_next || cli_parse_int(argv[++i], 3, 10000, &o.fmap.descr_k))
        return cli_usage("%s: --descr-k needs an integer between 3 and 10000", USAGE);
    } else if (!strcmp(a, "--timings")) {
      timings = 1;
    } else if (a[0] == '-' && a[1]) {
      return cli_usage("%s: unknown option '%s'", USAGE, a);
    } else if (!xp) {
      xp = a;
    } else if (!yp) {
      yp = a;
    } else {
      return cli_usage("%s: unexpected argument '%s'", USAGE, a);
    }
  }
  if (!xp || !yp) return cli_usage("%s: needs two meshes X and Y", USAGE);
  if (!lmp) return cli_usage("%s: missing --landmarks LM.txt", USAGE);
  if (!outp) return cli_usage("%s: missing -o MAP.txt", USAGE);
  if (o.fmap.zoomout_kmax && o.fmap.zoomout_kmax < o.fmap.k)
    return cli_usage("%s: --zoomout %d is below --k %d", USAGE, o.fmap.zoomout_kmax, o.fmap.k);
  if (o.fmap.descr_k < o.fmap.k) o.fmap.descr_k = o.fmap.k; /* a larger --k takes the descriptors along */

  ss_error err = {{0}};
  ss_mesh X = {0}, Y = {0};
  ss_match_result res = {0};
  int *lx = NULL, *ly = NULL, *lline = NULL, nl = 0, rc = SS_EXIT_OK;
  double t0 = ss_time();
  /* LM.txt: "i" or "i j" lines; their line numbers for the range checks below */
  if (ss_read_landmarks_lines(lmp, &lx, &ly, &lline, &nl, NULL, &err)) return cli_error("%s", err.msg);
  if (ss_read_mesh(xp, &X, &err) || ss_read_mesh(yp, &Y, &err)) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  double t_read = ss_time() - t0;
  for (int i = 0; i < nl; i++) { /* clear messages before the expensive part */
    if (lx[i] >= X.nv) {
      rc = cli_error("%s:%d: landmark vertex %d not on X (%s has %d vertices)", lmp, lline[i], lx[i], xp, X.nv);
      goto done;
    }
    if (ly[i] >= Y.nv) {
      rc = cli_error("%s:%d: landmark vertex %d not on Y (%s has %d vertices)", lmp, lline[i], ly[i], yp, Y.nv);
      goto done;
    }
  }
  if (ss_match(&X, &Y, nl, lx, ly, &o, &res, &err)) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  double t1 = ss_time();
  if (ss_write_ints(outp, res.map, res.nX, &err) ||
      (fmapp && ss_write_npy(fmapp, res.C, res.kc, res.kc, &err))) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  if (pairsp) {
    FILE *f = fopen(pairsp, "w");
    if (!f) {
      rc = cli_error("%s: %s", pairsp, strerror(errno));
      goto done;
    }
    for (int p = 0; p < res.pairs.n; p++) fprintf(f, "%d %d\n", res.centerX[p], res.centerY[p]);
    if (fclose(f)) {
      rc = cli_error("%s: write error", pairsp);
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
  static const char *choice[4] = {"STD", "STD + ZoomOut", "segment-aided", "segment-aided + ZoomOut"};
  printf("%d -> %d vertices, %d landmarks, %d of %d/%d segments paired, probes %s, k %d%s%s -> %s\n", X.nv, Y.nv, nl,
         res.pairs.n, res.pairs.nx, res.pairs.ny,
         o.probes == SS_PROBES_STD ? "std" : o.probes == SS_PROBES_ASA ? "asa" : "diff", o.fmap.k,
         o.refine == SS_REFINE_NONE ? "" : ", refined: ",
         res.refine_choice >= 0 ? choice[res.refine_choice] : o.refine == SS_REFINE_ZOOMOUT ? "ZoomOut" : "", outp);
  if (res.notes[0]) printf("note: %s\n", res.notes);
done:
  ss_match_result_free(&res);
  ss_mesh_free(&X);
  ss_mesh_free(&Y);
  free(lx);
  free(ly);
  free(lline);
  return rc;
}
