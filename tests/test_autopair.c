/* The landmark-free pairing (match.h, autopair.c): a shape with itself under a vertex permutation
 * (the answer is known exactly), a mirror-decidable constructed case (the synthetic humanoid and its
 * reflection: intrinsically the pairing and its mirror are equal, only the orientation tells them
 * apart), the search on constructed signatures, and FAUST pairs when the data are present. */
#include "match/autopair_internal.h"
#include "specseg/io.h"
#include "specseg/match.h"
#include "specseg/synth.h"
#include "testlib.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Y = X with its vertices renumbered: vertex i of X is vertex perm[i] of Y (faces keep their order
 * and orientation) */
static void permute(const ss_mesh *X, const int *perm, ss_mesh *Y) {
  ss_mesh_alloc(Y, X->nv, X->nf, NULL);
  for (int i = 0; i < X->nv; i++) memcpy(Y->V + 3 * (size_t)perm[i], X->V + 3 * (size_t)i, 3 * sizeof(double));
  for (int f = 0; f < 3 * X->nf; f++) Y->F[f] = perm[X->F[f]];
}

/* Y = the reflection of X in x = 0, faces flipped so that the normals stay outward */
static void reflect(const ss_mesh *X, ss_mesh *Y) {
  ss_mesh_copy(X, Y, NULL);
  for (int i = 0; i < Y->nv; i++) Y->V[3 * (size_t)i] = -Y->V[3 * (size_t)i];
  for (int f = 0; f < Y->nf; f++) {
    int t = Y->F[3 * (size_t)f + 1];
    Y->F[3 * (size_t)f + 1] = Y->F[3 * (size_t)f + 2];
    Y->F[3 * (size_t)f + 2] = t;
  }
}

/* pairing of X and Y through their signatures (sY's shape is pY); right = pairs whose X centre,
 * carried by gt (X vertex -> Y vertex), lies in the paired segment of Y */
static int pair_sigs(const ss_centre_signature *sX, const ss_centre_signature *sY, const int *gt,
                     const ss_autopair_options *ao, ss_autopair_info *info, int *npairs) {
  ss_segment_pairs pr;
  ss_error e;
  int right = -1;
  *npairs = 0;
  if (ss_pair_centres_auto(sX, sY, ao, &pr, info, &e) == SS_OK) {
    right = 0;
    for (int p = 0; p < pr.n; p++) right += sY->prep->seg.labels[gt[sX->prep->seg.centers[pr.sx[p]]]] == pr.sy[p];
    *npairs = pr.n;
    ss_segment_pairs_free(&pr);
  } else {
    printf("pair: %s\n", e.msg);
  }
  return right;
}

