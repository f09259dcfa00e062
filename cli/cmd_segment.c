/* specseg segment MESH -o LABELS.txt [--centers CENTERS.txt] [--ply OUT.ply] [--faces N]
 *                 [--no-streamline] [--timings] */
#include "cli.h"
#include "cli_shape.h"
#include "specseg/render.h"
#include "specseg/segment.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char USAGE[] =
    "usage: specseg segment MESH... -o LABELS.txt [--centers CENTERS.txt] [--ply OUT.ply] [--faces N]\n"
    "                       [--no-streamline] [--timings] [--jobs N] [--json]\n"
    "\n"
    "Coherent segmentation (paper section 4): CMCF smoothing, isotropic remeshing, critical points of\n"
    "the Fiedler function, intrinsic Voronoi cells, labels mapped back to the input's vertices. Prints\n"
    "a summary line (on stderr when an output goes to standard output).\n"
    "\n"
    "  MESH                mesh file (OFF, OBJ, PLY, STL, glTF, ...), or a prepared shape (specseg\n"
    "                      prepare, .sss: its stored segmentation, the same output; --faces /\n"
    "                      --no-streamline must match it); - reads standard input\n"
    "  -o, --output FILE   labels: one segment index (0..m-1) per input vertex, a line (required);\n"
    "                      batch: OUTDIR, labels in OUTDIR/NAME.labels.txt\n"
    "  --centers FILE      line s = input vertex at the centre of segment s (batch: a suffix)\n"
    "  --ply FILE          the input mesh coloured by segment, binary PLY with an int vertex property\n"
    "                      'label' (the segment) beside red green blue (batch: a suffix, e.g. .ply)\n"
    "  --faces N           remeshing target, 4..2000000 triangles (default 15000)\n"
    "  --no-streamline     everything straight on the input (no smoothing, no remeshing)\n"
    "  --timings           'timing: STAGE SECONDS' lines on stderr\n"
    "One of the output files may be - (standard output).\n" CLI_BATCH_HELP;

typedef struct seg_cfg {
  const char *labels, *centers, *ply;
  int timings, to_stdout;
  ss_segment_options opt;
} seg_cfg;

