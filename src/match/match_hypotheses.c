/* The hypotheses of a match. Landmark-free (ss_match_prepared_auto): each pairing hypothesis of the
 * landmark-free pairing is mapped with its paired protrusion centres as landmarks, and the map of
 * least hypothesis energy (hypotheses.c) is kept, with the margin that says how sure that is. With
 * landmarks and ss_autopair_options.hyp_landmarks (ssi_match_prepared_signed): the landmarks' map
 * against the hypotheses' maps that agree with them. */
#include "specseg/match.h"
#include "match/autopair_internal.h"
#include "match/hypotheses.h"
#include "match/match_internal.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The landmarks of a hypothesis pr: the centres of its round(keep · n) (at least 3) pairs whose X
 * centre is farthest on average from X's other centres (the protrusions), in pair order; all pairs
 * when keep >= 1. Returns their count. */
static int kept_pairs(const ss_centre_signature *SX, const ss_segment_pairs *pr, double keep, const ss_shape_prep *X,
                      const ss_shape_prep *Y, int *lx, int *ly) {
  const int n = pr->n, m = SX->m;
  int nk = n;
  if (keep < 1 && n > 3) {
    nk = (int)floor(keep * n + 0.5);
    if (nk < 3) nk = 3;
  }
  int q = 0;
  for (int p = 0; p < n; p++) {
    double ep = 0;
    for (int c = 0; c < m; c++) ep += SX->D[pr->sx[p] + (size_t)m * c];
    int rank = 0;
    for (int t = 0; t < n; t++) {
      double et = 0;
      for (int c = 0; c < m; c++) et += SX->D[pr->sx[t] + (size_t)m * c];
      rank += et > ep || (et == ep && t < p);
    }
    if (rank < nk) lx[q] = X->seg.centers[pr->sx[p]], ly[q++] = Y->seg.centers[pr->sy[p]];
  }
  return q;
}

/* The match's functional-map options (base) for a map of basis size k between shapes of kev
 * eigenpairs at least, with the orientation term of weight w_orient: every size within kev, no ZoomOut
 * when it would not grow the basis. */
static ss_fmap_match_options fmap_options_within(const ss_fmap_match_options *base, int kev, int k, double w_orient) {
  ss_fmap_match_options fo = *base;
  fo.k = k < kev ? k : kev;
  if (fo.descr_k > kev) fo.descr_k = kev;
  if (fo.zoomout_kmax > kev) fo.zoomout_kmax = kev;
  if (fo.zoomout_kmax <= fo.k) fo.zoomout_kmax = 0;
  fo.w_orient = w_orient;
  return fo;
}

/* a prepared shape as ss_fmap_match takes it (no descriptors of the caller's), with its probe cache
 * (an entry serves only where its options are those asked; the same bits either way) */
static ss_fmap_shape fmap_shape_of(const ss_shape_prep *p) {
  const ss_fmap_shape s = {p->mesh, p->M, p->evals, p->evecs, p->kev, NULL, 0, p->probe_cache, p->nprobe_cache};
  return s;
}

/* The descriptors' own landmarks (ss_autopair_options.hyp_descriptor_map): X's round(keep · m) (at
 * least 3) centres farthest on average from its others and their images under the functional map of
 * the WKS and the orientation term alone (no landmark, no segment; ZoomOut as the match's, with the
 * plan zp of X -> Y when not NULL), in lx, ly (SX->m room); *nl their count. A pairing-free map:
 * where the segmentations differ too much for any pairing hypothesis to be right (a quadruped curled
 * up), its protrusions still land near their partners. */
static ss_status descriptor_landmarks(const ss_shape_prep *X, const ss_shape_prep *Y, const ss_centre_signature *SX,
                                      const ss_match_options *o, ssi_fmap_work *fw, const ssi_zoomout_plan *zp,
                                      int *lx, int *ly, int *nl, ss_error *err) {
  const int m = SX->m, kmin = X->kev < Y->kev ? X->kev : Y->kev;
  const ss_fmap_match_options fo = fmap_options_within(&o->fmap, kmin, o->fmap.k, o->autopair.hyp_descriptor_orient);
  int *T = malloc(sizeof(int) * (size_t)X->mesh->nv), *kept = malloc(sizeof(int) * (size_t)m);
  if (!T || !kept) {
    free(T), free(kept);
    return ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
  }
  const ss_fmap_shape sX = fmap_shape_of(X), sY = fmap_shape_of(Y);
  /* the match's plan serves where this ZoomOut is the match's (not with fewer eigenpairs than it) */
  const ssi_zoomout_plan *plan = zp && zp->n_S > 0 && fo.zoomout_kmax == ssi_match_zoomout_size(o) ? zp : NULL;
  ss_status st = ssi_fmap_match_in(&sX, &sY, 0, NULL, NULL, 0, NULL, NULL, SS_PROBE_RAW, &fo, fw, plan, T, NULL, err);
  if (!st) {
    int q = 0;
    ssi_kept_centres(SX, o->autopair.hyp_keep, kept);
    for (int a = 0; a < m; a++)
      if (kept[a]) lx[q] = SX->centers[a], ly[q++] = T[SX->centers[a]];
    *nl = q;
  }
  free(T), free(kept);
  return st;
}

/* One candidate of X's left-right self-symmetry (ssi_symmetry_map): the functional map of size k from X
 * to its reflection in a plane (the same intrinsic shape, hence the same eigenpairs) with the WKS
 * and the orientation term of weight w, refined by ZoomOut as the match's. The reflection reverses
 * orientation, so the orientation term turns the trivial answer (the vertex identity, a perfect
 * isometry otherwise) away and keeps the intrinsic mirror. */
static ss_status symmetry_candidate(const ss_shape_prep *X, const ss_mesh *mirror, const ss_match_options *o, int k,
                                    double w, int *S, ss_error *err) {
  const ss_fmap_match_options fo = fmap_options_within(&o->fmap, X->kev, k, w);
  const ss_fmap_shape sX = fmap_shape_of(X);
  ss_fmap_shape sR = sX;
  sR.mesh = mirror;
  return ss_fmap_match(&sX, &sR, 0, NULL, NULL, 0, NULL, NULL, SS_PROBE_RAW, &fo, S, NULL, err);
}

/* (hypotheses.h) Of the candidates of sizes 8 and 20 (a small
 * basis keeps the orientation term strong; either alone leaves part of X on itself on some shapes,
 * the two seldom on the same ones), the one that moves X's farthest-point sources the farthest
 * (mean geodesic from s to S(s), a mirror moves every point off the symmetry plane) net of its metric
 * distortion (a map that mirrors part of X and keeps the rest tears where they meet). The centres'
 * own symmetry (ss_centre_signature.sigma) cannot serve: among a quadruped's 10–14 centres, swaps of
 * two near centres cost less than the whole mirror, and σ is mostly the identity there. */
ss_status ssi_symmetry_map(const ss_shape_prep *X, const ss_match_options *o, double w, int *S, ss_error *err) {
  static const int K[2] = {8, 20};
  const size_t nX = (size_t)X->mesh->nv;
  ss_mesh mirror = *X->mesh;
  mirror.V = malloc(sizeof(double) * 3 * nX);
  int *T = malloc(sizeof(int) * nX);
  ssi_hyp_ctx hs = {0};
  ss_status st = mirror.V && T ? SS_OK : ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
  for (size_t i = 0; !st && i < 3 * nX; i++) mirror.V[i] = i % 3 == 0 ? -X->mesh->V[i] : X->mesh->V[i];
  if (!st) st = ssi_hyp_ctx_new(X->mesh, X->mesh, 16, 0, &hs, err);
  double best = -INFINITY;
  for (int i = 0; !st && i < 2; i++) {
    double dist = 0, moved = 0;
    if ((st = symmetry_candidate(X, &mirror, o, K[i], w, T, err)) || (st = ssi_hyp_distortion(&hs, T, &dist, err))) break;
    int nm = 0;
    for (int j = 0; j < hs.nsrc; j++) {
      const double d = hs.dX[nX * j + (size_t)T[hs.src[j]]] / hs.sX;
      if (isfinite(d)) moved += d, nm++;
    }
    const double score = (nm ? moved / nm : 0) - dist;
    if (i == 0 || score > best) best = score, memcpy(S, T, sizeof(int) * nX);
  }
  ssi_hyp_ctx_free(&hs);
  free(mirror.V), free(T);
  return st;
}