static void test_permuted_and_mirrored(void) {
  ss_error e;
  ss_mesh X = {0}, P = {0}, R = {0};
  CHECK(ss_synth_humanoid(0, &X, &e) == SS_OK);
  /* the humanoid is front-back symmetric too, which makes left / right undecidable intrinsically (a
   * half turn about the vertical axis is then an orientation-preserving isometry that swaps them):
   * inflate its front half (z > 0) so that only the left-right mirror symmetry remains */
  for (int i = 0; i < X.nv; i++)
    if (X.V[3 * (size_t)i + 2] > 0) X.V[3 * (size_t)i + 2] *= 1.6;
  const int n = X.nv;
  int *perm = malloc(sizeof(int) * n), *sym = malloc(sizeof(int) * n), *gt = calloc((size_t)n, sizeof(int));
  unsigned r = 12345;
  for (int i = 0; i < n; i++) perm[i] = i;
  for (int i = n - 1; i > 0; i--) {
    r = r * 1664525u + 1013904223u;
    int j = (int)((r >> 8) % (unsigned)(i + 1)), t = perm[i];
    perm[i] = perm[j], perm[j] = t;
  }
  permute(&X, perm, &P);
  reflect(&X, &R);
  const double maxd = tl_mirror_map(X.V, X.nv, sym); /* the humanoid is mirror-symmetric */
  printf("humanoid: %d vertices, mirror map residual %.2g\n", n, maxd);
  ss_shape_prep pX, pP, pR;
  int kev = 100;
  CHECK(ss_shape_prep_compute(&X, NULL, kev, &pX, &e) == SS_OK);
  CHECK(ss_shape_prep_compute(&P, NULL, kev, &pP, &e) == SS_OK);
  CHECK(ss_shape_prep_compute(&R, NULL, kev, &pR, &e) == SS_OK);
  printf("segments: %d, permuted %d, reflected %d\n", pX.seg.m, pP.seg.m, pR.seg.m);
  CHECK(pX.seg.m == pP.seg.m && pX.seg.m == pR.seg.m);

  /* 1. the same shape under a vertex permutation: every pair right, orientation preserved (X's
   * signature serves the reflection's tests below too) */
  ss_centre_signature sX, sP, sR;
  CHECK(ss_centre_signature_compute(&pX, NULL, &sX, &e) == SS_OK && ss_centre_signature_compute(&pP, NULL, &sP, &e) == SS_OK);
  ss_autopair_info info;
  int np, right = pair_sigs(&sX, &sP, perm, NULL, &info, &np);
  ss_centre_signature_free(&sP);
  printf("permuted: %d of %d pairs right, energy %.3g, mirror candidate %.3g, gap %.3f, orientation %.3f vs %.3f%s\n",
         right, np, info.energy, info.energy_mirror, info.gap, info.mirror, info.mirror_other,
         info.confident ? ", confident" : "");
  CHECK(np == pX.seg.m && right == np);
  CHECK(info.exact && info.mirror > 0.8 && info.mirror_other < 0);

  /* 2. the reflection: the vertex-identity pairing is the orientation-REVERSING one (a mirror), as
   * intrinsic as the right answer; the right answer pairs x with the segment of its mirror vertex */
  CHECK(ss_centre_signature_compute(&pR, NULL, &sR, &e) == SS_OK);
  for (int i = 0; i < n; i++) gt[i] = sym[i];
  right = pair_sigs(&sX, &sR, gt, NULL, &info, &np);
  int ident = 0;
  {
    for (int i = 0; i < n; i++) gt[i] = i;
    int np2, r2 = pair_sigs(&sX, &sR, gt, NULL, NULL, &np2);
    ident = r2;
  }
  printf("reflected: %d of %d pairs right (the vertex identity would give %d), gap %.3f, orientation %.3f vs %.3f%s\n",
         right, np, ident, info.gap, info.mirror, info.mirror_other, info.confident ? ", confident" : "");
  CHECK(np == pX.seg.m && right == np);
  CHECK(ident < np); /* the identity pairing differs: the decision was the orientation's */
  CHECK(info.mirror > info.mirror_other && info.mirror_margin > 0);

  /* 2a. the reflection with every third face's winding reversed (not consistently oriented): the
   * signature takes the consistent orientation, so the same pairing and the same scores */
  {
    ss_mesh Rf = {0};
    ss_mesh_copy(&R, &Rf, NULL);
    for (int f = 0; f < Rf.nf; f += 3) {
      int t = Rf.F[3 * (size_t)f + 1];
      Rf.F[3 * (size_t)f + 1] = Rf.F[3 * (size_t)f + 2], Rf.F[3 * (size_t)f + 2] = t;
    }
    ss_shape_prep pRf = pR; /* the segmentation and the spectrum do not depend on the windings */
    pRf.mesh = &Rf;
    ss_centre_signature sRf;
    CHECK(ss_centre_signature_compute(&pRf, NULL, &sRf, &e) == SS_OK);
    ss_autopair_info inf;
    int npf, rf = pair_sigs(&sX, &sRf, sym, NULL, &inf, &npf);
    printf("reflected, every third face flipped: %d of %d right, orientation %.3f vs %.3f (consistent: %.3f vs %.3f)\n",
           rf, npf, inf.mirror, inf.mirror_other, info.mirror, info.mirror_other);
    CHECK(rf == npf && npf == np && fabs(inf.mirror - info.mirror) < 0.02 && fabs(inf.mirror_other - info.mirror_other) < 0.02);
    CHECK(fabs(sRf.volume_ratio - sR.volume_ratio) < 1e-9 * fabs(sR.volume_ratio));
    ss_centre_signature_free(&sRf);
    ss_mesh_free(&Rf);
  }

  /* 2b. the second orientation test (recheck_*): forced on every pairing it decides, reports its own
   * scores and keeps the first test's; off, the reported scores are the first test's */
  {
    ss_autopair_options ao;
    ss_autopair_default_options(&ao);
    ss_autopair_info i0, i1;
    ao.recheck_margin = 0;
    int np0, r0 = pair_sigs(&sX, &sR, sym, &ao, &i0, &np0);
    CHECK(r0 == np0 && !i0.rechecked && i0.mirror == i0.mirror_first && i0.mirror_other == i0.mirror_other_first);
    ao.recheck_margin = 2.0; /* margins are at most 1: always */
    ao.recheck_k = 20, ao.recheck_zoomout = 40, ao.recheck_samples = 500;
    int np1, r1 = pair_sigs(&sX, &sR, sym, &ao, &i1, &np1);
    printf("reflected, second test forced: %d of %d right, first %.3f vs %.3f, second %.3f vs %.3f%s\n", r1, np1,
           i1.mirror_first, i1.mirror_other_first, i1.mirror, i1.mirror_other, i1.confident ? ", confident" : "");
    CHECK(i1.rechecked == 1 && r1 == np1 && i1.mirror > i1.mirror_other);
    CHECK(i1.mirror_first == i0.mirror_first && i1.mirror_other_first == i0.mirror_other_first);
    CHECK(i1.mirror != i1.mirror_first); /* another map: ZoomOut to 40 from k 20 */
    /* the default second test (the protrusions' landmarks, the mean of both medians), forced */
    ss_autopair_options ad;
    ss_autopair_default_options(&ad);
    ad.recheck_margin = 2.0;
    ss_autopair_info i4;
    int np4, r4 = pair_sigs(&sX, &sR, sym, &ad, &i4, &np4);
    printf("reflected, default second test forced: %d of %d right, margin %.3f (first test alone %.3f)\n", r4, np4,
           i4.mirror_margin, i0.mirror_margin);
    CHECK(i4.rechecked == 1 && r4 == np4 && i4.mirror_margin > 0 && i4.mirror_margin != i0.mirror_margin);
    CHECK(i4.mirror_first == i0.mirror_first);
    /* only the 5 centres farthest from the others as the test's landmarks: another map, same answer */
    ss_autopair_options ak;
    ss_autopair_default_options(&ak);
    ak.orient_keep = 0.625;
    ss_autopair_info i2;
    int np2, r2 = pair_sigs(&sX, &sR, sym, &ak, &i2, &np2);
    printf("reflected, 5 protrusion centres in the test: %d of %d right, %.3f vs %.3f\n", r2, np2, i2.mirror, i2.mirror_other);
    CHECK(r2 == np2 && i2.mirror > i2.mirror_other && i2.mirror != i0.mirror);
    ao.recheck_k = 2;
    ss_segment_pairs pr;
    CHECK(ss_pair_centres_auto(&sX, &sR, &ao, &pr, NULL, &e) == SS_ERR_INVALID);
    ak.orient_keep = 0;
    CHECK(ss_pair_centres_auto(&sX, &sR, &ak, &pr, NULL, &e) == SS_ERR_INVALID);
    ss_autopair_default_options(&ak);
    ak.alt_max = -1;
    CHECK(ss_pair_centres_auto(&sX, &sR, &ak, &pr, NULL, &e) == SS_ERR_INVALID);
    ss_autopair_default_options(&ak);
    ak.alt_gap = NAN;
    CHECK(ss_pair_centres_auto(&sX, &sR, &ak, &pr, NULL, &e) == SS_ERR_INVALID);
    /* a signature without its probes (as read from a prepared-shape file) gives the same answer */
    ss_centre_signature sRn = sR;
    sRn.probe_A = NULL, sRn.probe_P = NULL;
    ss_autopair_info i3;
    int np3, r3 = pair_sigs(&sX, &sRn, sym, NULL, &i3, &np3);
    CHECK(r3 == np3 && fabs(i3.mirror - i0.mirror) < 1e-6 && fabs(i3.mirror_margin - i0.mirror_margin) < 1e-6);
  }
  /* 2b. the hypotheses: the answer first (as ss_pair_centres_auto gives it), then its mirror (the
   * vertex-identity pairing here), all distinct; maxh 1 is the answer alone; maxh out of range refused */
  {
    ss_segment_pairs ans, hyp[SS_MAX_HYPOTHESES];
    int nh = 0, nh1 = 0;
    CHECK(ss_pair_centres_auto(&sX, &sR, NULL, &ans, NULL, &e) == SS_OK);
    CHECK(ss_pair_centres_hypotheses(&sX, &sR, NULL, SS_MAX_HYPOTHESES, hyp, &nh, NULL, &e) == SS_OK);
    CHECK(nh >= 2 && nh <= SS_MAX_HYPOTHESES);
    CHECK(hyp[0].n == ans.n && !memcmp(hyp[0].sx, ans.sx, sizeof(int) * (size_t)ans.n) &&
          !memcmp(hyp[0].sy, ans.sy, sizeof(int) * (size_t)ans.n));
    int mirror_right = 0;
    for (int p = 0; p < hyp[1].n; p++)
      mirror_right += sR.prep->seg.labels[sX.prep->seg.centers[hyp[1].sx[p]]] == hyp[1].sy[p]; /* identity */
    printf("hypotheses: %d; the second is the vertex identity on %d of %d pairs\n", nh, mirror_right, hyp[1].n);
    CHECK(mirror_right == hyp[1].n);
    for (int a = 0; a < nh; a++)
      for (int b = a + 1; b < nh; b++)
        CHECK(hyp[a].n != hyp[b].n || memcmp(hyp[a].sy, hyp[b].sy, sizeof(int) * (size_t)hyp[a].n) ||
              memcmp(hyp[a].sx, hyp[b].sx, sizeof(int) * (size_t)hyp[a].n));
    for (int h = 0; h < nh; h++) ss_segment_pairs_free(&hyp[h]);
    CHECK(ss_pair_centres_hypotheses(&sX, &sR, NULL, 1, hyp, &nh1, NULL, &e) == SS_OK && nh1 == 1);
    CHECK(!memcmp(hyp[0].sy, ans.sy, sizeof(int) * (size_t)ans.n));
    ss_segment_pairs_free(&hyp[0]);
    CHECK(ss_pair_centres_hypotheses(&sX, &sR, NULL, 0, hyp, &nh1, NULL, &e) == SS_ERR_INVALID);
    CHECK(ss_pair_centres_hypotheses(&sX, &sR, NULL, SS_MAX_HYPOTHESES + 1, hyp, &nh1, NULL, &e) == SS_ERR_INVALID);
    ss_segment_pairs_free(&ans);
  }

  /* 2c. the map of the reflection without landmarks: every hypothesis mapped, the one of least
   * hypothesis energy returned, and it is the orientation-preserving one (the mirror map of the
   * vertex identity is an isometry too: only the orientation term tells them apart) */
  {
    ss_match_options mo;
    ss_match_default_options(&mo);
    mo.fmap.zoomout_kmax = kev; /* the eigenpairs prepared */
    const double dflt_w_reversed = mo.autopair.hyp_w_reversed;
    CHECK(mo.autopair.hyp_min_orientation == 0 && mo.autopair.hyp_confident_orientation == 0.45);
    /* every candidate mapped, so that each has its numbers (the skip rule: below) */
    CHECK(mo.autopair.hyp_skip_tol == 0);
    ss_autopair_info all;
    memset(&all, 0, sizeof all);
    ss_match_result res;
    double me0 = NAN; /* the default match's kept map: its own energy, whether confident, which */
    int conf0 = 0, kept0 = -1, *map0 = NULL;
    if (ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e)) {
      printf("match: %s\n", e.msg);
      CHECK(0);
    }
    if (res.map) {
      const ss_autopair_info *ai = &res.autopair;
      int right = 0;
      for (int i = 0; i < n; i++) right += res.map[i] == sym[i];
      printf("reflection, landmark-free map: %d hypotheses, #%d returned (energy %.4f; distortion %.4f, orientation "
             "%.3f); %d of %d vertices on their mirror\n", ai->hypotheses, ai->hypothesis, ai->hyp_energy[ai->hypothesis],
             ai->hyp_distortion[ai->hypothesis], ai->hyp_orientation[ai->hypothesis], right, n);
      CHECK(ai->hypotheses >= 2 && ai->hypothesis >= 0 && ai->hypothesis < ai->hypotheses);
      /* the descriptors' own candidate, last, maps this isometry orientation-preserving too */
      printf("  the descriptors' own candidate #%d: energy %.4f, orientation %.3f\n", ai->hyp_descriptor,
             ai->hyp_energy[ai->hyp_descriptor], ai->hyp_orientation[ai->hyp_descriptor]);
      CHECK(ai->hyp_descriptor >= 1 && ai->hyp_descriptor < ai->hypotheses && !ai->hyp_from_y[ai->hyp_descriptor] &&
            ai->hyp_orientation[ai->hyp_descriptor] > 0.5);
      /* X's own candidates first, the descriptors' last of them; then those from Y's side (hyp_reverse),
       * none a flip, each pairing one's pair energy that of one of Y's own pairing hypotheses against X */
      {
        ss_segment_pairs rh[SS_MAX_HYPOTHESES];
        int nrh = 0, from_y = 0;
        CHECK(ss_pair_centres_hypotheses(&sR, &sX, NULL, SS_MAX_HYPOTHESES, rh, &nrh, NULL, &e) == SS_OK);
        for (int h = 0; h < ai->hypotheses; h++) {
          if (!ai->hyp_from_y[h]) {
            CHECK(h <= ai->hyp_descriptor || ai->hyp_flip_of[h] >= 0);
            continue;
          }
          from_y++;
          CHECK(h > ai->hyp_descriptor && ai->hyp_flip_of[h] == -1);
          if (!isfinite(ai->hyp_pair_energy[h])) continue; /* Y's descriptors' candidate */
          int found = 0;
          for (int r = 0; r < nrh && !found; r++) {
            double pe = 0;
            for (int q = 0; q < rh[r].n; q++) pe += rh[r].energy[q];
            found = fabs(pe - ai->hyp_pair_energy[h]) <= 1e-9 * (1 + fabs(pe));
          }
          CHECK_MSG(found, "#%d from Y: pair energy %.17g is none of Y's %d hypotheses'", h, ai->hyp_pair_energy[h], nrh);
        }
        printf("  %d candidates from Y's side (Y's search: %d hypotheses)\n", from_y, nrh);
        for (int r = 0; r < nrh; r++) ss_segment_pairs_free(&rh[r]);
      }
      /* (the least energy is the first choice; a recheck in doubt may keep another, below) */
      for (int h = 0; h < ai->hypotheses; h++) CHECK(ai->hyp_energy[ai->hyp_recheck_from] <= ai->hyp_energy[h]);
      /* the hypothesis energy is its three terms: distortion, reversed segments, the map's own
       * selection energy (every candidate is refined with SS_REFINE_BEST here, so it has one) */
      for (int h = 0; h < ai->hypotheses; h++) {
        const double sum = ai->hyp_distortion[h] + mo.autopair.hyp_w_reversed * ai->hyp_reversed[h] +
                           mo.autopair.hyp_w_map * ai->hyp_map_energy[h];
        CHECK(isfinite(ai->hyp_map_energy[h]) && ai->hyp_map_energy[h] >= 0);
        CHECK_MSG(fabs(ai->hyp_energy[h] - sum) <= 1e-12 * (1 + fabs(sum)), "#%d: %.17g vs %.17g", h,
                  ai->hyp_energy[h], sum);
        /* the distortion's scale: 1 without the fit (hyp_fit_scale, off by default; the fit itself
         * is test_hyp_distortion's) */
        CHECK(mo.autopair.hyp_fit_scale == 0 && ai->hyp_scale[h] == 1);
      }
      CHECK(ai->hyp_orientation[ai->hypothesis] > 0.5);
      CHECK(right > n / 2);
      me0 = ai->hyp_map_energy[ai->hypothesis], conf0 = ai->confident, kept0 = ai->hypothesis;
      all = *ai;
      CHECK(ai->hyp_final_polished == 1);
      map0 = malloc(sizeof(int) * (size_t)n);
      if (map0) memcpy(map0, res.map, sizeof(int) * (size_t)n);
    }
    ss_match_result_free(&res);
    /* the skip rule (hyp_skip_tol 0.05; off by default): a candidate whose landmarks an earlier map already keeps
     * is not mapped. The candidates before the flips are the same ones in the same order, and each
     * one mapped has the numbers it had with every candidate mapped; each one skipped names an
     * earlier one that was mapped, has no numbers and is not kept. On this shape and its reflection
     * the candidates' maps coincide, so some are skipped. */
    if (all.hypotheses > 1) {
      mo.autopair.hyp_skip_tol = 0.05;
      CHECK_MSG(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_OK, "%s", e.msg);
      const ss_autopair_info *ai = &res.autopair;
      int skipped = 0, same = 1;
      for (int h = 0; h < ai->hypotheses && h < all.hypotheses; h++) {
        if (ai->hyp_flip_of[h] >= 0 || all.hyp_flip_of[h] >= 0) break;
        const int by = ai->hyp_skipped_by[h];
        if (by >= 0) {
          skipped++;
          CHECK_MSG(by < h && ai->hyp_skipped_by[by] == -1 && h != ai->hypothesis && isnan(ai->hyp_energy[h]) &&
                        isnan(ai->hyp_distortion[h]) && isnan(ai->hyp_differ[h]),
                    "#%d skipped by #%d", h, by);
        } else
          same &= ai->hyp_energy[h] == all.hyp_energy[h] && ai->hyp_distortion[h] == all.hyp_distortion[h];
      }
      printf("reflection, the skip rule: %d of %d candidates mapped (%d without it), #%d kept (#%d without it)\n",
             ai->hypotheses - skipped, ai->hypotheses, all.hypotheses, ai->hypothesis, all.hypothesis);
      CHECK(same && skipped > 0);
      CHECK(res.map && ai->hyp_orientation[ai->hypothesis] > 0.5);
      ss_match_result_free(&res);
      mo.autopair.hyp_skip_tol = 0;
    }
    /* the orientation rule: without the reversed-segment term the mirror map (an isometry of the
     * symmetric shape) may have the least energy; a candidate below hyp_min_orientation never wins
     * over one above it, and among those above it the least energy wins */
    {
      mo.autopair.hyp_w_reversed = 0;
      mo.autopair.hyp_confident_orientation = 0.99; /* no map reaches it: flagged, with a note saying why */
      CHECK_MSG(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_OK, "%s", e.msg);
      const ss_autopair_info *ai = &res.autopair;
      const int first = ai->hyp_recheck_from;
      const int kept_up = ai->hyp_orientation[first] >= 0;
      int any = 0;
      for (int h = 0; h < ai->hypotheses; h++) any |= ai->hyp_orientation[h] >= 0;
      printf("reflection, no reversed-segment term: #%d of %d kept, orientation %.3f\n", ai->hypothesis,
             ai->hypotheses, ai->hyp_orientation[ai->hypothesis]);
      CHECK(kept_up || !any);
      for (int h = 0; h < ai->hypotheses; h++)
        if ((ai->hyp_orientation[h] >= 0) == kept_up) CHECK(ai->hyp_energy[first] <= ai->hyp_energy[h]);
      CHECK(!ai->confident);
      /* in doubt, the closest candidates were polished and compared again (hyp_recheck_window): the
       * first choice among them; another kept only from within the window, as oriented, with a note */
      printf("  recheck: %d polished, #%d kept, first choice #%d\n", ai->hyp_rechecked, ai->hypothesis, first);
      CHECK(ai->hyp_rechecked >= 1 && ai->hyp_rechecked <= ai->hypotheses);
      if (ai->hypothesis != first) {
        CHECK(ai->hyp_energy[ai->hypothesis] - ai->hyp_energy[first] < mo.autopair.hyp_recheck_window);
        CHECK((ai->hyp_orientation[ai->hypothesis] >= mo.autopair.hyp_min_orientation) ==
              (ai->hyp_orientation[first] >= mo.autopair.hyp_min_orientation));
        CHECK_MSG(strstr(res.notes, "compared again") != NULL, "notes '%s'", res.notes);
      }
      CHECK_MSG(strstr(res.notes, "orientation score") != NULL, "notes '%s'", res.notes);
      /* no map keeps orientation clearly, so flipped candidates are looked for: only of candidates
       * that reverse it (here none does; test_flip has a pair where every one does) */
      for (int h = 0; h < ai->hypotheses; h++) {
        const int f = ai->hyp_flip_of[h];
        CHECK(f == -1 || (f < h && ai->hyp_orientation[f] < 0));
      }
      ss_match_result_free(&res);
    }
    mo.autopair.hyp_w_reversed = dflt_w_reversed;
    /* the flipped candidates' weight is checked (the flips themselves: test_flip) */
    mo.autopair.hyp_flip_orient = -1;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    mo.autopair.hyp_flip_orient = NAN;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    mo.autopair.hyp_flip_orient = 1e300; /* finite, but it would swamp the symmetry map's system */
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    CHECK_MSG(strstr(e.msg, "match: hyp_flip_orient 1e+300 outside [0, 1e+06]"), "%s", e.msg);
    const double dflt_w_orient = mo.fmap.w_orient;
    mo.fmap.w_orient = 1e300;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    mo.fmap.w_orient = dflt_w_orient;
    mo.autopair.hyp_flip_orient = 1;
    /* and so is the orientation shortfall's */
    CHECK(mo.autopair.hyp_w_orientation == 0.01);
    mo.autopair.hyp_w_orientation = -0.01;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    mo.autopair.hyp_w_orientation = INFINITY;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    mo.autopair.hyp_w_orientation = 0.01;
    /* whose symmetry flips: 0..2 */
    CHECK(mo.autopair.hyp_flip_side == 2);
    mo.autopair.hyp_flip_side = 3;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    CHECK_MSG(strstr(e.msg, "hyp_flip_side 3 outside 0..2"), "%s", e.msg);
    mo.autopair.hyp_flip_side = -1;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    mo.autopair.hyp_flip_side = 2;
    /* the further refinement of the map kept: 0..10000 eigenfunctions */
    CHECK(mo.autopair.hyp_final_kmax == 150);
    mo.autopair.hyp_final_kmax = -1;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID && strstr(e.msg, "hyp_final_kmax"));
    mo.autopair.hyp_final_kmax = 10001;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    mo.autopair.hyp_final_kmax = 150;
    mo.autopair.hyp_confident_orientation = 1.5;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    mo.autopair.hyp_confident_orientation = 0.45, mo.autopair.hyp_min_orientation = -1.5;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    mo.autopair.hyp_min_orientation = 0;
    /* one way only (hyp_reverse 0): X's own candidates, none from Y, at most 8 with the flips (the room
     * before hyp_reverse); the option is checked */
    CHECK(mo.autopair.hyp_reverse == 1);
    mo.autopair.hyp_reverse = 0;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_OK);
    CHECK(res.autopair.hypotheses >= 2 && res.autopair.hypotheses <= 8);
    for (int h = 0; h < res.autopair.hypotheses; h++) CHECK(!res.autopair.hyp_from_y[h]);
    ss_match_result_free(&res);
    mo.autopair.hyp_reverse = 2;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID && strstr(e.msg, "hyp_reverse"));
    mo.autopair.hyp_reverse = 1;
    /* the surface polish of the map kept (hyp_final_polish) is ss_map_polish of the map without it,
     * bit for bit; the option is checked */
    CHECK(mo.autopair.hyp_final_polish == 1);
    mo.autopair.hyp_final_polish = 0;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_OK);
    CHECK(res.map && res.autopair.hyp_final_polished == 0 && res.autopair.hypothesis == kept0);
    if (res.map && map0) {
      CHECK(ss_map_polish(pX.mesh, pR.mesh, res.map, NULL, res.map, &e) == SS_OK);
      CHECK(memcmp(res.map, map0, sizeof(int) * (size_t)n) == 0);
    }
    ss_match_result_free(&res);
    mo.autopair.hyp_final_polish = 2;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID && strstr(e.msg, "hyp_final_polish"));
    mo.autopair.hyp_final_polish = 1;
    mo.autopair.hyp_recheck_window = -1;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID && strstr(e.msg, "hyp_recheck_window"));
    mo.autopair.hyp_recheck_window = NAN;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    mo.autopair.hyp_recheck_window = 0.05;
    mo.autopair.hyp_fit_scale = 2;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID &&
          strstr(e.msg, "hyp_fit_scale 2 outside 0..1"));
    mo.autopair.hyp_fit_scale = 1;
    free(map0);
    /* one hypothesis: the pairing's answer alone, as before the hypotheses */
    mo.autopair.hypotheses = 1;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_OK);
    CHECK(res.autopair.hypotheses == 1 && res.autopair.hypothesis == 0 && res.autopair.hyp_descriptor == -1);
    ss_match_result_free(&res);
    mo.autopair.hypotheses = 4, mo.autopair.hyp_descriptor_orient = -1;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    mo.autopair.hyp_descriptor_orient = 2e6;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    mo.autopair.hyp_descriptor_orient = 0.001, mo.autopair.hyp_descriptor_map = 2;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    mo.autopair.hyp_descriptor_map = 1, mo.autopair.hyp_w_map = -0.1;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    mo.autopair.hyp_w_map = NAN;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    mo.autopair.hyp_w_map = 0.05;
    /* a map whose own selection energy is above hyp_max_map_energy is not confident, with a note
     * saying so; below it (the default match above, whose map is right) it is */
    {
      CHECK(mo.autopair.hyp_max_map_energy == 0.37);
      printf("reflection: the kept map's own energy %.4f, confident %d\n", me0, conf0);
      CHECK(isfinite(me0) && me0 < mo.autopair.hyp_max_map_energy && conf0);
      mo.autopair.hyp_max_map_energy = 0.5 * me0;
      CHECK_MSG(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_OK, "%s", e.msg);
      CHECK(res.autopair.hypothesis == kept0 && !res.autopair.confident); /* the choice is not changed */
      CHECK_MSG(strstr(res.notes, "own energy") != NULL, "notes '%s'", res.notes);
      ss_match_result_free(&res);
      mo.autopair.hyp_max_map_energy = NAN;
      CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
      mo.autopair.hyp_max_map_energy = 0.37;
    }
    mo.autopair.hypotheses = SS_MAX_HYPOTHESES + 1;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    { /* the option named, with its value and range */
      char want[64];
      snprintf(want, sizeof want, "hypotheses %d outside 1..%d", SS_MAX_HYPOTHESES + 1, SS_MAX_HYPOTHESES);
      CHECK_MSG(strstr(e.msg, want), "%s", e.msg);
    }
    const double dflt_keep = mo.autopair.hyp_keep;
    mo.autopair.hypotheses = 4, mo.autopair.hyp_keep = 0;
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
    CHECK_MSG(strstr(e.msg, "hyp_keep 0 outside (0, 1]"), "%s", e.msg);
    mo.autopair.hyp_keep = dflt_keep;
    /* three landmarks on their mirrors, hypotheses beside them (hyp_landmarks 1): the map of least
     * hypothesis energy, on the mirrors; off (the default): the landmarks' map alone */
    mo.autopair.hypotheses = 4;
    const int lx[3] = {pX.seg.centers[0], pX.seg.centers[1], pX.seg.centers[2]};
    const int ly[3] = {sym[lx[0]], sym[lx[1]], sym[lx[2]]};
    for (int h = 0; h < 3; h++) {
      mo.autopair.hyp_landmarks = h;
      CHECK_MSG(ss_match_prepared(&pX, &pR, 3, lx, ly, &mo, &res, &e) == SS_OK, "%s", e.msg);
      int right = 0;
      for (int i = 0; res.map && i < n; i++) right += res.map[i] == sym[i];
      const ss_autopair_info *ai = &res.autopair;
      printf("reflection, 3 landmarks, hyp_landmarks %d: %d hypotheses, #%d returned; %d of %d vertices on their mirror\n",
             h, ai->hypotheses, ai->hypothesis, right, n);
      CHECK(right > n / 2 && !ai->used);
      if (!h) CHECK(ai->hypotheses <= 1);
      if (h == 1)
        for (int q = 0; q < ai->hypotheses; q++) CHECK(ai->hyp_energy[ai->hypothesis] <= ai->hyp_energy[q]);
      if (h == 2) {
        CHECK(ai->hypotheses > 1 && ai->hyp_energy[ai->hypothesis] <= ai->hyp_energy[0]);
        /* the margin is taken against the maps that differ: the returned one differs nowhere from
         * itself, shares lie in [0, 1], and counting every candidate (share 0) can only shrink it */
        CHECK(ai->hyp_differ[ai->hypothesis] == 0);
        for (int q = 0; q < ai->hypotheses; q++) CHECK(ai->hyp_differ[q] >= 0 && ai->hyp_differ[q] <= 1);
        const double margin = ai->hyp_margin;
        ss_match_result_free(&res);
        mo.autopair.hyp_differ_share = 0;
        CHECK_MSG(ss_match_prepared(&pX, &pR, 3, lx, ly, &mo, &res, &e) == SS_OK, "%s", e.msg);
        printf("  hypothesis margin %.4g against the maps that differ, %.4g against all\n", margin,
               res.autopair.hyp_margin);
        CHECK(res.autopair.hyp_margin <= margin);
        ss_match_result_free(&res);
        mo.autopair.hyp_differ_share = 1.5;
        CHECK(ss_match_prepared(&pX, &pR, 3, lx, ly, &mo, &res, &e) == SS_ERR_INVALID);
        ss_autopair_options dflt;
        ss_autopair_default_options(&dflt);
        mo.autopair.hyp_differ_share = dflt.hyp_differ_share;
      }
      ss_match_result_free(&res);
    }
    /* five landmarks on their mirrors but the last one wrong (the far end of the shape): with hyp_landmarks 2 the map is still the right one, and a note
     * says that one landmark is off under it */
    {
      int l5x[5], l5y[5];
      for (int q = 0; q < 5; q++) l5x[q] = pX.seg.centers[q % pX.seg.m], l5y[q] = sym[l5x[q]];
      int far = 0; /* the last landmark's partner: the mirror of the vertex farthest from it */
      double dfar = -1;
      for (int i = 0; i < n; i++) {
        const double *a = X.V + 3 * (size_t)i, *b = X.V + 3 * (size_t)l5x[4];
        const double d = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
        if (d > dfar) dfar = d, far = i;
      }
      l5y[4] = sym[far];
      mo.autopair.hyp_landmarks = 2;
      CHECK_MSG(ss_match_prepared(&pX, &pR, 5, l5x, l5y, &mo, &res, &e) == SS_OK, "%s", e.msg);
      int right = 0;
      for (int i = 0; res.map && i < n; i++) right += res.map[i] == sym[i];
      printf("reflection, 5 landmarks (one on the wrong side), hyp_landmarks 2: #%d of %d kept; %d of %d vertices on "
             "their mirror; notes '%s'\n", res.autopair.hypothesis, res.autopair.hypotheses, right, n, res.notes);
      CHECK(right > n / 2);
      /* the wrong landmark is off under a right map: the note names it */
      CHECK_MSG(strstr(res.notes, "1 of the 5 landmarks lie farther") != NULL, "notes '%s'", res.notes);
      ss_match_result_free(&res);
      mo.autopair.hyp_landmarks = 3;
      CHECK(ss_match_prepared(&pX, &pR, 5, l5x, l5y, &mo, &res, &e) == SS_ERR_INVALID);
      mo.autopair.hyp_landmarks = 0;
    }
  }
  ss_centre_signature_free(&sX), ss_centre_signature_free(&sR);

  /* 3. ss_match_prepared without landmarks: the map of the permuted copy is near the truth */
  ss_match_options mo;
  ss_match_default_options(&mo);
  mo.refine = SS_REFINE_NONE;
  ss_match_result res;
  CHECK(ss_match_prepared(&pX, &pP, 0, NULL, NULL, &mo, &res, &e) == SS_OK);
  if (res.map) {
    int exact = 0;
    for (int i = 0; i < n; i++) exact += res.map[i] == perm[i];
    printf("landmark-free map of the permuted copy: %d of %d vertices exact; notes '%s'\n", exact, n, res.notes);
    CHECK(res.autopair.used == 1 && res.pairs.n == pX.seg.m);
    /* either a good map or a note that says the pairing is not confident: never a silent wrong map */
    CHECK(exact > n / 2 || (!res.autopair.confident && strstr(res.notes, "NOT confident")));
    /* the coverage: the map's distinct images over the smaller vertex count (the two have n) */
    char *seen = calloc((size_t)n, 1);
    int distinct = 0;
    for (int i = 0; seen && i < n; i++) distinct += !seen[res.map[i]], seen[res.map[i]] = 1;
    free(seen);
    CHECK_MSG(res.autopair.coverage == (double)distinct / n, "coverage %.17g, %d distinct of %d", res.autopair.coverage,
              distinct, n);
    printf("  its coverage %.4f (%d distinct images)\n", res.autopair.coverage, distinct);
    ss_match_result_free(&res);
    /* a map below hyp_min_coverage is not confident, with a note saying so, and is the same map: the
     * reflected copy's (the permuted copy's is a bijection, coverage 1) */
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_OK);
    const double cov = res.autopair.coverage;
    const int had = res.autopair.confident;
    int *copy = res.map ? malloc(sizeof(int) * (size_t)n) : NULL;
    if (copy) memcpy(copy, res.map, sizeof(int) * (size_t)n);
    printf("  the reflected copy's map: coverage %.4f, confident %d\n", cov, had);
    CHECK(cov > 0.3 && cov < 1);
    ss_match_result_free(&res);
    if (cov < 1) {
      mo.autopair.hyp_min_coverage = nextafter(cov, 2.0);
      CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_OK);
      CHECK(res.map && copy && !memcmp(res.map, copy, sizeof(int) * (size_t)n));
      CHECK(res.autopair.coverage == cov && !res.autopair.confident);
      CHECK_MSG(!had || strstr(res.notes, "images reach only"), "notes '%s'", res.notes);
      ss_match_result_free(&res);
    }
    mo.autopair.hyp_min_coverage = cov; /* at the bound: not below it */
    CHECK(ss_match_prepared(&pX, &pR, 0, NULL, NULL, &mo, &res, &e) == SS_OK);
    CHECK(res.autopair.confident == had);
    ss_match_result_free(&res);
    free(copy);
    mo.autopair.hyp_min_coverage = 1.5;
    CHECK(ss_match_prepared(&pX, &pP, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID && strstr(e.msg, "hyp_min_coverage"));
    mo.autopair.hyp_min_coverage = -0.1;
    CHECK(ss_match_prepared(&pX, &pP, 0, NULL, NULL, &mo, &res, &e) == SS_ERR_INVALID);
  }
  ss_match_result_free(&res);
  ss_shape_prep_free(&pX), ss_shape_prep_free(&pP), ss_shape_prep_free(&pR);
  ss_mesh_free(&X), ss_mesh_free(&P), ss_mesh_free(&R);
  free(perm), free(sym), free(gt);
}

