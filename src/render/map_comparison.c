/* The figure that compares point maps X -> Y, laid out as the paper's Figures 9–11: top row, the target
 * Y coloured by its coordinates and X pulled back through each map (colour transfer); bottom row, X
 * pulled back through the ground truth (what a perfect map shows above) and each map's per-vertex error
 * on one shared heat scale, drawn beside; optionally a last column with the segments of X and Y,
 * paired segments in one colour. `specseg eval --figures` (FAUST) and `specseg demo` (the synthetic
 * humanoid) both draw through here. */
#include "specseg/render.h"
#include "util/c_locale.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const unsigned char NEUTRAL[3] = {225, 225, 220}, CENTRE_RGB[3] = {20, 20, 20};
static const unsigned char LANDMARK_RGB[3] = {250, 250, 250};

void ss_map_comparison_init(ss_map_comparison *c, const ss_mesh *x, const ss_mesh *y) {
  memset(c, 0, sizeof *c);
  c->x = x, c->y = y;
  c->checker_period = 0.06;
}

static int dcmp(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  if (isnan(x) || isnan(y)) return isnan(x) - isnan(y); /* NaN last: a consistent order for qsort */
  return x < y ? -1 : x > y;
}

/* 1, 2, 2.5 or 5 times a power of ten, >= v: a colour-scale end that reads well. */
static double nice_ceil(double v) {
  if (!(v > 0) || !isfinite(v)) return 1;
  double p = pow(10, floor(log10(v))), steps[] = {1, 2, 2.5, 5, 10};
  for (int i = 0; i < 5; i++)
    if (steps[i] * p >= v * (1 - 1e-12)) return steps[i] * p;
  return 10 * p;
}

/* n vertex indices in [0, nv)? (n == 0 is fine) */
static int indices_ok(const int *idx, int n, int nv) {
  if (n > 0 && !idx) return 0;
  for (int k = 0; k < n; k++)
    if (idx[k] < 0 || idx[k] >= nv) return 0;
  return 1;
}

/* Marker spheres at the given vertices, all in one colour (malloc'd positions and colours). */
static ss_status markers(const ss_mesh *m, int n, const int *idx, const unsigned char rgb[3], double **pos,
                         unsigned char **col, ss_error *err) {
  *pos = malloc(sizeof(double) * 3 * (size_t)n + 1);
  *col = malloc(3 * (size_t)n + 1);
  if (!*pos || !*col) return ss_fail(err, SS_ERR_NOMEM, "map figure: out of memory");
  for (int k = 0; k < n; k++) {
    memcpy(*pos + 3 * (size_t)k, m->V + 3 * (size_t)idx[k], 3 * sizeof(double));
    memcpy(*col + 3 * (size_t)k, rgb, 3);
  }
  return SS_OK;
}

/* Per-face colours of one shape's segments: the pair index's colour for a paired segment, grey for an
 * unpaired one (pair: the shape's side of the pairs). */
static ss_status pair_face_colors(const ss_mesh *m, int nseg, const int *labels, int npairs, const int *pair,
                                  unsigned char *face_rgb, ss_error *err) {
  int *of = malloc(sizeof(int) * (size_t)nseg + 1), *lab = malloc(sizeof(int) * (size_t)m->nv + 1);
  if (!of || !lab) {
    free(of), free(lab);
    return ss_fail(err, SS_ERR_NOMEM, "map figure: out of memory");
  }
  for (int s = 0; s < nseg; s++) of[s] = -1;
  for (int p = 0; p < npairs; p++) of[pair[p]] = p;
  for (int i = 0; i < m->nv; i++) lab[i] = labels[i] < 0 ? -1 : of[labels[i]];
  ss_status st = ss_segmentation_face_colors(m, lab, NEUTRAL, face_rgb, err);
  free(of), free(lab);
  return st;
}

