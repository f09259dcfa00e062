/* The flipped candidates of a landmark-free match (ss_autopair_options.hyp_flip_orient,
 * match_hypotheses.c): X's own left-right symmetry on a mirror-symmetric constructed shape (the
 * synthetic humanoid: the mirror image of every vertex is known), and two TOSCA_r pairs when the data
 * are present, where only a flipped candidate is right: cat10 -> cat3 (every hypothesis came out as the
 * mirror image) and cat3 -> cat4 (the oriented map was wrong and its mirror images the better
 * isometries); and cat9 -> cat5, where only a flip by Y's own symmetry is right. */
#include "match/hypotheses.h"
#include "specseg/io.h"
#include "specseg/match.h"
#include "specseg/synth.h"
#include "testlib.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* X's own left-right symmetry (ssi_symmetry_map) on the humanoid, its front half inflated so that
 * the mirror in x = 0 is its only symmetry: every vertex must land on (or next to) its mirror image,
 * and every vertex off the symmetry plane must move (a failed symmetry leaves part of X on itself) */
static void test_symmetry_map(void) {
  ss_error e = {{0}};
  ss_mesh X = {0};
  CHECK(ss_synth_humanoid(0, &X, &e) == SS_OK);
  for (int i = 0; i < X.nv; i++)
    if (X.V[3 * (size_t)i + 2] > 0) X.V[3 * (size_t)i + 2] *= 1.6;
  const int n = X.nv;
  int *sym = malloc(sizeof(int) * (size_t)n), *S = malloc(sizeof(int) * (size_t)n);
  tl_mirror_map(X.V, n, sym);
  ss_shape_prep pX;
  const int kev = 100;
  CHECK_MSG(ss_shape_prep_compute(&X, NULL, kev, &pX, &e) == SS_OK, "%s", e.msg);
  ss_match_options mo;
  ss_match_default_options(&mo);
  mo.fmap.zoomout_kmax = kev;
  CHECK(mo.autopair.hyp_flip_orient == 1);
  CHECK_MSG(ssi_symmetry_map(&pX, &mo, mo.autopair.hyp_flip_orient, S, &e) == SS_OK, "%s", e.msg);
  const double r = sqrt(ss_mesh_area(&X));
  int near = 0, off_plane = 0, moved = 0;
  for (int i = 0; i < n; i++) {
    const double *p = X.V + 3 * (size_t)S[i], *q = X.V + 3 * (size_t)sym[i];
    const double d = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
    near += d <= 0.05 * r;
    if (sym[i] != i && fabs(X.V[3 * (size_t)i]) > 0.05 * r) off_plane++, moved += S[i] != i;
  }
  printf("the humanoid's own symmetry: %d of %d vertices within 0.05 sqrt(area) of their mirror image; %d of %d "
         "off the symmetry plane moved\n", near, n, moved, off_plane);
  CHECK(near >= 0.9 * n && moved == off_plane);
  ss_shape_prep_free(&pX);
  ss_mesh_free(&X);
  free(sym), free(S);
}

/* reads NAME.vts: one 1-based vertex index a line, returned 0-based; count in *n (NULL on failure) */
static int *read_vts(const char *path, int nv, int *n) {
  FILE *f = fopen(path, "r");
  if (!f) return NULL;
  int cap = 8192, *v = malloc(sizeof(int) * (size_t)cap), x;
  *n = 0;
  while (v && *n < cap && fscanf(f, "%d", &x) == 1) {
    if (x < 1 || x > nv) { free(v), v = NULL; break; }
    v[(*n)++] = x - 1;
  }
  fclose(f);
  return v;
}

