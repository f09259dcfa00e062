/* Software rasteriser: background, colours where they must be, the z-buffer hides the back. */
#include "specseg/mesh.h"
#include "specseg/synth.h"
#include "specseg/render.h"
#include "testlib.h"

#include <unistd.h>

static const unsigned char *px(const unsigned char *img, int w, int x, int y) { return img + 3 * ((size_t)y * w + x); }
static int is_bg(const unsigned char *p) { return p[0] == 255 && p[1] == 255 && p[2] == 255; }

int main(void) {
  ss_mesh s;
  CHECK(ss_synth_icosphere(3, &s, NULL) == SS_OK);
  unsigned char *vc = malloc(3 * (size_t)s.nv);
  /* front hemisphere (z > 0) pure green, back pure blue: a front view must show no blue */
  for (int i = 0; i < s.nv; i++) {
    int front = s.V[3 * i + 2] > 0;
    vc[3 * i] = 0; vc[3 * i + 1] = front ? 255 : 0; vc[3 * i + 2] = front ? 0 : 255;
  }
  ss_render_options o;
  ss_render_default_options(&o);
  o.width = o.height = 101;
  unsigned char *img = malloc(3 * 101 * 101);
  CHECK(ss_render_mesh(&s, vc, NULL, &o, img, NULL) == SS_OK);
  const unsigned char *c = px(img, 101, 50, 50), *corner = px(img, 101, 0, 0);
  CHECK(corner[0] == 255 && corner[1] == 255 && corner[2] == 255);
  CHECK_MSG(c[1] > 150 && c[2] < 30 && c[0] < 80, "centre %d %d %d", c[0], c[1], c[2]);
  int blue = 0, shape = 0;
  for (int y = 0; y < 101; y++)
    for (int x = 0; x < 101; x++) {
      const unsigned char *p = px(img, 101, x, y);
      if (!(p[0] == 255 && p[1] == 255 && p[2] == 255)) shape++;
      /* rim triangles straddle z = 0 and blend both colours: look inside the silhouette only */
      double r = hypot(x - 50, y - 50) / (50 * 0.9);
      if (r < 0.9 && p[2] > p[1] + 40) blue++;
    }
  CHECK(blue == 0);
  /* the disc covers ~π/4 of the fitted square (margin 5%) */
  double frac = shape / (101.0 * 101.0), expect = M_PI / 4 * 0.9 * 0.9;
  CHECK_NEAR(frac, expect, 0.03);
  /* from the back, the blue side shows */
  o.azimuth = 180;
  CHECK(ss_render_mesh(&s, vc, NULL, &o, img, NULL) == SS_OK);
  c = px(img, 101, 50, 50);
  CHECK_MSG(c[2] > 150 && c[1] < 30, "back centre %d %d %d", c[0], c[1], c[2]);
  /* per-face colours win: top faces red */
  unsigned char *fc = malloc(3 * (size_t)s.nf);
  for (int f = 0; f < s.nf; f++) {
    double y = s.V[3 * s.F[3 * f] + 1] + s.V[3 * s.F[3 * f + 1] + 1] + s.V[3 * s.F[3 * f + 2] + 1];
    ss_label_color(y > 0 ? 0 : 3, fc + 3 * f);
  }
  o.azimuth = 0;
  CHECK(ss_render_mesh(&s, NULL, fc, &o, img, NULL) == SS_OK);
  unsigned char red[3], blu[3];
  ss_label_color(0, red); ss_label_color(3, blu);
  const unsigned char *top = px(img, 101, 50, 25), *bot = px(img, 101, 50, 75);
  CHECK_MSG(top[0] > top[2] + 60, "top %d %d %d", top[0], top[1], top[2]);
  CHECK_MSG(bot[2] > bot[0] + 60, "bottom %d %d %d", bot[0], bot[1], bot[2]);
  /* bad size is an error */
  o.width = 0;
  CHECK(ss_render_mesh(&s, NULL, NULL, &o, img, NULL) == SS_ERR_INVALID);
  /* colormap ends and monotone luminance */
  unsigned char a[3], b[3];
  ss_colormap(0, a); ss_colormap(1, b);
  CHECK(a[0] == 68 && b[1] == 231);
  double prev = -1; int mono = 1;
  for (int i = 0; i <= 100; i++) {
    ss_colormap(i / 100.0, a);
    double lum = 0.2126 * a[0] + 0.7152 * a[1] + 0.0722 * a[2];
    if (lum < prev - 0.5) mono = 0;
    prev = lum;
  }
  CHECK(mono);
  /* PNG signature */
  o.width = 101;
  char path[] = "/tmp/ss_test_render.png";
  CHECK(ss_write_png(path, img, 101, 101, NULL) == SS_OK);
  FILE *f = fopen(path, "rb");
  unsigned char sig[8] = {0};
  if (f) { CHECK(fread(sig, 1, 8, f) == 8); fclose(f); }
  CHECK(sig[0] == 0x89 && sig[1] == 'P' && sig[2] == 'N' && sig[3] == 'G');
  remove(path);
  CHECK(ss_write_png("/nonexistent-dir/x.png", img, 101, 101, NULL) == SS_ERR_IO);
  /* a failed write: the reason in the message, nothing printed (libpng's own handler wrote
   * "libpng error: Write Error" on stderr) */
  if ((f = fopen("/dev/full", "wb")) != NULL) {
    fclose(f);
    fflush(stderr);
    FILE *cap = tmpfile();
    int saved = dup(2);
    if (cap && saved >= 0) dup2(fileno(cap), 2);
    ss_error e = {{0}};
    ss_status st = ss_write_png("/dev/full", img, 101, 101, &e);
    fflush(stderr);
    if (cap && saved >= 0) dup2(saved, 2), close(saved);
    long printed = cap ? (fseek(cap, 0, SEEK_END), ftell(cap)) : 0;
    if (cap) fclose(cap);
    CHECK(st == SS_ERR_IO);
    CHECK_MSG(strstr(e.msg, "/dev/full: PNG write failed: No space left on device") != NULL, "%s", e.msg);
    CHECK_MSG(printed == 0, "%ld bytes printed on stderr", printed);
  }

  /* ---- fitted scale and a fixed scale ---- */
  o.width = o.height = 101;
  o.azimuth = 0;
  CHECK_NEAR(ss_render_fit_scale(&s, &o), 0.9 * 101 / 2, 0.6); /* the icosphere's extent is ~2 */
  o.scale = 20; /* radius 1 -> a disc of radius 20 pixels */
  CHECK(ss_render_mesh(&s, NULL, NULL, &o, img, NULL) == SS_OK);
  CHECK(!is_bg(px(img, 101, 50 + 15, 50)) && is_bg(px(img, 101, 50 + 25, 50)));
  CHECK(!is_bg(px(img, 101, 50, 50 - 15)) && is_bg(px(img, 101, 50, 50 - 25)));
  o.scale = 0;

  /* ---- the z-buffer: two overlapping squares, the nearer one wins whatever the drawing order ---- */
  {
    ss_mesh q;
    CHECK(ss_mesh_alloc(&q, 8, 4, NULL) == SS_OK);
    const double sq[8][3] = {{-1, -1, 0}, {0.5, -1, 0}, {0.5, 0.5, 0}, {-1, 0.5, 0},
                             {-0.5, -0.5, 1}, {1, -0.5, 1}, {1, 1, 1}, {-0.5, 1, 1}};
    memcpy(q.V, sq, sizeof sq);
    for (int order = 0; order < 2; order++) {
      const int back[2][3] = {{0, 1, 2}, {0, 2, 3}}, front[2][3] = {{4, 5, 6}, {4, 6, 7}};
      for (int f = 0; f < 2; f++) {
        memcpy(q.F + 3 * (order ? f : f + 2), back[f], sizeof back[f]);
        memcpy(q.F + 3 * (order ? f + 2 : f), front[f], sizeof front[f]);
      }
      unsigned char qc[12];
      for (int f = 0; f < 4; f++) {
        int is_front = q.F[3 * f] >= 4;
        qc[3 * f] = is_front ? 250 : 0, qc[3 * f + 1] = 0, qc[3 * f + 2] = is_front ? 0 : 250;
      }
      CHECK(ss_render_mesh(&q, NULL, qc, &o, img, NULL) == SS_OK);
      /* image centre = world (0, 0): inside both squares */
      const unsigned char *p = px(img, 101, 50, 50);
      CHECK_MSG(p[0] > 150 && p[2] < 60, "order %d: overlap %d %d %d", order, p[0], p[1], p[2]);
      /* world (-0.8, -0.8): only the back square */
      p = px(img, 101, 50 - 36, 50 + 36);
      CHECK_MSG(p[2] > 150 && p[0] < 60, "order %d: back only %d %d %d", order, p[0], p[1], p[2]);
    }
    /* seen from behind the order flips */
    o.azimuth = 180;
    CHECK(ss_render_mesh(&q, NULL, (unsigned char[12]){0, 0, 250, 0, 0, 250, 250, 0, 0, 250, 0, 0}, &o, img, NULL) ==
          SS_OK);
    const unsigned char *p = px(img, 101, 50, 50);
    CHECK_MSG(p[2] > 150 && p[0] < 60, "from behind %d %d %d", p[0], p[1], p[2]);
    o.azimuth = 0;
    ss_mesh_free(&q);
  }

  /* ---- isolines of the height on the sphere: levels -0.5, 0, 0.5 for 3 lines over [-1, 1] ---- */
  {
    double *hgt = malloc(sizeof(double) * s.nv);
    for (int i = 0; i < s.nv; i++) hgt[i] = s.V[3 * i + 1];
    unsigned char *grey = malloc(3 * (size_t)s.nv);
    memset(grey, 200, 3 * (size_t)s.nv);
    ss_render_scene sc;
    ss_render_scene_init(&sc, &s);
    sc.vertex_rgb = grey;
    sc.scalar = hgt;
    sc.isolines = 3;
    sc.scalar_min = -1, sc.scalar_max = 1;
    o.scale = 40; /* sphere radius = 40 px; y = 0 at row 50 */
    CHECK(ss_render(&sc, &o, img, NULL) == SS_OK);
    int dark_rows = 0, lines_at[3] = {0, 0, 0};
    for (int y = 22; y <= 78; y++) { /* |height| <= 0.7: away from the dark rim */
      const unsigned char *p = px(img, 101, 50, y);
      if (p[0] < 120) {
        dark_rows++;
        for (int l = 0; l < 3; l++)
          if (fabs(y + 0.5 - (50.5 - 40 * (0.5 * l - 0.5))) <= 2) lines_at[l] = 1;
      }
    }
    CHECK_MSG(lines_at[0] && lines_at[1] && lines_at[2], "isolines at %d %d %d", lines_at[0], lines_at[1], lines_at[2]);
    CHECK_MSG(dark_rows >= 3 && dark_rows <= 9, "%d dark rows along the centre column", dark_rows);
    /* between the lines the surface keeps its colour */
    CHECK(px(img, 101, 50, 50 - 10)[0] > 150 && px(img, 101, 50, 50 + 10)[0] > 150);
    /* no isolines -> no dark pixels at all on the centre column */
    sc.isolines = 0;
    CHECK(ss_render(&sc, &o, img, NULL) == SS_OK);
    int dark = 0;
    for (int y = 22; y <= 78; y++) dark += px(img, 101, 50, y)[0] < 120;
    CHECK(dark == 0);
    free(hgt); free(grey);
  }

  /* ---- markers: a sphere at the front pole shows, one at the back pole is hidden ---- */
  {
    const double front_pole[3] = {0, 0, 1.02}, back_pole[3] = {0, 0, -1.02};
    const unsigned char red[3] = {250, 0, 0};
    ss_render_scene sc;
    ss_render_scene_init(&sc, &s);
    sc.nmarkers = 1, sc.marker_rgb = red, sc.marker_radius = 0.15;
    sc.markers = front_pole;
    CHECK(ss_render(&sc, &o, img, NULL) == SS_OK);
    const unsigned char *p = px(img, 101, 50, 50);
    CHECK_MSG(p[0] > 180 && p[1] < 60, "front marker %d %d %d", p[0], p[1], p[2]);
    sc.markers = back_pole;
    CHECK(ss_render(&sc, &o, img, NULL) == SS_OK);
    p = px(img, 101, 50, 50);
    CHECK_MSG(abs(p[0] - p[1]) < 10, "back marker must be hidden: %d %d %d", p[0], p[1], p[2]);
    sc.markers = NULL;
    CHECK(ss_render(&sc, &o, img, NULL) == SS_ERR_INVALID);
  }

  /* ---- deterministic, supersampling keeps the colours ---- */
  {
    unsigned char *img2 = malloc(3 * 101 * 101);
    CHECK(ss_render_mesh(&s, vc, NULL, &o, img, NULL) == SS_OK);
    CHECK(ss_render_mesh(&s, vc, NULL, &o, img2, NULL) == SS_OK);
    CHECK(memcmp(img, img2, 3 * 101 * 101) == 0);
    o.supersample = 1;
    CHECK(ss_render_mesh(&s, vc, NULL, &o, img2, NULL) == SS_OK);
    const unsigned char *a1 = px(img, 101, 50, 50), *a2 = px(img2, 101, 50, 50);
    CHECK(abs(a1[0] - a2[0]) + abs(a1[1] - a2[1]) + abs(a1[2] - a2[2]) < 12);
    o.supersample = 2;
    free(img2);
  }

  /* ---- segmentation colours: boundary faces neutral, alignment of ids ---- */
  {
    int *lab = malloc(sizeof(int) * s.nv), *ref = malloc(sizeof(int) * s.nv);
    for (int i = 0; i < s.nv; i++) {
      ref[i] = s.V[3 * i + 1] > 0;       /* top = 1, bottom = 0 */
      lab[i] = s.V[3 * i + 1] > 0 ? 0 : 5; /* the same split with other ids */
    }
    unsigned char *fcol = malloc(3 * (size_t)s.nf), l0[3], l5[3];
    const unsigned char neutral[3] = {1, 2, 3};
    CHECK(ss_segmentation_face_colors(&s, lab, neutral, fcol, NULL) == SS_OK);
    ss_label_color(0, l0), ss_label_color(5, l5);
    int nneutral = 0, ok = 1;
    for (int f = 0; f < s.nf; f++) {
      const int *t = s.F + 3 * f;
      int same = lab[t[0]] == lab[t[1]] && lab[t[0]] == lab[t[2]];
      const unsigned char *want = !same ? neutral : (lab[t[0]] == 0 ? l0 : l5);
      if (memcmp(fcol + 3 * f, want, 3)) ok = 0;
      nneutral += !same;
    }
    CHECK(ok && nneutral > 0 && nneutral < s.nf / 4);
    CHECK(ss_labels_align(lab, ref, s.nv, NULL) == SS_OK);
    int agree = 1;
    for (int i = 0; i < s.nv; i++) agree &= lab[i] == ref[i];
    CHECK(agree);
    lab[0] = -7;
    CHECK(ss_labels_align(lab, ref, s.nv, NULL) == SS_ERR_INVALID);
    free(lab); free(ref); free(fcol);
  }

  /* ---- hostile coordinates: NaN and huge vertices are skipped, nothing overflows ---- */
  {
    ss_mesh h;
    CHECK(ss_mesh_copy(&s, &h, NULL) == SS_OK);
    h.V[0] = NAN;
    h.V[4] = 1e300;
    h.V[8] = -1e300;
    o.scale = 0;
    CHECK(ss_render_mesh(&h, NULL, NULL, &o, img, NULL) == SS_OK);
    o.scale = 1e200; /* everything far outside the image */
    CHECK(ss_render_mesh(&h, NULL, NULL, &o, img, NULL) == SS_OK);
    const double far_marker[3] = {1e250, -1e250, 0};
    ss_render_scene sc;
    ss_render_scene_init(&sc, &h);
    sc.nmarkers = 1, sc.markers = far_marker, sc.marker_radius = 1e280;
    CHECK(ss_render(&sc, &o, img, NULL) == SS_OK);
    o.scale = 0;
    ss_mesh_free(&h);
  }

  /* ---- 2-D drawing: text, colour bar, blit ---- */
  {
    const unsigned char black[3] = {0, 0, 0}, white[3] = {255, 255, 255};
    ss_image_fill(img, 101, 101, white);
    int w = ss_draw_text(img, 101, 101, 2, 2, 1, black, "0.5");
    CHECK(w == ss_text_width("0.5", 1) && w == 17);
    int ink = 0, outside = 0;
    for (int y = 0; y < 101; y++)
      for (int x = 0; x < 101; x++) {
        int on = px(img, 101, x, y)[0] == 0;
        if (x >= 2 && x < 2 + w && y >= 2 && y < 9) ink += on;
        else outside += on;
      }
    CHECK(ink > 10 && outside == 0);
    ss_image_fill(img, 101, 101, white);
    ss_draw_colorbar(img, 101, 101, 10, 20, 8, 60, SS_CMAP_HEAT, 0, 1, "e", 1, black);
    unsigned char top[3], bot[3];
    ss_colormap_kind_rgb(SS_CMAP_HEAT, 1, top);
    ss_colormap_kind_rgb(SS_CMAP_HEAT, 0, bot);
    CHECK(memcmp(px(img, 101, 13, 20), top, 3) == 0 && memcmp(px(img, 101, 13, 79), bot, 3) == 0);
    CHECK(bot[0] == 255 && bot[1] == 255 && bot[2] == 255); /* zero error is white */
    unsigned char small[3 * 4] = {9, 9, 9, 9, 9, 9, 9, 9, 9, 9, 9, 9};
    ss_image_blit(img, 101, 101, small, 2, 2, 100, 100); /* clipped to one pixel */
    CHECK(px(img, 101, 100, 100)[0] == 9 && px(img, 101, 99, 99)[0] != 9);
  }
  free(img); free(vc); free(fc);
  ss_mesh_free(&s);
  TEST_MAIN_END();
}