/* FAUST shapes, each read, prepared (100 eigenpairs) and given its signature once: the pairs below
 * share shapes 10 and 15 */
enum { NFAUST = 8 };
static const int faust_ids[NFAUST] = {31, 39, 15, 45, 10, 42, 33, 48};
static struct {
  ss_mesh m;
  ss_shape_prep p;
  ss_centre_signature s;
  int state; /* 0: not yet, 1: ready, -1: failed */
} faust[NFAUST];

static const ss_centre_signature *faust_shape(const char *d, int id) {
  int q = 0;
  while (q < NFAUST && faust_ids[q] != id) q++;
  if (q == NFAUST) return NULL;
  if (!faust[q].state) {
    char path[4096];
    ss_error e = {{0}};
    snprintf(path, sizeof path, "%s/faust/tr_reg_%03d.off", d, id);
    int ok = ss_read_mesh(path, &faust[q].m, &e) == SS_OK &&
             ss_shape_prep_compute(&faust[q].m, NULL, 100, &faust[q].p, &e) == SS_OK &&
             ss_centre_signature_compute(&faust[q].p, NULL, &faust[q].s, &e) == SS_OK;
    CHECK_MSG(ok, "FAUST %d: %s", id, e.msg);
    faust[q].state = ok ? 1 : -1;
  }
  return faust[q].state == 1 ? &faust[q].s : NULL;
}