/* A TOSCA_r pair a -> b of the tuning split, landmark-free: the kept map must be a flipped candidate
 * (the mirror map composed with a's own symmetry, or b's: by_y 0 or 1, -1 either), keep orientation
 * clearly and have a mean Euclidean error / sqrt(area of b) on the ground-truth points below 0.05.
 * flip_side >= 0 makes the flips by that side alone (ss_autopair_options.hyp_flip_side; -1: the
 * default), and want_right 0 asks for the map to be wrong instead (the other side's flip is needed).
 * - cat10 -> cat3: every pairing hypothesis and the descriptors' candidate came out as the mirror
 *   image (orientation -0.44, error 20.8 x 100), so no selection could help; the flip is the right
 *   way round (error 3.0; here the flipped map 0.03, the mirror 0.15).
 * - cat3 -> cat4: the map kept before the flips kept orientation (0.63) but was wrong (error 16.3);
 *   its mirror images had the lower energy, which is what asks for the flips now (error 2.8). */
static void test_tosca_flip(const char *a, const char *b, int by_y, int flip_side, int want_right) {
  const char *d = tl_data_dir();
  char px[4096], py[4096], vx[4096], vy[4096];
  if (d) {
    snprintf(px, sizeof px, "%s/bcicp_tune/TOSCA_Isometric/vtx_5k/%s.off", d, a);
    snprintf(py, sizeof py, "%s/bcicp_tune/TOSCA_Isometric/vtx_5k/%s.off", d, b);
    snprintf(vx, sizeof vx, "%s/bcicp_tune/TOSCA_Isometric/vtx_5k/corres/%s.vts", d, a);
    snprintf(vy, sizeof vy, "%s/bcicp_tune/TOSCA_Isometric/vtx_5k/corres/%s.vts", d, b);
  }
  FILE *probe = d ? fopen(px, "rb") : NULL;
  if (!probe) { SKIP("TOSCA_r data not found (SS_DATA_DIR/bcicp_tune)"); return; }
  fclose(probe);
  ss_error e = {{0}};
  ss_mesh X = {0}, Y = {0};
  CHECK_MSG(ss_read_mesh(px, &X, &e) == SS_OK && ss_read_mesh(py, &Y, &e) == SS_OK, "%s", e.msg);
  int nx = 0, ny = 0, *gx = read_vts(vx, X.nv, &nx), *gy = read_vts(vy, Y.nv, &ny);
  CHECK(gx && gy && nx > 1000 && ny > 1000);
  ss_match_options mo;
  ss_match_default_options(&mo);
  CHECK(mo.autopair.hyp_flip_side == 2);
  if (flip_side >= 0) mo.autopair.hyp_flip_side = flip_side;
  ss_match_result res;
  memset(&res, 0, sizeof res);
  if (gx && gy && X.nv > 0 && Y.nv > 0) CHECK_MSG(ss_match(&X, &Y, 0, NULL, NULL, &mo, &res, &e) == SS_OK, "%s", e.msg);
  if (res.map) {
    const double area = ss_mesh_area(&Y);
    double err = 0;
    const int np = nx < ny ? nx : ny;
    for (int k = 0; k < np; k++) {
      const double *p = Y.V + 3 * (size_t)res.map[gx[k]], *q = Y.V + 3 * (size_t)gy[k];
      err += sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
    }
    err /= np * sqrt(area);
    const ss_autopair_info *ai = &res.autopair;
    char what[64] = "not a flip";
    if (ai->hyp_flip_of[ai->hypothesis] >= 0)
      snprintf(what, sizeof what, "the flip of #%d by %s's symmetry", ai->hyp_flip_of[ai->hypothesis],
               ai->hyp_flip_by_y[ai->hypothesis] ? "Y" : "X");
    printf("TOSCA_r %s -> %s (flips by %s): #%d of %d kept (%s), orientation %.3f; mean error %.4f "
           "(Euclidean / sqrt(area), %d points)\n", a, b,
           flip_side < 0 ? "default" : flip_side == 0 ? "X" : flip_side == 1 ? "Y" : "both", ai->hypothesis,
           ai->hypotheses, what, ai->hyp_orientation[ai->hypothesis], err, np);
    if (!want_right) {
      /* (twice the right maps' error, 0.023-0.028 here: the polish's second pass took this one from
       * above 0.05 to 0.049, still half mirrored, orientation 0.21) */
      CHECK(err > 0.04 && ai->hyp_flip_of[ai->hypothesis] < 0);
      goto out;
    }
    CHECK(ai->hyp_flip_of[ai->hypothesis] >= 0 && ai->hyp_orientation[ai->hypothesis] > 0.45);
    if (by_y >= 0) CHECK(ai->hyp_flip_by_y[ai->hypothesis] == by_y);
    CHECK(err < 0.05);
    /* the selection: none that keeps orientation when the kept one does not, and none of the kept
     * one's class of lower energy (landmark-free: every candidate is eligible) */
    int lv[SS_MAX_HYPOTHESES];
    for (int h = 0; h < ai->hypotheses; h++) {
      const double or = ai->hyp_orientation[h];
      lv[h] = !(or < mo.autopair.hyp_min_orientation);
      printf("  #%d: energy %.4f, orientation %.3f (class %d), flip of %d%s\n", h, ai->hyp_energy[h], or, lv[h],
             ai->hyp_flip_of[h], ai->hyp_flip_of[h] >= 0 && ai->hyp_flip_by_y[h] ? " by Y" : "");
      /* a flip is never flipped again, and only the flips say which side made them */
      if (ai->hyp_flip_of[h] >= 0) CHECK(ai->hyp_flip_of[ai->hyp_flip_of[h]] < 0);
      else CHECK(ai->hyp_flip_by_y[h] == 0);
    }
    /* each candidate's energy is its distortion, reversed share, own map energy and orientation
     * shortfall below the confident level, weighted as the options say */
    const ss_autopair_options *ao = &mo.autopair;
    for (int h = 0; h < ai->hypotheses; h++) {
      const double me = ai->hyp_map_energy[h], sh = ao->hyp_confident_orientation - ai->hyp_orientation[h];
      const double E = ai->hyp_distortion[h] + ao->hyp_w_reversed * ai->hyp_reversed[h] +
                       (isfinite(me) ? ao->hyp_w_map * me : 0) + (sh > 0 ? ao->hyp_w_orientation * sh : 0);
      CHECK_MSG(fabs(E - ai->hyp_energy[h]) <= 1e-12 * (1 + fabs(E)), "#%d: energy %.15g, its terms sum to %.15g", h,
                ai->hyp_energy[h], E);
    }
    for (int h = 0; h < ai->hypotheses; h++) {
      CHECK(lv[h] <= lv[ai->hypothesis]);
      if (lv[h] == lv[ai->hypothesis]) CHECK(ai->hyp_energy[ai->hypothesis] <= ai->hyp_energy[h]);
    }
    /* the flips were looked for (the kept map is one), and none was needed only if the kept map
     * keeps orientation clearly and no mirror image has the lower energy */
    int flips = 0, mirror_below = 0;
    for (int h = 0; h < ai->hypotheses; h++) {
      flips += ai->hyp_flip_of[h] >= 0;
      mirror_below |= !lv[h] && ai->hyp_energy[h] < ai->hyp_energy[ai->hypothesis];
    }
    CHECK(flips > 0 || (!mirror_below && ai->hyp_orientation[ai->hypothesis] >= ao->hyp_confident_orientation));
  }
out:
  ss_match_result_free(&res);
  free(gx), free(gy);
  ss_mesh_free(&X), ss_mesh_free(&Y);
}

int main(void) {
  test_symmetry_map();
  test_tosca_flip("cat10", "cat3", -1, -1, 1);
  test_tosca_flip("cat3", "cat4", -1, -1, 1);
  /* X = cat9 curled up: its own symmetry map fails, cat5's turns the mirrored map round (10.0 -> 3.9
   * geodesic x 100 with flips by X alone, docs/tuning.md) */
  test_tosca_flip("cat9", "cat5", 1, -1, 1);
  test_tosca_flip("cat9", "cat5", -1, 0, 0);
  TEST_MAIN_END();
}
