/* ss_match_refine: a given point map X -> Y through the match's refinement (its functional map at
 * the match's size k, then the match's ZoomOut), so that a rough map (another method's, a few
 * landmarks' nearest neighbours) gets what specseg match gives its own. */
#include "specseg/match.h"
#include "match/match_internal.h"

#include <stdlib.h>
#include <string.h>

ss_status ss_match_refine(const ss_shape_prep *X, const ss_shape_prep *Y, const int *map_in, const ss_match_options *opts,
                          int *map_out, double *C_out, ss_error *err) {
  ss_match_options o;
  if (opts) o = *opts;
  else ss_match_default_options(&o);
  if (!X || !Y || !X->mesh || !Y->mesh || !X->evecs || !Y->evecs || !X->M || !Y->M)
    return ss_fail(err, SS_ERR_INVALID, "refine: shapes not prepared");
  if (!map_in || !map_out) return ss_fail(err, SS_ERR_INVALID, "refine: NULL map");
  const int nX = X->mesh->nv, nY = Y->mesh->nv, k = o.fmap.k;
  const int kz = o.fmap.zoomout_kmax > k ? o.fmap.zoomout_kmax : k;
  if (k < 1 || o.fmap.zoomout_kmax < 0 || o.fmap.zoomout_step < 0 || o.fmap.zoomout_samples < 0)
    return ss_fail(err, SS_ERR_INVALID, "refine: bad sizes (k %d, ZoomOut %d, step %d, samples %d)", k,
                   o.fmap.zoomout_kmax, o.fmap.zoomout_step, o.fmap.zoomout_samples);
  if (X->kev < kz || Y->kev < kz)
    return ss_fail(err, SS_ERR_INVALID, "refine: %s has %d eigenpairs, the refinement needs %d (k %d, ZoomOut %d)",
                   X->kev < kz ? "X" : "Y", X->kev < kz ? X->kev : Y->kev, kz, k, o.fmap.zoomout_kmax);
  for (int i = 0; i < nX; i++)
    if (map_in[i] < 0 || map_in[i] >= nY)
      return ss_fail(err, SS_ERR_INVALID, "refine: map entry %d is %d, not a vertex of Y (0..%d)", i, map_in[i], nY - 1);
  /* C maps functions on Y to functions on X, as the match's (source S = Y, target T = X) */
  double *C0 = malloc(sizeof(double) * (size_t)k * k);
  ssi_zoomout_plan plan = {0};
  ss_status st = C0 ? SS_OK : ss_fail(err, SS_ERR_NOMEM, "refine: out of memory");
  if (!st) st = ss_fmap_from_p2p(nY, nX, k, k, Y->evecs, X->evecs, X->M, map_in, C0, err);
  if (!st && kz > k) {
    /* the match's own ZoomOut plan (samples of X, one pass on every vertex at the end) */
    const int step = o.fmap.zoomout_step > 0 ? o.fmap.zoomout_step : 1;
    o.refine = SS_REFINE_BEST; /* (the plan is made for a refining match) */
    st = ssi_match_plan(X, Y, &o, &plan, err);
    if (!st) st = ssi_zoomout_plan_run(&plan, Y->evecs, X->evecs, X->M, k, C0, kz, step, map_out, C_out, err);
  } else if (!st) {
    /* no ZoomOut: the map through its own functional map of size k (a projection that smooths it) */
    st = ss_fmap_p2p(nY, nX, k, k, Y->evecs, X->evecs, C0, map_out, err);
    if (!st && C_out) memcpy(C_out, C0, sizeof(double) * (size_t)k * k);
  }
  ssi_zoomout_plan_free(&plan);
  free(C0);
  return st;
}