static void faust_free(void) {
  for (int q = 0; q < NFAUST; q++)
    if (faust[q].state == 1)
      ss_centre_signature_free(&faust[q].s), ss_shape_prep_free(&faust[q].p), ss_mesh_free(&faust[q].m);
}

/* FAUST (ground truth = identity): pairs measured on the tuning split; a confident pairing must be
 * right, and most of these are right */
static void test_faust(void) {
  const char *d = tl_data_dir();
  if (!d) { SKIP("FAUST data not found (SS_DATA_DIR)"); return; }
  static const int pairs[][2] = {{31, 39}, {15, 45}, {10, 42}, {15, 33}};
  const int np = (int)(sizeof pairs / sizeof pairs[0]);
  int nright = 0, nconf_wrong = 0, *id = NULL;
  for (int q = 0; q < np; q++) {
    const ss_centre_signature *sX = faust_shape(d, pairs[q][0]), *sY = faust_shape(d, pairs[q][1]);
    if (!sX || !sY) break;
    if (!id) {
      id = malloc(sizeof(int) * sX->prep->mesh->nv);
      for (int i = 0; i < sX->prep->mesh->nv; i++) id[i] = i;
    }
    ss_autopair_info info;
    int n, right = pair_sigs(sX, sY, id, NULL, &info, &n);
    printf("FAUST %d -> %d: %d of %d pairs right, gap %.3f, orientation %.3f vs %.3f, %s, %.3f s CPU\n", pairs[q][0],
           pairs[q][1], right, n, info.gap, info.mirror, info.mirror_other, info.confident ? "confident" : "NOT confident",
           info.cpu);
    nright += right == n;
    nconf_wrong += info.confident && right != n;
  }
  free(id);
  CHECK(nconf_wrong == 0);
  CHECK(nright >= np - 1); /* 15 -> 33 was wrong before the median rule (its torso saddles sit front / back) */
}