/* The hypothesis energy of a map (match.h: ss_autopair_options.hyp_w_reversed, hyp_w_map,
 * hyp_w_orientation; a map without a selection energy or an orientation score, NaN, adds none) */
static double hypothesis_energy(const ss_autopair_options *o, double distortion, double reversed, double map_energy,
                                double orientation) {
  const double shortfall = o->hyp_confident_orientation - orientation;
  return distortion + o->hyp_w_reversed * reversed + (isfinite(map_energy) ? o->hyp_w_map * map_energy : 0) +
         (shortfall > 0 ? o->hyp_w_orientation * shortfall : 0);
}

/* With given landmarks, the kept pairs (kx, ky; nk) of a hypothesis that agree with them: neither
 * centre within tol of a given landmark (that one anchors the place already), and every given
 * landmark as far from one centre as from the other within tol (edge-graph geodesics over √area;
 * gdX, gdY: nX x nlg and nY x nlg distances from the given landmarks). Returns their count. */
static int agreeing_pairs(const ssi_hyp_ctx *hc, int nlg, const double *gdX, const double *gdY, int nk, const int *kx,
                          const int *ky, double tol, int *ex, int *ey) {
  const size_t nX = (size_t)hc->X->nv, nY = (size_t)hc->Y->nv;
  int q = 0;
  for (int p = 0; p < nk; p++) {
    int keep = 1;
    for (int i = 0; i < nlg && keep; i++) {
      const double dx = gdX[nX * i + kx[p]] / hc->sX, dy = gdY[nY * i + ky[p]] / hc->sY;
      keep = isfinite(dx) && isfinite(dy) && dx > tol && dy > tol && fabs(dx - dy) <= tol;
    }
    if (keep) ex[q] = kx[p], ey[q++] = ky[p];
  }
  return q;
}

/* whether the n landmark pairs (a, b) are the m pairs (c, d) in any order (a set from Y's side lists
 * them in Y's order) */
static int same_set(int n, const int *a, const int *b, int m, const int *c, const int *d) {
  if (n != m) return 0;
  for (int i = 0; i < n; i++) {
    int found = 0;
    for (int j = 0; j < m && !found; j++) found = a[i] == c[j] && b[i] == d[j];
    if (!found) return 0;
  }
  return 1;
}

/* The candidates of a match, nc of them (SS_MAX_HYPOTHESES at most). Candidate c: its n[c] landmark
 * pairs (cand_x / cand_y: stride ints each); seg[c], the pairing whose segments its map uses (NULL: its
 * landmarks pair the segments); lm_free[c], whether it is landmark-free; pairs_of[c], the pairing
 * hypothesis behind it, X's or Y's (NULL: none). The slot nc is where the next one is written. */
typedef struct {
  int nc, stride, *lx, *ly;
  int n[SS_MAX_HYPOTHESES], lm_free[SS_MAX_HYPOTHESES];
  const ss_segment_pairs *seg[SS_MAX_HYPOTHESES], *pairs_of[SS_MAX_HYPOTHESES];
} cand_set;

static int *cand_x(const cand_set *cs, int c) { return cs->lx + (size_t)cs->stride * c; }
static int *cand_y(const cand_set *cs, int c) { return cs->ly + (size_t)cs->stride * c; }

/* Candidate nc: the cnt landmark pairs already written in its slot, and what it comes from */
static void cand_push(cand_set *cs, int cnt, const ss_segment_pairs *seg, int lm_free, const ss_segment_pairs *pairs_of) {
  const int c = cs->nc++;
  cs->n[c] = cnt, cs->seg[c] = seg, cs->lm_free[c] = lm_free, cs->pairs_of[c] = pairs_of;
}

/* whether the cnt landmark pairs in slot nc repeat an earlier landmark-free candidate's */
static int repeats_free(const cand_set *cs, int cnt) {
  const int *cx = cand_x(cs, cs->nc), *cy = cand_y(cs, cs->nc);
  for (int c = 0; c < cs->nc; c++)
    if (cs->lm_free[c] && same_set(cs->n[c], cand_x(cs, c), cand_y(cs, c), cnt, cx, cy)) return 1;
  return 0;
}

/* The share of X's nX vertices whose images under maps a and b (vertices of Y) lie farther apart
 * than tol_abs (Euclidean, in Y's units: the caller scales hyp_differ_tol by √area of Y). */
static double map_differ_share(const ss_mesh *Y, double tol_abs, int nX, const int *a, const int *b) {
  int far = 0;
  for (int v = 0; v < nX; v++) {
    const double *p = Y->V + 3 * (size_t)a[v], *q = Y->V + 3 * (size_t)b[v];
    const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    far += dx * dx + dy * dy + dz * dz > tol_abs * tol_abs;
  }
  return nX > 0 ? (double)far / nX : 0;
}

/* one option's range check, naming the option and its value (NaN is outside every range) */
static int real_outside(double v, double lo, double hi, const char *name, ss_error *err) {
  if (v >= lo && v <= hi) return 0;
  ss_fail(err, SS_ERR_INVALID, "match: %s %g outside [%g, %g]", name, v, lo, hi);
  return 1;
}
static int int_outside(int v, int lo, int hi, const char *name, ss_error *err) {
  if (v >= lo && v <= hi) return 0;
  ss_fail(err, SS_ERR_INVALID, "match: %s %d outside %d..%d", name, v, lo, hi);
  return 1;
}

/* the hypotheses' options (ss_autopair_options.hyp_*): the first one out of its range is named */
static ss_status hyp_options_check(const ss_autopair_options *a, ss_error *err) {
  const double F = DBL_MAX, I = INFINITY;
  if (int_outside(a->hypotheses, 1, SS_MAX_HYPOTHESES, "hypotheses", err) ||
      real_outside(a->hyp_gap, 0, I, "hyp_gap", err) || real_outside(a->hyp_w_reversed, 0, F, "hyp_w_reversed", err) ||
      real_outside(a->hyp_reversed_below, -F, F, "hyp_reversed_below", err) ||
      real_outside(a->hyp_min_margin, -F, F, "hyp_min_margin", err) ||
      real_outside(a->hyp_landmark_tol, 0, I, "hyp_landmark_tol", err) ||
      int_outside(a->hyp_landmarks, 0, 2, "hyp_landmarks", err) ||
      real_outside(a->hyp_differ_tol, 0, F, "hyp_differ_tol", err) ||
      real_outside(a->hyp_differ_share, 0, 1, "hyp_differ_share", err) ||
      real_outside(a->hyp_min_orientation, -1, 1, "hyp_min_orientation", err) ||
      real_outside(a->hyp_confident_orientation, -1, 1, "hyp_confident_orientation", err) ||
      int_outside(a->hyp_descriptor_map, 0, 1, "hyp_descriptor_map", err) ||
      real_outside(a->hyp_descriptor_orient, 0, 1e6, "hyp_descriptor_orient", err) ||
      real_outside(a->hyp_w_map, 0, F, "hyp_w_map", err) ||
      real_outside(a->hyp_max_map_energy, -I, I, "hyp_max_map_energy", err) ||
      real_outside(a->hyp_flip_orient, 0, 1e6, "hyp_flip_orient", err) ||
      real_outside(a->hyp_w_orientation, 0, F, "hyp_w_orientation", err) ||
      int_outside(a->hyp_flip_side, 0, 2, "hyp_flip_side", err) ||
      int_outside(a->hyp_final_kmax, 0, 10000, "hyp_final_kmax", err) ||
      int_outside(a->hyp_reverse, 0, 1, "hyp_reverse", err) ||
      int_outside(a->hyp_final_polish, 0, 1, "hyp_final_polish", err) ||
      int_outside(a->hyp_fit_scale, 0, 1, "hyp_fit_scale", err) ||
      real_outside(a->hyp_recheck_window, 0, 1e6, "hyp_recheck_window", err) ||
      real_outside(a->hyp_skip_tol, 0, 1e6, "hyp_skip_tol", err) ||
      real_outside(a->hyp_min_coverage, 0, 1, "hyp_min_coverage", err))
    return SS_ERR_INVALID;
  /* (0, 1]: a share of the pairs, at least one kept */
  if (!(a->hyp_keep > 0 && a->hyp_keep <= 1))
    return ss_fail(err, SS_ERR_INVALID, "match: hyp_keep %g outside (0, 1]", a->hyp_keep);
  return SS_OK;
}

