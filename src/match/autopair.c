/* Landmark-free pairing of the segments of two shapes (match.h), the decision and the public entry
 * points: the search's best pairing (pairing_search.c) against its mirror candidate by the first
 * left / right test (pairing_orientation.c), a second test on a close call, the oriented polish
 * (pairing_polish.c), the near-tie
 * alternatives, the hypotheses, the segment pairs and the pairing's confidence; the options'
 * defaults. The centres' signatures: centre_signature.c. */
#include "specseg/match.h"
#include "match/autopair_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Defaults measured in docs/tuning.md (issue 16). */
void ss_autopair_default_options(ss_autopair_options *o) {
  memset(o, 0, sizeof *o);
  o->descr_k = 100;
  o->n_energies = 100;
  o->sigma_factor = 7.0;
  o->descr_radius = 0.05;
  o->w_descr = 0.1;
  o->w_geo = 1.0;
  o->exact_max = 10;
  o->orient_k = 30;
  o->orient_descr_k = 100;
  o->min_gap = 0.03;
  o->min_mirror = 0.15;
  o->orient_keep = 1.0;
  o->recheck_margin = 0.075;
  o->recheck_k = 50;
  o->recheck_zoomout = 0;
  o->recheck_samples = 1000;
  o->recheck_keep = 0.625;
  o->alt_max = 2;
  o->alt_gap = 0.03;
  o->alt_margin = 0.05;
  o->alt_min_score = 0.35;
  o->hypotheses = 4;
  o->hyp_gap = 0.5;
  o->hyp_w_reversed = 0.05;
  o->hyp_reversed_below = 0.15;
  o->hyp_keep = 0.625;
  o->hyp_min_margin = 0.005;
  o->hyp_landmarks = 2;
  o->hyp_landmark_tol = 0.1;
  o->hyp_differ_tol = 0.1;
  o->hyp_differ_share = 0.05;
  o->hyp_min_orientation = 0.0;
  o->hyp_confident_orientation = 0.45;
  o->polish_rounds = 5;
  o->polish_orient_tol = 0.1;
  o->hyp_descriptor_map = 1;
  o->hyp_descriptor_orient = 0.001;
  o->hyp_w_map = 0.05;
  o->hyp_max_map_energy = 0.37;
  o->hyp_flip_orient = 1;
  o->hyp_w_orientation = 0.01;
  o->hyp_flip_side = 2;
  o->hyp_final_kmax = 150;
  o->hyp_reverse = 1;
  o->hyp_final_polish = 1;
  o->hyp_recheck_window = 0.05;
  o->hyp_fit_scale = 0;
  o->hyp_skip_tol = 0;
  o->hyp_min_coverage = 0.65;
}