/* FAUST 10 -> 48 (tuning split): the search's best pairing swaps two torso saddles (energy gap
 * 0.002 to the right one); the near-tie test (alt_*) finds the right one, without it the swap stays */
static void test_faust_near_tie(void) {
  const char *d = tl_data_dir();
  if (!d) { SKIP("FAUST data not found (SS_DATA_DIR)"); return; }
  const ss_centre_signature *sg[2] = {faust_shape(d, 10), faust_shape(d, 48)};
  if (!sg[0] || !sg[1]) return;
  const int nv = sg[0]->prep->mesh->nv;
  int *id = malloc(sizeof(int) * nv);
  for (int i = 0; i < nv; i++) id[i] = i;
  ss_autopair_options ao;
  ss_autopair_default_options(&ao);
  ss_autopair_info i0, i1;
  int n1, r1 = pair_sigs(sg[0], sg[1], id, &ao, &i1, &n1);
  ao.alt_max = 0;
  int n0, r0 = pair_sigs(sg[0], sg[1], id, &ao, &i0, &n0);
  printf("FAUST 10 -> 48: near-tie test %d of %d right (%d tested, chosen %d, score %.3f), without it %d of %d "
         "(score %.3f)\n", r1, n1, i1.alternatives, i1.alternative, i1.mirror_first, r0, n0, i0.mirror_first);
  CHECK(r1 == n1 && n1 == 8 && i1.alternative == 1 && i1.alternatives >= 1);
  CHECK(r0 < n0 && i0.alternatives == 0 && i0.alternative == 0);
  CHECK(i1.mirror_first > i0.mirror_first && !i1.confident);
  /* the search's best is now the runner-up: the gap says the answer is not the lowest energy */
  CHECK(fabs(i1.energy_other - i0.energy) <= 1e-12 * i0.energy && i1.gap < 0);
  free(id);
}