/* Whether the flipped candidates are looked for (ss_autopair_options.hyp_flip_orient): when the map
 * kept (kept) does not keep orientation clearly, or when a candidate that reverses orientation has
 * the lower hypothesis energy (the mirror image is the better isometry, so the oriented map kept is
 * suspect: TOSCA_r cat3 -> cat4, kept at orientation 0.63 and error 16, its mirror's distortion half
 * of it; docs/tuning.md). */
static int flips_wanted(const ss_autopair_info *info, const int *oriented, int nc, int kept, double confident) {
  if (info->hyp_orientation[kept] < confident) return 1;
  for (int c = 0; c < nc; c++)
    if (!oriented[c] && info->hyp_skipped_by[c] < 0 && info->hyp_energy[c] < info->hyp_energy[kept]) return 1;
  return 0;
}

/* The flipped candidates (ss_autopair_options.hyp_flip_orient): for each of the nc candidates mapped
 * so far whose map reverses orientation (oriented[c] 0) and is not itself a flip, in order of
 * hypothesis energy (energy[c]; the best mirror first, when room runs short), the landmarks X's
 * protrusion centres (hyp_keep) and the images under that map of their mirror images on X (by_y 0),
 * or the mirror images on Y of their images (by_y 1; ssi_symmetry_map of that shape): the mirror map
 * turned the right way round. A set equal to an earlier landmark-free one is skipped. Appends to cs
 * (up to cap candidates in all) and sets info's hyp_flip_of[new] = c, hyp_flip_by_y[new] = by_y. On
 * failure none is added. */
static ss_status add_flipped(const ss_shape_prep *X, const ss_shape_prep *Y, int by_y, const ss_centre_signature *SX,
                             const ss_match_options *o, const int *maps, const int *oriented, int cap, cand_set *cs,
                             ss_autopair_info *info, ss_error *err) {
  const int nc0 = cs->nc, m = SX->m;
  const double *energy = info->hyp_energy;
  int *flip_of = info->hyp_flip_of;
  const size_t nX = (size_t)X->mesh->nv;
  const ss_shape_prep *Z = by_y ? Y : X; /* the shape whose own symmetry turns the maps round */
  int any = 0;
  for (int c = 0; c < nc0; c++) any |= flip_of[c] < 0 && !oriented[c] && info->hyp_skipped_by[c] < 0;
  if (!any) return SS_OK;
  int *S = malloc(sizeof(int) * (size_t)Z->mesh->nv), *kept = malloc(sizeof(int) * (size_t)m);
  ss_status st = S && kept ? SS_OK : ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
  if (!st) st = ssi_symmetry_map(Z, o, o->autopair.hyp_flip_orient, S, err);
  if (!st) ssi_kept_centres(SX, o->autopair.hyp_keep, kept);
  int order[SS_MAX_HYPOTHESES];
  for (int i = 0; i < nc0; i++) {
    int j = i; /* insertion by energy, ties in candidate order */
    for (; j > 0 && energy[order[j - 1]] > energy[i]; j--) order[j] = order[j - 1];
    order[j] = i;
  }
  for (int i = 0; !st && i < nc0 && cs->nc < cap; i++) {
    const int c = order[i];
    /* (a flip is not flipped back; a candidate not mapped has no map of its own) */
    if (flip_of[c] >= 0 || oriented[c] || info->hyp_skipped_by[c] >= 0) continue;
    int *cx = cand_x(cs, cs->nc), *cy = cand_y(cs, cs->nc), q = 0;
    for (int a = 0; a < m; a++)
      if (kept[a]) /* x -> T(S_X(x)), or x -> S_Y(T(x)) */
        cx[q] = SX->centers[a],
        cy[q++] = by_y ? S[maps[nX * c + (size_t)SX->centers[a]]] : maps[nX * c + (size_t)S[SX->centers[a]]];
    if (q < 3 || repeats_free(cs, q)) continue;
    flip_of[cs->nc] = c, info->hyp_flip_by_y[cs->nc] = by_y;
    cand_push(cs, q, NULL, 1, NULL);
  }
  free(S), free(kept);
  return st;
}

/* The map kept, refined further (ss_autopair_options.hyp_final_kmax) as ss_match_refine refines a
 * map: its functional map at the match's ZoomOut size, then ZoomOut to the final size; out's map and
 * C are replaced. *k_done: the size reached (0: not refined further). Shapes of fewer eigenpairs
 * stop at theirs, with a note. */
static ss_status refine_kept(const ss_shape_prep *X, const ss_shape_prep *Y, const ss_match_options *o,
                             ss_match_result *out, int *k_done, ss_error *err) {
  *k_done = 0;
  const int k0 = ssi_match_zoomout_size(o);
  const int kev = X->kev < Y->kev ? X->kev : Y->kev;
  int kf = o->autopair.hyp_final_kmax;
  if (o->refine == SS_REFINE_NONE || kf <= k0 || !out->map) return SS_OK;
  if (kev < kf) {
    char msg[240];
    snprintf(msg, sizeof msg, "the shapes hold %d eigenpairs, fewer than hyp_final_kmax %d: the map kept is refined to "
             "%d only (prepare them again for the default)", kev, kf, kev > k0 ? kev : k0);
    ssi_match_note(out, msg);
    kf = kev;
    if (kf <= k0) return SS_OK;
  }
  ss_match_options ro = *o;
  ro.fmap.k = k0, ro.fmap.zoomout_kmax = kf;
  int *map = malloc(sizeof(int) * (size_t)X->mesh->nv);
  double *C = malloc(sizeof(double) * (size_t)kf * kf);
  ss_status st = map && C ? SS_OK : ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
  if (!st) st = ss_match_refine(X, Y, out->map, &ro, map, C, err);
  if (st) {
    free(map), free(C);
    return st;
  }
  free(out->map), free(out->C);
  out->map = map, out->C = C, out->kc = kf;
  *k_done = kf;
  return SS_OK;
}

/* Candidate c's map: the match with its landmarks, and its pairing's segments when it has one (with
 * the options oall, else o); the ZoomOut plan zp and the solver's buffers fw shared by all */
static ss_status map_candidate(const ss_shape_prep *X, const ss_shape_prep *Y, const cand_set *cs, int c,
                               const ss_match_options *o, const ss_match_options *oall, const ssi_zoomout_plan *zp,
                               ssi_fmap_work *fw, ss_match_result *r, ss_error *err) {
  const int nl = cs->n[c], *cx = cand_x(cs, c), *cy = cand_y(cs, c);
  if (cs->seg[c]) return ssi_match_core_planned(X, Y, nl, cx, cy, cs->seg[c], oall, zp, fw, r, err);
  ss_match_options ok = *o;
  if (cs->lm_free[c] && ok.pairing.min_landmarks > nl) ok.pairing.min_landmarks = nl;
  return ssi_match_core_planned(X, Y, nl, cx, cy, NULL, &ok, zp, fw, r, err);
}

