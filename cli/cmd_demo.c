/* specseg demo [-o DIR]: the pipeline on built-in synthetic shapes, no data and no download.
 *
 * Stages are plain functions over a shared demo_ctx, run in order by cmd_demo; a later stage
 * (segmentation, matching, ...) is one more function appended to `stages[]`. Every file a stage
 * writes goes through demo_path() + demo_record() so the closing summary lists it. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>

#include "cli.h"
#include "specseg/render.h"
#include "specseg/match.h"
#include "specseg/synth.h"

static const char USAGE[] =
    "usage: specseg demo [-o DIR]\n"
    "\n"
    "Builds a synthetic humanoid in two poses (same connectivity: ground truth = identity), a sphere and\n"
    "a torus, writes them as OFF and PLY into DIR, and prints their mesh facts and first Laplace-Beltrami\n"
    "eigenvalues, segments the poses (humanoid_segments.png) and matches them with STD, ASA and DIFF\n"
    "probes (the DIFF map as text; humanoid_matching.png: colour transfer and error heat maps, like the\n"
    "paper's Figure 9). No data or download needed.\n"
    "\n"
    "  -o DIR              output folder, created if missing (default specseg-demo)\n";

#define DEMO_MAX_SHAPES 8
#define DEMO_MAX_FILES 64

typedef struct demo_shape {
  char name[64];   /* file stem, e.g. "humanoid_pose0" */
  char what[160];  /* one-line description */
  ss_mesh mesh;
  int humanoid_pose; /* -1 unless a humanoid pose: all poses share vertices (ground truth = identity) */
} demo_shape;

typedef struct demo_ctx {
  const char *dir;
  demo_shape shapes[DEMO_MAX_SHAPES];
  int nshapes;
  char files[DEMO_MAX_FILES][96]; /* written files (relative to dir) and what they hold */
  char notes[DEMO_MAX_FILES][96];
  int nfiles;
} demo_ctx;

static int demo_path(const demo_ctx *c, const char *file, char *out, size_t n) {
  int w = snprintf(out, n, "%s/%s", c->dir, file);
  return w < 0 || (size_t)w >= n ? -1 : 0;
}
static void demo_record(demo_ctx *c, const char *file, const char *note) {
  if (c->nfiles >= DEMO_MAX_FILES) return;
  snprintf(c->files[c->nfiles], sizeof c->files[0], "%s", file);
  snprintf(c->notes[c->nfiles], sizeof c->notes[0], "%s", note);
  c->nfiles++;
}

/* mkdir -p */
static int make_dir(const char *path) {
  char buf[4096];
  size_t n = strlen(path);
  if (n == 0 || n >= sizeof buf) {
    errno = ENAMETOOLONG;
    return -1;
  }
  memcpy(buf, path, n + 1);
  for (size_t i = 1; i <= n; i++) {
    if (buf[i] != '/' && buf[i] != '\0') continue;
    char saved = buf[i];
    buf[i] = '\0';
    if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
    buf[i] = saved;
  }
  struct stat st;
  if (stat(path, &st) != 0) return -1;
  if (!S_ISDIR(st.st_mode)) {
    errno = ENOTDIR;
    return -1;
  }
  return 0;
}

static demo_shape *add_shape(demo_ctx *c, const char *name, const char *what) {
  demo_shape *s = &c->shapes[c->nshapes++];
  memset(s, 0, sizeof *s);
  snprintf(s->name, sizeof s->name, "%s", name);
  snprintf(s->what, sizeof s->what, "%s", what);
  s->humanoid_pose = -1;
  return s;
}

