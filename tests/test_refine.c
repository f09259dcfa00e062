/* ss_match_refine on the synthetic humanoid (all poses share one vertex order: the ground truth is
 * the identity): it is ss_fmap_from_p2p then ss_zoomout, bit for bit, on every vertex; the identity
 * of a shape onto itself stays the identity; a map scrambled within small neighbourhoods comes back
 * near the truth; bad arguments are refused. */
#include "specseg/fmap.h"
#include "specseg/match.h"
#include "specseg/synth.h"
#include "testlib.h"

static double map_error(const ss_mesh *Y, int n, const int *map) {
  double mean = NAN;
  double *e = malloc(sizeof(double) * (size_t)n);
  ss_error err;
  if (!e || ss_map_geodesic_error(Y, n, map, NULL, NULL, e, &mean, &err)) mean = NAN;
  free(e);
  return mean;
}


int main(void) {
  ss_error e;
  ss_mesh X = {0}, Y = {0};
  CHECK(ss_synth_humanoid(0, &X, &e) == SS_OK);
  CHECK(ss_synth_humanoid(5, &Y, &e) == SS_OK);
  const int kev = 60;
  ss_shape_prep pX = {0}, pY = {0};
  if (ss_shape_prep_compute_spectral(&X, kev, &pX, &e) || ss_shape_prep_compute_spectral(&Y, kev, &pY, &e)) {
    printf("prep: %s\n", e.msg);
    CHECK(0);
    TEST_MAIN_END();
  }
  const int n = X.nv, k = 20, kz = 60;
  CHECK(Y.nv == n);
  int *id = malloc(sizeof(int) * n), *rough = malloc(sizeof(int) * n), *out = malloc(sizeof(int) * n),
      *ref = malloc(sizeof(int) * n), *alias = malloc(sizeof(int) * n);
  double *C = malloc(sizeof(double) * kz * kz), *Cref = malloc(sizeof(double) * kz * kz), *C0 = malloc(sizeof(double) * k * k);
  for (int i = 0; i < n; i++) id[i] = i;
  tl_scrambled_identity(X.nv, X.nf, X.F, 7u, rough);
  ss_match_options o;
  ss_match_default_options(&o);
  o.fmap.k = k, o.fmap.zoomout_kmax = kz, o.fmap.zoomout_step = 4;

  /* on every vertex (zoomout_samples 0) it is the functional map of the rough map, then ss_zoomout */
  o.fmap.zoomout_samples = 0;
  CHECK(ss_match_refine(&pX, &pY, rough, &o, out, C, &e) == SS_OK);
  CHECK(ss_fmap_from_p2p(n, n, k, k, pY.evecs, pX.evecs, pX.M, rough, C0, &e) == SS_OK);
  CHECK(ss_zoomout(n, n, pY.evecs, pX.evecs, pX.M, k, C0, kz, 4, ref, Cref, &e) == SS_OK);
  CHECK(memcmp(out, ref, sizeof(int) * n) == 0);
  CHECK(memcmp(C, Cref, sizeof(double) * kz * kz) == 0);
  /* map_out may be map_in */
  memcpy(alias, rough, sizeof(int) * n);
  CHECK(ss_match_refine(&pX, &pY, alias, &o, alias, NULL, &e) == SS_OK);
  CHECK(memcmp(alias, ref, sizeof(int) * n) == 0);

  /* the match's ZoomOut (samples of X, then every vertex): the scrambled map comes back near the truth */
  ss_match_default_options(&o);
  o.fmap.k = k, o.fmap.zoomout_kmax = kz;
  o.fmap.zoomout_samples = n / 4;
  const double e_rough = map_error(&Y, n, rough);
  CHECK(ss_match_refine(&pX, &pY, rough, &o, out, C, &e) == SS_OK);
  const double e_refined = map_error(&Y, n, out);
  int same = 0;
  for (int i = 0; i < n; i++) same += out[i] == i;
  printf("humanoid pose 0 -> 5 (%d vertices), identity scrambled by 2-step walks: error %.4f, refined %.4f, %d of %d "
         "vertices exact\n", n, e_rough, e_refined, same, n);
  CHECK(e_refined < 0.5 * e_rough);
  CHECK(same > n / 4);
  int finite = 1;
  for (int i = 0; i < kz * kz; i++) finite &= isfinite(C[i]) != 0;
  CHECK(finite);

  /* the identity of a shape onto itself stays the identity, with and without ZoomOut */
  CHECK(ss_match_refine(&pX, &pX, id, &o, out, NULL, &e) == SS_OK);
  CHECK(memcmp(out, id, sizeof(int) * n) == 0);
  ss_match_options p = o;
  p.fmap.zoomout_kmax = 0; /* no ZoomOut: the map through its own k x k functional map */
  CHECK(ss_match_refine(&pX, &pX, id, &p, out, C, &e) == SS_OK);
  CHECK(memcmp(out, id, sizeof(int) * n) == 0);
  /* … which is ss_fmap_p2p of ss_fmap_from_p2p, C its k x k map */
  CHECK(ss_match_refine(&pX, &pY, rough, &p, out, C, &e) == SS_OK);
  CHECK(ss_fmap_from_p2p(n, n, k, k, pY.evecs, pX.evecs, pX.M, rough, C0, &e) == SS_OK);
  CHECK(ss_fmap_p2p(n, n, k, k, pY.evecs, pX.evecs, C0, ref, &e) == SS_OK);
  CHECK(memcmp(out, ref, sizeof(int) * n) == 0);
  CHECK(memcmp(C, C0, sizeof(double) * k * k) == 0);

  /* refused: an entry off Y, NULLs, too few eigenpairs, bad sizes */
  memcpy(alias, rough, sizeof(int) * n);
  alias[n / 2] = n;
  CHECK(ss_match_refine(&pX, &pY, alias, &o, out, NULL, &e) == SS_ERR_INVALID && strstr(e.msg, "not a vertex of Y"));
  alias[n / 2] = -1;
  CHECK(ss_match_refine(&pX, &pY, alias, &o, out, NULL, &e) == SS_ERR_INVALID);
  CHECK(ss_match_refine(&pX, &pY, NULL, &o, out, NULL, &e) == SS_ERR_INVALID);
  CHECK(ss_match_refine(&pX, &pY, rough, &o, NULL, NULL, &e) == SS_ERR_INVALID);
  CHECK(ss_match_refine(NULL, &pY, rough, &o, out, NULL, &e) == SS_ERR_INVALID);
  p = o, p.fmap.zoomout_kmax = kev + 1;
  CHECK(ss_match_refine(&pX, &pY, rough, &p, out, NULL, &e) == SS_ERR_INVALID && strstr(e.msg, "eigenpairs"));
  p = o, p.fmap.k = 0;
  CHECK(ss_match_refine(&pX, &pY, rough, &p, out, NULL, &e) == SS_ERR_INVALID);
  p = o, p.fmap.zoomout_samples = -1;
  CHECK(ss_match_refine(&pX, &pY, rough, &p, out, NULL, &e) == SS_ERR_INVALID);
  ss_shape_prep none = {0};
  CHECK(ss_match_refine(&none, &pY, rough, &o, out, NULL, &e) == SS_ERR_INVALID);
  /* NULL options: the match's defaults (k 50, ZoomOut 110): more eigenpairs than these preps have */
  CHECK(ss_match_refine(&pX, &pY, rough, NULL, out, NULL, &e) == SS_ERR_INVALID && strstr(e.msg, "needs 110"));

  free(id), free(rough), free(out), free(ref), free(alias), free(C), free(Cref), free(C0);
  ss_shape_prep_free(&pX), ss_shape_prep_free(&pY);
  ss_mesh_free(&X), ss_mesh_free(&Y);
  TEST_MAIN_END();
}