/* Where the landmark-free choice is in doubt: the map kept and each candidate within `window` of its
 * energy that is eligible, as oriented, and differs from it (hyp_differ_share) are polished on the
 * surfaces (ss_map_polish), and each energy is taken again with the polished map's distortion in
 * place of its own. The orientation terms stay those of the map as it was: the polish turns every
 * part to face Y's way, so after it they no longer tell a mirror image from the map. A map right
 * but for thin parts turned over (a leg's front and back exchanged) loses its distortion to the
 * polish, a wrong one does not (TOSCA_r cat4 -> cat9; docs/tuning.md). *choice: the candidate of
 * least such energy; *polished: how many were polished. */
static ss_status recheck_polished(const ss_shape_prep *X, const ss_shape_prep *Y, ssi_hyp_ctx *hc, int nc,
                                  const int *maps, const int *eligible, const int *oriented, double window,
                                  double differ_share, const ss_autopair_info *info, int *choice, int *polished,
                                  ss_error *err) {
  const int kept = info->hypothesis, nX = X->mesh->nv;
  *choice = kept, *polished = 0;
  int *pm = malloc(sizeof(int) * (size_t)nX);
  if (!pm) return ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
  ss_status st = SS_OK;
  double least = INFINITY;
  for (int c = 0; c < nc; c++) {
    if (c != kept && !(eligible[c] && oriented[c] == oriented[kept] && info->hyp_differ[c] >= differ_share &&
                       info->hyp_energy[c] - info->hyp_energy[kept] < window))
      continue;
    double dist = NAN;
    if ((st = ss_map_polish(X->mesh, Y->mesh, maps + (size_t)nX * c, NULL, pm, err)) ||
        (st = ssi_hyp_distortion(hc, pm, &dist, err)))
      break;
    (*polished)++;
    const double E = info->hyp_energy[c] - info->hyp_distortion[c] + dist;
    if (E < least) least = E, *choice = c;
  }
  free(pm);
  return st;
}

/* The earlier candidate (mapped, not itself skipped) whose map sends every landmark of candidate c
 * within tol (Euclidean, Y's units) of its partner, -1 when none does (ss_autopair_options
 * .hyp_skip_tol; tol 0: none). Such a candidate's map would be that one's or near it (about a quarter
 * of the candidates of the FAUST_r and TOSCA_r tuning splits at 0.05), but its own hypothesis energy,
 * which can differ from that one's by more than two distinct maps differ, is then not known
 * (docs/tuning.md). */
static int kept_by_earlier(const ss_mesh *Y, const cand_set *cs, int c, const int *maps, size_t nX,
                           const int *skipped_by, double tol) {
  if (!(tol > 0) || cs->n[c] < 1) return -1;
  const int *lx = cand_x(cs, c), *ly = cand_y(cs, c);
  for (int e = 0; e < c; e++) {
    if (skipped_by[e] >= 0) continue;
    const int *map = maps + nX * (size_t)e;
    int all = 1;
    for (int i = 0; i < cs->n[c] && all; i++) {
      const double *p = Y->V + 3 * (size_t)map[lx[i]], *q = Y->V + 3 * (size_t)ly[i];
      const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
      all = dx * dx + dy * dy + dz * dz <= tol * tol;
    }
    if (all) return e;
  }
  return -1;
}

/* Candidate c not mapped, as its map would be candidate by's: its numbers are NaN, and it is neither
 * chosen, compared, flipped nor read as a map (not eligible; hyp_skipped_by set). */
static void skip_candidate(ss_autopair_info *info, int c, int by, int *eligible, int *oriented, int *lm_off) {
  info->hyp_skipped_by[c] = by;
  info->hyp_pair_energy[c] = info->hyp_distortion[c] = info->hyp_orientation[c] = NAN;
  info->hyp_scale[c] = info->hyp_energy[c] = info->hyp_map_energy[c] = NAN;
  info->hyp_reversed[c] = info->hyp_orientation_min[c] = info->hyp_differ[c] = NAN;
  eligible[c] = 0, oriented[c] = oriented[by], lm_off[c] = 0;
}

/* One match's candidates as they are built, mapped and compared: match_hypotheses_cached's state,
 * read and written by its stages below. */
typedef struct {
  const ss_shape_prep *X, *Y;
  const ss_centre_signature *SX, *SY;
  ss_match_options o;
  ss_match_options oall; /* for a candidate whose map uses its pairing's segments (see map_candidate) */
  int nlg;               /* given landmarks, lgX[i] on X and lgY[i] on Y */
  const int *lgX, *lgY;
  double *gdX, *gdY; /* the given landmarks' graph distance fields, nv x nlg each */
  ssi_hyp_ctx hc;    /* the distortion context (and the geodesic graphs) */
  ssi_zoomout_plan plan;
  ssi_fmap_work fw;
  cand_set cs;
  size_t nX;
  int *maps;    /* every mapped candidate's map, nX each (several candidates only) */
  double *segs; /* scratch of ssi_map_orientation_reversed, 2 per centre of X */
  ss_autopair_info info;
  int eligible[SS_MAX_HYPOTHESES], lm_off[SS_MAX_HYPOTHESES], oriented[SS_MAX_HYPOTHESES];
  double best; /* the hypothesis energy of the map kept so far */
} hyp_run;

/* With given landmarks: their distance fields, and their own candidate (slot 0) */
static ss_status add_given_landmarks(hyp_run *R, ss_error *err) {
  const int nlg = R->nlg, nvX = R->X->mesh->nv, nvY = R->Y->mesh->nv;
  R->gdX = malloc(sizeof(double) * (size_t)nvX * nlg);
  R->gdY = malloc(sizeof(double) * (size_t)nvY * nlg);
  if (!R->gdX || !R->gdY) return ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
  ss_status st;
  for (int i = 0; i < nlg; i++)
    if ((st = ss_graph_dijkstra(&R->hc.gX, &R->lgX[i], 1, 0, R->gdX + (size_t)nvX * i, NULL, err)) ||
        (st = ss_graph_dijkstra(&R->hc.gY, &R->lgY[i], 1, 0, R->gdY + (size_t)nvY * i, NULL, err)))
      return st;
  memcpy(R->cs.lx, R->lgX, sizeof(int) * (size_t)nlg), memcpy(R->cs.ly, R->lgY, sizeof(int) * (size_t)nlg);
  cand_push(&R->cs, nlg, NULL, 0, NULL);
  return SS_OK;
}

/* Each of X's nh pairing hypotheses as a landmark-free candidate (its kept pairs; sets repeating an
 * earlier one skipped), up to want of them. Beside given landmarks (hyp_landmarks 2) they are
 * eligible where they keep them (see score_candidate): a landmark on a spot where two body parts
 * touch and the mesh joins them (FAUST_r tr_reg_017's foot) misleads the landmarks' map, not the
 * protrusions'. Returns the hypotheses looked at (the agreeing pairs use as many). */
static int add_free_hypotheses(hyp_run *R, const ss_segment_pairs *hyp, int nh, int want) {
  cand_set *cs = &R->cs;
  int nfree = 0, hused = nh < want ? nh : want;
  for (int h = 0; (R->nlg == 0 || R->o.autopair.hyp_landmarks == 2) && h < nh && nfree < want &&
                  cs->nc < SS_MAX_HYPOTHESES;
       h++) {
    int *cx = cand_x(cs, cs->nc), *cy = cand_y(cs, cs->nc);
    const int nk = kept_pairs(R->SX, &hyp[h], R->o.autopair.hyp_keep, R->X, R->Y, cx, cy);
    hused = h + 1;
    if (repeats_free(cs, nk)) continue;
    cand_push(cs, nk, nk < hyp[h].n ? NULL : &hyp[h], 1, &hyp[h]);
    nfree++;
  }
  return hused;
}

/* Landmark-free: the descriptors' own candidate (X's protrusion centres and their images under the
 * descriptors' functional map), then, with hyp_reverse, Y's pairing hypotheses read from X's side and
 * Y's descriptors' candidate with its pairs swapped. *desc_c: X's descriptor candidate (-1: none). */
