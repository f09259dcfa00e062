/* Software rasteriser: background, colours where they must be, the z-buffer hides the back. */
#include "specseg/mesh.h"
#include "specseg/render.h"
#include "testlib.h"

static const unsigned char *px(const unsigned char *img, int w, int x, int y) { return img + 3 * ((size_t)y * w + x); }

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
  free(img); free(vc); free(fc);
  ss_mesh_free(&s);
  TEST_MAIN_END();
}