/* Stage 1: build the shapes and write each as OFF and PLY. */
static int stage_shapes(demo_ctx *c) {
  ss_error err = {{0}};
  const int poses[2] = {0, 2};
  printf("== shapes ==\n");
  for (int i = 0; i < 2; i++) {
    char name[32], what[160];
    snprintf(name, sizeof name, "humanoid_pose%d", poses[i]);
    snprintf(what, sizeof what, "synthetic humanoid, pose %d: %s", poses[i], ss_synth_humanoid_pose_name(poses[i]));
    demo_shape *s = add_shape(c, name, what);
    s->humanoid_pose = poses[i];
    double t = ss_time();
    if (ss_synth_humanoid(poses[i], &s->mesh, &err)) return cli_error("demo: humanoid: %s", err.msg);
    printf("%s: built in %.3f s\n", name, ss_time() - t);
  }
  demo_shape *s = add_shape(c, "sphere", "unit icosphere, 4 subdivisions");
  if (ss_synth_icosphere(4, &s->mesh, &err)) return cli_error("demo: sphere: %s", err.msg);
  s = add_shape(c, "torus", "torus R = 1, r = 0.4, 64 x 32 samples");
  if (ss_synth_torus(1.0, 0.4, 64, 32, &s->mesh, &err)) return cli_error("demo: torus: %s", err.msg);

  for (int i = 0; i < c->nshapes; i++) {
    static const char *ext[2] = {"off", "ply"};
    for (int e = 0; e < 2; e++) {
      char file[96], path[4096];
      snprintf(file, sizeof file, "%s.%s", c->shapes[i].name, ext[e]);
      if (demo_path(c, file, path, sizeof path)) return cli_error("demo: output path too long");
      if (ss_write_mesh(path, &c->shapes[i].mesh, NULL, &err)) return cli_error("demo: %s", err.msg);
      demo_record(c, file, c->shapes[i].what);
    }
  }
  printf("ground truth between the humanoid poses: identity (same vertex order)\n\n");
  return SS_EXIT_OK;
}

/* Stage 2: `info` facts and the first Laplace-Beltrami eigenvalues of every shape. */
static int stage_spectrum(demo_ctx *c) {
  ss_error err = {{0}};
  enum { K = 10 };
  for (int i = 0; i < c->nshapes; i++) {
    const demo_shape *s = &c->shapes[i];
    ss_mesh_report r;
    if (ss_mesh_check(&s->mesh, &r, &err)) return cli_error("demo: %s: %s", s->name, err.msg);
    printf("== %s == (%s)\n", s->name, s->what);
    printf("vertices: %d\nfaces: %d\narea: %.6g\ncomponents: %d\nboundary_loops: %d\nmanifold: %s\n"
           "bbox_diagonal: %.6g\neuler_characteristic: %d\n",
           r.vertices, r.faces, r.area, r.components, r.boundary_loops, r.manifold ? "yes" : "no", r.bbox_diagonal,
           r.euler_characteristic);
    if (r.manifold && r.boundary_edges == 0) printf("genus: %d\n", (2 * r.components - r.euler_characteristic) / 2);
    double ev[K], t = ss_time();
    if (ss_mesh_eigs(&s->mesh, K, ev, NULL, &err)) return cli_error("demo: %s: eigenvalues: %s", s->name, err.msg);
    printf("eigenvalues (first %d, %.3f s):", K, ss_time() - t);
    for (int k = 0; k < K; k++) printf(" %.6g", ev[k]);
    printf("\n");
    if (!strcmp(s->name, "sphere")) printf("  (unit sphere, exact: l(l+1) = 0, 2 x3, 6 x5, 12 ...)\n");
    printf("\n");
  }
  return SS_EXIT_OK;
}

/* Stage (render): segment every humanoid pose and draw the segmentations side by side, like the
 * paper's Figure 3: segment colours aligned to the first pose (all poses share vertices, so the ground
 * truth is the identity), boundary triangles neutral, segment centres as black spheres, one scale. */