static ss_status add_free_extras(hyp_run *R, int want, ss_segment_pairs *rhyp, int *nrh, int *desc_c, ss_error *err) {
  cand_set *cs = &R->cs;
  const ss_autopair_options *a = &R->o.autopair;
  ss_status st;
  *desc_c = -1;
  if (a->hyp_descriptor_map && want > 1 && cs->nc < SS_MAX_HYPOTHESES) {
    int nd = 0;
    if ((st = ssi_match_plan(R->X, R->Y, &R->o, &R->plan, err))) return st;
    if ((st = descriptor_landmarks(R->X, R->Y, R->SX, &R->o, &R->fw, &R->plan, cand_x(cs, cs->nc), cand_y(cs, cs->nc),
                                   &nd, err)))
      return st;
    if (nd >= 3) *desc_c = cs->nc, cand_push(cs, nd, NULL, 1, NULL);
  }
  if (!a->hyp_reverse || want < 2) return SS_OK;
  if ((st = ss_pair_centres_hypotheses(R->SY, R->SX, a, SS_MAX_HYPOTHESES, rhyp, nrh, NULL, err))) return st;
  int nrev = 0;
  for (int h = 0; h < *nrh && nrev < want && cs->nc < SS_MAX_HYPOTHESES; h++) {
    const ss_segment_pairs turned = {rhyp[h].n, rhyp[h].sy, rhyp[h].sx, rhyp[h].energy, rhyp[h].ny, rhyp[h].nx};
    const int nk = kept_pairs(R->SX, &turned, a->hyp_keep, R->X, R->Y, cand_x(cs, cs->nc), cand_y(cs, cs->nc));
    if (repeats_free(cs, nk)) continue;
    R->info.hyp_from_y[cs->nc] = 1;
    cand_push(cs, nk, NULL, 1, &rhyp[h]);
    nrev++;
  }
  if (a->hyp_descriptor_map && cs->nc < SS_MAX_HYPOTHESES) {
    int nd = 0;
    if ((st = descriptor_landmarks(R->Y, R->X, R->SY, &R->o, &R->fw, NULL, cand_y(cs, cs->nc), cand_x(cs, cs->nc), &nd,
                                   err)))
      return st;
    if (nd >= 3 && !repeats_free(cs, nd)) R->info.hyp_from_y[cs->nc] = 1, cand_push(cs, nd, NULL, 1, NULL);
  }
  return SS_OK;
}

/* With given landmarks: for each of the first hused hypotheses, the landmarks plus the hypothesis's
 * kept pairs that agree with them (agreeing_pairs), distinct sets only; mx: room for a kept set */
static ss_status add_agreeing(hyp_run *R, const ss_segment_pairs *hyp, int hused, int mx, ss_error *err) {
  cand_set *cs = &R->cs;
  const int nlg = R->nlg;
  int *kx = malloc(sizeof(int) * (size_t)mx), *ky = malloc(sizeof(int) * (size_t)mx);
  if (!kx || !ky) {
    free(kx), free(ky);
    return ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
  }
  for (int h = 0; h < hused && cs->nc < SS_MAX_HYPOTHESES; h++) {
    int nk = kept_pairs(R->SX, &hyp[h], R->o.autopair.hyp_keep, R->X, R->Y, kx, ky);
    int *cx = cand_x(cs, cs->nc), *cy = cand_y(cs, cs->nc);
    memcpy(cx, R->lgX, sizeof(int) * (size_t)nlg), memcpy(cy, R->lgY, sizeof(int) * (size_t)nlg);
    const double tol = R->o.autopair.hyp_landmark_tol;
    int ne = agreeing_pairs(&R->hc, nlg, R->gdX, R->gdY, nk, kx, ky, tol, cx + nlg, cy + nlg);
    int dup = ne == 0;
    for (int c = 1; c < cs->nc && !dup; c++)
      dup = !cs->lm_free[c] && same_set(cs->n[c], cand_x(cs, c), cand_y(cs, c), nlg + ne, cx, cy);
    if (!dup) cand_push(cs, nlg + ne, NULL, 0, NULL);
  }
  free(kx), free(ky);
  return SS_OK;
}

/* Candidate c's numbers from its map r (info's hyp_* of c, oriented[c], eligible[c], lm_off[c]) */
static ss_status score_map(hyp_run *R, int c, const ss_match_result *r, ss_error *err) {
  const ss_autopair_options *a = &R->o.autopair;
  ss_autopair_info *info = &R->info;
  double E = 0, dist = NAN, pe = NAN, scale = NAN;
  const double map_energy = r->refine_choice >= 0 ? r->refine_energy[r->refine_choice] : NAN;
  const ss_segment_pairs *hp = R->cs.pairs_of[c]; /* the pairing hypothesis behind it, X's or Y's */
  if (hp) {
    pe = 0;
    for (int p = 0; p < hp->n; p++) pe += hp->energy[p];
  }
  const double orient = ssi_map_orientation(R->SX, R->SY, r->map);
  /* a map that reverses orientation on most of X is a mirror image (TOSCA_r's cats and horses: the
   * whole mirror has the lower distortion and even the lower reversed-segment share; docs/tuning.md) */
  R->oriented[c] = !(orient < a->hyp_min_orientation);
  if (R->cs.nc > 1) {
    memcpy(R->maps + R->nX * c, r->map, sizeof(int) * R->nX);
    ss_status st = ssi_hyp_distortion(&R->hc, r->map, &dist, err);
    if (st) return st;
    scale = R->hc.scale;
    const double rev = ssi_map_orientation_reversed(R->SX, R->SY, r->map, a->hyp_reversed_below, R->segs,
                                                    &info->hyp_orientation_min[c]);
    info->hyp_reversed[c] = rev;
    E = hypothesis_energy(a, dist, rev, map_energy, orient);
  }
  info->hyp_pair_energy[c] = pe, info->hyp_distortion[c] = dist, info->hyp_orientation[c] = orient;
  info->hyp_scale[c] = scale;
  info->hyp_energy[c] = E;
  info->hyp_map_energy[c] = map_energy;
  /* a landmark-free map beside given landmarks must keep them: at most a quarter of them (none of
   * three or fewer) farther than hyp_landmark_tol (geodesic / √area) from their partners */
  int off = 0;
  const size_t nvY = (size_t)R->Y->mesh->nv;
  for (int i = 0; i < R->nlg; i++) off += !(R->gdY[nvY * i + r->map[R->lgX[i]]] / R->hc.sY <= a->hyp_landmark_tol);
  R->eligible[c] = !R->cs.lm_free[c] || off <= R->nlg / 4, R->lm_off[c] = off;
  return SS_OK;
}

/* Candidate c mapped and scored; its result becomes *out when it is the best so far (eligible, as
 * oriented as the best, and of lower energy), else it is freed. zp: the shared ZoomOut plan. */
static ss_status map_and_score(hyp_run *R, int c, const ssi_zoomout_plan *zp, ss_match_result *out, ss_error *err) {
  ss_match_result r;
  memset(&r, 0, sizeof r);
  ss_status st = map_candidate(R->X, R->Y, &R->cs, c, &R->o, &R->oall, zp, &R->fw, &r, err);
  if (!st) st = score_map(R, c, &r, err);
  if (st) {
    ss_match_result_free(&r);
    return st;
  }
  const int hk = R->info.hypothesis, *oriented = R->oriented;
  const double E = R->info.hyp_energy[c];
  if (c == 0 || (R->eligible[c] && (oriented[c] > oriented[hk] || (oriented[c] == oriented[hk] && E < R->best)))) {
    if (c > 0) ss_match_result_free(out);
    *out = r, R->best = E, R->info.hypothesis = c, R->info.hyp_landmarks = R->cs.n[c];
  } else
    ss_match_result_free(&r);
  return SS_OK;
}

