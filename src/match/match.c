/* The matching pipeline of paper §6 on two shapes: pairing of the segments, their probe functions as
 * extra probes of the functional map (STD / ASA / DIFF), point map, ZoomOut. */
#include "specseg/match.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void ss_match_default_options(ss_match_options *o) {
  memset(o, 0, sizeof *o);
  o->probes = SS_PROBES_DIFF;
  ss_fmap_match_default_options(&o->fmap);
  ss_segment_default_options(&o->seg);
  o->segment_profile = SS_PROFILE_TENT;
}

void ss_match_result_free(ss_match_result *r) {
  if (!r) return;
  free(r->map);
  free(r->C);
  free(r->centerX);
  free(r->centerY);
  ss_segment_pairs_free(&r->pairs);
  memset(r, 0, sizeof *r);
}

ss_status ss_match_prepared(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX, const int *lmY,
                            const ss_match_options *opts_in, ss_match_result *out, ss_error *err) {
  double t_start = ss_time();
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  memset(out, 0, sizeof *out);
  ss_match_options o;
  if (opts_in) o = *opts_in;
  else ss_match_default_options(&o);
  if (!X || !Y || !X->mesh || !Y->mesh || !X->evecs || !Y->evecs)
    return ss_fail(err, SS_ERR_INVALID, "match: shapes not prepared");
  if ((int)o.segment_profile < SS_PROFILE_INDICATOR || o.segment_profile > SS_PROFILE_SOFT)
    return ss_fail(err, SS_ERR_INVALID, "match: unknown segment profile %d", (int)o.segment_profile);
  if (o.probes < SS_PROBES_STD || o.probes > SS_PROBES_DIFF)
    return ss_fail(err, SS_ERR_INVALID, "match: unknown probe set %d", (int)o.probes);
  if (nl < 1 || !lmX || !lmY) return ss_fail(err, SS_ERR_INVALID, "match: needs at least one landmark");
  if (o.ndescr < 0 || (o.ndescr > 0 && (!o.descrX || !o.descrY)))
    return ss_fail(err, SS_ERR_INVALID, "match: %d descriptors without their values", o.ndescr);
  const int nX = X->mesh->nv, nY = Y->mesh->nv, k = o.fmap.k, kz = o.fmap.zoomout_kmax;
  for (int i = 0; i < nl; i++) {
    if (lmX[i] < 0 || lmX[i] >= nX)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on X [0,%d)", i, lmX[i], nX);
    if (lmY[i] < 0 || lmY[i] >= nY)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on Y [0,%d)", i, lmY[i], nY);
  }
  if (k < 3 || (kz != 0 && kz < k))
    return ss_fail(err, SS_ERR_INVALID, "match: bad basis sizes (k %d, ZoomOut %d)", k, kz);
  int need = kz > k ? kz : k;
  if (X->kev < need || Y->kev < need)
    return ss_fail(err, SS_ERR_INVALID, "match: %d eigenpairs needed, shapes have %d and %d", need, X->kev, Y->kev);

  ss_status st = SS_OK;
  double *EX = NULL, *EY = NULL, *Ck = NULL;
  out->nX = nX;
  out->t_segment = X->t_segment + Y->t_segment;
  out->t_eigs = X->t_eigs + Y->t_eigs;

  /* 1. pairing of the segments (reported for every probe set) */
  double t0 = ss_time();
  if ((st = ss_pair_segments(&X->seg, &Y->seg, nl, lmX, lmY, &out->pairs, err))) goto fail;
  int np = out->pairs.n;
  out->centerX = malloc(sizeof(int) * (size_t)(np > 0 ? np : 1));
  out->centerY = malloc(sizeof(int) * (size_t)(np > 0 ? np : 1));
  if (!out->centerX || !out->centerY) goto nomem;
  for (int p = 0; p < np; p++) {
    out->centerX[p] = X->seg.centers[out->pairs.sx[p]];
    out->centerY[p] = Y->seg.centers[out->pairs.sy[p]];
  }
  double t1 = ss_time();
  out->t_pair = t1 - t0;

  /* 2. functional map at size k with the chosen probes */
  int nextra = o.probes == SS_PROBES_STD ? 0 : np;
  if (nextra > 0) {
    if ((st = ss_segment_probes(&X->seg, np, out->pairs.sx, o.segment_profile, &EX, err))) goto fail;
    if ((st = ss_segment_probes(&Y->seg, np, out->pairs.sy, o.segment_profile, &EY, err))) goto fail;
  }
  out->map = malloc(sizeof(int) * (size_t)nX);
  Ck = malloc(sizeof(double) * (size_t)k * k);
  if (!out->map || !Ck) goto nomem;
  ss_fmap_shape sX = {X->mesh, X->M, X->evals, X->evecs, X->kev, o.descrX, o.ndescr},
                sY = {Y->mesh, Y->M, Y->evals, Y->evecs, Y->kev, o.descrY, o.ndescr};
  ss_fmap_match_options fo = o.fmap;
  fo.zoomout_kmax = 0; /* ZoomOut is run (and timed) below */
  if ((st = ss_fmap_match(&sX, &sY, nl, lmX, lmY, nextra, EX, EY,
                          o.probes == SS_PROBES_DIFF ? SS_PROBE_WAVE : SS_PROBE_RAW, &fo, out->map, Ck, err)))
    goto fail;
  double t2 = ss_time();
  out->t_fmap = t2 - t1;

  /* 3. optional ZoomOut from k to kz */
  if (kz > k) {
    out->kc = kz;
    out->C = malloc(sizeof(double) * (size_t)kz * kz);
    if (!out->C) goto nomem;
    int step = o.fmap.zoomout_step > 0 ? o.fmap.zoomout_step : 1;
    if ((st = ss_zoomout(nY, nX, Y->evecs, X->evecs, X->M, k, Ck, kz, step, out->map, out->C, err))) goto fail;
    out->t_zoomout = ss_time() - t2;
  } else {
    out->kc = k;
    out->C = Ck;
    Ck = NULL;
  }
  out->t_total = out->t_segment + out->t_eigs + (ss_time() - t_start);
  free(EX);
  free(EY);
  free(Ck);
  return SS_OK;
nomem:
  st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
fail:
  free(EX);
  free(EY);
  free(Ck);
  ss_match_result_free(out);
  return st;
}