static int stage_pictures(demo_ctx *c) {
  enum { PW = 480, PH = 600 };
  static const unsigned char CENTRE[3] = {20, 20, 20};
  ss_error err = {{0}};
  int idx[DEMO_MAX_SHAPES], n = 0, rc = SS_EXIT_OK;
  for (int i = 0; i < c->nshapes; i++)
    if (c->shapes[i].humanoid_pose >= 0) idx[n++] = i;
  if (n == 0) return SS_EXIT_OK;
  printf("== segmentation pictures ==\n");
  ss_segmentation seg[DEMO_MAX_SHAPES];
  memset(seg, 0, sizeof seg);
  ss_panel P[DEMO_MAX_SHAPES];
  memset(P, 0, sizeof P);
  char title[DEMO_MAX_SHAPES][96];
  unsigned char *frgb[DEMO_MAX_SHAPES] = {NULL}, *mrgb[DEMO_MAX_SHAPES] = {NULL}, *canvas = NULL;
  double *mk[DEMO_MAX_SHAPES] = {NULL};
  for (int k = 0; k < n; k++) {
    const demo_shape *s = &c->shapes[idx[k]];
    const ss_mesh *m = &s->mesh;
    double t = ss_time();
    if (ss_segment(m, NULL, &seg[k], &err)) { rc = cli_error("demo: %s: segment: %s", s->name, err.msg); goto out; }
    if (k > 0 && seg[k].nv == seg[0].nv && ss_labels_align(seg[k].labels, seg[0].labels, seg[k].nv, &err)) {
      rc = cli_error("demo: %s: %s", s->name, err.msg);
      goto out;
    }
    printf("%s: %d segments in %.2f s\n", s->name, seg[k].m, ss_time() - t);
    frgb[k] = malloc(3 * (size_t)m->nf + 1);
    mk[k] = malloc(sizeof(double) * 3 * (size_t)seg[k].m + 1);
    mrgb[k] = malloc(3 * (size_t)seg[k].m + 1);
    if (!frgb[k] || !mk[k] || !mrgb[k]) { rc = cli_error("demo: out of memory"); goto out; }
    if (ss_segmentation_face_colors(m, seg[k].labels, NULL, frgb[k], &err)) { rc = cli_error("demo: %s", err.msg); goto out; }
    for (int j = 0; j < seg[k].m; j++) {
      memcpy(mk[k] + 3 * (size_t)j, m->V + 3 * (size_t)seg[k].centers[j], 3 * sizeof(double));
      memcpy(mrgb[k] + 3 * (size_t)j, CENTRE, 3);
    }
    ss_render_scene_init(&P[k].scene, m);
    P[k].scene.face_rgb = frgb[k];
    P[k].scene.nmarkers = seg[k].m, P[k].scene.markers = mk[k], P[k].scene.marker_rgb = mrgb[k];
    snprintf(title[k], sizeof title[k], "%s (%d)", s->name, seg[k].m);
    P[k].title = title[k];
  }
  ss_render_options o;
  ss_render_default_options(&o);
  o.width = PW, o.height = PH, o.azimuth = 25, o.elevation = 10;
  ss_panel_layout L; /* one row, titles, one scale: the poses compare */
  ss_panel_layout_init(&L);
  int w, h;
  double t = ss_time();
  if (ss_render_panels(P, n, &o, &L, &canvas, &w, &h, &err)) { rc = cli_error("demo: render: %s", err.msg); goto out; }
  char path[4096];
  const char *file = "humanoid_segments.png";
  if (demo_path(c, file, path, sizeof path)) { rc = cli_error("demo: output path too long"); goto out; }
  if (ss_write_png(path, canvas, w, h, &err)) { rc = cli_error("demo: %s", err.msg); goto out; }
  demo_record(c, file, "segmentations of the humanoid poses (colours aligned)");
  printf("rendered %d panels %dx%d in %.3f s -> %s\n\n", n, PW, PH, ss_time() - t, file);
out:
  for (int k = 0; k < n; k++) ss_segmentation_free(&seg[k]), free(frgb[k]), free(mk[k]), free(mrgb[k]);
  free(canvas);
  return rc;
}

/* Stage (matching, paper §6): the first humanoid pose matched to the second with five landmarks at
 * the head, hands and feet (extreme vertices of the rest pose: y up, left side on +x), STD, ASA and
 * DIFF probes, errors against the identity ground truth, drawn like the paper's Figure 9
 * (ss_render_map_comparison: colour transfer through each map above, per-vertex error below). */
