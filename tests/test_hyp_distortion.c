/* The hypothesis energy's metric distortion (match/hypotheses.h): with the scale fit, distances that
 * agree up to one common factor give no distortion and that factor as the scale; the factor is
 * clamped to [0.5, 2]; without the fit, the distortion is the plain mean of |d_X/√A_X − d_Y/√A_Y|. */
#include "match/hypotheses.h"
#include "geodesic_meshes.h"
#include "testlib.h"

/* Y = X's grid and, beside it (not joined), a flat square of `extra` times X's area: X's distances
 * are kept on Y's first component while √area(Y) grows by sqrt(1 + extra). */
static void grid_and_square(const ss_mesh *X, double w, double h, double extra, ss_mesh *Y) {
  const int nv = X->nv, nf = X->nf;
  ss_mesh_alloc(Y, nv + 4, nf + 2, NULL);
  memcpy(Y->V, X->V, sizeof(double) * 3 * (size_t)nv);
  memcpy(Y->F, X->F, sizeof(int) * 3 * (size_t)nf);
  const double side = sqrt(extra * w * h), x0 = 2 * w + 1;
  const double sq[12] = {x0, 0, 0, x0 + side, 0, 0, x0 + side, side, 0, x0, side, 0};
  memcpy(Y->V + 3 * (size_t)nv, sq, sizeof sq);
  const int f[6] = {nv, nv + 1, nv + 2, nv, nv + 2, nv + 3};
  memcpy(Y->F + 3 * (size_t)nf, f, sizeof f);
}

/* mean over the context's sources and X's vertices of |a − b/k|, a = d_X/√A_X (the identity map
 * onto Y's copy of X, whose √area is k times X's) */
static double plain_mean(const ssi_hyp_ctx *c, double k) {
  double s = 0;
  long n = 0;
  for (size_t j = 0; j < (size_t)c->X->nv * c->nsrc; j++)
    if (isfinite(c->dX[j])) s += fabs(c->dX[j] / c->sX - c->dX[j] / c->sX / k), n++;
  return s / n;
}

int main(void) {
  ss_mesh X = {0};
  const double w = 2, h = 1;
  gm_flat_grid(21, 11, w, h, 0.3, &X);
  int *id = malloc(sizeof(int) * X.nv);
  for (int v = 0; v < X.nv; v++) id[v] = v;
  ss_error e;
  /* extra area 1: √area ×√2, inside the clamp; extra area 15: ×4, clamped to 2 */
  const double extras[2] = {1, 15}, want_scale[2] = {sqrt(2.0), 2};
  for (int t = 0; t < 2; t++) {
    ss_mesh Y = {0};
    grid_and_square(&X, w, h, extras[t], &Y);
    const double k = sqrt(1 + extras[t]);
    ssi_hyp_ctx c;
    CHECK(ssi_hyp_ctx_new(&X, &Y, 8, 0, &c, &e) == SS_OK);
    CHECK(c.fit_scale == 0 && c.nsrc == 8 && c.scale == 1);
    CHECK_NEAR(c.sY / c.sX, k, 1e-12);
    double d0 = NAN, d1 = NAN;
    /* without the fit: the distances over √area as they are */
    CHECK(ssi_hyp_distortion(&c, id, &d0, &e) == SS_OK);
    CHECK_NEAR(d0, plain_mean(&c, k), 1e-12);
    CHECK(d0 > 0.05 && c.scale == 1);
    /* with it: the factor found, and nothing left (or what the clamp leaves) */
    c.fit_scale = 1;
    CHECK(ssi_hyp_distortion(&c, id, &d1, &e) == SS_OK);
    CHECK_NEAR(c.scale, want_scale[t], 1e-12);
    CHECK_NEAR(d1, plain_mean(&c, k / want_scale[t]), 1e-12);
    if (t == 0) CHECK(d1 < 1e-12);
    else CHECK(d1 > 0.05 && d1 < d0);
    ssi_hyp_ctx_free(&c);
    ss_mesh_free(&Y);
  }
  /* a map that collapses X onto one vertex: no distance to fit, the scale stays 1 */
  {
    ss_mesh Y = {0};
    grid_and_square(&X, w, h, 1, &Y);
    ssi_hyp_ctx c;
    CHECK(ssi_hyp_ctx_new(&X, &Y, 8, 1, &c, &e) == SS_OK && c.fit_scale == 1);
    int *one = calloc(X.nv, sizeof(int));
    double d = NAN;
    CHECK(ssi_hyp_distortion(&c, one, &d, &e) == SS_OK);
    CHECK(c.scale == 1);
    CHECK_NEAR(d, plain_mean(&c, INFINITY), 1e-12);
    free(one);
    ssi_hyp_ctx_free(&c);
    ss_mesh_free(&Y);
  }
  free(id);
  ss_mesh_free(&X);
  TEST_MAIN_END();
}
