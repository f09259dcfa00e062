/* One match of two prepared shapes from landmarks (paper §6): what a match needs (eigenpairs,
 * segments); the pairing of the segments; their probe functions as extra probes of the functional
 * map (STD / ASA / DIFF); the point map and its refinement (ZoomOut; SS_REFINE_BEST keeps the
 * candidate of least selection energy). */
#include "specseg/match.h"
#include "mesh/mesh_topology.h"
#include "fmap/fmap_options.h"
#include "match/match_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* eigenpairs the options need on each shape */
static int match_kev(const ss_match_options *o) {
  int kev = o->fmap.k;
  if (o->refine != SS_REFINE_NONE && o->fmap.zoomout_kmax > kev) kev = o->fmap.zoomout_kmax;
  if (o->fmap.descr_k > kev) kev = o->fmap.descr_k;
  if (o->probes != SS_PROBES_STD && o->seg_descr_k > kev) kev = o->seg_descr_k;
  return kev;
}

int ss_match_segments(const ss_match_options *opts, int nl) {
  ss_match_options d;
  if (!opts) ss_match_default_options(&d), opts = &d;
  return nl == 0 || opts->probes != SS_PROBES_STD || opts->std_pairs;
}

int ss_match_eigenpairs(const ss_match_options *opts, int nl) {
  ss_match_options d;
  if (!opts) ss_match_default_options(&d), opts = &d;
  int kev = match_kev(opts);
  if (nl == 0) { /* the landmark-free pairing's descriptors and orientation test */
    if (opts->autopair.descr_k > kev) kev = opts->autopair.descr_k;
    if (opts->autopair.orient_k > kev) kev = opts->autopair.orient_k;
  }
  /* the map kept among hypotheses, refined further (with landmarks: the hypotheses beside them) */
  const int hypotheses = nl == 0 || (opts->autopair.hyp_landmarks && opts->autopair.hypotheses > 1 &&
                                     opts->refine == SS_REFINE_BEST && ss_match_segments(opts, nl));
  if (hypotheses && opts->refine != SS_REFINE_NONE && opts->autopair.hyp_final_kmax > kev)
    kev = opts->autopair.hyp_final_kmax;
  return kev;
}

/* the selection energy of SS_REFINE_BEST for the point map X -> Y (see match.h) */
static ss_status select_energy(const ss_shape_prep *X, const ss_shape_prep *Y, const ss_match_options *o, int k, int kz,
                               const ss_fmap_probes *bX, const ss_fmap_probes *bY, const int *map, double *E, ss_error *err) {
  *E = NAN;
  ss_status st = ss_p2p_energy(Y->mesh->nv, X->mesh->nv, Y->evals, X->evals, Y->evecs, X->evecs, X->M, map, k, kz, 1,
                               o->refine_w_lap, E, NULL, NULL, err);
  if (st || !(o->refine_w_descr > 0)) return st;
  double r;
  if ((st = ss_p2p_descr_residual(Y->mesh->nv, X->mesh->nv, Y->evecs, X->evecs, X->M, bY, bX, map, &r, err))) return st;
  *E += o->refine_w_descr * r;
  return SS_OK;
}

void ssi_match_note(ss_match_result *r, const char *msg) {
  size_t n = strlen(r->notes);
  snprintf(r->notes + n, sizeof r->notes - n, "%s%s", n ? "; " : "", msg);
}

static int count_components(const ss_mesh *m) {
  int *comp = malloc(sizeof(int) * (size_t)(m->nv > 0 ? m->nv : 1));
  int nc = comp ? ssi_mesh_components(m, comp) : -1;
  free(comp);
  return nc;
}

/* The functional-map system could not be solved (normal equations singular: "fmap: ... dsposv info
 * N"): say why that usually happens and what to do. */
