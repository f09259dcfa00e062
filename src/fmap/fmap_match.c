/* The functional-map matching pipeline of paper §6: STD (WKS + landmark wave-kernel maps, descriptor
 * commutativity, NO17), plus paired extra probes (ASA raw / DIFF wave-filtered), optional ZoomOut. */
#include "fmap/fmap_options.h"
#include "fmap/fmap_work.h"
#include "specseg/laplacian.h"

#include <cblas.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>


ss_status ss_fmap_pair_weights(const ss_fmap_shape *X, const ss_fmap_shape *Y, const ss_fmap_match_options *opts,
                               ss_fmap_weights *w, ss_error *err) {
  ss_fmap_match_options o;
  ss_status st = ssi_fmap_options_resolve(opts, &o, err);
  if (!st) st = ssi_fmap_check_shape(X, "X", o.k, err);
  if (!st) st = ssi_fmap_check_shape(Y, "Y", o.k, err);
  if (st) return st;
  const int k = o.k;
  double sd = 0, areaX = 0, areaY = 0;
  for (int r = 0; r < k; r++)
    for (int c = 0; c < k; c++) sd += (X->evals[r] - Y->evals[c]) * (X->evals[r] - Y->evals[c]);
  if (X->M)
    for (int x = 0; x < X->mesh->nv; x++) areaX += X->M[x];
  else
    areaX = ss_mesh_area(X->mesh);
  if (Y->M)
    for (int y = 0; y < Y->mesh->nv; y++) areaY += Y->M[y];
  else
    areaY = ss_mesh_area(Y->mesh);
  if (!(areaX > 0) || !(areaY > 0)) return ss_fail(err, SS_ERR_INVALID, "match: shape of zero area");
  ss_fmap_weights ww = {o.w_descr, sd > 0 ? o.w_lap / sd : 0.0, o.w_dcomm, o.fix_constant, 0.0, o.w_orient};
  ww.const_value = (X->evecs[0] * Y->evecs[0] < 0 ? -1.0 : 1.0) * sqrt(areaX / areaY);
  *w = ww;
  return SS_OK;
}

/* ss_fmap_match_finish with the pair's ZoomOut plan when given (NULL: one of its own) */
static ss_status match_finish_planned(const ss_fmap_shape *X, const ss_fmap_shape *Y, const ss_fmap_match_options *opts,
                                      const double *Ck, const ssi_zoomout_plan *given, int *map, double *C,
                                      ss_error *err) {
  ss_fmap_match_options o;
  ss_status st0 = ssi_fmap_options_resolve(opts, &o, err);
  if (st0) return st0;
  const int k = o.k, need = ssi_fmap_basis_needed(&o);
  if (!Ck || !map) return ss_fail(err, SS_ERR_INVALID, "match: NULL functional map or output");
  st0 = ssi_fmap_check_shape(X, "X", need, err);
  if (!st0) st0 = ssi_fmap_check_shape(Y, "Y", need, err);
  if (st0) return st0;
  if (o.zoomout_kmax > k) {
    if (!X->M) return ss_fail(err, SS_ERR_INVALID, "match: ZoomOut needs the masses of X");
    if (given)
      return ssi_zoomout_plan_run(given, Y->evecs, X->evecs, X->M, k, Ck, o.zoomout_kmax, o.zoomout_step, map, C, err);
    ssi_zoomout_plan plan;
    st0 = ssi_zoomout_plan_new(Y->mesh, Y->M, Y->evecs, X->mesh, X->M, o.zoomout_samples, o.zoomout_kmax, &plan, err);
    if (!st0) st0 = ssi_zoomout_plan_run(&plan, Y->evecs, X->evecs, X->M, k, Ck, o.zoomout_kmax, o.zoomout_step, map, C, err);
    ssi_zoomout_plan_free(&plan);
    return st0;
  }
  ss_status st = ss_fmap_p2p(Y->mesh->nv, X->mesh->nv, k, k, Y->evecs, X->evecs, Ck, map, err);
  if (!st && C) memcpy(C, Ck, sizeof(double) * k * k);
  return st;
}

ss_status ss_fmap_match_finish(const ss_fmap_shape *X, const ss_fmap_shape *Y, const ss_fmap_match_options *opts,
                               const double *Ck, int *map, double *C, ss_error *err) {
  return match_finish_planned(X, Y, opts, Ck, NULL, map, C, err);
}