static double cpu_now(void) {
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static int same(const int *a, const int *b, int n) { return !memcmp(a, b, sizeof(int) * (size_t)n); }

/* The energy of the best leaf of the search other than p1 and p2 (INFINITY: none), copied to other */
static double best_other(const ssi_search *S, const int *p1, const int *p2, int *other) {
  for (int k = 0; k < SSI_TOPK; k++)
    if (isfinite(S->top_e[k]) && !same(S->top_p[k], p1, S->na) && !same(S->top_p[k], p2, S->na)) {
      memcpy(other, S->top_p[k], sizeof(int) * (size_t)S->na);
      return S->top_e[k];
    }
  return INFINITY;
}

/* The mirror candidate of p: p∘σ_A or σ_B∘p, whichever has the lower energy (a mirror is an
 * isometry; a wrong σ costs energy); p itself when neither differs from it. */
static void mirror_candidate(const ssi_search *S, const ss_centre_signature *A, const ss_centre_signature *B, const int *p,
                             int *mir, int *tmp) {
  const int na = A->m;
  for (int a = 0; a < na; a++) mir[a] = p[A->sigma[a]], tmp[a] = B->sigma[p[a]];
  const int id2 = same(mir, p, na), idb = same(tmp, p, na);
  if (!idb && (id2 || ssi_full_energy(S, tmp, NULL) < ssi_full_energy(S, mir, NULL))) memcpy(mir, tmp, sizeof(int) * (size_t)na);
}

/* The first left / right test of p1 against p2: both maps' whole-shape scores r1, r2 (r2 = r1 when
 * p2 = p1) and the decision's margin *med (> 0: p1), the median over A's segments of the two maps'
 * score difference (the torso saddles' segments follow their centres front or back, the
 * protrusions' are too small to map well: a few segments vote wrong, the median is robust to them);
 * ties: the whole-shape scores. seg1, seg2: 2·A->m scratch (per-segment scores), dtmp: A->m. */
static ss_status first_test(ssi_orient_ctx *oc, const int *p1, const int *p2, double *seg1, double *seg2, double *dtmp,
                            double *r1, double *r2, double *med, ss_error *err) {
  const int na = oc->A->m;
  ss_status st = ssi_orient_ctx_score(oc, p1, r1, seg1, err);
  if (st) return st;
  if (same(p1, p2, na)) *r2 = *r1, memcpy(seg2, seg1, sizeof(double) * (size_t)na);
  else if ((st = ssi_orient_ctx_score(oc, p2, r2, seg2, err))) return st;
  *med = ssi_median_margin(na, seg1, seg2, dtmp);
  if (*med == 0) *med = *r1 - *r2;
  return SS_OK;
}

/* A near-tie pairing p against its own mirror by the first test: win / lose (A->m each) receive
 * the one the test picks and the other, sw / sl their whole-shape scores, *med the margin (>= 0). */
static ss_status decide_family(ssi_orient_ctx *oc, const ssi_search *S, const int *p, int *win, int *lose, double *seg1,
                               double *seg2, double *dtmp, double *sw, double *sl, double *med, ss_error *err) {
  const int na = oc->A->m;
  mirror_candidate(S, oc->A, oc->B, p, lose, win);
  double r1 = 0, r2 = 0, m = 0;
  ss_status st = first_test(oc, p, lose, seg1, seg2, dtmp, &r1, &r2, &m, err);
  if (st) return st;
  if (m >= 0) memcpy(win, p, sizeof(int) * (size_t)na), *sw = r1, *sl = r2, *med = m;
  else memcpy(win, lose, sizeof(int) * (size_t)na), memcpy(lose, p, sizeof(int) * (size_t)na), *sw = r2, *sl = r1, *med = -m;
  return SS_OK;
}

/* The segment pairs of an assignment p (A index -> B index; swap: A is Y), sorted by sx; share
 * (A->m, may be NULL): the per-pair energies. */
static ss_status pairs_of_assignment(const ss_centre_signature *X, const ss_centre_signature *Y, int swap, const int *p,
                                     const double *share, ss_segment_pairs *out, ss_error *err) {
  const int na = swap ? Y->m : X->m, nb = swap ? X->m : Y->m;
  memset(out, 0, sizeof *out);
  out->nx = X->m, out->ny = Y->m, out->n = na;
  out->sx = malloc(sizeof(int) * (size_t)na);
  out->sy = malloc(sizeof(int) * (size_t)na);
  out->energy = malloc(sizeof(double) * (size_t)na);
  if (!out->sx || !out->sy || !out->energy) {
    ss_segment_pairs_free(out);
    return ss_fail(err, SS_ERR_NOMEM, "autopair: out of memory");
  }
  if (!swap) {
    for (int a = 0; a < na; a++) out->sx[a] = a, out->sy[a] = p[a], out->energy[a] = share ? share[a] : NAN;
  } else {
    int q = 0;
    for (int b = 0; b < nb; b++)
      for (int a = 0; a < na; a++)
        if (p[a] == b) out->sx[q] = b, out->sy[q] = a, out->energy[q++] = share ? share[a] : NAN;
  }
  return SS_OK;
}

/* Appends p to the distinct hypotheses hyp (na each, *nh of them, at most maxh) */
static void add_hypothesis(int na, const int *p, int maxh, int *hyp, int *nh) {
  if (*nh >= maxh) return;
  for (int h = 0; h < *nh; h++)
    if (same(hyp + (size_t)na * h, p, na)) return;
  memcpy(hyp + (size_t)na * (*nh)++, p, sizeof(int) * (size_t)na);
}

static ss_status pair_auto(const ss_centre_signature *X, const ss_centre_signature *Y, const ss_autopair_options *o_in,
                           int maxh, ss_segment_pairs *hyp_out, int *nh_out, ss_segment_pairs *out,
                           ss_autopair_info *info, ss_error *err);

/* 1 when the descriptors and distances the search's energies are made of are finite */
static int signature_finite(const ss_centre_signature *s) {
  for (size_t i = 0; i < (size_t)s->m * s->nd; i++)
    if (!isfinite(s->descr[i])) return 0;
  for (size_t i = 0; i < (size_t)s->m * s->m; i++)
    if (!isfinite(s->D[i])) return 0;
  return 1;
}

ss_status ss_pair_centres_auto(const ss_centre_signature *X, const ss_centre_signature *Y, const ss_autopair_options *o_in,
                               ss_segment_pairs *out, ss_autopair_info *info, ss_error *err) {
  return pair_auto(X, Y, o_in, 0, NULL, NULL, out, info, err);
}

ss_status ss_pair_centres_hypotheses(const ss_centre_signature *X, const ss_centre_signature *Y,
                                     const ss_autopair_options *o, int maxh, ss_segment_pairs *hyp, int *nh,
                                     ss_autopair_info *info, ss_error *err) {
  if (nh) *nh = 0;
  if (!hyp || !nh || maxh < 1 || maxh > SS_MAX_HYPOTHESES) return ss_fail(err, SS_ERR_INVALID, "autopair: no room for hypotheses");
  for (int h = 0; h < maxh; h++) memset(&hyp[h], 0, sizeof hyp[h]);
  ss_segment_pairs answer;
  ss_status st = pair_auto(X, Y, o, maxh, hyp, nh, &answer, info, err);
  ss_segment_pairs_free(&answer);
  return st;
}

static ss_status pair_auto(const ss_centre_signature *X, const ss_centre_signature *Y, const ss_autopair_options *o_in,
                           int maxh, ss_segment_pairs *hyp_out, int *nh_out, ss_segment_pairs *out,
                           ss_autopair_info *info, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "autopair: NULL output");
  memset(out, 0, sizeof *out);
  if (info) {
    memset(info, 0, sizeof *info);
    for (int c = 0; c < SS_MAX_HYPOTHESES; c++) info->hyp_flip_of[c] = info->hyp_skipped_by[c] = -1;
  }
  ss_autopair_options o;
  if (o_in) o = *o_in;
  else ss_autopair_default_options(&o);
  if (!X || !Y || X->m < 1 || Y->m < 1 || !X->descr || !Y->descr || !X->D || !Y->D || !X->prep || !Y->prep)
    return ss_fail(err, SS_ERR_INVALID, "autopair: empty signature");
  if (X->nd != Y->nd)
    return ss_fail(err, SS_ERR_INVALID, "autopair: signatures computed with different options");
  /* a NaN energy is never below another: the search would keep no leaf and the mirror search
   * would read an unset assignment */
  if (!signature_finite(X) || !signature_finite(Y))
    return ss_fail(err, SS_ERR_INVALID, "autopair: a signature's descriptors or distances are not finite");
  if (!(o.w_descr >= 0) || !(o.w_geo >= 0) || !isfinite(o.w_descr + o.w_geo))
    return ss_fail(err, SS_ERR_INVALID, "autopair: weights must be finite and non-negative");
  if (!(o.orient_keep > 0 && o.orient_keep <= 1))
    return ss_fail(err, SS_ERR_INVALID, "autopair: orient_keep must be in (0, 1]");
  if (!(o.recheck_margin >= 0) ||
      (o.recheck_margin > 0 && (o.recheck_k < 3 || o.recheck_zoomout < 0 || o.recheck_samples < 0 ||
                                !(o.recheck_keep > 0 && o.recheck_keep <= 1))))
    return ss_fail(err, SS_ERR_INVALID,
                   "autopair: bad second-test options (recheck_margin >= 0, recheck_k >= 3, recheck_keep in (0, 1])");
  if (o.alt_max < 0 || !(o.alt_gap >= 0) || !isfinite(o.alt_gap) || !(o.alt_margin >= 0) || !isfinite(o.alt_margin) ||
      !isfinite(o.alt_min_score))
    return ss_fail(err, SS_ERR_INVALID, "autopair: bad near-tie options (alt_max >= 0, alt_gap and alt_margin finite, >= 0)");
  if (o.polish_rounds < 0 || o.polish_rounds > 100 || !(o.polish_orient_tol >= 0) || !isfinite(o.polish_orient_tol))
    return ss_fail(err, SS_ERR_INVALID, "autopair: bad polish options (polish_rounds 0..100, polish_orient_tol finite, >= 0)");
  double c0 = cpu_now();
  const int swap = X->m > Y->m;
  const ss_centre_signature *A = swap ? Y : X, *B = swap ? X : Y;
  const int na = A->m, nb = B->m;
  ss_status st = SS_OK;
  int status = 0, nh = 0, *hyp = NULL;
  const int nbuf = SSI_TOPK + 5;
  double *U = malloc(sizeof(double) * (size_t)nb * nb), *minU = malloc(sizeof(double) * ((size_t)nb + 1));
  double *share = malloc(sizeof(double) * (size_t)na), *seg1 = malloc(sizeof(double) * 2 * (size_t)na);
  double *seg2 = malloc(sizeof(double) * 2 * (size_t)na);
  int *cur = malloc(sizeof(int) * (size_t)nb), *used = malloc(sizeof(int) * (size_t)nb);
  int *buf = malloc(sizeof(int) * (size_t)na * nbuf), *alt_seen = malloc(sizeof(int) * (size_t)na * 2 * SSI_TOPK);
  ssi_search S;
  ssi_orient_ctx oc = {0};
  if (!U || !minU || !share || !seg1 || !seg2 || !cur || !used || !buf || !alt_seen) {
    st = ss_fail(err, SS_ERR_NOMEM, "autopair: out of memory");
    goto done;
  }
  ssi_init_search(&S, A, &o, U, minU, cur, used, buf);
  int *pi1 = buf + (size_t)na * SSI_TOPK, *pi2 = pi1 + na, *third = pi2 + na, *before = third + na;
  const int exact = na <= o.exact_max && ssi_count_injections(na, nb) <= 5e7;
  ssi_fill_unary(&S, U, minU, A, B, o.w_descr);
  ssi_run_search(&S, exact, SSI_TOPK, 0, &status);
  if (status) { st = ss_fail(err, SS_ERR_NOMEM, "autopair: out of memory"); goto done; }
  if (!isfinite(S.top_e[0])) { /* no leaf kept (energies not finite): S.top_p[0] is unset */
    st = ss_fail(err, SS_ERR_INVALID, "autopair: no pairing of finite energy (the signatures' values are not finite)");
    goto done;
  }
  memcpy(pi1, S.top_p[0], sizeof(int) * (size_t)na);
  mirror_candidate(&S, A, B, pi1, pi2, third);
  double e1 = ssi_full_energy(&S, pi1, NULL), e2 = ssi_full_energy(&S, pi2, NULL), e3 = best_other(&S, pi1, pi2, third);
  /* left / right: the candidate whose map preserves orientation */
  if (same(pi1, pi2, na) && isfinite(e3)) { /* no symmetry found: the runner-up is the other candidate */
    memcpy(pi2, third, sizeof(int) * (size_t)na), e2 = e3;
    e3 = best_other(&S, pi1, pi2, third); /* the gap is to the next leaf */
  }
  double r1 = 0, r2 = 0, med = 0;
  if ((st = ssi_orient_ctx_new(A, B, o.orient_k, o.orient_descr_k, o.orient_keep, &oc, err))) goto done;
  if ((st = first_test(&oc, pi1, pi2, seg1, seg2, share, &r1, &r2, &med, err))) goto done;
  const double r1_first = r1, r2_first = r2;
  int rechecked = 0;
  if (!same(pi1, pi2, na) && fabs(med) / 2 < o.recheck_margin) { /* a close call: a second test */
    if (o.recheck_zoomout > o.recheck_k) { /* ZoomOut-refined maps, whose scores decide */
      if ((st = ssi_autopair_recheck_score(A, B, pi1, &o, &r1, err))) goto done;
      if ((st = ssi_autopair_recheck_score(A, B, pi2, &o, &r2, err))) goto done;
      med = r1 - r2;
    } else { /* the protrusions' landmarks only: the mean of both tests' medians */
      ssi_orient_ctx oc2;
      if ((st = ssi_orient_ctx_new(A, B, o.recheck_k, o.orient_descr_k, o.recheck_keep, &oc2, err))) goto done;
      st = ssi_orient_ctx_score(&oc2, pi1, &r1, seg1, err);
      if (!st) st = ssi_orient_ctx_score(&oc2, pi2, &r2, seg2, err);
      ssi_orient_ctx_free(&oc2);
      if (st) goto done;
      med = 0.5 * (med + ssi_median_margin(na, seg1, seg2, share));
    }
    rechecked = 1;
  }
  double f1 = r1_first, f2 = r2_first;
  if (med < 0) {
    med = -med;
    f1 = r2_first, f2 = r1_first;
    int *t = pi1;
    pi1 = pi2, pi2 = t;
    double x = r1;
    r1 = r2, r2 = x;
    x = e1, e1 = e2, e2 = x;
  }
  /* near-ties beyond the mirror pair: each with its own mirror through the first test; one replaces
   * the answer when its winner's map is clearly orientation-preserving (whole-shape score at least
   * alt_min_score) and beats both first-test scores of the answer's pair by alt_margin (a swap of
   * two torso saddles is a partial mirror: its map reverses orientation there; where the second
   * test decided, the first test's scores of the pair are both weak) */
  int n_alt = 0, alt = 0;
  const int amax = o.alt_max < SSI_TOPK ? o.alt_max : SSI_TOPK;
  for (int k = 0; k < SSI_TOPK && n_alt < amax; k++) {
    if (!isfinite(S.top_e[k]) || S.top_e[k] > S.top_e[0] * (1 + o.alt_gap)) break;
    const int *c = S.top_p[k];
    int seen = same(c, pi1, na) || same(c, pi2, na);
    for (int t = 0; t < 2 * n_alt && !seen; t++) seen = same(c, alt_seen + (size_t)na * t, na);
    if (seen) continue;
    int *win = alt_seen + (size_t)na * 2 * n_alt, *lose = win + na;
    double sw, sl, am;
    if ((st = decide_family(&oc, &S, c, win, lose, seg1, seg2, share, &sw, &sl, &am, err))) goto done;
    n_alt++;
    if (sw >= o.alt_min_score && sw > (f1 > f2 ? f1 : f2) + o.alt_margin) {
      memcpy(pi1, win, sizeof(int) * (size_t)na), memcpy(pi2, lose, sizeof(int) * (size_t)na);
      r1 = f1 = sw, r2 = f2 = sl, med = am, rechecked = 0, alt = 1;
      e1 = ssi_full_energy(&S, pi1, NULL), e2 = ssi_full_energy(&S, pi2, NULL);
    }
  }
  if (alt) e3 = best_other(&S, pi1, pi2, third); /* the search's best, now the runner-up */
  int polished = 0;
  memcpy(before, pi1, sizeof(int) * (size_t)na);
  if (o.polish_rounds > 0) {
    int *inv = malloc(sizeof(int) * (size_t)nb);
    double *mv = malloc(sizeof(double) * 2 * (size_t)na * nb);
    if (!inv || !mv) st = ss_fail(err, SS_ERR_NOMEM, "autopair: out of memory");
    if (!st) st = ssi_polish_oriented(&oc, &S, pi1, &e1, &f1, o.polish_rounds, o.polish_orient_tol, pi2, f2, third, inv, mv,
                                        &polished, err);
    free(inv), free(mv);
    if (st) goto done;
    if (polished) r1 = f1;
  }
  (void)ssi_full_energy(&S, pi1, share);
  if ((st = pairs_of_assignment(X, Y, swap, pi1, share, out, err))) goto done;
  if (maxh > 0) { /* the answer, its mirror, then the search's next leaves, each followed by its mirror */
    if (!(hyp = malloc(sizeof(int) * (size_t)na * ((size_t)maxh + 1)))) {
      st = ss_fail(err, SS_ERR_NOMEM, "autopair: out of memory");
      goto done;
    }
    int *mir = hyp + (size_t)na * maxh;
    add_hypothesis(na, pi1, maxh, hyp, &nh);
    if (polished) add_hypothesis(na, before, maxh, hyp, &nh);
    add_hypothesis(na, pi2, maxh, hyp, &nh);
    for (int k = 0; k < SSI_TOPK && nh < maxh; k++) {
      if (!isfinite(S.top_e[k]) || S.top_e[k] > S.top_e[0] * (1 + o.hyp_gap)) break;
      add_hypothesis(na, S.top_p[k], maxh, hyp, &nh);
      mirror_candidate(&S, A, B, S.top_p[k], mir, third);
      add_hypothesis(na, mir, maxh, hyp, &nh);
    }
    for (int h = 0; h < nh; h++) {
      (void)ssi_full_energy(&S, hyp + (size_t)na * h, share);
      if ((st = pairs_of_assignment(X, Y, swap, hyp + (size_t)na * h, share, &hyp_out[h], err))) {
        for (int g = 0; g < h; g++) ss_segment_pairs_free(&hyp_out[g]);
        nh = 0;
        goto done;
      }
    }
    *nh_out = nh;
  }
  if (info) {
    double emin = e1 < e2 ? e1 : e2;
    info->used = 1;
    info->exact = exact;
    info->energy = e1;
    info->energy_mirror = e2;
    info->energy_other = e3;
    info->gap = isfinite(e3) ? (e3 - emin) / (emin > 1e-300 ? emin : 1e-300) : INFINITY;
    info->mirror = r1;
    info->mirror_other = r2;
    info->mirror_margin = med / 2;
    info->confident = info->gap >= o.min_gap && info->mirror_margin >= o.min_mirror;
    info->pairing_confident = info->confident;
    info->rechecked = rechecked;
    info->mirror_first = f1;
    info->mirror_other_first = f2;
    info->cpu = cpu_now() - c0;
    info->alternatives = n_alt;
    info->alternative = alt;
    info->polished = polished;
  }
done:
  ssi_orient_ctx_free(&oc);
  free(U), free(minU), free(share), free(seg1), free(seg2), free(cur), free(used), free(buf), free(alt_seen);
  free(hyp);
  if (st) ss_segment_pairs_free(out);
  return st;
}
