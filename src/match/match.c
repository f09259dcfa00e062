/* The matching pipeline of paper §6 on two shapes: pairing of the segments, their probe functions as
 * extra probes of the functional map (STD / ASA / DIFF), point map, ZoomOut. */
#include "util/warnings.h"
#include "specseg/match.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_topology.h"
#include "specseg/streamline.h"
#include "fmap/fmap_options.h"
#include "match/match_internal.h"
#include "match/match_submesh.h"
#include "match/hypotheses.h"
#include "match/autopair_internal.h"
#include "match/landmark_check.h"
#include "util/side_by_side.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Defaults of what the paper leaves open (docs/tuning.md). */
#define SS_DEFAULT_DESCR_K 100
#define SS_DEFAULT_REFINE_KMAX 110
#define SS_DEFAULT_REFINE_W_DESCR 1.0
#define SS_DEFAULT_REFINE_STEP 5
#define SS_DEFAULT_REFINE_SAMPLES 1000
#define SS_DEFAULT_REFINE_SINGLE 1
#define SS_DEFAULT_W_ORIENT 1e-3

void ss_match_default_options(ss_match_options *o) {
  memset(o, 0, sizeof *o);
  o->probes = SS_PROBES_DIFF;
  ss_fmap_match_default_options(&o->fmap);
  o->fmap.descr_k = SS_DEFAULT_DESCR_K;
  o->fmap.zoomout_kmax = SS_DEFAULT_REFINE_KMAX;
  o->fmap.zoomout_step = SS_DEFAULT_REFINE_STEP;
  o->fmap.zoomout_samples = SS_DEFAULT_REFINE_SAMPLES;
  o->fmap.w_orient = SS_DEFAULT_W_ORIENT;
  ss_segment_default_options(&o->seg);
  o->segment_profile = SS_PROFILE_TENT;
  ss_pairing_default_options(&o->pairing);
  o->refine = SS_REFINE_BEST;
  o->refine_w_lap = 0.0;
  o->refine_w_descr = SS_DEFAULT_REFINE_W_DESCR;
  o->refine_single = SS_DEFAULT_REFINE_SINGLE;
  ss_autopair_default_options(&o->autopair);
}