static int stage_match(demo_ctx *c) {
  int ia = -1, ib = -1;
  for (int i = 0; i < c->nshapes; i++)
    if (c->shapes[i].humanoid_pose >= 0) {
      if (ia < 0) ia = i;
      else if (ib < 0) ib = i;
    }
  if (ia < 0 || ib < 0) return SS_EXIT_OK;
  const ss_mesh *X = &c->shapes[ia].mesh, *Y = &c->shapes[ib].mesh;
  printf("== matching %s -> %s ==\n", c->shapes[ia].name, c->shapes[ib].name);
  int lm[5] = {0, 0, 0, 0, 0};
  double best[5];
  for (int l = 0; l < 5; l++) best[l] = -1e300;
  for (int i = 0; i < X->nv; i++) {
    const double *p = X->V + 3 * (size_t)i;
    double sc[5] = {p[1], p[0], -p[0], p[0] > 0.05 ? -p[1] + 0.1 * p[2] : -1e300,
                    p[0] < -0.05 ? -p[1] + 0.1 * p[2] : -1e300};
    for (int l = 0; l < 5; l++)
      if (sc[l] > best[l]) best[l] = sc[l], lm[l] = i;
  }
  printf("landmarks (head, left hand, right hand, left foot, right foot): %d %d %d %d %d\n", lm[0], lm[1], lm[2],
         lm[3], lm[4]);
  ss_error err = {{0}};
  ss_match_options o;
  ss_match_paper_options(&o); /* the demo shows the paper's DIFF (its shapes carry k eigenpairs) */
  o.fmap.k = 40;
  ss_shape_prep pa, pb;
  double t = ss_time();
  if (ss_shape_prep_compute(X, &o.seg, o.fmap.k, &pa, &err)) return cli_error("demo: match: %s", err.msg);
  if (ss_shape_prep_compute(Y, &o.seg, o.fmap.k, &pb, &err)) {
    ss_shape_prep_free(&pa);
    return cli_error("demo: match: %s", err.msg);
  }
  printf("shapes prepared (segmentation + %d eigenpairs each) in %.2f s\n", o.fmap.k, ss_time() - t);
  int rc = SS_EXIT_OK;
  static const char *names[3] = {"STD", "ASA", "DIFF"};
  ss_match_result r[3];
  memset(r, 0, sizeof r);
  double e[3] = {0}, *errs = malloc(sizeof(double) * 3 * (size_t)X->nv + 1);
  int *ident = malloc(sizeof(int) * (size_t)X->nv + 1);
  unsigned char *img = NULL;
  if (!errs || !ident) { rc = cli_error("demo: out of memory"); goto out; }
  for (int v = 0; v < 3; v++) {
    o.probes = v == 0 ? SS_PROBES_STD : v == 1 ? SS_PROBES_ASA : SS_PROBES_DIFF;
    t = ss_time();
    if (ss_match_prepared(&pa, &pb, 5, lm, lm, &o, &r[v], &err) ||
        ss_map_geodesic_error(Y, r[v].nX, r[v].map, NULL, NULL, errs + (size_t)v * X->nv, &e[v], &err)) {
      rc = cli_error("demo: match: %s", err.msg);
      goto out;
    }
    if (v == 1) printf("%d of %d/%d segments paired\n", r[v].pairs.n, r[v].pairs.nx, r[v].pairs.ny); /* (STD pairs none) */
    printf("%-4s mean geodesic error %.4f (/sqrt(area), exact geodesics; %.2f s)\n", names[v], e[v], ss_time() - t);
    if (v == 2) {
      char file[96], path[4096];
      snprintf(file, sizeof file, "map_%.40s_to_%.40s.txt", c->shapes[ia].name, c->shapes[ib].name);
      if (demo_path(c, file, path, sizeof path) || ss_write_ints(path, r[v].map, r[v].nX, &err)) {
        rc = cli_error("demo: match: cannot write %s", file);
        goto out;
      }
      demo_record(c, file, "DIFF point map (line i = vertex of pose B)");
    }
  }

  /* the picture: poses share vertices, so the ground truth is the identity */
  for (int i = 0; i < X->nv; i++) ident[i] = i;
  char heading[160];
  snprintf(heading, sizeof heading, "synthetic humanoid, pose %d to pose %d: 5 landmarks (head, hands, feet), %d segment pairs",
           c->shapes[ia].humanoid_pose, c->shapes[ib].humanoid_pose, r[2].pairs.n);
  ss_map_comparison fig;
  ss_map_comparison_init(&fig, X, Y);
  fig.x_name = c->shapes[ia].name, fig.y_name = c->shapes[ib].name, fig.heading = heading;
  fig.nmaps = 3;
  for (int v = 0; v < 3; v++)
    fig.map[v] = r[v].map, fig.error[v] = errs + (size_t)v * X->nv, fig.mean_error[v] = e[v], fig.method[v] = names[v];
  fig.gt = ident;
  fig.nlandmarks = 5, fig.landmarks_x = fig.landmarks_y = lm;
  fig.segments_x = pa.seg.m, fig.segments_y = pb.seg.m;
  fig.labels_x = pa.seg.labels, fig.labels_y = pb.seg.labels;
  fig.centers_x = pa.seg.centers, fig.centers_y = pb.seg.centers;
  fig.npairs = r[2].pairs.n, fig.pair_x = r[2].pairs.sx, fig.pair_y = r[2].pairs.sy; /* ASA's and DIFF's */
  ss_render_options ro;
  ss_render_default_options(&ro);
  /* the segment gallery's panels and view: the spread arms fit, the raised leg shows */
  ro.width = 480, ro.height = 600, ro.azimuth = 25, ro.elevation = 10;
  int w, h;
  double hi;
  char path[4096];
  const char *file = "humanoid_matching.png";
  t = ss_time();
  if (ss_render_map_comparison(&fig, &ro, &img, &w, &h, &hi, &err)) { rc = cli_error("demo: render: %s", err.msg); goto out; }
  if (demo_path(c, file, path, sizeof path)) { rc = cli_error("demo: output path too long"); goto out; }
  if (ss_write_png(path, img, w, h, &err)) { rc = cli_error("demo: %s", err.msg); goto out; }
  demo_record(c, file, "STD/ASA/DIFF maps: colour transfer and error heat maps");
  printf("rendered %dx%d in %.3f s (error scale 0..%g) -> %s\n", w, h, ss_time() - t, hi, file);
out:
  printf("\n");
  for (int v = 0; v < 3; v++) ss_match_result_free(&r[v]);
  free(errs), free(ident), free(img);
  ss_shape_prep_free(&pa);
  ss_shape_prep_free(&pb);
  return rc;
}