/* Once the first candidates are mapped: the flipped ones, when the map kept is not clearly
 * orientation-preserving (a quadruped mapped as its mirror image: TOSCA_r's cats, dogs, centaurs) or
 * a mirror image beats it; by X's own symmetry, then by Y's (hyp_flip_side): where one shape's
 * symmetry map fails (a cat curled up) the other's turns the mirror round. The flips are optional:
 * a side that fails (other than for memory) is skipped with a note, written in skipped (cap bytes),
 * instead of failing a match whose candidates are all mapped. */
static ss_status add_flips(hyp_run *R, char *skipped, size_t cap, ss_error *err) {
  const ss_autopair_options *a = &R->o.autopair;
  if (!(R->nlg == 0 && R->cs.nc > 1 && a->hyp_flip_orient > 0 &&
        flips_wanted(&R->info, R->oriented, R->cs.nc, R->info.hypothesis, a->hyp_confident_orientation)))
    return SS_OK;
  /* the flips' room: the 8 candidates in all that a match had before hyp_reverse, all of it with it */
  const int flip_cap = a->hyp_reverse ? SS_MAX_HYPOTHESES : 8;
  for (int by_y = 0; by_y < 2; by_y++) {
    if (a->hyp_flip_side != 2 && a->hyp_flip_side != by_y) continue;
    ss_error ferr = {{0}};
    const ss_status fs = add_flipped(R->X, R->Y, by_y, R->SX, &R->o, R->maps, R->oriented, flip_cap, &R->cs, &R->info,
                                     &ferr);
    if (fs == SS_ERR_NOMEM) return ss_fail(err, fs, "%s", ferr.msg);
    if (fs)
      snprintf(skipped, cap, "no flipped candidates by %s's symmetry: its own symmetry map failed (%s)",
               by_y ? "Y" : "X", ferr.msg);
  }
  return SS_OK;
}

/* Every candidate mapped and scored in turn (a candidate whose landmarks an earlier map keeps is
 * skipped: hyp_skip_tol), the flipped ones added once the first are done; the best is *out. */
static ss_status map_candidates(hyp_run *R, const ssi_zoomout_plan *zp, ss_match_result *out, char *flip_skipped,
                                size_t cap, ss_error *err) {
  ss_autopair_info *info = &R->info;
  for (int c = 0; c < SS_MAX_HYPOTHESES; c++) info->hyp_flip_of[c] = info->hyp_skipped_by[c] = -1; /* (flip_by_y: 0) */
  R->best = INFINITY;
  int flips_looked = 0;
  ss_status st;
  for (int c = 0; c < R->cs.nc; c++) {
    const int by = R->nlg == 0 && R->cs.nc > 1 ? kept_by_earlier(R->Y->mesh, &R->cs, c, R->maps, R->nX,
                                                                 info->hyp_skipped_by,
                                                                 R->o.autopair.hyp_skip_tol * R->hc.sY)
                                               : -1;
    if (by >= 0) skip_candidate(info, c, by, R->eligible, R->oriented, R->lm_off); /* its map would be #by's */
    else if ((st = map_and_score(R, c, zp, out, err)))
      return st;
    if (c == R->cs.nc - 1 && !flips_looked) {
      flips_looked = 1;
      if ((st = add_flips(R, flip_skipped, cap, err))) return st;
    }
  }
  return SS_OK;
}

/* How far the map kept (before any recheck) can be trusted */
typedef struct {
  int oriented;        /* it keeps orientation (or no candidate does) */
  int low_orient;      /* it keeps it, but not clearly */
  int high_map_energy; /* its own refinement energy is high */
  int low_coverage;    /* the map returned reaches few of the vertices (judged once it is final) */
  double orientation, map_energy; /* its orientation score and own energy (the notes name them) */
} doubts;

/* The margin against the maps that differ from the one kept (info's hyp_differ, hyp_margin) and the
 * confidence; with landmarks, the landmarks' map and a right landmark-free map agree at almost equal
 * energy, and that tie is no doubt (FAUST_r tuning pairs with gt:5: 83 of 97 flagged by it alone;
 * docs/tuning.md) */
static doubts judge_kept(hyp_run *R) {
  ss_autopair_info *info = &R->info;
  const ss_autopair_options *a = &R->o.autopair;
  const int nc = R->cs.nc, kept = info->hypothesis;
  doubts d;
  d.oriented = nc > 0 && R->oriented[kept];
  info->hyp_margin = INFINITY;
  for (int c = 0; c < nc && nc > 1; c++) {
    if (info->hyp_skipped_by[c] >= 0) continue; /* (NaN: not mapped) */
    info->hyp_differ[c] = map_differ_share(R->Y->mesh, a->hyp_differ_tol * R->hc.sY, (int)R->nX, R->maps + R->nX * c,
                                           R->maps + R->nX * kept);
    if (c != kept && R->eligible[c] && R->oriented[c] == d.oriented && info->hyp_differ[c] >= a->hyp_differ_share &&
        info->hyp_energy[c] - R->best < info->hyp_margin)
      info->hyp_margin = info->hyp_energy[c] - R->best;
  }
  if (nc > 1) info->confident = info->hyp_margin >= a->hyp_min_margin;
  else if (R->nlg > 0) info->confident = 1; /* no hypothesis agreeing with the landmarks offers another map */
  d.orientation = info->hyp_orientation[kept], d.map_energy = info->hyp_map_energy[kept];
  d.low_orient = d.oriented && d.orientation < a->hyp_confident_orientation;
  /* NaN (no such energy) compares false: not flagged by it */
  d.high_map_energy = d.map_energy > a->hyp_max_map_energy;
  d.low_coverage = 0;
  if (!d.oriented || d.low_orient || d.high_map_energy) info->confident = 0;
  return d;
}

/* The share of the smaller shape's vertex count that the map's distinct images make up
 * (ss_autopair_info.coverage); seen: scratch of nY bytes */
static double map_coverage(const int *map, int nX, int nY, unsigned char *seen) {
  memset(seen, 0, (size_t)nY);
  int distinct = 0;
  for (int i = 0; i < nX; i++) {
    distinct += !seen[map[i]];
    seen[map[i]] = 1;
  }
  return (double)distinct / (nX < nY ? nX : nY);
}

/* The map returned, once final: its coverage, and no confidence below hyp_min_coverage */
static ss_status judge_coverage(hyp_run *R, const ss_match_result *out, doubts *d, ss_error *err) {
  const int nY = R->Y->mesh->nv;
  unsigned char *seen = malloc((size_t)nY);
  if (!seen) return ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
  R->info.coverage = map_coverage(out->map, (int)R->nX, nY, seen);
  free(seen);
  d->low_coverage = R->info.coverage < R->o.autopair.hyp_min_coverage;
  if (d->low_coverage) R->info.confident = 0;
  return SS_OK;
}

/* A landmark-free choice in doubt, rechecked by the polished maps (recheck_polished); another choice
 * is mapped again, for its whole result, into *out, with a note. */
static ss_status recheck_choice(hyp_run *R, const ssi_zoomout_plan *zp, ss_match_result *out, ss_error *err) {
  ss_autopair_info *info = &R->info;
  const ss_autopair_options *a = &R->o.autopair;
  info->hyp_recheck_from = info->hypothesis;
  if (!(R->nlg == 0 && R->cs.nc > 1 && !info->confident && a->hyp_recheck_window > 0 && R->o.refine != SS_REFINE_NONE))
    return SS_OK;
  int choice;
  ss_status st = recheck_polished(R->X, R->Y, &R->hc, R->cs.nc, R->maps, R->eligible, R->oriented,
                                  a->hyp_recheck_window, a->hyp_differ_share, info, &choice, &info->hyp_rechecked, err);
  if (st || choice == info->hypothesis) return st;
  ss_match_result r;
  memset(&r, 0, sizeof r);
  if ((st = map_candidate(R->X, R->Y, &R->cs, choice, &R->o, &R->oall, zp, &R->fw, &r, err))) {
    ss_match_result_free(&r);
    return st;
  }
  ss_match_result_free(out);
  *out = r, info->hypothesis = choice, info->hyp_landmarks = R->cs.n[choice];
  char msg[220];
  snprintf(msg, sizeof msg, "the choice in doubt, the %d closest candidates polished and compared again: #%d kept "
           "instead of #%d (the confidence below is #%d's)", info->hyp_rechecked, choice, info->hyp_recheck_from,
           info->hyp_recheck_from);
  ssi_match_note(out, msg);
  return SS_OK;
}