void ss_match_paper_options(ss_match_options *o) {
  ss_match_default_options(o);
  o->fmap.descr_k = 0;
  o->seg_descr_k = 0;
  o->fmap.zoomout_kmax = 0;
  o->fmap.w_orient = 0.0;
  ss_pairing_paper_options(&o->pairing);
  o->refine = SS_REFINE_NONE;
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

/* "match: what" -> "match: SHAPE: what" (every message of a shape's preparation is about one mesh) */
static void name_shape(ss_error *err, const char *shape) {
  if (!err) return;
  char tmp[sizeof err->msg];
  const char *m = err->msg;
  if (!strncmp(m, "match: ", 7)) m += 7;
  snprintf(tmp, sizeof tmp, "match: %s: %.900s", shape, m);
  memcpy(err->msg, tmp, sizeof tmp);
}

/* One shape's preparation for ss_match: segmented (ASA, DIFF, landmark-free) or spectral only. */
typedef struct prep_task {
  const ss_mesh *m;
  int segment, kev;
  const ss_segment_options *so;
  ss_shape_prep *p;
  int done;
} prep_task;
static ss_status prep_task_run(void *arg, ss_error *err) {
  prep_task *t = arg;
  ss_status st = t->segment ? ss_shape_prep_compute(t->m, t->so, t->kev, t->p, err)
                            : ss_shape_prep_compute_spectral(t->m, t->kev, t->p, err);
  t->done = !st;
  return st;
}

/* Both shapes' preparations, side by side (ssi_run_both). Errors name the shape, X's first;
 * *have_x / *have_y: which preparation succeeded (to be freed). */
static ss_status prepare_both(const ss_mesh *PX, const ss_mesh *PY, int segment, const ss_segment_options *so, int kev,
                              ss_shape_prep *pX, ss_shape_prep *pY, int *have_x, int *have_y, ss_error *err) {
  prep_task tx = {PX, segment, kev, so, pX, 0}, ty = {PY, segment, kev, so, pY, 0};
  ss_status st = ssi_run_both(prep_task_run, &tx, prep_task_run, &ty, 1, err);
  *have_x = tx.done, *have_y = ty.done;
  if (st) name_shape(err, !tx.done ? "X (the first mesh)" : "Y (the second mesh)");
  return st;
}

ss_status ss_match_prepared(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX, const int *lmY,
                            const ss_match_options *opts, ss_match_result *out, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  return ssi_match_prepared_signed(X, Y, NULL, NULL, nl, lmX, lmY, opts, out, err);
}


ss_status ss_match_prepared_pairs(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX, const int *lmY,
                                  const ss_segment_pairs *pairs, const ss_match_options *opts, ss_match_result *out,
                                  ss_error *err) {
  if (!pairs) {
    if (out) memset(out, 0, sizeof *out);
    return ss_fail(err, SS_ERR_INVALID, "match: NULL segment pairs");
  }
  return ssi_match_core(X, Y, nl, lmX, lmY, pairs, opts, out, err);
}

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

/* The hypothesis energy of a map (match.h: ss_autopair_options.hyp_w_reversed) */
static double hypothesis_energy(const ss_autopair_options *o, double distortion, double reversed) {
  return distortion + o->hyp_w_reversed * reversed;
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

static int same_set(int n, const int *a, const int *b, int m, const int *c, const int *d) {
  if (n != m) return 0;
  for (int i = 0; i < n; i++)
    if (a[i] != c[i] || b[i] != d[i]) return 0;
  return 1;
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

static ss_status hyp_options_check(const ss_autopair_options *a, ss_error *err) {
  if (a->hypotheses < 1 || a->hypotheses > SS_MAX_HYPOTHESES || !(a->hyp_gap >= 0) ||
      !(a->hyp_w_reversed >= 0) || !isfinite(a->hyp_w_reversed) ||
      !isfinite(a->hyp_reversed_below) || !(a->hyp_keep > 0 && a->hyp_keep <= 1) ||
      !isfinite(a->hyp_min_margin) || !(a->hyp_landmark_tol >= 0) ||
      a->hyp_landmarks < 0 || a->hyp_landmarks > 2 || !(a->hyp_differ_tol >= 0) || !isfinite(a->hyp_differ_tol) ||
      !(a->hyp_differ_share >= 0 && a->hyp_differ_share <= 1))
    return ss_fail(err, SS_ERR_INVALID, "match: hypotheses %d (1..%d), hyp_gap >= 0, hyp_w_reversed >= 0 and hyp_reversed_below finite, hyp_keep in (0, 1], hyp_landmark_tol >= 0, hyp_landmarks 0..2, hyp_differ_tol finite >= 0, hyp_differ_share in [0, 1]",
                   a->hypotheses, SS_MAX_HYPOTHESES);
  return SS_OK;
}

/* The hypotheses' maps and the one of least hypothesis energy (ss_match_prepared_auto; with nlg > 0
 * given landmarks, ss_match_prepared's hypotheses: the given landmarks alone first, then each
 * pairing hypothesis's agreeing protrusion pairs added to them, distinct sets only). */
static ss_status match_hypotheses(const ss_shape_prep *X, const ss_shape_prep *Y, const ss_centre_signature *sigX,
                                  const ss_centre_signature *sigY, int nlg, const int *lgX, const int *lgY,
                                  const ss_match_options *opts_in, ss_match_result *out, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  memset(out, 0, sizeof *out);
  ss_match_options o;
  if (opts_in) o = *opts_in;
  else ss_match_default_options(&o);
  if (!X || !Y || !X->mesh || !Y->mesh || !X->evecs || !Y->evecs)
    return ss_fail(err, SS_ERR_INVALID, "match: shapes not prepared");
  if (hyp_options_check(&o.autopair, err)) return SS_ERR_INVALID;
  ss_centre_signature own[2];
  memset(own, 0, sizeof own);
  ss_segment_pairs hyp[SS_MAX_HYPOTHESES];
  memset(hyp, 0, sizeof hyp);
  int nh = 0;
  ss_autopair_info info;
  ssi_hyp_ctx hc = {0};
  ss_match_result r;
  memset(&r, 0, sizeof r);
  int *lx = NULL, *ly = NULL, *cand = NULL, *maps = NULL;
  double *segs = NULL, *gdX = NULL, *gdY = NULL;
  ss_status st = SS_OK;
  double t0 = ss_time();
  if (!sigX && (st = ss_centre_signature_compute(X, &o.autopair, &own[0], err))) goto done;
  if (!sigY && (st = ss_centre_signature_compute(Y, &o.autopair, &own[1], err))) goto done;
  const ss_centre_signature *SX = sigX ? sigX : &own[0], *SY = sigY ? sigY : &own[1];
  /* with given landmarks, one candidate slot is theirs alone */
  const int want = nlg > 0 && o.autopair.hypotheses >= SS_MAX_HYPOTHESES ? SS_MAX_HYPOTHESES - 1 : o.autopair.hypotheses;
  if ((st = ss_pair_centres_hypotheses(SX, SY, &o.autopair, want, hyp, &nh, &info, err))) goto done;
  if (nlg > 0) info.used = 0;
  if ((nh > 1 || nlg > 0) && (st = ssi_hyp_ctx_new(X->mesh, Y->mesh, 16, &hc, err))) goto done;
  double t_pair = ss_time() - t0;
  int mx = 1;
  for (int h = 0; h < nh; h++)
    if (hyp[h].n > mx) mx = hyp[h].n;
  /* the candidates' landmark sets: cand[c] = its count, its sets at lx / ly + c * stride */
  const int stride = nlg + mx, ncap = 2 * nh + 1;
  lx = malloc(sizeof(int) * (size_t)stride * ncap);
  ly = malloc(sizeof(int) * (size_t)stride * ncap);
  cand = malloc(sizeof(int) * (size_t)ncap);
  segs = malloc(sizeof(double) * 2 * (size_t)SX->m);
  if (!lx || !ly || !cand || !segs) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
  /* from_pairs[c]: hypothesis whose pairing is the segments' (-1: none); free[c]: a landmark-free
   * candidate (hypothesis hyp_of[c]'s protrusion pairs alone) */
  int nc = 0, from_pairs[SS_MAX_HYPOTHESES], free_of[SS_MAX_HYPOTHESES], hyp_of[SS_MAX_HYPOTHESES];
  if (nlg > 0) {
    gdX = malloc(sizeof(double) * (size_t)X->mesh->nv * nlg);
    gdY = malloc(sizeof(double) * (size_t)Y->mesh->nv * nlg);
    if (!gdX || !gdY) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
    for (int i = 0; i < nlg; i++)
      if ((st = ss_graph_dijkstra(&hc.gX, &lgX[i], 1, 0, gdX + (size_t)X->mesh->nv * i, NULL, err)) ||
          (st = ss_graph_dijkstra(&hc.gY, &lgY[i], 1, 0, gdY + (size_t)Y->mesh->nv * i, NULL, err)))
        goto done;
    memcpy(lx, lgX, sizeof(int) * (size_t)nlg), memcpy(ly, lgY, sizeof(int) * (size_t)nlg);
    cand[0] = nlg, from_pairs[0] = -1, free_of[0] = 0, hyp_of[0] = -1, nc = 1;
  }
  /* each hypothesis's landmark-free map; beside given landmarks (hyp_landmarks 2) eligible where it
   * keeps them (see the selection below): a landmark on a spot where two body parts touch and the
   * mesh joins them (FAUST_r tr_reg_017's foot) misleads the landmarks' map, not the protrusions' */
  for (int h = 0; (nlg == 0 || o.autopair.hyp_landmarks == 2) && h < nh && nc < SS_MAX_HYPOTHESES; h++) {
    cand[nc] = kept_pairs(SX, &hyp[h], o.autopair.hyp_keep, X, Y, lx + (size_t)stride * nc, ly + (size_t)stride * nc);
    from_pairs[nc] = cand[nc] < hyp[h].n ? -1 : h;
    free_of[nc] = 1, hyp_of[nc] = h;
    nc++;
  }
  if (nlg > 0) {
    int *kx = malloc(sizeof(int) * (size_t)mx), *ky = malloc(sizeof(int) * (size_t)mx);
    if (!kx || !ky) { free(kx), free(ky); st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
    for (int h = 0; h < nh && nc < SS_MAX_HYPOTHESES; h++) {
      int nk = kept_pairs(SX, &hyp[h], o.autopair.hyp_keep, X, Y, kx, ky);
      int *cx = lx + (size_t)stride * nc, *cy = ly + (size_t)stride * nc;
      memcpy(cx, lgX, sizeof(int) * (size_t)nlg), memcpy(cy, lgY, sizeof(int) * (size_t)nlg);
      int ne = agreeing_pairs(&hc, nlg, gdX, gdY, nk, kx, ky, o.autopair.hyp_landmark_tol, cx + nlg, cy + nlg);
      int dup = ne == 0;
      for (int c = 1; c < nc && !dup; c++)
        dup = !free_of[c] && same_set(cand[c], lx + (size_t)stride * c, ly + (size_t)stride * c, nlg + ne, cx, cy);
      if (!dup) cand[nc] = nlg + ne, from_pairs[nc] = -1, free_of[nc] = 0, hyp_of[nc++] = -1;
    }
    free(kx), free(ky);
  }
  /* hyp_keep = 1 (landmark-free): the paired centres are the landmarks and the pairing is the
   * segments'; otherwise the segments are paired from the landmarks as with given landmarks (the
   * saddles' centres sit front or back inconsistently between shapes) */
  ss_match_options oall = o;
  oall.pairing.min_landmarks = 1;
  oall.pairing.min_map_share = 0; /* the STD map is built from these very centres: no independent check */
  double best = INFINITY, t_loop = ss_time();
  int eligible[SS_MAX_HYPOTHESES], lm_off[SS_MAX_HYPOTHESES];
  const size_t nX = (size_t)X->mesh->nv;
  /* every candidate's map, to tell the candidates that differ from the returned one */
  if (nc > 1 && !(maps = malloc(sizeof(int) * nX * (size_t)nc))) {
    st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
    goto done;
  }
  for (int c = 0; c < nc; c++) {
    const int nl = cand[c], *cx = lx + (size_t)stride * c, *cy = ly + (size_t)stride * c;
    if (from_pairs[c] >= 0) {
      if ((st = ssi_match_core(X, Y, nl, cx, cy, &hyp[from_pairs[c]], &oall, &r, err))) goto done;
    } else {
      ss_match_options ok = o;
      if (free_of[c] && ok.pairing.min_landmarks > nl) ok.pairing.min_landmarks = nl;
      if ((st = ssi_match_core(X, Y, nl, cx, cy, NULL, &ok, &r, err))) goto done;
    }
    double E = 0, dist = NAN, orient = NAN, pe = NAN;
    const int h = hyp_of[c]; /* the pairing hypothesis behind it (landmark-free) */
    if (h >= 0) {
      pe = 0;
      for (int p = 0; p < hyp[h].n; p++) pe += hyp[h].energy[p];
    }
    if (nc > 1) {
      memcpy(maps + nX * c, r.map, sizeof(int) * nX);
      if ((st = ssi_hyp_distortion(&hc, r.map, &dist, err))) goto done;
      orient = ssi_map_orientation(SX, SY, r.map);
      double rev = ssi_map_orientation_reversed(SX, SY, r.map, o.autopair.hyp_reversed_below, segs,
                                                &info.hyp_orientation_min[c]);
      info.hyp_reversed[c] = rev;
      E = hypothesis_energy(&o.autopair, dist, rev);
    }
    info.hyp_pair_energy[c] = pe, info.hyp_distortion[c] = dist, info.hyp_orientation[c] = orient;
    info.hyp_energy[c] = E;
    info.hyp_map_energy[c] = r.refine_choice >= 0 ? r.refine_energy[r.refine_choice] : NAN;
    /* a landmark-free map beside given landmarks must keep them: at most a quarter of them (none of
     * three or fewer) farther than hyp_landmark_tol (geodesic / √area) from their partners */
    int off = 0;
    for (int i = 0; i < nlg; i++)
      off += !(gdY[(size_t)Y->mesh->nv * i + r.map[lgX[i]]] / hc.sY <= o.autopair.hyp_landmark_tol);
    eligible[c] = !free_of[c] || off <= nlg / 4, lm_off[c] = off;
    if (c == 0 || (eligible[c] && E < best)) {
      if (c > 0) ss_match_result_free(out);
      *out = r, best = E, info.hypothesis = c, info.hyp_landmarks = nl;
    } else
      ss_match_result_free(&r);
    memset(&r, 0, sizeof r);
  }
  info.hypotheses = nc;
  info.hyp_margin = INFINITY;
  /* the margin against the maps that differ from the returned one: with landmarks, the landmarks'
   * map and a right landmark-free map agree at almost equal energy, and that tie is no doubt
   * (FAUST_r tuning pairs with gt:5: 83 of 97 flagged by it alone; docs/tuning.md) */
  for (int c = 0; c < nc && nc > 1; c++) {
    info.hyp_differ[c] = map_differ_share(Y->mesh, o.autopair.hyp_differ_tol * hc.sY, (int)nX, maps + nX * c,
                                          maps + nX * info.hypothesis);
    if (c != info.hypothesis && eligible[c] && info.hyp_differ[c] >= o.autopair.hyp_differ_share &&
        info.hyp_energy[c] - best < info.hyp_margin)
      info.hyp_margin = info.hyp_energy[c] - best;
  }
  if (nc > 1) info.confident = info.hyp_margin >= o.autopair.hyp_min_margin;
  else if (nlg > 0) info.confident = 1; /* no hypothesis agreeing with the landmarks offers another map */
  /* the other hypotheses' maps count as pairing time */
  out->t_pair += t_pair + (ss_time() - t_loop) - (out->t_pair + out->t_fmap + out->t_zoomout);
  out->t_total = out->t_segment + out->t_eigs + (ss_time() - t0);
  out->autopair = info;
  if (nlg > 0 && lm_off[info.hypothesis] > 0) {
    char msg[256];
    snprintf(msg, sizeof msg, "%d of the %d landmarks lie farther than %.2g (geodesic / sqrt(area)) from their partners "
             "under the map kept (hypothesis #%d%s); check them", lm_off[info.hypothesis], nlg,
             o.autopair.hyp_landmark_tol, info.hypothesis, free_of[info.hypothesis] ? ", landmark-free" : "");
    ssi_match_note(out, msg);
  }
  if (!info.confident) {
    char msg[240];
    if (nc > 1)
      snprintf(msg, sizeof msg, "%s map NOT confident (hypothesis margin %.3g, min %.3g): another pairing "
               "hypothesis maps almost as well; the map may be wrong (%s)", nlg ? "the" : "landmark-free",
               info.hyp_margin, o.autopair.hyp_min_margin, nlg ? "check the landmarks, add some" : "give landmarks");
    else
      snprintf(msg, sizeof msg, "landmark-free pairing NOT confident (gap %.3g, min %.3g; orientation margin %.2f, min "
               "%.2f): the map may be wrong (give landmarks)", info.gap, o.autopair.min_gap, info.mirror_margin,
               o.autopair.min_mirror);
    ssi_match_note(out, msg);
  }
done:
  if (st) ss_match_result_free(out);
  ss_match_result_free(&r);
  ssi_hyp_ctx_free(&hc);
  ss_centre_signature_free(&own[0]);
  ss_centre_signature_free(&own[1]);
  for (int h = 0; h < nh; h++) ss_segment_pairs_free(&hyp[h]);
  free(lx), free(ly), free(cand), free(segs), free(gdX), free(gdY), free(maps);
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

ss_status ss_match(const ss_mesh *X, const ss_mesh *Y, int nl, const int *lmX, const int *lmY,
                   const ss_match_options *opts_in, ss_match_result *out, ss_error *err) {
  return ss_match_warn(X, Y, nl, lmX, lmY, opts_in, out, NULL, 0, err);
}

ss_status ss_match_warn(const ss_mesh *X, const ss_mesh *Y, int nl, const int *lmX, const int *lmY,
                        const ss_match_options *opts_in, ss_match_result *out, char *warnings, size_t warnings_size,
                        ss_error *err) {
  if (warnings && warnings_size) warnings[0] = '\0';
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  memset(out, 0, sizeof *out);
  ss_match_options o;
  if (opts_in) o = *opts_in;
  else ss_match_default_options(&o);
  if (!X || !Y) return ss_fail(err, SS_ERR_INVALID, "match: NULL mesh");
  /* check the landmarks before the expensive part */
  if (nl < 0 || (nl > 0 && (!lmX || !lmY))) return ss_fail(err, SS_ERR_INVALID, "match: bad landmarks");
  for (int i = 0; i < nl; i++) {
    if (lmX[i] < 0 || lmX[i] >= X->nv)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on X [0,%d)", i, lmX[i], X->nv);
    if (lmY[i] < 0 || lmY[i] >= Y->nv)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on Y [0,%d)", i, lmY[i], Y->nv);
  }
  if (ss_landmarks_check(nl, lmX, lmY, NULL, NULL, err)) return SS_ERR_INVALID; /* too many, two partners */
  ssi_kept kx, ky;
  ss_status st = ssi_keep_landmark_components(X, "X (the first mesh)", nl, lmX, &kx, err);
  if (st) return st;
  if ((st = ssi_keep_landmark_components(Y, "Y (the second mesh)", nl, lmY, &ky, err))) {
    ssi_kept_free(&kx);
    return st;
  }
  const ss_mesh *PX = kx.sub.active ? &kx.sub.mesh : X, *PY = ky.sub.active ? &ky.sub.mesh : Y;
  int *lx = malloc(sizeof(int) * (size_t)(nl > 0 ? nl : 1)), *ly = malloc(sizeof(int) * (size_t)(nl > 0 ? nl : 1));
  double *dX = NULL, *dY = NULL; /* the caller's descriptors on the kept vertices */
  ss_shape_prep pX = {0}, pY = {0};
  ssi_submesh cx = {0}, cy = {0};
  int have_x = 0, have_y = 0;
  if (!lx || !ly) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
  if (o.ndescr > 0 && o.descrX && o.descrY) {
    for (int s = 0; s < 2; s++) {
      const ssi_submesh *kk = s ? &ky.sub : &kx.sub;
      if (!kk->active) continue;
      double *d = malloc(sizeof(double) * (size_t)kk->mesh.nv * (size_t)o.ndescr);
      if (!d) { st = ss_fail(err, SS_ERR_NOMEM, "match: out of memory"); goto done; }
      ssi_submesh_restrict(kk, s ? Y->nv : X->nv, o.ndescr, s ? o.descrY : o.descrX, d);
      if (s) dY = d, o.descrY = d;
      else dX = d, o.descrX = d;
    }
  }
  for (int i = 0; i < nl; i++) lx[i] = ssi_submesh_sub_vertex(&kx.sub, lmX[i]), ly[i] = ssi_submesh_sub_vertex(&ky.sub, lmY[i]);
  int kev = ss_match_eigenpairs(&o, nl);
  /* very large meshes are matched through coarse proxies (topology kept), the map lifted back */
  const ss_mesh *FX = PX;
  /* (not with the caller's descriptors: their rows are the mesh's vertices, not the proxy's) */
  if (!(o.ndescr > 0 && o.descrX && o.descrY) &&
      ((st = ssi_proxy_make(PX, nl, lx, &cx, err)) || (st = ssi_proxy_make(PY, nl, ly, &cy, err))))
    goto done;
  if (cx.active) PX = &cx.mesh;
  if (cy.active) PY = &cy.mesh;
  /* STD with landmarks uses no segments: only the spectra, unless the pairing is asked for */
  const int segment = ss_match_segments(&o, nl);
  double t_prep = ss_time();
  if ((st = prepare_both(PX, PY, segment, &o.seg, kev, &pX, &pY, &have_x, &have_y, err))) goto done;
  t_prep = ss_time() - t_prep;
  if ((st = ssi_check_landmarks_segmented(&pX, &pY, nl, lx, ly, lmX, lmY, err))) goto done;
  if ((st = ss_match_prepared(&pX, &pY, nl, lx, ly, &o, out, err))) goto done;
  /* the stage times add up both shapes' work; the total is the time this call took */
  out->t_total += t_prep - (pX.t_segment + pY.t_segment + pX.t_eigs + pY.t_eigs);
  /* back to the input meshes' vertices: from the proxies, then from the kept components */
  if ((st = ssi_match_lift(&cx, &cy, FX, out, err))) goto done;
  if ((st = ssi_match_lift(&kx.sub, &ky.sub, X, out, err))) goto done;
  ssi_kept_warning(&kx, X, "X (the first mesh)", 1, warnings, warnings_size);
  ssi_kept_warning(&ky, Y, "Y (the second mesh)", 0, warnings, warnings_size);
done:
  if (st) ss_match_result_free(out);
  if (have_x) ss_shape_prep_free(&pX);
  if (have_y) ss_shape_prep_free(&pY);
  free(lx);
  free(ly);
  free(dX);
  free(dY);
  ssi_kept_free(&kx);
  ssi_kept_free(&ky);
  ssi_submesh_free(&cx);
  ssi_submesh_free(&cy);
  return st;
}

ss_status ss_pair_auto(const ss_mesh *X, const ss_mesh *Y, const ss_match_options *opts_in, ss_segment_pairs *pairs,
                       int **centerX, int **centerY, ss_autopair_info *info, ss_error *err) {
  if (!pairs) return ss_fail(err, SS_ERR_INVALID, "pair: NULL output");
  memset(pairs, 0, sizeof *pairs);
  if (centerX) *centerX = NULL;
  if (centerY) *centerY = NULL;
  if (!X || !Y) return ss_fail(err, SS_ERR_INVALID, "pair: NULL mesh");
  ss_match_options o;
  if (opts_in) o = *opts_in;
  else ss_match_default_options(&o);
  int kev = o.autopair.descr_k > o.autopair.orient_k ? o.autopair.descr_k : o.autopair.orient_k;
  const int nmin = X->nv < Y->nv ? X->nv : Y->nv;
  if (kev >= nmin) kev = nmin - 1;
  ss_shape_prep pX = {0}, pY = {0};
  ss_centre_signature sX = {0}, sY = {0};
  ss_status st = ss_shape_prep_compute(X, &o.seg, kev, &pX, err);
  if (!st) st = ss_shape_prep_compute(Y, &o.seg, kev, &pY, err);
  if (!st) st = ss_centre_signature_compute(&pX, &o.autopair, &sX, err);
  if (!st) st = ss_centre_signature_compute(&pY, &o.autopair, &sY, err);
  if (!st) st = ss_pair_centres_auto(&sX, &sY, &o.autopair, pairs, info, err);
  if (!st && (centerX || centerY)) {
    int *cx = malloc(sizeof(int) * (size_t)(pairs->n > 0 ? pairs->n : 1));
    int *cy = malloc(sizeof(int) * (size_t)(pairs->n > 0 ? pairs->n : 1));
    if (!cx || !cy) {
      free(cx), free(cy);
      ss_segment_pairs_free(pairs);
      st = ss_fail(err, SS_ERR_NOMEM, "pair: out of memory");
    } else {
      for (int p = 0; p < pairs->n; p++) cx[p] = pX.seg.centers[pairs->sx[p]], cy[p] = pY.seg.centers[pairs->sy[p]];
      if (centerX) *centerX = cx;
      else free(cx);
      if (centerY) *centerY = cy;
      else free(cy);
    }
  }
  ss_centre_signature_free(&sX);
  ss_centre_signature_free(&sY);
  ss_shape_prep_free(&pX);
  ss_shape_prep_free(&pY);
  return st;
}