static void explain_singular(const ss_mesh *X, const ss_mesh *Y, int nl, int npairs, int k, ss_error *err) {
  if (!err) return;
  char what[512];
  snprintf(what, sizeof what, "%.500s", err->msg);
  int cx = count_components(X), cy = count_components(Y);
  if (cx > 1 || cy > 1)
    ss_fail(err, SS_ERR_NUMERIC,
            "match: the functional-map system is singular (%s): X has %d connected components and Y %d, and the "
            "probe functions do not determine the map on components without a landmark; match only the components "
            "that hold landmarks (ss_match does) or put landmarks on every component",
            what, cx, cy);
  else
    ss_fail(err, SS_ERR_NUMERIC,
            "match: the functional-map system is singular (%s): the probe functions (descriptors, %d landmark%s, %d "
            "paired segment%s) do not determine the %d x %d map; use more landmarks or a smaller basis (k)",
            what, nl, nl == 1 ? "" : "s", npairs, npairs == 1 ? "" : "s", k, k);
}

/* a copy of the given pairing, checked against the segmentations */
static ss_status copy_pairs(const ss_segment_pairs *in, const ss_shape_prep *X, const ss_shape_prep *Y, ss_segment_pairs *out,
                            ss_error *err) {
  memset(out, 0, sizeof *out);
  if (in->n < 0 || (in->n > 0 && (!in->sx || !in->sy)))
    return ss_fail(err, SS_ERR_INVALID, "match: bad segment pairs (%d)", in->n);
  for (int p = 0; p < in->n; p++)
    if (in->sx[p] < 0 || in->sx[p] >= X->seg.m || in->sy[p] < 0 || in->sy[p] >= Y->seg.m)
      return ss_fail(err, SS_ERR_INVALID, "match: segment pair %d (%d, %d) out of range (%d, %d segments)", p, in->sx[p],
                     in->sy[p], X->seg.m, Y->seg.m);
  const size_t n = (size_t)(in->n > 0 ? in->n : 1);
  out->sx = malloc(sizeof(int) * n), out->sy = malloc(sizeof(int) * n), out->energy = malloc(sizeof(double) * n);
  if (!out->sx || !out->sy || !out->energy) {
    ss_segment_pairs_free(out);
    return ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
  }
  out->n = in->n, out->nx = in->nx, out->ny = in->ny;
  if (in->n > 0) {
    memcpy(out->sx, in->sx, sizeof(int) * (size_t)in->n);
    memcpy(out->sy, in->sy, sizeof(int) * (size_t)in->n);
    if (in->energy) memcpy(out->energy, in->energy, sizeof(double) * (size_t)in->n);
    else
      for (int p = 0; p < in->n; p++) out->energy[p] = NAN;
  }
  return SS_OK;
}

/* (match_internal.h) */
int ssi_match_zoomout_size(const ss_match_options *o) {
  return o->refine != SS_REFINE_NONE && o->fmap.zoomout_kmax > o->fmap.k ? o->fmap.zoomout_kmax : o->fmap.k;
}

ss_status ssi_match_plan(const ss_shape_prep *X, const ss_shape_prep *Y, const ss_match_options *o,
                         ssi_zoomout_plan *p, ss_error *err) {
  memset(p, 0, sizeof *p);
  const int kz = ssi_match_zoomout_size(o);
  /* (too few eigenpairs: none; the match says so) */
  if (kz <= o->fmap.k || X->kev < kz || Y->kev < kz) return SS_OK;
  return ssi_zoomout_plan_new(Y->mesh, Y->M, Y->evecs, X->mesh, X->M, o->fmap.zoomout_samples, kz, p, err);
}

ss_status ssi_match_core(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX, const int *lmY,
                         const ss_segment_pairs *pairs_in, const ss_match_options *opts_in, ss_match_result *out,
                         ss_error *err) {
  return ssi_match_core_planned(X, Y, nl, lmX, lmY, pairs_in, opts_in, NULL, NULL, out, err);
}