/* The notes that say why the map kept may be wrong */
static void note_doubts(const hyp_run *R, const doubts *d, ss_match_result *out) {
  const ss_autopair_info *info = &R->info;
  const ss_autopair_options *a = &R->o.autopair;
  const int nlg = R->nlg, kept = info->hypothesis;
  char msg[256];
  const size_t cap = sizeof msg;
  const char *ask = nlg ? "check the landmarks" : "give landmarks";
  if (nlg > 0 && R->lm_off[kept] > 0) {
    snprintf(msg, cap, "%d of the %d landmarks lie farther than %.2g (geodesic / sqrt(area)) from their partners "
             "under the map kept (hypothesis #%d%s); check them", R->lm_off[kept], nlg, a->hyp_landmark_tol, kept,
             R->cs.lm_free[kept] ? ", landmark-free" : "");
    ssi_match_note(out, msg);
  }
  if (!d->oriented)
    snprintf(msg, cap, "map NOT confident: it reverses orientation (whole-map orientation score %.2f, below %.2g, "
             "and no hypothesis reaches it): it may be a mirror image (%s)", info->hyp_orientation[kept],
             a->hyp_min_orientation, ask);
  else if (d->low_orient)
    snprintf(msg, cap, "map NOT confident: its orientation score %.2f is below %.2g (part of it may be mirrored; %s)",
             d->orientation, a->hyp_confident_orientation, ask);
  else if (d->high_map_energy)
    snprintf(msg, cap, "map NOT confident: its own energy %.3g is above %.3g (its functional map is far from "
             "orthogonal or the descriptors badly kept; %s)", d->map_energy, a->hyp_max_map_energy, ask);
  else if (d->low_coverage)
    snprintf(msg, cap, "map NOT confident: its images reach only %.3f of the vertices, below %.3g (part of it "
             "slides or folds onto the rest; %s)", info->coverage, a->hyp_min_coverage, ask);
  else if (!info->confident && R->cs.nc > 1)
    snprintf(msg, cap, "%s map NOT confident (hypothesis margin %.3g, min %.3g): another pairing "
             "hypothesis maps almost as well; the map may be wrong (%s)", nlg ? "the" : "landmark-free",
             info->hyp_margin, a->hyp_min_margin, nlg ? "check the landmarks, add some" : "give landmarks");
  else if (!info->confident)
    snprintf(msg, cap, "landmark-free pairing NOT confident (gap %.3g, min %.3g; orientation margin %.2f, min "
             "%.2f): the map may be wrong (give landmarks)", info->gap, a->min_gap, info->mirror_margin, a->min_mirror);
  else
    return;
  ssi_match_note(out, msg);
}

/* The hypotheses' maps and the one of least hypothesis energy (ss_match_prepared_auto; with nlg > 0
 * given landmarks, ss_match_prepared's hypotheses: the given landmarks alone first, then each
 * pairing hypothesis's agreeing protrusion pairs added to them, distinct sets only); the shapes
 * carry their probe caches (match_hypotheses). */
static ss_status match_hypotheses_cached(const ss_shape_prep *X, const ss_shape_prep *Y,
                                         const ss_centre_signature *sigX, const ss_centre_signature *sigY, int nlg,
                                         const int *lgX, const int *lgY, const ss_match_options *opts_in,
                                         ss_match_result *out, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  memset(out, 0, sizeof *out);
  if (!X || !Y || !X->mesh || !Y->mesh || !X->evecs || !Y->evecs)
    return ss_fail(err, SS_ERR_INVALID, "match: shapes not prepared");
  /* (the options were checked by match_hypotheses, its only caller, before the probe caches) */
  hyp_run R;
  memset(&R, 0, sizeof R);
  if (opts_in) R.o = *opts_in;
  else ss_match_default_options(&R.o);
  R.X = X, R.Y = Y, R.nlg = nlg, R.lgX = lgX, R.lgY = lgY, R.nX = (size_t)X->mesh->nv;
  const ss_autopair_options *a = &R.o.autopair;
  ss_centre_signature own[2];
  memset(own, 0, sizeof own);
  ss_segment_pairs hyp[SS_MAX_HYPOTHESES], rhyp[SS_MAX_HYPOTHESES];
  memset(hyp, 0, sizeof hyp), memset(rhyp, 0, sizeof rhyp);
  int nh = 0, nrh = 0;
  ss_status st = SS_OK;
  double t0 = ss_time();
  if (!sigX && (st = ss_centre_signature_compute(X, a, &own[0], err))) goto done;
  if (!sigY && (st = ss_centre_signature_compute(Y, a, &own[1], err))) goto done;
  R.SX = sigX ? sigX : &own[0], R.SY = sigY ? sigY : &own[1];
  /* with given landmarks, one candidate slot is theirs alone */
  const int want = nlg > 0 && a->hypotheses >= SS_MAX_HYPOTHESES ? SS_MAX_HYPOTHESES - 1 : a->hypotheses;
  /* the search gives every hypothesis it has; one whose landmarks (its kept protrusion pairs) are an
   * earlier one's would give the same map and is skipped, so the `want` maps differ (on TOSCA_r's
   * 14-centre shapes the pairings of the first four often differ only in pairs that are not kept) */
  if ((st = ss_pair_centres_hypotheses(R.SX, R.SY, a, SS_MAX_HYPOTHESES, hyp, &nh, &R.info, err))) goto done;
  if (nlg > 0) R.info.used = 0;
  /* the given landmarks' distance fields need the graphs now; landmark-free, the context is built
   * once the candidates are known (below) */
  if (nlg > 0 && (st = ssi_hyp_ctx_new(X->mesh, Y->mesh, 16, a->hyp_fit_scale, &R.hc, err))) goto done;
  double t_pair = ss_time() - t0;
  /* the candidates' landmark sets: room for the given landmarks and every centre */
  int mx = 1;
  for (int h = 0; h < nh; h++)
    if (hyp[h].n > mx) mx = hyp[h].n;
  if (R.SX->m > mx) mx = R.SX->m; /* the descriptors' candidates */
  if (R.SY->m > mx) mx = R.SY->m;
  R.cs.stride = nlg + mx;
  R.cs.lx = malloc(sizeof(int) * (size_t)R.cs.stride * SS_MAX_HYPOTHESES);
  R.cs.ly = malloc(sizeof(int) * (size_t)R.cs.stride * SS_MAX_HYPOTHESES);
  R.segs = malloc(sizeof(double) * 2 * (size_t)R.SX->m);
  if (!R.cs.lx || !R.cs.ly || !R.segs) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
  if (nlg > 0 && (st = add_given_landmarks(&R, err))) goto done;
  const int hused = add_free_hypotheses(&R, hyp, nh, want);
  int desc_c = -1; /* (one hypothesis: the pairing's answer alone) */
  if (nlg == 0 && (st = add_free_extras(&R, want, rhyp, &nrh, &desc_c, err))) goto done;
  if (nlg > 0 && (st = add_agreeing(&R, hyp, hused, mx, err))) goto done;
  /* hyp_keep = 1 (landmark-free): the paired centres are the landmarks and the pairing is the
   * segments'; otherwise the segments are paired from the landmarks as with given landmarks (the
   * saddles' centres sit front or back inconsistently between shapes) */
  R.oall = R.o;
  R.oall.pairing.min_landmarks = 1;
  R.oall.pairing.min_map_share = 0; /* the STD map is built from these very centres: no independent check */
  const double t_loop = ss_time();
  /* every candidate's map, to tell the candidates that differ from the returned one */
  if (R.cs.nc > 1 && !(R.maps = malloc(sizeof(int) * R.nX * SS_MAX_HYPOTHESES))) {
    st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
    goto done;
  }
  /* the distortion context whenever candidates are compared: Y's hypotheses or the descriptors'
   * candidate can make several even where X's search gave one */
  if (R.cs.nc > 1 && !R.hc.X && (st = ssi_hyp_ctx_new(X->mesh, Y->mesh, 16, a->hyp_fit_scale, &R.hc, err))) goto done;
  /* one ZoomOut plan for every candidate (unless made above; an empty one, no ZoomOut, costs nothing) */
  if (R.cs.nc > 1 && R.plan.n_S == 0 && (st = ssi_match_plan(X, Y, &R.o, &R.plan, err))) goto done;
  const ssi_zoomout_plan *zp = R.plan.n_S > 0 ? &R.plan : NULL;
  char flip_skipped[sizeof(ss_error) + 96] = "";
  if ((st = map_candidates(&R, zp, out, flip_skipped, sizeof flip_skipped, err))) goto done;
  R.info.hypotheses = R.cs.nc;
  R.info.hyp_descriptor = desc_c;
  doubts d = judge_kept(&R);
  if ((st = recheck_choice(&R, zp, out, err))) goto done;
  /* the map kept, refined further and polished, with landmarks or without (their time is ZoomOut's) */
  const double t_final = ss_time();
  if ((st = refine_kept(X, Y, &R.o, out, &R.info.hyp_final_k, err))) goto done;
  if (a->hyp_final_polish && R.o.refine != SS_REFINE_NONE && out->map) {
    if ((st = ss_map_polish(X->mesh, Y->mesh, out->map, NULL, out->map, err))) goto done;
    R.info.hyp_final_polished = 1;
  }
  R.info.coverage = NAN;
  if (out->map && (st = judge_coverage(&R, out, &d, err))) goto done;
  out->t_zoomout += ss_time() - t_final;
  /* the other hypotheses' maps count as pairing time */
  out->t_pair += t_pair + (ss_time() - t_loop) - (out->t_pair + out->t_fmap + out->t_zoomout);
  out->t_total = out->t_segment + out->t_eigs + (ss_time() - t0);
  out->autopair = R.info;
  if (flip_skipped[0]) ssi_match_note(out, flip_skipped);
  note_doubts(&R, &d, out);
done:
  if (st) ss_match_result_free(out);
  ssi_hyp_ctx_free(&R.hc);
  ssi_zoomout_plan_free(&R.plan);
  ssi_fmap_work_free(&R.fw);
  ss_centre_signature_free(&own[0]);
  ss_centre_signature_free(&own[1]);
  for (int h = 0; h < nh; h++) ss_segment_pairs_free(&hyp[h]);
  for (int h = 0; h < nrh; h++) ss_segment_pairs_free(&rhyp[h]);
  free(R.cs.lx), free(R.cs.ly), free(R.segs), free(R.gdX), free(R.gdY), free(R.maps);
  return st;
}

