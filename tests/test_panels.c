/* Panel grids (ss_render_panels), map colour transfer, coordinate colours and landmark files. */
#include "specseg/io.h"
#include "specseg/mesh.h"
#include "specseg/synth.h"
#include "specseg/render.h"
#include "testlib.h"

static const unsigned char *px(const unsigned char *img, int w, int x, int y) { return img + 3 * ((size_t)y * w + x); }
static int is_bg(const unsigned char *p) { return p[0] == 255 && p[1] == 255 && p[2] == 255; }

static void write_text(const char *path, const char *text) {
  FILE *f = fopen(path, "wb");
  if (f) {
    fputs(text, f);
    fclose(f);
  }
}

int main(void) {
  ss_mesh s;
  CHECK(ss_synth_icosphere(2, &s, NULL) == SS_OK);

  /* ---- coordinate colours: red grows with x, green with y, blue with z; inside [0.12, 0.97] ---- */
  unsigned char *c = malloc(3 * (size_t)s.nv), *c2 = malloc(3 * (size_t)s.nv);
  ss_coordinate_colors(&s, c);
  int xmin = 0, xmax = 0, ok_range = 1;
  for (int i = 0; i < s.nv; i++) {
    if (s.V[3 * i] < s.V[3 * xmin]) xmin = i;
    if (s.V[3 * i] > s.V[3 * xmax]) xmax = i;
    for (int d = 0; d < 3; d++) ok_range &= c[3 * i + d] >= 30 && c[3 * i + d] <= 248;
  }
  CHECK(ok_range);
  CHECK(c[3 * xmin] == 31 && c[3 * xmax] == 247);
  /* the pattern only darkens */
  ss_coordinate_pattern_colors(&s, 0.3, c2);
  int darker = 1, some = 0;
  for (int i = 0; i < 3 * s.nv; i++) darker &= c2[i] <= c[i], some += c2[i] + 20 < c[i];
  CHECK(darker && some > 0);
  ss_coordinate_pattern_colors(&s, 0, c2);
  CHECK(memcmp(c, c2, 3 * (size_t)s.nv) == 0);

  /* ---- map transfer: pull-back of the target's colours; out-of-range map entries fail ---- */
  {
    int map[3] = {xmax, xmin, 0};
    unsigned char out[9];
    CHECK(ss_map_transfer_colors(3, map, s.nv, c, out, NULL) == SS_OK);
    CHECK(memcmp(out, c + 3 * xmax, 3) == 0 && memcmp(out + 3, c + 3 * xmin, 3) == 0 && memcmp(out + 6, c, 3) == 0);
    map[2] = s.nv;
    ss_error e = {{0}};
    CHECK(ss_map_transfer_colors(3, map, s.nv, c, out, &e) == SS_ERR_INVALID);
    CHECK(strstr(e.msg, "line 3") != NULL);
  }
  /* ---- scalar colours: colormap ends, non-finite grey ---- */
  {
    double v[4] = {0, 1, NAN, 5};
    unsigned char out[12], lo[3], hi[3];
    ss_scalar_colors(v, 4, SS_CMAP_HEAT, 0, 1, out);
    ss_colormap_kind_rgb(SS_CMAP_HEAT, 0, lo);
    ss_colormap_kind_rgb(SS_CMAP_HEAT, 1, hi);
    CHECK(memcmp(out, lo, 3) == 0 && memcmp(out + 3, hi, 3) == 0 && memcmp(out + 9, hi, 3) == 0);
    CHECK(out[6] == 150 && out[7] == 150 && out[8] == 150);
  }

  /* ---- panels: 3 panels in 2 columns, the last cell empty, titles, a colour bar ---- */
  {
    ss_render_options o;
    ss_render_default_options(&o);
    o.width = 80, o.height = 100;
    ss_panel P[3];
    memset(P, 0, sizeof P);
    ss_render_scene_init(&P[0].scene, &s);
    ss_render_scene_init(&P[1].scene, &s);
    P[0].scene.vertex_rgb = c;
    P[0].title = "a";
    P[1].title = "b";
    P[2].title = "";
    ss_panel_layout L;
    ss_panel_layout_init(&L);
    L.cols = 2;
    L.colorbar = 1;
    L.bar_kind = SS_CMAP_HEAT;
    L.bar_lo = 0, L.bar_hi = 0.0625; /* long tick labels: must not be clipped */
    L.bar_title = "error";
    unsigned char *img = NULL;
    int w = 0, h = 0;
    CHECK(ss_render_panels(P, 3, &o, &L, &img, &w, &h, NULL) == SS_OK);
    /* text scale 1 below 600 px: title line 7 + 6 px */
    CHECK_MSG(h == 2 * (100 + 13), "height %d", h);
    CHECK_MSG(w > 160 && w < 260, "width %d", w);
    if (img) {
      /* panel centres: the sphere in the two rendered cells, background in the empty one */
      CHECK(!is_bg(px(img, w, 40, 50)) && !is_bg(px(img, w, 120, 50)));
      CHECK(is_bg(px(img, w, 120, 113 + 50)));
      /* a title under the first panel (dark pixels in its title band) */
      int dark = 0;
      for (int y = 100; y < 113; y++)
        for (int x = 0; x < 80; x++) dark += px(img, w, x, y)[0] < 100;
      CHECK(dark > 5);
      /* nothing drawn in the last two columns: the bar's labels fit */
      int edge = 0;
      for (int y = 0; y < h; y++) edge += !is_bg(px(img, w, w - 1, y)) + !is_bg(px(img, w, w - 2, y));
      CHECK_MSG(edge == 0, "%d pixels at the right edge", edge);
      /* one common scale: both spheres equally wide on their centre rows */
      int wa = 0, wb = 0;
      for (int x = 0; x < 80; x++) wa += !is_bg(px(img, w, x, 50)), wb += !is_bg(px(img, w, 80 + x, 50));
      CHECK(wa == wb && wa > 40);
    }
    free(img);
    /* a heading adds a text line on top; the empty cell needs no mesh */
    L.heading = "heading";
    CHECK(ss_render_panels(P, 3, &o, &L, &img, &w, &h, NULL) == SS_OK);
    CHECK_MSG(h == 2 * (100 + 13) + 15, "height with heading %d", h);
    free(img);
    /* errors */
    ss_error e = {{0}};
    o.width = 0;
    CHECK(ss_render_panels(P, 3, &o, &L, &img, &w, &h, &e) == SS_ERR_INVALID && img == NULL);
    o.width = 8000, o.height = 8000;
    CHECK(ss_render_panels(P, 3, &o, &L, &img, &w, &h, &e) == SS_ERR_INVALID && img == NULL);
    CHECK(strstr(e.msg, "pixels") != NULL);
    CHECK(ss_render_panels(P, 0, &o, &L, &img, &w, &h, &e) == SS_ERR_INVALID);
    CHECK(ss_render_panels(P, 3, &o, &L, NULL, &w, &h, &e) == SS_ERR_INVALID);
  }

  /* ---- landmark files: one or two columns, comments, errors with line numbers ---- */
  {
    const char *path = "/tmp/ss_test_panels_lm.txt";
    int *a = NULL, *b = NULL, n = 0, cols = 0;
    write_text(path, "# head\n3\n\n5 7  # hand\n");
    CHECK(ss_read_landmarks(path, &a, &b, &n, &cols, NULL) == SS_OK);
    CHECK(n == 2 && cols == 2);
    if (n == 2) CHECK(a[0] == 3 && b[0] == 3 && a[1] == 5 && b[1] == 7);
    free(a), free(b);
    write_text(path, "1\n2\n");
    CHECK(ss_read_landmarks(path, &a, &b, &n, &cols, NULL) == SS_OK && n == 2 && cols == 1);
    free(a), free(b);
    ss_error e = {{0}};
    write_text(path, "1 2\n1 2 3\n");
    CHECK(ss_read_landmarks(path, &a, &b, &n, NULL, &e) == SS_ERR_PARSE && a == NULL);
    CHECK_MSG(strstr(e.msg, ":2:") != NULL, "%s", e.msg);
    CHECK(ss_read_landmarks(path, NULL, &b, &n, NULL, &e) == SS_ERR_INVALID);
    write_text(path, "1 -2\n");
    CHECK(ss_read_landmarks(path, &a, &b, &n, NULL, &e) == SS_ERR_PARSE);
    write_text(path, "1 x\n");
    CHECK(ss_read_landmarks(path, &a, &b, &n, NULL, &e) == SS_ERR_PARSE);
    write_text(path, "# nothing\n");
    CHECK(ss_read_landmarks(path, &a, &b, &n, NULL, &e) == SS_ERR_PARSE);
    remove(path);
    CHECK(ss_read_landmarks("/nonexistent/lm.txt", &a, &b, &n, NULL, &e) == SS_ERR_IO);
  }
  free(c), free(c2);
  ss_mesh_free(&s);
  TEST_MAIN_END();
}
