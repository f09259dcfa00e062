/* Defaults and checks of the functional-map options, and of the shapes they are applied to. */
#include "fmap/fmap_options.h"

#include <math.h>
#include <string.h>

void ss_fmap_match_default_options(ss_fmap_match_options *o) {
  memset(o, 0, sizeof *o);
  o->k = 50;
  o->n_energies = 100;
  o->sigma_factor = 7.0;
  o->descr_step = 5;
  o->w_descr = 30.0; /* tuned on FAUST; see docs/tuning.md */
  o->w_lap = 1e-3;
  o->w_dcomm = 1.0;
  o->fix_constant = 1;
  o->zoomout_kmax = 0;
  o->zoomout_step = 1;
  o->w_extra = 0.5; /* tuned on FAUST; see docs/tuning.md */
  o->extra_dcomm = 0;
  o->descr_k = 0;
  o->zoomout_samples = 0;
  o->no_wks = 0;
  o->w_orient = 0.0;
}

ss_status ssi_fmap_check_options(const ss_fmap_match_options *o, ss_error *err) {
  if (o->k < 3 || o->n_energies < 1 || o->descr_step < 1 || !(o->sigma_factor > 0) || !isfinite(o->sigma_factor))
    return ss_fail(err, SS_ERR_INVALID, "match: invalid options (k %d, energies %d, step %d, sigma %g)", o->k,
                   o->n_energies, o->descr_step, o->sigma_factor);
  if (!(o->w_descr >= 0) || !(o->w_lap >= 0) || !(o->w_dcomm >= 0) || !isfinite(o->w_descr) || !isfinite(o->w_lap) ||
      !isfinite(o->w_dcomm))
    return ss_fail(err, SS_ERR_INVALID, "match: weights must be finite and non-negative (%g, %g, %g)", o->w_descr,
                   o->w_lap, o->w_dcomm);
  /* above 1e6 the orientation term swamps every other (the CLI's --orient has the same bound) */
  if (!(o->w_orient >= 0 && o->w_orient <= 1e6))
    return ss_fail(err, SS_ERR_INVALID, "match: orientation weight %g must be in [0, 1e6]", o->w_orient);
  if (!(o->w_extra >= 0) || !isfinite(o->w_extra))
    return ss_fail(err, SS_ERR_INVALID, "match: negative extra-probe weight %g", o->w_extra);
  if (o->zoomout_samples < 0) return ss_fail(err, SS_ERR_INVALID, "match: ZoomOut samples %d below 0", o->zoomout_samples);
  if (o->zoomout_step < 1) return ss_fail(err, SS_ERR_INVALID, "match: ZoomOut step %d below 1", o->zoomout_step);
  if (o->zoomout_kmax != 0 && o->zoomout_kmax < o->k)
    return ss_fail(err, SS_ERR_INVALID, "match: ZoomOut size %d below k = %d", o->zoomout_kmax, o->k);
  if (o->descr_k != 0 && o->descr_k < o->k)
    return ss_fail(err, SS_ERR_INVALID, "match: descriptor basis %d below k = %d", o->descr_k, o->k);
  return SS_OK;
}

ss_status ssi_fmap_options_resolve(const ss_fmap_match_options *opts, ss_fmap_match_options *o, ss_error *err) {
  if (opts) *o = *opts;
  else ss_fmap_match_default_options(o);
  return ssi_fmap_check_options(o, err);
}

ss_status ssi_fmap_check_shape(const ss_fmap_shape *s, const char *name, int need, ss_error *err) {
  if (!s || !s->mesh || !s->evals || !s->evecs || s->mesh->nv < 1)
    return ss_fail(err, SS_ERR_INVALID, "match: shape %s incomplete", name);
  if (s->kev < need)
    return ss_fail(err, SS_ERR_INVALID, "match: shape %s has %d eigenpairs, %d needed", name, s->kev, need);
  return SS_OK;
}

int ssi_fmap_basis_needed(const ss_fmap_match_options *o) {
  int need = o->zoomout_kmax > o->k ? o->zoomout_kmax : o->k;
  return o->descr_k > need ? o->descr_k : need;
}

int ssi_fmap_descr_k(const ss_fmap_match_options *o) { return o->descr_k > o->k ? o->descr_k : o->k; }