/* match_hypotheses_cached on shapes that carry the probe caches of the match's options: made here,
 * once, for a shape without them (ss_shape_prep_compute's), instead of in each candidate's maps
 * (ssi_match_core makes them per call); the same entries, so the same maps to the bit */
static ss_status match_hypotheses(const ss_shape_prep *X, const ss_shape_prep *Y, const ss_centre_signature *sigX,
                                  const ss_centre_signature *sigY, int nlg, const int *lgX, const int *lgY,
                                  const ss_match_options *opts_in, ss_match_result *out, ss_error *err) {
  if (!out || !X || !Y || !X->mesh || !Y->mesh || !X->evecs || !Y->evecs) /* its messages */
    return match_hypotheses_cached(X, Y, sigX, sigY, nlg, lgX, lgY, opts_in, out, err);
  ss_match_options o;
  if (opts_in) o = *opts_in;
  else ss_match_default_options(&o);
  /* options out of range are refused before the caches' work */
  if (hyp_options_check(&o.autopair, err)) {
    memset(out, 0, sizeof *out);
    return SS_ERR_INVALID;
  }
  ss_fmap_probe_cache *cx = NULL, *cy = NULL;
  int nx = 0, ny = 0;
  ss_status st = ssi_match_probe_caches_both(X, Y, &o, &cx, &nx, &cy, &ny, err);
  if (st) {
    memset(out, 0, sizeof *out);
    return st;
  }
  ss_shape_prep Xc = *X, Yc = *Y; /* shallow: the shapes' own arrays, read only */
  if (cx) Xc.probe_cache = cx, Xc.nprobe_cache = nx;
  if (cy) Yc.probe_cache = cy, Yc.nprobe_cache = ny;
  st = match_hypotheses_cached(&Xc, &Yc, sigX, sigY, nlg, lgX, lgY, opts_in, out, err);
  for (int i = 0; i < nx; i++) ss_fmap_probe_cache_free(&cx[i]);
  for (int i = 0; i < ny; i++) ss_fmap_probe_cache_free(&cy[i]);
  free(cx), free(cy);
  return st;
}

ss_status ss_match_prepared_auto(const ss_shape_prep *X, const ss_shape_prep *Y, const ss_centre_signature *sigX,
                                 const ss_centre_signature *sigY, const ss_match_options *opts_in, ss_match_result *out,
                                 ss_error *err) {
  return match_hypotheses(X, Y, sigX, sigY, 0, NULL, NULL, opts_in, out, err);
}

ss_status ssi_match_prepared_signed(const ss_shape_prep *X, const ss_shape_prep *Y, const ss_centre_signature *sigX,
                                    const ss_centre_signature *sigY, int nl, const int *lmX, const int *lmY,
                                    const ss_match_options *opts, ss_match_result *out, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  if (nl == 0) return match_hypotheses(X, Y, sigX, sigY, 0, NULL, NULL, opts, out, err);
  memset(out, 0, sizeof *out);
  ss_match_options o;
  if (opts) o = *opts;
  else ss_match_default_options(&o);
  if (o.autopair.hyp_landmarks < 0 || o.autopair.hyp_landmarks > 2)
    return ss_fail(err, SS_ERR_INVALID, "match: hyp_landmarks %d (0..2)", o.autopair.hyp_landmarks);
  /* hypotheses beside given landmarks: the refined default only, on segmented shapes */
  if (o.autopair.hyp_landmarks && o.autopair.hypotheses > 1 && o.refine == SS_REFINE_BEST && X && Y &&
      X->seg.centers && Y->seg.centers && X->mesh && Y->mesh) {
    for (int i = 0; i < nl; i++)
      if (!lmX || !lmY || lmX[i] < 0 || lmX[i] >= X->mesh->nv || lmY[i] < 0 || lmY[i] >= Y->mesh->nv)
        return ssi_match_core(X, Y, nl, lmX, lmY, NULL, opts, out, err); /* its own messages */
    if (hyp_options_check(&o.autopair, err)) return SS_ERR_INVALID;
    /* an extra beside the landmarks' map: where it cannot be formed (a shape in several components
     * has no pairing signature), the landmarks' map alone, with a note */
    ss_error he = {{0}};
    ss_status hs = match_hypotheses(X, Y, sigX, sigY, nl, lmX, lmY, &o, out, &he);
    if (hs != SS_ERR_INVALID) {
      if (hs && err) *err = he;
      return hs;
    }
    memset(out, 0, sizeof *out);
    ss_status cs = ssi_match_core(X, Y, nl, lmX, lmY, NULL, opts, out, err);
    if (!cs) {
      char note[200];
      snprintf(note, sizeof note, "no hypotheses beside the landmarks (%.150s)", he.msg);
      ssi_match_note(out, note);
    }
    return cs;
  }
  memset(out, 0, sizeof *out);
  return ssi_match_core(X, Y, nl, lmX, lmY, NULL, opts, out, err);
}
