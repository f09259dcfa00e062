/* The map-comparison figure (ss_render_map_comparison): layout size, colour transfer through the identity
 * equals the target's colours, the heat rows and shared scale, the optional ground-truth and segment
 * panels, and refusal of out-of-range input. */
#include "specseg/mesh.h"
#include "specseg/synth.h"
#include "specseg/render.h"
#include "testlib.h"

#include <math.h>

static const unsigned char *px(const unsigned char *img, int w, int x, int y) { return img + 3 * ((size_t)y * w + x); }
static int is_bg(const unsigned char *p) { return p[0] == 255 && p[1] == 255 && p[2] == 255; }

int main(void) {
  ss_mesh s;
  CHECK(ss_synth_icosphere(2, &s, NULL) == SS_OK);
  const int n = s.nv;
  int *ident = malloc(sizeof(int) * n), *shift = malloc(sizeof(int) * n), *labels = malloc(sizeof(int) * n);
  double *e0 = calloc((size_t)n, sizeof(double)), *e1 = malloc(sizeof(double) * n);
  for (int i = 0; i < n; i++) {
    ident[i] = i, shift[i] = (i + 7) % n, e1[i] = 0.3;
    labels[i] = s.V[3 * i] > 0 ? 0 : 1;
  }
  int lm[2] = {0, 5}, centers[2] = {0, 1}, pair0 = 0;

  ss_render_options o;
  ss_render_default_options(&o);
  o.width = 80, o.height = 100;
  ss_map_comparison c;
  ss_map_comparison_init(&c, &s, &s);
  c.nmaps = 2;
  c.map[0] = ident, c.error[0] = e0, c.mean_error[0] = 0, c.method[0] = "A";
  c.map[1] = shift, c.error[1] = e1, c.mean_error[1] = 0.3, c.method[1] = "B";
  c.gt = ident;
  c.nlandmarks = 2, c.landmarks_x = c.landmarks_y = lm;

  /* Y | A | B over GT | heat A | heat B, bar beside: 3 columns of 80, 2 rows of 100 + 13 (text scale 1) */
  unsigned char *img = NULL;
  int w = 0, h = 0;
  double hi = 0;
  CHECK(ss_render_map_comparison(&c, &o, &img, &w, &h, &hi, NULL) == SS_OK);
  CHECK_MSG(h == 2 * 113, "height %d", h);
  CHECK_MSG(w > 3 * 80 && w < 3 * 80 + 100, "width %d", w);
  /* pooled 95th percentile of {0 x n, 0.3 x n} is 0.3, rounded up to 0.5 */
  CHECK_NEAR(hi, 0.5, 1e-12);
  if (img) {
    /* X pulled back through the identity looks exactly like Y (same mesh, view and scale) */
    CHECK(memcmp(px(img, w, 40, 50), px(img, w, 80 + 40, 50), 3) == 0 && !is_bg(px(img, w, 40, 50)));
    /* the ground truth panel below the target: the identity again */
    CHECK(memcmp(px(img, w, 40, 50), px(img, w, 40, 113 + 50), 3) == 0);
    /* heat maps: zero error is white (shaded grey), 0.3 of 0.5 is red */
    const unsigned char *a = px(img, w, 80 + 40, 113 + 50), *b = px(img, w, 160 + 40, 113 + 50);
    CHECK_MSG(abs(a[0] - a[1]) < 8 && abs(a[1] - a[2]) < 8 && a[0] > 150, "zero error %d %d %d", a[0], a[1], a[2]);
    CHECK_MSG(b[0] > b[1] + 60 && b[0] > b[2] + 60, "error 0.3 %d %d %d", b[0], b[1], b[2]);
  }
  free(img);

  /* a given scale is kept; without gt the bottom-left cell stays empty */
  c.error_max = 1;
  c.gt = NULL;
  CHECK(ss_render_map_comparison(&c, &o, &img, &w, &h, &hi, NULL) == SS_OK && hi == 1);
  if (img) CHECK(is_bg(px(img, w, 40, 113 + 50)));
  free(img);

  /* segments add one column of 80 */
  int w3 = w;
  c.segments_x = c.segments_y = 2;
  c.labels_x = c.labels_y = labels;
  c.centers_x = c.centers_y = centers;
  c.npairs = 1, c.pair_x = c.pair_y = &pair0;
  c.heading = "heading";
  CHECK(ss_render_map_comparison(&c, &o, &img, &w, &h, NULL, NULL) == SS_OK);
  CHECK_MSG(w == w3 + 80 && h > 2 * 113, "%d x %d", w, h);
  free(img);

  /* refused: a map entry, a label, a pair, a landmark out of range; no map */
  ss_error e;
  shift[3] = n;
  CHECK(ss_render_map_comparison(&c, &o, &img, &w, &h, NULL, &e) == SS_ERR_INVALID && img == NULL);
  shift[3] = 3;
  labels[2] = 2;
  CHECK(ss_render_map_comparison(&c, &o, &img, &w, &h, NULL, &e) == SS_ERR_INVALID && img == NULL);
  labels[2] = 0;
  pair0 = 2;
  CHECK(ss_render_map_comparison(&c, &o, &img, &w, &h, NULL, &e) == SS_ERR_INVALID);
  pair0 = 0;
  lm[1] = -1;
  CHECK(ss_render_map_comparison(&c, &o, &img, &w, &h, NULL, &e) == SS_ERR_INVALID);
  lm[1] = 5;
  c.nmaps = 0;
  CHECK(ss_render_map_comparison(&c, &o, &img, &w, &h, NULL, &e) == SS_ERR_INVALID);
  c.nmaps = 2;
  CHECK(ss_render_map_comparison(&c, &o, &img, &w, &h, NULL, &e) == SS_OK);
  free(img);
  CHECK(ss_render_map_comparison(&c, &o, NULL, &w, &h, NULL, &e) == SS_ERR_INVALID);
  /* NaN errors (e.g. unreachable vertices) do not disturb the automatic scale */
  c.error_max = 0;
  for (int i = 0; i < n; i += 3) e1[i] = NAN;
  ss_status stn = ss_render_map_comparison(&c, &o, &img, &w, &h, &hi, &e);
  CHECK_MSG(stn == SS_OK, "NaN errors: %s", e.msg);
  CHECK_MSG(isfinite(hi) && hi > 0, "scale with NaN errors: %g", hi);
  free(img);

  free(ident), free(shift), free(labels), free(e0), free(e1);
  ss_mesh_free(&s);
  TEST_MAIN_END();
}