ss_status ss_match(const ss_mesh *X, const ss_mesh *Y, int nl, const int *lmX, const int *lmY,
                   const ss_match_options *opts_in, ss_match_result *out, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  memset(out, 0, sizeof *out);
  ss_match_options o;
  if (opts_in) o = *opts_in;
  else ss_match_default_options(&o);
  if (!X || !Y) return ss_fail(err, SS_ERR_INVALID, "match: NULL mesh");
  /* check the landmarks before the expensive part */
  if (nl < 1 || !lmX || !lmY) return ss_fail(err, SS_ERR_INVALID, "match: needs at least one landmark");
  for (int i = 0; i < nl; i++) {
    if (lmX[i] < 0 || lmX[i] >= X->nv)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on X [0,%d)", i, lmX[i], X->nv);
    if (lmY[i] < 0 || lmY[i] >= Y->nv)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on Y [0,%d)", i, lmY[i], Y->nv);
  }
  int kev = o.fmap.zoomout_kmax > o.fmap.k ? o.fmap.zoomout_kmax : o.fmap.k;
  ss_shape_prep pX, pY;
  ss_status st = ss_shape_prep_compute(X, &o.seg, kev, &pX, err);
  if (st) return st;
  if ((st = ss_shape_prep_compute(Y, &o.seg, kev, &pY, err))) {
    ss_shape_prep_free(&pX);
    return st;
  }
  st = ss_match_prepared(&pX, &pY, nl, lmX, lmY, &o, out, err);
  ss_shape_prep_free(&pX);
  ss_shape_prep_free(&pY);
  return st;
}