ss_status ss_fmap_match(const ss_fmap_shape *X, const ss_fmap_shape *Y, int nl, const int *lmX, const int *lmY,
                        int nextra, const double *extraX, const double *extraY, ss_probe_filter extra_filter,
                        const ss_fmap_match_options *opts, int *map, double *C, ss_error *err) {
  return ssi_fmap_match_in(X, Y, nl, lmX, lmY, nextra, extraX, extraY, extra_filter, opts, NULL, NULL, map, C, err);
}

ss_status ssi_fmap_match_in(const ss_fmap_shape *X, const ss_fmap_shape *Y, int nl, const int *lmX, const int *lmY,
                            int nextra, const double *extraX, const double *extraY, ss_probe_filter extra_filter,
                            const ss_fmap_match_options *opts, ssi_fmap_work *work, const ssi_zoomout_plan *plan,
                            int *map, double *C, ss_error *err) {
  ss_fmap_match_options o;
  ss_status st = ssi_fmap_options_resolve(opts, &o, err);
  if (st) return st;
  const int need = ssi_fmap_basis_needed(&o);
  st = ssi_fmap_check_shape(X, "X", need, err);
  if (!st) st = ssi_fmap_check_shape(Y, "Y", need, err);
  if (st) return st;
  if (nl < 0 || nextra < 0 || (nl > 0 && (!lmX || !lmY)) || (nextra > 0 && (!extraX || !extraY)))
    return ss_fail(err, SS_ERR_INVALID, "match: missing landmarks or extra probes");
  if (X->ndescr != Y->ndescr)
    return ss_fail(err, SS_ERR_INVALID, "match: %d descriptors on X, %d on Y (columns must correspond)", X->ndescr,
                   Y->ndescr);
  const int k = o.k, ops = o.w_dcomm > 0, xops = ops && o.extra_dcomm;
  ss_fmap_probes bX = {0}, bY = {0}, xX = {0}, xY = {0};
  ss_fmap_system *sys = NULL;
  ss_fmap_shape sX = *X, sY = *Y;
  double *MX = NULL, *MY = NULL, *Ck = malloc(sizeof(double) * k * k);
  if (!Ck) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
  /* masses once for every stage below */
  if (!sX.M) {
    if (!(MX = malloc(sizeof(double) * X->mesh->nv))) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
    if ((st = ss_mass_lumped(X->mesh, SS_MASS_BARYCENTRIC, MX, err))) goto done;
    sX.M = MX;
  }
  if (!sY.M) {
    if (!(MY = malloc(sizeof(double) * Y->mesh->nv))) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
    if ((st = ss_mass_lumped(Y->mesh, SS_MASS_BARYCENTRIC, MY, err))) goto done;
    sY.M = MY;
  }
  if ((st = ss_fmap_base_probes(&sX, nl, lmX, &o, ops, &bX, err))) goto done;
  if ((st = ss_fmap_base_probes(&sY, nl, lmY, &o, ops, &bY, err))) goto done;
  if (nextra > 0) {
    if ((st = ss_fmap_extra_probes(&sX, nl, nextra, extraX, extra_filter, &o, xops, &xX, err))) goto done;
    if ((st = ss_fmap_extra_probes(&sY, nl, nextra, extraY, extra_filter, &o, xops, &xY, err))) goto done;
  }
  /* source S = Y, target T = X: C maps functions on Y to functions on X, so its point map is X -> Y */
  ss_fmap_weights w;
  if ((st = ss_fmap_pair_weights(&sX, &sY, &o, &w, err))) goto done;
  if ((st = ssi_fmap_system_new_in(k, k, Y->evals, X->evals, &bY, &bX, &w, work, &sys, err))) goto done;
  if ((st = ssi_fmap_system_solve_in(sys, nextra > 0 ? &xY : NULL, nextra > 0 ? &xX : NULL, o.w_extra, o.extra_dcomm,
                                     work, Ck, err)))
    goto done;
  st = match_finish_planned(&sX, &sY, &o, Ck, plan, map, C, err);
done:
  ss_fmap_system_free(sys);
  ss_fmap_probes_free(&bX), ss_fmap_probes_free(&bY), ss_fmap_probes_free(&xX), ss_fmap_probes_free(&xY);
  free(MX), free(MY), free(Ck);
  return st;
}