ss_status ssi_match_core_planned(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX,
                                 const int *lmY, const ss_segment_pairs *pairs_in, const ss_match_options *opts_in,
                                 const ssi_zoomout_plan *given_plan, ssi_fmap_work *work, ss_match_result *out,
                                 ss_error *err) {
  double t_start = ss_time();
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  memset(out, 0, sizeof *out);
  out->refine_choice = -1;
  for (int i = 0; i < 4; i++) out->refine_energy[i] = NAN;
  ss_match_options o;
  if (opts_in) o = *opts_in;
  else ss_match_default_options(&o);
  if (!X || !Y || !X->mesh || !Y->mesh || !X->evecs || !Y->evecs)
    return ss_fail(err, SS_ERR_INVALID, "match: shapes not prepared");
  if ((int)o.segment_profile < SS_PROFILE_INDICATOR || o.segment_profile > SS_PROFILE_SOFT)
    return ss_fail(err, SS_ERR_INVALID, "match: unknown segment profile %d", (int)o.segment_profile);
  if (o.probes < SS_PROBES_STD || o.probes > SS_PROBES_DIFF)
    return ss_fail(err, SS_ERR_INVALID, "match: unknown probe set %d", (int)o.probes);
  if (o.seg_descr_k != 0 && o.seg_descr_k < o.fmap.k)
    return ss_fail(err, SS_ERR_INVALID, "match: seg_descr_k %d below k = %d", o.seg_descr_k, o.fmap.k);
  if (o.refine < SS_REFINE_NONE || o.refine > SS_REFINE_BEST)
    return ss_fail(err, SS_ERR_INVALID, "match: unknown refinement %d", (int)o.refine);
  if (!(o.refine_w_lap >= 0) || !isfinite(o.refine_w_lap) || !(o.refine_w_descr >= 0) || !isfinite(o.refine_w_descr))
    return ss_fail(err, SS_ERR_INVALID, "match: refine weights %g, %g must be finite and non-negative", o.refine_w_lap,
                   o.refine_w_descr);
  if (nl < 1 || !lmX || !lmY) return ss_fail(err, SS_ERR_INVALID, "match: needs at least one landmark");
  if (o.ndescr < 0 || (o.ndescr > 0 && (!o.descrX || !o.descrY)))
    return ss_fail(err, SS_ERR_INVALID, "match: %d descriptors without their values", o.ndescr);
  const int nX = X->mesh->nv, nY = Y->mesh->nv, k = o.fmap.k;
  for (int i = 0; i < nl; i++) {
    if (lmX[i] < 0 || lmX[i] >= nX)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on X [0,%d)", i, lmX[i], nX);
    if (lmY[i] < 0 || lmY[i] >= nY)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on Y [0,%d)", i, lmY[i], nY);
  }
  if (k < 3 || (o.fmap.zoomout_kmax != 0 && o.fmap.zoomout_kmax < k))
    return ss_fail(err, SS_ERR_INVALID, "match: bad basis sizes (k %d, ZoomOut %d)", k, o.fmap.zoomout_kmax);
  /* ZoomOut size: only with refinement */
  const int kz = ssi_match_zoomout_size(&o);
  int need = match_kev(&o);
  if (X->kev < need || Y->kev < need)
    return ss_fail(err, SS_ERR_INVALID, "match: %d eigenpairs needed, shapes have %d and %d", need, X->kev, Y->kev);

  ss_status st = SS_OK;
  double *EX = NULL, *EY = NULL, *Ck[2] = {NULL, NULL}, *Cz = NULL, *Cbest = NULL;
  int *zmap = NULL, *smap[2] = {NULL, NULL};
  ss_fmap_probes bX = {0}, bY = {0}, xX = {0}, xY = {0}, sbX = {0}, sbY = {0}; /* sb: STD's base (selection energy) */
  ss_fmap_system *sys = NULL;
  ssi_zoomout_plan plan = {0};
  ss_fmap_probe_cache *cacheX = NULL, *cacheY = NULL; /* this match's own, when the shapes' do not serve */
  int ncacheX = 0, ncacheY = 0;
  out->nX = nX;
  out->t_segment = X->t_segment + Y->t_segment;
  out->t_eigs = X->t_eigs + Y->t_eigs;

  /* 1. pairing of the segments (with STD only when asked for: its map does not use them) */
  double t0 = ss_time();
  if (pairs_in) {
    if ((st = copy_pairs(pairs_in, X, Y, &out->pairs, err))) goto fail;
  } else if (ss_match_segments(&o, nl)) {
    if (!X->seg.centers || !Y->seg.centers) {
      st = ss_fail(err, SS_ERR_INVALID, "match: %s not segmented (ss_shape_prep_compute_spectral): %s",
                   !X->seg.centers ? "X is" : "Y is", o.probes != SS_PROBES_STD ? "ASA and DIFF pair its segments"
                                                                                 : "std_pairs pairs its segments");
      goto fail;
    }
    if ((st = ss_pair_segments_prepared(X, Y, nl, lmX, lmY, &o.pairing, &out->pairs, err))) goto fail;
  }
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

  /* 2. functional maps at size k: STD (base probes alone) and the segment-aided one (with the
   * chosen extra probes), against one assembled system per descriptor basis */
  int use_seg = o.probes != SS_PROBES_STD;
  if (use_seg && nl < o.pairing.min_landmarks) {
    char msg[160];
    snprintf(msg, sizeof msg, "%d landmarks (fewer than %d): no segment probes, STD map", nl, o.pairing.min_landmarks);
    ssi_match_note(out, msg);
    use_seg = 0;
  } else if (use_seg && np == 0) {
    ssi_match_note(out, "no segment paired: STD map");
    use_seg = 0;
  }
  /* candidate starts: 0 STD, 1 segment-aided */
  /* the map check of the pairing (pairing.min_map_share) needs the STD map */
  const int check = use_seg && o.pairing.min_map_share > 0;
  const int want_std = !use_seg || o.refine == SS_REFINE_BEST || check, want_seg = use_seg;
  /* the shape-only parts of the base probes: the shapes' caches, else computed here by the same
   * function (so a prepared shape and its mesh give the same map) */
  if ((st = ssi_match_probe_caches_both(X, Y, &o, &cacheX, &ncacheX, &cacheY, &ncacheY, err))) goto fail;
  ss_fmap_shape sX = {X->mesh, X->M, X->evals, X->evecs, X->kev, o.descrX, o.ndescr, cacheX ? cacheX : X->probe_cache,
                      cacheX ? ncacheX : X->nprobe_cache},
                sY = {Y->mesh, Y->M, Y->evals, Y->evecs, Y->kev, o.descrY, o.ndescr, cacheY ? cacheY : Y->probe_cache,
                      cacheY ? ncacheY : Y->nprobe_cache};
  /* fo[0]: the STD map's options, fo[1]: the segment-aided one's (its own descriptor basis); one
   * assembled system per distinct descriptor basis (ZoomOut is run and timed below) */
  ss_fmap_match_options fo[2];
  ssi_match_start_options(&o, fo);
  const int ops = o.fmap.w_dcomm > 0, xops = ops && o.fmap.extra_dcomm;
  const int own1 = want_seg && (!want_std || ssi_fmap_descr_k(&fo[1]) != ssi_fmap_descr_k(&fo[0])); /* its own base */
  ss_fmap_weights w;
  if ((st = ss_fmap_pair_weights(&sX, &sY, &fo[0], &w, err))) goto fail;
  for (int c = 0; c < 2; c++) {
    if (!(c ? want_seg : want_std)) continue;
    if (c == 1 && check) { /* drop the pairs the STD map contradicts (pairing.c) */
      /* the STD start's point map, kept for the selection energy below */
      int dropped = 0;
      if (!(smap[0] = malloc(sizeof(int) * (size_t)nX))) goto nomem;
      st = ss_fmap_p2p(nY, nX, k, k, Y->evecs, X->evecs, Ck[0], smap[0], err);
      if (!st) st = ss_segment_pairs_check_map(&X->seg, &Y->seg, X->M, smap[0], o.pairing.min_map_share, &out->pairs,
                                               NULL, &dropped, err);
      if (st) goto fail;
      np = out->pairs.n;
      for (int p = 0; p < np; p++)
        out->centerX[p] = X->seg.centers[out->pairs.sx[p]], out->centerY[p] = Y->seg.centers[out->pairs.sy[p]];
      if (dropped) {
        char msg[160];
        snprintf(msg, sizeof msg, "%d of %d segment pairs dropped: the STD map sends under %.2g of the segment there%s",
                 dropped, np + dropped, o.pairing.min_map_share, np ? "" : "; STD map");
        ssi_match_note(out, msg);
      }
      if (np == 0) { use_seg = 0; break; }
    }
    if (c == 0 || own1) {
      if (c == 1 && want_std) {
        /* STD's base probes are kept for the selection energy (it reads their coefficients only) */
        sbX = bX, sbY = bY;
        memset(&bX, 0, sizeof bX), memset(&bY, 0, sizeof bY);
      }
      ss_fmap_probes_free(&bX), ss_fmap_probes_free(&bY);
      ss_fmap_system_free(sys);
      sys = NULL;
      if ((st = ss_fmap_base_probes(&sX, nl, lmX, &fo[c], ops, &bX, err))) goto fail;
      if ((st = ss_fmap_base_probes(&sY, nl, lmY, &fo[c], ops, &bY, err))) goto fail;
      /* source S = Y, target T = X: C maps functions on Y to functions on X, so its point map is X -> Y */
      if ((st = ssi_fmap_system_new_in(k, k, Y->evals, X->evals, &bY, &bX, &w, work, &sys, err))) goto fail;
    }
    if (c == 1) {
      ss_probe_filter filt = o.probes == SS_PROBES_DIFF ? SS_PROBE_WAVE : SS_PROBE_RAW;
      if ((st = ss_segment_probes(&X->seg, np, out->pairs.sx, o.segment_profile, &EX, err))) goto fail;
      if ((st = ss_segment_probes(&Y->seg, np, out->pairs.sy, o.segment_profile, &EY, err))) goto fail;
      if ((st = ss_fmap_extra_probes(&sX, nl, np, EX, filt, &fo[1], xops, &xX, err))) goto fail;
      if ((st = ss_fmap_extra_probes(&sY, nl, np, EY, filt, &fo[1], xops, &xY, err))) goto fail;
    }
    if (!(Ck[c] = malloc(sizeof(double) * (size_t)k * k))) goto nomem;
    if ((st = ssi_fmap_system_solve_in(sys, c ? &xY : NULL, c ? &xX : NULL, o.fmap.w_extra, o.fmap.extra_dcomm, work,
                                       Ck[c], err))) {
      if (st == SS_ERR_NUMERIC) explain_singular(X->mesh, Y->mesh, nl, c ? np : 0, k, err);
      goto fail;
    }
  }
  out->map = malloc(sizeof(int) * (size_t)nX);
  if (!out->map) goto nomem;
  double t2 = ss_time();
  out->t_fmap = t2 - t1;
  /* the ZoomOut plan: the caller's, else made here (counted as ZoomOut time) */
  if (!given_plan && kz > k && (st = ssi_match_plan(X, Y, &o, &plan, err))) goto fail;
  const ssi_zoomout_plan *zp = given_plan ? given_plan : &plan;
  const double t_plan = ss_time() - t2;

  /* 3. point map: unrefined, ZoomOut of the chosen probes' map, or the best of the candidates */
  const int main_c = use_seg ? 1 : 0;
  if (o.refine != SS_REFINE_BEST) {
    if (kz > k) {
      out->kc = kz;
      if (!(out->C = malloc(sizeof(double) * (size_t)kz * kz))) goto nomem;
      int step = o.fmap.zoomout_step > 0 ? o.fmap.zoomout_step : 1;
      if ((st = ssi_zoomout_plan_run(zp, Y->evecs, X->evecs, X->M, k, Ck[main_c], kz, step, out->map, out->C, err)))
        goto fail;
      out->t_zoomout = ss_time() - t2;
    } else {
      if ((st = ss_fmap_p2p(nY, nX, k, k, Y->evecs, X->evecs, Ck[main_c], out->map, err))) goto fail;
      out->kc = k;
      out->C = Ck[main_c];
      Ck[main_c] = NULL;
    }
  } else {
    /* candidates 2c (start c at size k) and 2c+1 (its ZoomOut to kz), selection energy at size kz */
    zmap = malloc(sizeof(int) * (size_t)nX);
    Cz = malloc(sizeof(double) * (size_t)kz * kz);
    Cbest = malloc(sizeof(double) * (size_t)kz * kz);
    if (!zmap || !Cz || !Cbest) goto nomem;
    const int step = o.fmap.zoomout_step > 0 ? o.fmap.zoomout_step : 1;
    /* the STD base probes of the selection energy: kept apart when the segment-aided map had its own */
    const ss_fmap_probes *qX = sbX.A ? &sbX : &bX, *qY = sbY.A ? &sbY : &bY;
    double best = INFINITY;
    int kbest = k;
    /* the starts' energies first (with refine_single only the lower one is refined) */
    for (int c = 0; c < 2; c++) {
      if (!Ck[c]) continue;
      if (!smap[c]) { /* (the map check may have computed the STD start's already) */
        if (!(smap[c] = malloc(sizeof(int) * (size_t)nX))) goto nomem;
        if ((st = ss_fmap_p2p(nY, nX, k, k, Y->evecs, X->evecs, Ck[c], smap[c], err))) goto fail;
      }
      if ((st = select_energy(X, Y, &o, k, kz, qX, qY, smap[c], &out->refine_energy[2 * c], err))) goto fail;
    }
    out->t_zoomout += t_plan;
    for (int c = 0; c < 2; c++) {
      if (!Ck[c]) continue;
      double e0 = out->refine_energy[2 * c], e1 = INFINITY;
      /* refine_single: the other start has the lower energy (ties: STD's is refined) */
      const double eo = out->refine_energy[2 * (1 - c)];
      const int skip = o.refine_single && Ck[1 - c] && (eo < e0 || (eo == e0 && c == 1));
      if (kz > k && !skip) {
        double tz = ss_time();
        if ((st = ssi_zoomout_plan_run(zp, Y->evecs, X->evecs, X->M, k, Ck[c], kz, step, zmap, Cz, err))) goto fail;
        out->t_zoomout += ss_time() - tz;
        if ((st = select_energy(X, Y, &o, k, kz, qX, qY, zmap, &e1, err))) goto fail;
        out->refine_energy[2 * c + 1] = e1;
      }
      /* the start, then its refinement only when it lowers the energy (ties keep the earlier one) */
      if (e0 < best) {
        best = e0, out->refine_choice = 2 * c, kbest = k;
        memcpy(out->map, smap[c], sizeof(int) * (size_t)nX);
        memcpy(Cbest, Ck[c], sizeof(double) * (size_t)k * k);
      }
      if (e1 < best && e1 <= e0) {
        best = e1, out->refine_choice = 2 * c + 1, kbest = kz;
        memcpy(out->map, zmap, sizeof(int) * (size_t)nX);
        memcpy(Cbest, Cz, sizeof(double) * (size_t)kz * kz);
      }
    }
    out->kc = kbest;
    out->C = Cbest;
    Cbest = NULL;
  }
  out->t_total = out->t_segment + out->t_eigs + (ss_time() - t_start);
  goto cleanup;
nomem:
  st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
fail:
  ss_match_result_free(out);
cleanup:
  ss_fmap_system_free(sys);
  ssi_zoomout_plan_free(&plan);
  ss_fmap_probes_free(&bX), ss_fmap_probes_free(&bY), ss_fmap_probes_free(&xX), ss_fmap_probes_free(&xY);
  ss_fmap_probes_free(&sbX), ss_fmap_probes_free(&sbY);
  free(EX), free(EY), free(Ck[0]), free(Ck[1]), free(Cz), free(Cbest), free(zmap);
  free(smap[0]), free(smap[1]);
  for (int i = 0; i < ncacheX; i++) ss_fmap_probe_cache_free(&cacheX[i]);
  for (int i = 0; i < ncacheY; i++) ss_fmap_probe_cache_free(&cacheY[i]);
  free(cacheX), free(cacheY);
  return st;
}