static int segment_job(cli_job *j, void *vcfg) {
  const seg_cfg *c = vcfg;
  const char *in = j->input;
  const char *labels_path = cli_job_output(j, c->labels, ".labels.txt");
  const char *centers_path = cli_job_extra(j, c->centers), *ply_path = cli_job_extra(j, c->ply);
  FILE *report = cli_job_report(j, c->to_stdout);
  ss_error err = {{0}};
  ss_mesh m = {0};
  ss_segmentation seg = {0};
  int rc = SS_EXIT_OK;
  double t0 = ss_time();
  cli_shape S;
  if (cli_read_shape(in, &S, &err)) return cli_error("%s", err.msg);
  double t_read = ss_time() - t0;
  char warnings[2048] = "";
  if (S.prepared) { /* the stored segmentation (nothing computed here: its timings are 0) */
    const ss_segment_options *so = &S.ps.seg;
    /* the output is the one from the mesh with these options only */
    if (c->opt.no_streamline != so->no_streamline || (!so->no_streamline && c->opt.target_faces != so->target_faces)) {
      char was[64], asked[64]; /* both named: which option differs is not always the one given */
      if (so->no_streamline) snprintf(was, sizeof was, "--no-streamline");
      else snprintf(was, sizeof was, "--faces %d", so->target_faces);
      if (c->opt.no_streamline) snprintf(asked, sizeof asked, "--no-streamline");
      else snprintf(asked, sizeof asked, "--faces %d", c->opt.target_faces);
      rc = cli_error("%s: was prepared with %s, not %s; give the same options (or the mesh)", cli_in_name(in), was,
                     asked);
      cli_shape_free(&S);
      return rc;
    }
    m = S.ps.mesh, seg = S.ps.prep.seg; /* moved out */
    memset(&S.ps.mesh, 0, sizeof m), memset(&S.ps.prep.seg, 0, sizeof seg);
    seg.t_smooth = seg.t_remesh = seg.t_psi = seg.t_spectrum = seg.t_critical = seg.t_ivd = seg.t_total = 0;
  } else {
    m = S.ps.mesh;
    memset(&S.ps.mesh, 0, sizeof m);
  }
  cli_shape_free(&S);
  if (!seg.labels && ss_segment_warn(&m, &c->opt, &seg, warnings, sizeof warnings, &err)) {
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
    cli_warn("%s: %d of the %d segments received no input vertex", cli_in_name(in), seg.empty_segments, seg.m);
  if (c->timings) { /* stderr; in a batch with the report (prefixed by the mesh) */
    FILE *tf = j->b && j->b->batch ? report : stderr;
    fprintf(tf, "timing: read %.6f\n", seg.t_read);
    fprintf(tf, "timing: smooth %.6f\n", seg.t_smooth);
    fprintf(tf, "timing: remesh %.6f\n", seg.t_remesh + seg.t_psi);
    fprintf(tf, "timing: spectrum %.6f\n", seg.t_spectrum);
    fprintf(tf, "timing: critical %.6f\n", seg.t_critical);
    fprintf(tf, "timing: ivd %.6f\n", seg.t_ivd);
    fprintf(tf, "timing: total %.6f\n", seg.t_read + seg.t_total);
  }
  fprintf(report, "%d segments (%d critical points before clean-up), %d vertices -> %s\n", seg.m, seg.ncrit_raw,
          seg.nv, cli_out_name(labels_path));
  cli_job_int(j, "segments", seg.m);
  cli_job_int(j, "critical_points", seg.ncrit_raw);
  cli_job_int(j, "vertices", seg.nv);
  cli_job_int(j, "faces", m.nf);
  cli_job_int(j, "empty_segments", seg.empty_segments);
  cli_job_num(j, "t_read", seg.t_read);
  cli_job_num(j, "t_smooth", seg.t_smooth);
  cli_job_num(j, "t_remesh", seg.t_remesh + seg.t_psi);
  cli_job_num(j, "t_spectrum", seg.t_spectrum);
  cli_job_num(j, "t_critical", seg.t_critical);
  cli_job_num(j, "t_ivd", seg.t_ivd);
  cli_job_num(j, "t_total", seg.t_read + seg.t_total);
done:
  ss_segmentation_free(&seg);
  ss_mesh_free(&m);
  return rc;
}

int cmd_segment(int argc, char **argv) {
  seg_cfg c;
  memset(&c, 0, sizeof c);
  ss_segment_default_options(&c.opt);
  cli_batch B;
  cli_batch_init(&B, "segment");
  const cli_opt opts[] = {CLI_BATCH_OPTIONS(&B),
                          CLI_OPT_STR("-o|--output", &c.labels),
                          CLI_OPT_STR("--centers", &c.centers),
                          CLI_OPT_STR("--ply", &c.ply),
                          CLI_OPT_INT("--faces", &c.opt.target_faces, 4, SS_REMESH_MAX_FACES, NULL),
                          CLI_OPT_FLAG("--no-streamline", &c.opt.no_streamline, 1),
                          CLI_OPT_FLAG("--timings", &c.timings, 1),
                          CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, opts);
  int rc = cli_parse(&A);
  if (rc < 0 && B.nin == 0) rc = cli_bad(&A, "missing MESH");
  const char *extras[2] = {c.centers, c.ply};
  if (rc < 0) rc = cli_batch_setup(&B, &A, c.labels, 1, ".labels.txt", extras, 2);
  if (rc < 0 && !c.labels) rc = cli_bad(&A, "missing -o LABELS.txt");
  if (rc < 0 && !B.batch) {
    const char *outs[3] = {c.labels, c.centers, c.ply};
    c.to_stdout = cli_count_std(outs, 3);
    if (c.to_stdout > 1) rc = cli_bad(&A, "only one output can go to standard output ('-')");
    else if (c.to_stdout && B.json) rc = cli_bad(&A, "--json and an output to '-' both want standard output");
  }
  return cli_batch_finish(&B, rc, segment_job, &c);
}