ss_status ss_render_map_comparison(const ss_map_comparison *c, const ss_render_options *o, unsigned char **rgb,
                                   int *width, int *height, double *error_max, ss_error *err) {
  if (!rgb || !width || !height) return ss_fail(err, SS_ERR_INVALID, "map comparison: NULL output");
  *rgb = NULL;
  *width = *height = 0;
  if (error_max) *error_max = 0;
  if (!c || !o || !c->x || !c->y || c->nmaps < 1 || c->nmaps > SS_MAP_COMPARISON_MAX)
    return ss_fail(err, SS_ERR_INVALID, "map figure: needs two meshes and 1 to %d maps", SS_MAP_COMPARISON_MAX);
  const ss_mesh *X = c->x, *Y = c->y;
  const int nx = X->nv, ny = Y->nv, nm = c->nmaps, segs = c->labels_x != NULL;
  for (int m = 0; m < nm; m++)
    if (!c->map[m] || !c->error[m]) return ss_fail(err, SS_ERR_INVALID, "map figure: map %d or its errors missing", m + 1);
  if (c->nlandmarks < 0 || !indices_ok(c->landmarks_x, c->nlandmarks, nx) ||
      !indices_ok(c->landmarks_y, c->nlandmarks, ny))
    return ss_fail(err, SS_ERR_INVALID, "map figure: landmark missing or not a vertex of its shape");
  if (segs) {
    if (!c->labels_y || c->segments_x < 1 || c->segments_y < 1 || c->npairs < 0 ||
        !indices_ok(c->pair_x, c->npairs, c->segments_x) || !indices_ok(c->pair_y, c->npairs, c->segments_y) ||
        (c->centers_x && !indices_ok(c->centers_x, c->segments_x, nx)) ||
        (c->centers_y && !indices_ok(c->centers_y, c->segments_y, ny)))
      return ss_fail(err, SS_ERR_INVALID, "map figure: bad segments, pairs or centres");
    for (int i = 0; i < nx; i++)
      if (c->labels_x[i] < -1 || c->labels_x[i] >= c->segments_x)
        return ss_fail(err, SS_ERR_INVALID, "map figure: label %d of X vertex %d not in [-1, %d)", c->labels_x[i], i,
                       c->segments_x);
    for (int i = 0; i < ny; i++)
      if (c->labels_y[i] < -1 || c->labels_y[i] >= c->segments_y)
        return ss_fail(err, SS_ERR_INVALID, "map figure: label %d of Y vertex %d not in [-1, %d)", c->labels_y[i], i,
                       c->segments_y);
  }

  ss_status st = SS_OK;
  double *sorted = NULL, *mpos[4] = {NULL};
  unsigned char *ycol = NULL, *xcol[SS_MAP_COMPARISON_MAX + 1] = {NULL}, *ecol[SS_MAP_COMPARISON_MAX] = {NULL};
  unsigned char *scol[2] = {NULL}, *mcol[4] = {NULL};

  /* one heat scale for all maps, by default 0 to the pooled 95th percentile (rounded up): a few far-off
   * vertices (a swapped hand) would otherwise wash every other error out to white */
  double hi = c->error_max;
  if (!(hi > 0) || !isfinite(hi)) {
    size_t ne = 0; /* the finite errors only (NaN / inf: unreachable vertices) */
    if (!(sorted = malloc(sizeof(double) * (size_t)nm * nx + 1))) { st = ss_fail(err, SS_ERR_NOMEM, "map figure: out of memory"); goto done; }
    for (int m = 0; m < nm; m++)
      for (int i = 0; i < nx; i++)
        if (isfinite(c->error[m][i])) sorted[ne++] = c->error[m][i];
    qsort(sorted, ne, sizeof(double), dcmp);
    hi = ne ? nice_ceil(sorted[(size_t)(0.95 * (ne - 1))]) : 1;
  }

  /* colours */
  ycol = malloc(3 * (size_t)ny + 1);
  int ok = ycol != NULL;
  for (int m = 0; m <= nm; m++) ok &= (xcol[m] = malloc(3 * (size_t)nx + 1)) != NULL;
  for (int m = 0; m < nm; m++) ok &= (ecol[m] = malloc(3 * (size_t)nx + 1)) != NULL;
  if (segs) {
    ok &= (scol[0] = malloc(3 * (size_t)X->nf + 1)) != NULL;
    ok &= (scol[1] = malloc(3 * (size_t)Y->nf + 1)) != NULL;
  }
  if (!ok) { st = ss_fail(err, SS_ERR_NOMEM, "map figure: out of memory"); goto done; }
  ss_coordinate_pattern_colors(Y, c->checker_period, ycol);
  if (c->gt && (st = ss_map_transfer_colors(nx, c->gt, ny, ycol, xcol[nm], err))) goto done;
  for (int m = 0; m < nm; m++) {
    if ((st = ss_map_transfer_colors(nx, c->map[m], ny, ycol, xcol[m], err))) goto done;
    ss_scalar_colors(c->error[m], nx, SS_CMAP_HEAT, 0, hi, ecol[m]);
  }
  if (segs && ((st = pair_face_colors(X, c->segments_x, c->labels_x, c->npairs, c->pair_x, scol[0], err)) ||
               (st = pair_face_colors(Y, c->segments_y, c->labels_y, c->npairs, c->pair_y, scol[1], err))))
    goto done;
  /* markers: landmarks (white) on Y and on X's colour transfers, segment centres (black) */
  int ncx = segs && c->centers_x ? c->segments_x : 0, ncy = segs && c->centers_y ? c->segments_y : 0;
  if ((st = markers(Y, c->nlandmarks, c->landmarks_y, LANDMARK_RGB, &mpos[0], &mcol[0], err)) ||
      (st = markers(X, c->nlandmarks, c->landmarks_x, LANDMARK_RGB, &mpos[1], &mcol[1], err)) ||
      (st = markers(X, ncx, c->centers_x, CENTRE_RGB, &mpos[2], &mcol[2], err)) ||
      (st = markers(Y, ncy, c->centers_y, CENTRE_RGB, &mpos[3], &mcol[3], err)))
    goto done;

  /* panels: (1 + maps + segments) columns x 2 rows */
  enum { NP = 2 * (SS_MAP_COMPARISON_MAX + 2), TL = 96 };
  const int cols = 1 + nm + segs;
  char title[NP][TL];
  ss_panel P[NP];
  memset(P, 0, sizeof P);
  memset(title, 0, sizeof title);
  for (int k = 0; k < 2 * cols; k++) P[k].title = title[k];
  ss_render_scene *s = &P[0].scene; /* the target */
  ss_render_scene_init(s, Y);
  s->vertex_rgb = ycol;
  s->nmarkers = c->nlandmarks, s->markers = mpos[0], s->marker_rgb = mcol[0];
  snprintf(title[0], TL, "Y%s%s", c->y_name ? " " : "", c->y_name ? c->y_name : "");
  for (int m = 0; m < nm; m++) {
    const char *name = c->method[m] ? c->method[m] : "";
    ss_render_scene *t = &P[1 + m].scene, *b = &P[cols + 1 + m].scene;
    ss_render_scene_init(t, X);
    t->vertex_rgb = xcol[m];
    t->nmarkers = c->nlandmarks, t->markers = mpos[1], t->marker_rgb = mcol[1];
    snprintf(title[1 + m], TL, "%s", name);
    ss_render_scene_init(b, X);
    b->vertex_rgb = ecol[m];
    ssi_snprintf_c(title[cols + 1 + m], TL, "%s%smean %.4f", name, *name ? " " : "", c->mean_error[m]);
  }
  if (c->gt) { /* the ground truth, under the target */
    s = &P[cols].scene;
    ss_render_scene_init(s, X);
    s->vertex_rgb = xcol[nm];
    s->nmarkers = c->nlandmarks, s->markers = mpos[1], s->marker_rgb = mcol[1];
    snprintf(title[cols], TL, "X%s%s via GT", c->x_name ? " " : "", c->x_name ? c->x_name : "");
  }
  if (segs) {
    s = &P[cols - 1].scene;
    ss_render_scene_init(s, X);
    s->face_rgb = scol[0];
    s->nmarkers = ncx, s->markers = mpos[2], s->marker_rgb = mcol[2];
    snprintf(title[cols - 1], TL, "X segments (%d)", c->segments_x);
    s = &P[2 * cols - 1].scene;
    ss_render_scene_init(s, Y);
    s->face_rgb = scol[1];
    s->nmarkers = ncy, s->markers = mpos[3], s->marker_rgb = mcol[3];
    snprintf(title[2 * cols - 1], TL, "Y segments (%d)", c->segments_y);
  }
  ss_panel_layout L;
  ss_panel_layout_init(&L);
  L.cols = cols;
  L.colorbar = 1;
  L.bar_kind = SS_CMAP_HEAT;
  L.bar_lo = 0, L.bar_hi = hi;
  L.bar_title = "error";
  L.bar_row = 1;
  L.heading = c->heading;
  if ((st = ss_render_panels(P, 2 * cols, o, &L, rgb, width, height, err))) goto done;
  if (error_max) *error_max = hi;
done:
  for (int m = 0; m <= SS_MAP_COMPARISON_MAX; m++) free(xcol[m]);
  for (int m = 0; m < SS_MAP_COMPARISON_MAX; m++) free(ecol[m]);
  for (int m = 0; m < 4; m++) free(mpos[m]), free(mcol[m]);
  free(scol[0]), free(scol[1]), free(sorted), free(ycol);
  return st;
}