typedef int (*demo_stage)(demo_ctx *);
/* Later stages (segmentation, matching) are appended here. */
static const demo_stage stages[] = {stage_shapes, stage_spectrum, stage_pictures, stage_match};

/* -o DIR: a folder */
static int take_dir(cli_args *A, const cli_opt *o, const char *dir) {
  if (cli_is_std(dir)) return cli_bad(A, "-o takes a folder, not standard output ('-')");
  *(const char **)o->dest = dir;
  return -1;
}

int cmd_demo(int argc, char **argv) {
  const char *dir = "specseg-demo";
  const cli_opt opts[] = {CLI_OPT_CALL("-o", take_dir, &dir, NULL), CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, opts);
  int rc = cli_parse(&A);
  if (rc >= 0) return rc;
  if (make_dir(dir)) return cli_error("demo: cannot create directory '%s': %s", dir, strerror(errno));

  demo_ctx *c = calloc(1, sizeof *c);
  if (!c) return cli_error("demo: out of memory");
  c->dir = dir;
  double t0 = ss_time();
  rc = SS_EXIT_OK;
  for (size_t i = 0; i < sizeof stages / sizeof stages[0] && rc == SS_EXIT_OK; i++) rc = stages[i](c);
  if (rc == SS_EXIT_OK) {
    printf("== summary ==\nwrote %d files into %s/ in %.2f s:\n", c->nfiles, dir, ss_time() - t0);
    for (int i = 0; i < c->nfiles; i++) printf("  %-22s %s\n", c->files[i], c->notes[i]);
    if (fflush(stdout) != 0) rc = cli_error("cannot write to standard output");
  }
  for (int i = 0; i < c->nshapes; i++) ss_mesh_free(&c->shapes[i].mesh);
  free(c);
  return rc;
}
