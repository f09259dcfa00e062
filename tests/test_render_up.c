/* The up axis of the renderer: ss_render_options.up turns the mesh so that the chosen axis is drawn
 * upwards, and ss_render_guess_up finds +y on FAUST (y-up) and +z on TOSCA (z-up) shapes. */
#include "specseg/io.h"
#include "specseg/render.h"
#include "specseg/synth.h"
#include "testlib.h"

/* Bounding box of the non-white pixels: width and height, and the row of the topmost one. */
static void silhouette(const unsigned char *img, int w, int h, int *bw, int *bh) {
  int x0 = w, x1 = -1, y0 = h, y1 = -1;
  for (int y = 0; y < h; y++)
    for (int x = 0; x < w; x++) {
      const unsigned char *p = img + 3 * ((size_t)y * w + x);
      if (p[0] == 255 && p[1] == 255 && p[2] == 255) continue;
      if (x < x0) x0 = x;
      if (x > x1) x1 = x;
      if (y < y0) y0 = y;
      if (y > y1) y1 = y;
    }
  *bw = x1 - x0 + 1, *bh = y1 - y0 + 1;
}

/* (x, y, z) -> (x, -z, y): a y-up mesh becomes z-up (its old +y points along +z). */
static void to_z_up(ss_mesh *m) {
  for (int i = 0; i < m->nv; i++) {
    double *p = m->V + 3 * (size_t)i, y = p[1], z = p[2];
    p[1] = -z, p[2] = y;
  }
}

static ss_up_axis guess1(const ss_mesh *m) {
  const ss_mesh *one[1] = {m};
  return ss_render_guess_up(one, 1);
}

int main(void) {
  /* ---- the rotation: a humanoid (y-up) turned z-up is drawn upright again with up = +z ---- */
  ss_mesh h;
  CHECK(ss_synth_humanoid(0, &h, NULL) == SS_OK);
  for (int i = 0; i < h.nv; i++) h.V[3 * (size_t)i] *= 0.5; /* arms spread: narrower, taller than wide */
  ss_render_options o;
  ss_render_default_options(&o);
  o.width = o.height = 120;
  unsigned char *a = malloc(3 * 120 * 120), *b = malloc(3 * 120 * 120);
  CHECK(ss_render_mesh(&h, NULL, NULL, &o, a, NULL) == SS_OK);
  int aw, ah, bw, bh;
  silhouette(a, 120, 120, &aw, &ah);
  CHECK_MSG(ah > aw, "y-up humanoid %dx%d", aw, ah);
  CHECK(guess1(&h) == SS_UP_Y);
  ss_mesh hz;
  CHECK(ss_mesh_copy(&h, &hz, NULL) == SS_OK);
  to_z_up(&hz);
  CHECK(guess1(&hz) == SS_UP_Z);
  CHECK(ss_render_mesh(&hz, NULL, NULL, &o, b, NULL) == SS_OK); /* default up: lies on its back */
  silhouette(b, 120, 120, &bw, &bh);
  CHECK_MSG(bh < bw || bh < ah / 2, "z-up humanoid drawn y-up: %dx%d", bw, bh);
  o.up = SS_UP_Z;
  CHECK(ss_render_mesh(&hz, NULL, NULL, &o, b, NULL) == SS_OK);
  /* (x, y, z) -> (x, -z, y) then up = +z, (x, z, -y): back to (x, y, z), the same picture */
  CHECK(memcmp(a, b, 3 * 120 * 120) == 0);
  /* upside down: the picture flips, mirrored in both axes (a turn by 180 degrees) */
  o.up = SS_UP_NEG_Y;
  CHECK(ss_render_mesh(&h, NULL, NULL, &o, b, NULL) == SS_OK);
  int flipped = 0, same = 0;
  for (int y = 0; y < 120; y++)
    for (int x = 0; x < 120; x++) {
      const unsigned char *p = a + 3 * ((size_t)y * 120 + x), *q = b + 3 * ((size_t)(119 - y) * 120 + (119 - x));
      int pb = p[0] == 255 && p[1] == 255 && p[2] == 255, qb = q[0] == 255 && q[1] == 255 && q[2] == 255;
      flipped += pb == qb;
      same++;
    }
  CHECK_MSG(flipped > same * 97 / 100, "%d of %d pixels agree with the turned picture", flipped, same);
  /* every axis gives a valid rotation: the fit scale of a sphere does not change */
  ss_mesh s;
  CHECK(ss_synth_icosphere(3, &s, NULL) == SS_OK);
  o.up = 0;
  double s0 = ss_render_fit_scale(&s, &o);
  for (int u = -3; u <= 3; u++) {
    o.up = u;
    CHECK_NEAR(ss_render_fit_scale(&s, &o), s0, 1e-9 * s0);
  }
  CHECK(ss_render_guess_up(NULL, 0) == SS_UP_Y);
  ss_mesh_free(&s);
  ss_mesh_free(&h);
  ss_mesh_free(&hz);

  /* ---- the rule on the data sets ---- */
  const char *dir = tl_data_dir();
  if (!dir) {
    SKIP("FAUST / TOSCA absent (SS_DATA_DIR): up axis of the data sets not checked");
  } else {
    int faust_y = 0, faust_n = 0;
    char path[4200];
    for (int i = 0; i < 100; i++) {
      ss_mesh m;
      snprintf(path, sizeof path, "%s/faust/tr_reg_%03d.off", dir, i);
      if (ss_read_mesh(path, &m, NULL)) continue;
      faust_n++;
      ss_up_axis u = guess1(&m);
      faust_y += u == SS_UP_Y;
      if (i < 10) CHECK_MSG(u == SS_UP_Y, "tr_reg_%03d: up %d", i, (int)u);
      ss_mesh_free(&m);
    }
    CHECK_MSG(faust_n == 100 && faust_y >= 97, "FAUST: +y on %d of %d", faust_y, faust_n);
    static const char *cls[] = {"cat", "centaur", "david", "dog", "horse", "michael", "victoria", "wolf"};
    int tosca_z = 0, tosca_n = 0;
    for (int c = 0; c < 8; c++)
      for (int i = 0; i < 30; i++) {
        ss_mesh m;
        snprintf(path, sizeof path, "%s/tosca/%s%d.off", dir, cls[c], i);
        FILE *f = fopen(path, "rb");
        if (!f) continue;
        fclose(f);
        if (ss_read_mesh(path, &m, NULL)) continue;
        tosca_n++;
        ss_up_axis u = guess1(&m);
        tosca_z += u == SS_UP_Z;
        if (i == 0) CHECK_MSG(u == SS_UP_Z, "%s0: up %d", cls[c], (int)u);
        /* a picture of several shapes of a class: one axis for all */
        ss_mesh_free(&m);
      }
    CHECK_MSG(tosca_n >= 70 && tosca_z >= tosca_n - 4, "TOSCA: +z on %d of %d", tosca_z, tosca_n);
    if (tosca_n == 0) SKIP("TOSCA absent");
  }
  free(a);
  free(b);
  TEST_MAIN_END();
}