/* The oriented polish mends one exchange: FAUST 31 -> 39's right pairing (the search's best here,
 * whose moves all raise the energy) with two centres' partners exchanged is polished back to it in
 * one move (the exchange raised the energy; undoing it keeps the orientation), never to the pairing
 * given as rejected, and a right pairing is left as it is. */
static void test_faust_polish(void) {
  const char *d = tl_data_dir();
  if (!d) { SKIP("FAUST data not found (SS_DATA_DIR)"); return; }
  const ss_centre_signature *A = faust_shape(d, 31), *B = faust_shape(d, 39);
  if (!A || !B) return;
  const int na = A->m, nb = B->m, nv = A->prep->mesh->nv;
  if (na > nb) { SKIP("FAUST 31 has more segments than 39"); return; }
  ss_autopair_options o;
  ss_autopair_default_options(&o);
  double *U = malloc(sizeof(double) * (size_t)nb * nb), *minU = malloc(sizeof(double) * ((size_t)nb + 1));
  double *mv = malloc(sizeof(double) * 2 * (size_t)na * nb);
  int *cur = malloc(sizeof(int) * (size_t)nb), *used = malloc(sizeof(int) * (size_t)nb), *inv = malloc(sizeof(int) * (size_t)nb);
  int *buf = malloc(sizeof(int) * (size_t)na * SSI_TOPK), *p = malloc(sizeof(int) * (size_t)na);
  int *right = malloc(sizeof(int) * (size_t)na), *cand = malloc(sizeof(int) * (size_t)na);
  ssi_search S;
  ssi_init_search(&S, A, &o, U, minU, cur, used, buf);
  ssi_fill_unary(&S, U, minU, A, B, o.w_descr);
  int status = 0;
  ssi_run_search(&S, 1, SSI_TOPK, 0, &status);
  CHECK(status == 0);
  for (int a = 0; a < na; a++) /* the right partner: the segment of B holding A's centre (identity ground truth) */
    right[a] = B->prep->seg.labels[A->centers[a] < nv ? A->centers[a] : 0];
  CHECK(!memcmp(S.top_p[0], right, sizeof(int) * (size_t)na)); /* the search's best is right here */
  ssi_orient_ctx oc;
  ss_error e;
  CHECK(ssi_orient_ctx_new(A, B, o.orient_k, o.orient_descr_k, o.orient_keep, &oc, &e) == SS_OK);
  double r_right = 0;
  CHECK(ssi_orient_ctx_score(&oc, right, &r_right, NULL, &e) == SS_OK);
  const double e_right = ssi_full_energy(&S, right, NULL);
  /* a right pairing: every move raises the energy, nothing to do */
  memcpy(p, right, sizeof(int) * (size_t)na);
  double E = e_right, r = r_right;
  int moves = -1;
  CHECK(ssi_polish_oriented(&oc, &S, p, &E, &r, 5, 0.1, NULL, -2, cand, inv, mv, &moves, &e) == SS_OK);
  CHECK(moves == 0 && !memcmp(p, right, sizeof(int) * (size_t)na) && E == e_right && r == r_right);
  /* every exchange of two partners, mended */
  int tried = 0, mended = 0, refused = 0;
  const clock_t t0 = clock();
  for (int a = 0; a < na; a++)
    for (int c = a + 1; c < na; c++) {
      memcpy(p, right, sizeof(int) * (size_t)na);
      p[a] = right[c], p[c] = right[a];
      E = ssi_full_energy(&S, p, NULL);
      CHECK(ssi_orient_ctx_score(&oc, p, &r, NULL, &e) == SS_OK);
      const double E0 = E, r0 = r;
      CHECK(ssi_polish_oriented(&oc, &S, p, &E, &r, 5, 0.1, NULL, -2, cand, inv, mv, &moves, &e) == SS_OK);
      tried++;
      mended += !memcmp(p, right, sizeof(int) * (size_t)na);
      CHECK(E <= E0 && (moves == 0 || r >= r0 - 0.1 * moves - 1e-12));
      /* the right pairing given as the rejected one: never reached */
      memcpy(p, right, sizeof(int) * (size_t)na);
      p[a] = right[c], p[c] = right[a];
      E = E0, r = r0;
      CHECK(ssi_polish_oriented(&oc, &S, p, &E, &r, 5, 0.1, right, -2, cand, inv, mv, &moves, &e) == SS_OK);
      refused += memcmp(p, right, sizeof(int) * (size_t)na) != 0;
    }
  printf("FAUST 31 -> 39 polish: %d of %d single exchanges mended (score of the right pairing %.3f), %d of %d kept "
         "away from the rejected pairing, %.2f s CPU\n", mended, tried, r_right, refused, tried,
         (double)(clock() - t0) / CLOCKS_PER_SEC);
  CHECK(tried > 0 && mended >= tried * 3 / 4 && refused == tried);
  ssi_orient_ctx_free(&oc);
  free(U), free(minU), free(mv), free(cur), free(used), free(inv), free(buf), free(p), free(right), free(cand);
}

int main(void) {
  test_permuted_and_mirrored();
  test_faust();
  test_faust_near_tie();
  test_faust_polish();
  faust_free();
  TEST_MAIN_END();
}
