/* specseg segment MESH -o LABELS.txt [--centers CENTERS.txt] [--ply OUT.ply] [--faces N]
 *                 [--no-streamline] [--timings] */
#include "cli.h"
#include "specseg/render.h"
#include "specseg/segment.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char USAGE[] =
    "usage: specseg segment MESH -o LABELS.txt [--centers CENTERS.txt] [--ply OUT.ply] [--faces N]\n"
    "                       [--no-streamline] [--timings]\n"
    "\n"
    "Coherent segmentation (paper section 4): CMCF smoothing, isotropic remeshing, critical points of\n"
    "the Fiedler function, intrinsic Voronoi cells, labels mapped back to the input's vertices. Prints\n"
    "a summary line (on stderr when an output goes to standard output).\n"
    "\n"
    "  MESH                mesh file (OFF, OBJ, PLY, STL, glTF, ...); - reads standard input\n"
    "  -o, --output FILE   labels: one segment index (0..m-1) per input vertex, a line (required)\n"
    "  --centers FILE      line s = input vertex at the centre of segment s\n"
    "  --ply FILE          the input mesh coloured by segment, binary PLY with an int vertex property\n"
    "                      'label' (the segment) beside red green blue\n"
    "  --faces N           remeshing target, 4..100000000 triangles (default 15000)\n"
    "  --no-streamline     everything straight on the input (no smoothing, no remeshing)\n"
    "  --timings           'timing: STAGE SECONDS' lines on stderr\n"
    "One of the output files may be - (standard output).\n";

static const char *const OPTS[] = {"-o=", "--output=", "--centers=", "--ply=", "--faces=", "--no-streamline",
                                   "--timings", NULL};

int cmd_segment(int argc, char **argv) {
  const char *in = NULL, *labels_path = NULL, *centers_path = NULL, *ply_path = NULL;
  int timings = 0;
  ss_segment_options opt;
  ss_segment_default_options(&opt);
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, OPTS);
  while (cli_next(&A)) {
    const char *v = A.val;
    if (A.pos) {
      if (in) return cli_bad(&A, "unexpected argument '%s'", A.pos);
      in = A.pos;
    } else if (cli_is(&A, "-o") || cli_is(&A, "--output")) {
      labels_path = v;
    } else if (cli_is(&A, "--centers")) {
      centers_path = v;
    } else if (cli_is(&A, "--ply")) {
      ply_path = v;
    } else if (cli_is(&A, "--faces")) {
      if (cli_parse_int(v, 4, 100000000, &opt.target_faces))
        return cli_bad(&A, "--faces needs an integer between 4 and 100000000, not '%s'", v);
    } else if (cli_is(&A, "--no-streamline")) {
      opt.no_streamline = 1;
    } else if (cli_is(&A, "--timings")) {
      timings = 1;
    }
  }
  if (A.rc >= 0) return A.rc;
  if (!in) return cli_bad(&A, "missing MESH");
  if (!labels_path) return cli_bad(&A, "missing -o LABELS.txt");
  const char *outs[3] = {labels_path, centers_path, ply_path};
  int to_stdout = cli_count_std(outs, 3);
  if (to_stdout > 1) return cli_bad(&A, "only one output can go to standard output ('-')");
  FILE *report = to_stdout ? stderr : stdout;

  ss_error err = {{0}};
  ss_mesh m = {0};
  ss_segmentation seg = {0};
  int rc = SS_EXIT_OK;
  double t0 = ss_time();
  if (cli_read_mesh(in, &m, &err)) return cli_error("%s", err.msg);
  double t_read = ss_time() - t0;
  char warnings[2048];
  if (ss_segment_warn(&m, &opt, &seg, warnings, sizeof warnings, &err)) {
    rc = cli_error("%s: %s", cli_in_name(in), err.msg);
    goto done;
  }
  if (warnings[0]) cli_warn("%s: %s", cli_in_name(in), warnings);
  seg.t_read = t_read;
  if (cli_write_ints(labels_path, seg.labels, seg.nv, &err)) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  if (centers_path && cli_write_ints(centers_path, seg.centers, seg.m, &err)) {
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
    ss_status st = cli_write_mesh_labels(ply_path, &m, rgb, seg.labels, "ply", &err);
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
  fprintf(report, "%d segments (%d critical points before clean-up), %d vertices -> %s\n", seg.m, seg.ncrit_raw,
          seg.nv, cli_out_name(labels_path));
done:
  ss_segmentation_free(&seg);
  ss_mesh_free(&m);
  return rc;
}
