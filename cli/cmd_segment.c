/* specseg segment MESH -o LABELS.txt [--centers CENTERS.txt] [--ply OUT.ply] [--faces N]
 *                 [--no-streamline] [--timings] */
#include "cli.h"
#include "specseg/render.h"
#include "specseg/segment.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *USAGE =
    "specseg segment MESH -o LABELS.txt [--centers CENTERS.txt] [--ply OUT.ply] [--faces N] "
    "[--no-streamline] [--timings]";

int cmd_segment(int argc, char **argv) {
  const char *in = NULL, *labels_path = NULL, *centers_path = NULL, *ply_path = NULL;
  int timings = 0;
  ss_segment_options opt;
  ss_segment_default_options(&opt);
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
      printf("usage: %s\n\n"
             "Coherent segmentation (paper §4): CMCF smoothing, isotropic remeshing, critical points of\n"
             "the Fiedler function, intrinsic Voronoi cells. LABELS: one segment index (0..m-1) per input\n"
             "vertex. CENTERS: line s = input vertex at the centre of segment s. --ply writes the input\n"
             "mesh coloured by segment. --faces N: remeshing target (default 15000). --no-streamline:\n"
             "everything straight on the input. --timings: 'timing: STAGE SECONDS' lines on stderr.\n",
             USAGE);
      return SS_EXIT_OK;
    }
    int has_next = i + 1 < argc;
    if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
      if (!has_next) return cli_usage("%s: %s needs a file", USAGE, a);
      labels_path = argv[++i];
    } else if (!strcmp(a, "--centers")) {
      if (!has_next) return cli_usage("%s: --centers needs a file", USAGE);
      centers_path = argv[++i];
    } else if (!strcmp(a, "--ply")) {
      if (!has_next) return cli_usage("%s: --ply needs a file", USAGE);
      ply_path = argv[++i];
    } else if (!strcmp(a, "--faces")) {
      if (!has_next || cli_parse_int(argv[++i], 4, 100000000, &opt.target_faces))
        return cli_usage("%s: --faces needs an integer between 4 and 100000000", USAGE);
    } else if (!strcmp(a, "--no-streamline")) {
      opt.no_streamline = 1;
    } else if (!strcmp(a, "--timings")) {
      timings = 1;
    } else if (a[0] == '-' && a[1]) {
      return cli_usage("%s: unknown option '%s'", USAGE, a);
    } else if (!in) {
      in = a;
    } else {
      return cli_usage("%s: unexpected argument '%s'", USAGE, a);
    }
  }
  if (!in) return cli_usage("%s: missing MESH", USAGE);
  if (!labels_path) return cli_usage("%s: missing -o LABELS.txt", USAGE);

  ss_error err = {{0}};
  ss_mesh m = {0};
  ss_segmentation seg = {0};
  int rc = SS_EXIT_OK;
  double t0 = ss_time();
  if (ss_read_mesh(in, &m, &err)) return cli_error("%s", err.msg);
  double t_read = ss_time() - t0;
  char warnings[2048];
  if (ss_segment_warn(&m, &opt, &seg, warnings, sizeof warnings, &err)) {
    rc = cli_error("%s: %s", in, err.msg);
    goto done;
  }
  if (warnings[0]) cli_warn("%s: %s", in, warnings);
  seg.t_read = t_read;
  if (ss_write_ints(labels_path, seg.labels, seg.nv, &err)) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  if (centers_path && ss_write_ints(centers_path, seg.centers, seg.m, &err)) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  if (ply_path) {
    unsigned char *rgb = malloc(3 * (size_t)m.nv);
    if (!rgb) {
      rc = cli_error("out of memory");
      goto done;
    }
    for (int i = 0; i < m.nv; i++) ss_label_color(seg.labels[i], rgb + 3 * (size_t)i);
    ss_status st = ss_write_mesh(ply_path, &m, rgb, &err);
    free(rgb);
    if (st) {
      rc = cli_error("%s", err.msg);
      goto done;
    }
  }
  if (seg.empty_segments)
    cli_warn("%d of the %d segments received no input vertex", seg.empty_segments, seg.m);
  if (timings) {
    fprintf(stderr, "timing: read %.6f\n", seg.t_read);
    fprintf(stderr, "timing: smooth %.6f\n", seg.t_smooth);
    fprintf(stderr, "timing: remesh %.6f\n", seg.t_remesh + seg.t_psi);
    fprintf(stderr, "timing: spectrum %.6f\n", seg.t_spectrum);
    fprintf(stderr, "timing: critical %.6f\n", seg.t_critical);
    fprintf(stderr, "timing: ivd %.6f\n", seg.t_ivd);
    fprintf(stderr, "timing: total %.6f\n", seg.t_read + seg.t_total);
  }
  printf("%d segments (%d critical points before clean-up), %d vertices -> %s\n", seg.m, seg.ncrit_raw, seg.nv,
         labels_path);
done:
  ss_segmentation_free(&seg);
  ss_mesh_free(&m);
  return rc;
}
