/* specseg — shape matching with coherent segments as probe functions (paper §6): pairing of the
 * segments through landmark distance fields (§6.1), the paired segments as probe functions,
 * per-shape preparation (segmentation + eigenpairs, cacheable) and the whole STD / ASA / DIFF
 * pipeline from two meshes to a point map. The functional-map machinery it builds on (descriptors,
 * Eq. (1), point maps, ZoomOut) is in fmap.h and knows nothing of segments. */
#ifndef SPECSEG_MATCH_H
#define SPECSEG_MATCH_H

#include "specseg/core.h"
#include "specseg/fmap.h"
#include "specseg/segment.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Pairing of segments (pairing.c) ------------------------------------------------------------ */

/* Pairs of segments of two shapes (X, Y), from the pairing with landmarks or the landmark-free one.
 * Free with ss_segment_pairs_free.
 */
typedef struct ss_segment_pairs {
  int n;          /* number of pairs */
  int *sx, *sy;   /* n: segment index on X / on Y of each pair */
  double *energy; /* n: ‖(d_X^i(x) − d_Y^i(y))_i‖₂ of the pair (distances divided by √area) */
  int nx, ny;     /* critical points (segments) on each shape */
} ss_segment_pairs;

/* Confidence rules on top of the paper's pairing (all off = the paper's rule; ss_pairing_default_options
 * gives the library's defaults, chosen in docs/tuning.md). For a chooser a (a critical point of the
 * shape with fewer of them) with best candidate b* (energy e1) and second-best candidate (e2):
 *  - min_ratio > 1: the pair is kept only when e2 ≥ min_ratio · e1 (an unambiguous choice);
 *  - mutual: kept only when a is also the best chooser for b* among ALL choosers (mutual nearest
 *    neighbours in landmark-distance space; the paper keeps the best of those that chose b*);
 *  - max_rel_energy > 0: kept only when e1 ≤ max_rel_energy · ‖d(a)‖ / √nl, ‖d(a)‖/√nl the RMS
 *    distance of a to the landmarks: the energy relative to how far the point is from them;
 *  - min_landmarks: with fewer landmarks ss_match_prepared uses no segment probes at all (it says so
 *    in its notes); the pairing itself is still computed and reported;
 *  - min_map_share > 0: a check against the STD map (WKS + landmarks alone, which the pairing does not
 *    influence): ss_match_prepared keeps a pair only when that map sends at least this share (by
 *    mass) of X's segment into the paired segment of Y (ss_segment_pairs_check_map), and says in its
 *    notes how many it dropped. A wrong pair that the ratio test lets through pulls the segment-aided
 *    map away from a good STD map (TOSCA, docs/tuning.md); a right one agrees with it. */
typedef struct ss_pairing_options {
  double min_ratio;
  int mutual;
  double max_rel_energy;
  int min_landmarks;
  double min_map_share;
} ss_pairing_options;

/* Fills o with the library's confidence rules (ss_pairing_options above; values chosen in
 * docs/tuning.md).
 *
 * Outputs:
 *   o        every field written
 */
SS_API void ss_pairing_default_options(ss_pairing_options *o);
/* Fills o with the paper's rule: every confidence test off, min_landmarks 1.
 *
 * Outputs:
 *   o        every field written
 */
SS_API void ss_pairing_paper_options(ss_pairing_options *o);

/* Pairs the segments of two shapes through landmark distance fields (§6.1): exact (VTP) fields from
 * each landmark on both work meshes, each divided by √area(work); for every critical point x of the
 * shape with fewer of them (X on ties) the critical point y* of the other shape minimising
 * ‖(d_X^i(x) − d_Y^i(y))_i‖₂; when several x choose the same y*, only the one with the smallest energy
 * keeps it (the paper's conservative rule).
 *
 * Inputs:
 *   X, Y     segmentations from ss_segment on inputs its sanitizer left unchanged (psi indexed by
 *            input vertex)
 *   nl       number of landmarks (>= 1)
 *   lmX, lmY nl corresponding INPUT vertices (< X->nv, < Y->nv); Ψ carries them to the work meshes
 * Outputs:
 *   out      pairs sorted by sx (free with ss_segment_pairs_free)
 * Errors: SS_ERR_INVALID on a NULL output, an incomplete segmentation, no landmark or a landmark out
 *   of range; errors of the geodesic fields; SS_ERR_NOMEM.
 */
SS_API ss_status ss_pair_segments(const ss_segmentation *X, const ss_segmentation *Y, int nl, const int *lmX,
                                  const int *lmY, ss_segment_pairs *out, ss_error *err);
/* The pairing of ss_pair_segments from precomputed landmark fields at the critical points.
 *
 * Inputs:
 *   mx, my   critical points (segments) on X and Y
 *   nl       number of landmarks (>= 1)
 *   dX       mx x nl, column-major: dX[s + mx·i] = scaled distance from landmark i to critical point s
 *   dY       my x nl, likewise
 * Outputs:
 *   out      pairs sorted by sx (free with ss_segment_pairs_free)
 * Errors: SS_ERR_INVALID on a NULL output or bad sizes; SS_ERR_NOMEM.
 */
SS_API ss_status ss_pair_critical_points(int mx, int my, int nl, const double *dX, const double *dY,
                                         ss_segment_pairs *out, ss_error *err);
/* ss_pair_critical_points with the confidence rules of po.
 *
 * Inputs:
 *   mx, my, nl, dX, dY  as ss_pair_critical_points
 *   po       the rules (NULL: the paper's rule, as ss_pair_critical_points)
 * Outputs:
 *   out      pairs sorted by sx (free with ss_segment_pairs_free)
 * Errors: SS_ERR_INVALID on a NULL output or bad sizes; SS_ERR_NOMEM.
 */
SS_API ss_status ss_pair_critical_points_conf(int mx, int my, int nl, const double *dX, const double *dY,
                                              const ss_pairing_options *po, ss_segment_pairs *out, ss_error *err);
/* ss_pair_segments with the confidence rules of po.
 *
 * Inputs:
 *   X, Y, nl, lmX, lmY  as ss_pair_segments
 *   po       the rules (NULL: the paper's rule, as ss_pair_segments)
 * Outputs:
 *   out      pairs sorted by sx (free with ss_segment_pairs_free)
 * Errors: as ss_pair_segments.
 */
SS_API ss_status ss_pair_segments_conf(const ss_segmentation *X, const ss_segmentation *Y, int nl, const int *lmX,
                                       const int *lmY, const ss_pairing_options *po, ss_segment_pairs *out,
                                       ss_error *err);
/* Frees the arrays of p and zeroes it; safe on a zeroed struct.
 *
 * Inputs:
 *   p        pairs from any pairing call
 */
SS_API void ss_segment_pairs_free(ss_segment_pairs *p);
/* The check of min_map_share: for each pair p, share_p = Σ M(x) over the vertices x of X's segment
 * sx[p] whose image map[x] lies in Y's segment sy[p], divided by Σ M(x) over that segment; pairs with
 * share_p < min_share are removed from pairs in place (order kept).
 *
 * Inputs:
 *   X, Y     the segmentations (their iVd labels of the input vertices are used)
 *   MX       X's vertex masses (NULL: every vertex 1)
 *   map      X->nv vertices of Y
 *   min_share  the threshold
 *   pairs    the pairs (updated in place)
 * Outputs:
 *   share    (may be NULL) pairs->n values: the shares before dropping
 *   dropped  (may be NULL) how many pairs were removed
 * Errors: SS_ERR_INVALID on incomplete input or a pair out of range; SS_ERR_NOMEM.
 */
SS_API ss_status ss_segment_pairs_check_map(const ss_segmentation *X, const ss_segmentation *Y, const double *MX,
                                            const int *map, double min_share, ss_segment_pairs *pairs, double *share,
                                            int *dropped, ss_error *err);

/* ---- Segment probe functions (segment_probes.c) ------------------------------------------------- */

typedef enum ss_segment_profile {
  SS_PROFILE_INDICATOR = 0, /* 1 on the segment, 0 elsewhere */
  SS_PROFILE_TENT = 1,      /* 1 − d/R on the segment (d: the segmentation's distance to the segment's
                               centre, R: its largest value on the segment), 0 elsewhere */
  SS_PROFILE_SOFT = 2       /* soft iVd membership exp(−d_s/τ) / Σ_j exp(−d_j/τ) over all m segments,
                               d_j the NPP22-graph distance on the work mesh from centre j (pulled
                               back through Ψ), τ = 0.2·√area(work): a partition of unity whose
                               arg-max is the segment itself */
} ss_segment_profile;

/* The probe functions of paired segments on one shape: column p is segment seg[p] in the given
 * profile. The tent needs the segmentation's distances (work_dist, psi), the soft profile its work
 * mesh and critical points (m graph Dijkstras).
 *
 * Inputs:
 *   sg       the segmentation, nv input vertices
 *   npairs   number of columns
 *   seg      npairs segment indices in [0, sg->m)
 *   profile  SS_PROFILE_INDICATOR, SS_PROFILE_TENT or SS_PROFILE_SOFT
 * Outputs:
 *   E        *E: malloc'd nv x npairs, column-major (free())
 * Errors: SS_ERR_INVALID on an unknown profile, a segment out of range or a segmentation without what
 *   the profile needs; SS_ERR_NOMEM.
 */
SS_API ss_status ss_segment_probes(const ss_segmentation *sg, int npairs, const int *seg, ss_segment_profile profile,
                                   double **E, ss_error *err);

/* ---- Per-shape preparation (shape_prep.c) ------------------------------------------------------- */

/* What a match needs from one shape alone (segmentation, unit-area eigenpairs, optional caches),
 * computed once by ss_shape_prep_compute and reused across pairs. Free with ss_shape_prep_free.
 */
typedef struct ss_shape_prep {
  const ss_mesh *mesh;  /* the input mesh (borrowed: must outlive the prep) */
  ss_segmentation seg;  /* ss_segment of the input */
  int kev;              /* eigenpairs computed on the input */
  /* The spectral data of the input scaled to unit area (ss_shape_prep_unit_area), as functional maps
   * compare shapes (pyFM's and ZoomOut's area normalisation): the eigenvalues times `area`, the
   * eigenvectors times √area, the masses divided by `area`. So neither shape's scale reaches the map:
   * a pair at sizes s_X and s_Y gives the map it gives at 1 and 1 (tests/test_scale.c). */
  double *evals;        /* kev: λ·area */
  double *evecs;        /* nv x kev, column-major, M-orthonormal (M the unit-area masses below) */
  double *M;            /* nv barycentric lumped masses / area (they sum to 1) */
  double area;          /* the input's area (sum of its barycentric masses) */
  double t_segment, t_eigs; /* seconds */
  /* Optional (NULL: not computed; ss_shape_prep_crit_fields fills it): the exact geodesic fields on
   * the work mesh seg.work from each of the seg.m critical points, unscaled (seg.work.nv x seg.m,
   * column-major). With them the segment pairing reads every landmark-to-centre distance instead of
   * propagating a field from each landmark at every match (distances are symmetric). */
  double *crit_fields;
  /* Optional (NULL: none; ss_shape_prep_probe_cache fills it): the shape-only parts of the base
   * probes of a match's functional maps (ss_fmap_probe_cache), nprobe_cache entries; a match whose
   * options they do not cover computes its own, with the same result. */
  ss_fmap_probe_cache *probe_cache;
  int nprobe_cache;
} ss_shape_prep;

/* Segments m and computes its first kev Laplace–Beltrami eigenpairs, then scaled to unit area
 * (ss_shape_prep above). The result depends only on the shape, so it can be computed once and reused
 * across pairs. With two or more OpenMP threads (outside a parallel region) the segmentation and the
 * eigenpairs run side by side, one thread each, with the same results as one after the other.
 *
 * Inputs:
 *   m        triangle mesh (borrowed: must outlive out) that the sanitizer would leave unchanged (no
 *            non-manifold or degenerate input: repair it first, its vertex indices are what landmarks
 *            and maps refer to)
 *   seg_opts segmentation options (NULL: ss_segment_default_options)
 *   kev      eigenpairs, 3 <= kev < nv
 * Outputs:
 *   out      the prep (free with ss_shape_prep_free)
 * Errors: SS_ERR_INVALID on an empty mesh, kev out of range or a mesh the sanitizer would change;
 *   those of ss_segment and ss_eigs (SS_ERR_UNSUPPORTED, SS_ERR_NUMERIC); SS_ERR_NOMEM.
 */
SS_API ss_status ss_shape_prep_compute(const ss_mesh *m, const ss_segment_options *seg_opts, int kev, ss_shape_prep *out,
                                       ss_error *err);
/* ss_shape_prep_compute without the segmentation (seg left empty): what a match with STD probes and
 * landmarks needs (ss_match_options.std_pairs), about half the cost.
 *
 * Inputs:
 *   m, kev   as ss_shape_prep_compute
 * Outputs:
 *   out      the prep (free with ss_shape_prep_free)
 * Errors: as ss_shape_prep_compute, less the segmentation's.
 */
SS_API ss_status ss_shape_prep_compute_spectral(const ss_mesh *m, int kev, ss_shape_prep *out, ss_error *err);
/* Frees everything p owns (segmentation, spectral data, caches; not the borrowed mesh) and zeroes
 * it; safe on a zeroed struct.
 *
 * Inputs:
 *   p        from ss_shape_prep_compute / ss_shape_prep_compute_spectral
 */
SS_API void ss_shape_prep_free(ss_shape_prep *p);
/* Fills p->crit_fields when it is NULL: seg.m exact single-source fields on seg.work
 * (ss_geodesic_fields, in parallel). Worth it for a shape matched more than once (specseg prepare,
 * Python Shape); a match computes nl fields per shape otherwise.
 *
 * Inputs:
 *   p        a prep with a segmentation (updated in place)
 * Errors: SS_ERR_INVALID on a NULL prep or an incomplete segmentation; errors of the geodesic fields;
 *   SS_ERR_NOMEM.
 */
SS_API ss_status ss_shape_prep_crit_fields(ss_shape_prep *p, ss_error *err);
/* ss_pair_segments_conf of two prepared shapes: the landmark-to-centre distances are read from a
 * shape's crit_fields when it has them (the same distances, up to rounding: d(l, c) = d(c, l)) and
 * propagated from its landmarks otherwise.
 *
 * Inputs:
 *   X, Y     prepared shapes with segmentations
 *   nl, lmX, lmY  as ss_pair_segments (input vertices)
 *   po       the rules (NULL: the paper's rule)
 * Outputs:
 *   out      pairs sorted by sx (free with ss_segment_pairs_free)
 * Errors: as ss_pair_segments (SS_ERR_INVALID also for a NULL shape).
 */
SS_API ss_status ss_pair_segments_prepared(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX,
                                           const int *lmY, const ss_pairing_options *po, ss_segment_pairs *out,
                                           ss_error *err);
/* In place: eigenpairs and masses of a shape of the given area become those of the shape scaled to
 * unit area (λ·area, φ·√area, M/area). What ss_shape_prep_compute applies, for callers that fill an
 * ss_shape_prep themselves (more eigenpairs of the same shape: scale them with the prep's `area`).
 *
 * Inputs:
 *   area     the shape's area
 *   nv, kev  vertices and eigenpairs
 *   evals    (may be NULL) kev eigenvalues, scaled in place
 *   evecs    (may be NULL) nv x kev, column-major, scaled in place
 *   M        (may be NULL) nv masses, scaled in place
 */
SS_API void ss_shape_prep_unit_area(double area, int nv, int kev, double *evals, double *evecs, double *M);

/* ---- Landmark-free pairing of the segments (autopair.c) ---------------------------------------- *
 * Pairs the segment centres of two shapes without landmarks, from what each shape carries alone
 * (its ss_centre_signature, computed once per shape):
 *  - a descriptor per centre: the WKS (ss_wks, descr_k eigenpairs, n_energies energies) averaged
 *    over the geodesic disc of radius descr_radius·√area around the centre, scaled to unit length;
 *  - the centre-to-centre exact geodesic distances D (ss_geodesic_fields on the input mesh) / √area.
 * 1. Intrinsic pairing. The energy of an injective pairing π of the centres of the shape with fewer
 *    (A) into the other (B):
 *      E(π) = w_descr · mean_a ‖d_A(a) − d_B(π a)‖²  +  w_geo · Σ_{a<a'} (D_A(a,a') − D_B(πa,πa'))² / Σ D_A²,
 *    minimised exactly by depth-first branch and bound when the count allows (na ≤ exact_max and at
 *    most 5·10⁷ injections; 8! = 40,320), otherwise relaxed: Hungarian assignment on descriptor +
 *    distance-profile costs (each centre's sorted distances to the others), then swaps / moves to
 *    free centres while E decreases (a local minimum, no guarantee). E cannot tell left from right
 *    (a mirror is an isometry).
 * 2. Left / right. The mirror candidate is π∘σ_A or σ_B∘π, whichever has the lower E, σ the centres'
 *    own left-right symmetry (per shape:
 *    of the 6 best non-identity pairings of the centres with themselves by E — relaxed: single
 *    swaps — the one whose map below is the most clearly orientation-reversing), falling back to
 *    the best other pairing when there is none. For both candidates a small functional map (ss_fmap_match:
 *    orient_k eigenfunctions, descriptors from orient_descr_k eigenpairs, the candidate's paired
 *    centres as landmarks) gives a point map A -> B, and its orientation score is (faces whose
 *    image triangle keeps its orientation − faces whose image flips) / faces, measured against B's
 *    outward vertex normals: +1 for an orientation-preserving map, −1 for a mirror. A left–right
 *    swap of the landmarks makes the functional map a reflection (orientation-reversing), so the
 *    candidate that keeps orientation is the answer, decided segment by segment: the median over
 *    A's segments of (segment score under π − under its mirror) (the torso saddles' segments follow
 *    their centres, which sit front or back inconsistently between shapes, and vote wrong); when
 *    its half (mirror_margin) is below recheck_margin a second pair of maps with only the
 *    protrusion centres as landmarks adds its median (options below). This needs consistently
 *    oriented meshes: faces wound against their component's majority are taken reversed, and the
 *    sign of the signed volume fixes outward normals on both shapes (an open surface of ~zero
 *    volume cannot tell: volume_ratio). The intrinsic energy alone cannot decide it: a mirror is an
 *    isometry.
 * Confidence: gap = (E₃ − E₁) / E₁ with E₃ the best intrinsic energy of a pairing other than the
 * answer and its mirror, and the orientation margin mirror_margin. */
/* Options of the landmark-free pairing (start from ss_autopair_default_options; the method above). */
typedef struct ss_autopair_options {
  int descr_k;         /* eigenpairs of the WKS (default 100; min with what the shapes have) */
  int n_energies;      /* WKS energies (default 100) */
  double sigma_factor; /* WKS σ (default 7) */
  double descr_radius; /* disc radius / √area for the averaged descriptor (default 0.05; 0: the centre) */
  double w_descr, w_geo; /* energy weights (defaults docs/tuning.md) */
  int exact_max;       /* exact search up to this many centres on the smaller side (default 10) */
  int orient_k;        /* basis of the orientation test's functional maps (default 30) */
  int orient_descr_k;  /* eigenpairs of its descriptors (default 100; min with what the shapes have) */
  double min_gap;      /* confidence thresholds: below either the result says so (notes) */
  double min_mirror;
  /* Second orientation test, only when the first one's margin (mirror_margin below) is below
   * recheck_margin (0: never; default 0.075): both candidates' maps again with recheck_k
   * eigenfunctions (default 50) and only round(recheck_keep · m) centres as landmarks (default
   * 0.625: the 5 protrusions of 8 on FAUST, whose maps do not follow the torso saddles front or back);
   * the decision is then the mean of the two tests' median segment margins. With recheck_zoomout >
   * recheck_k instead: ZoomOut-refined maps up to recheck_zoomout (step 5 on recheck_samples samples
   * of the smaller-count shape, then once on every vertex), orient_keep's landmarks, and that test's
   * whole-shape scores decide alone. docs/tuning.md has the measurements. */
  double recheck_margin;
  int recheck_k;
  /* The left / right test (both tests) uses only round(orient_keep · m), at least 3, of the smaller
   * shape's centres as landmarks: those with the largest summed geodesic distance to the others
   * (the protrusions; the torso saddles fall front or back inconsistently between shapes). Default
   * 1 (all); docs/tuning.md has the measurements. */
  double orient_keep;
  int recheck_zoomout;
  int recheck_samples;
  double recheck_keep;
  /* Near-ties beyond the mirror pair: up to alt_max (default 2; 0: off) other pairings of the
   * search whose energy is within a relative alt_gap (default 0.03) of the best go through the same
   * left / right test (each with its own mirror); one replaces the answer when its winner's
   * whole-shape score is at least alt_min_score (default 0.35) and beats both first-test scores of
   * the answer and its mirror by more than alt_margin (default 0.05).
   * The intrinsic energy cannot tell two torso saddles apart when they sit front / back alike; a
   * swap of them is a partial mirror, which the orientation test sees. docs/tuning.md. */
  int alt_max;
  double alt_gap;
  double alt_margin;
  double alt_min_score;
  /* Hypotheses carried through the map (ss_match_prepared_auto): up to `hypotheses` pairings
   * (default 4, at most SS_MAX_HYPOTHESES; 1: the answer alone) — the answer, its mirror, then the
   * search's next leaves whose energy is within a relative hyp_gap (default 0.5) of the best, each
   * followed by its own mirror; each gives a refined map, and the map of lowest hypothesis energy
   * (ss_match_result.autopair.hyp_*) is returned. */
  int hypotheses;
  double hyp_gap;
  /* hypothesis energy = metric distortion + hyp_w_reversed (default 0.05) · the share of X's
   * segments on which the map scores below hyp_reversed_below (default 0.15) in orientation
   * (ss_autopair_info.hyp_*; a right map keeps orientation on every segment, a mirrored limb or a
   * torso mapped front to back reverses it there; docs/tuning.md) + hyp_w_map · the map's own
   * selection energy (below) */
  double hyp_w_reversed;
  double hyp_reversed_below;
  /* the landmarks of a hypothesis's map: its round(hyp_keep · pairs) protrusion pairs (default
   * 0.625), the segments then paired from them as with given landmarks; 1: every pair is a landmark
   * and the hypothesis is the segment pairing */
  double hyp_keep;
  /* a landmark-free map is confident when its hypothesis energy is at least hyp_min_margin (default
   * 0.005) below every other hypothesis's (docs/tuning.md) */
  double hyp_min_margin;
  /* with given landmarks (ss_match_prepared, the refined default): 0 the landmarks' map alone
   * (Table 1's refined rows); 1 maps the landmarks alone and, beside them, the landmarks plus each pairing hypothesis's
   * protrusion pairs that agree with them — neither centre within hyp_landmark_tol (default 0.1,
   * geodesic / √area) of a given landmark, every given landmark as far from both centres within it;
   * 2 (default) also maps each pairing hypothesis landmark-free (as without landmarks), eligible when at most a
   * quarter of the given landmarks (none of three or fewer) land farther than hyp_landmark_tol from
   * their partners under it. The map of least hypothesis energy is returned (a note names the
   * landmarks a landmark-free map departs from); where no pairing signature can be formed (a shape
   * in several components), the landmarks' map alone with a note. docs/tuning.md has the measurements */
  int hyp_landmarks;
  double hyp_landmark_tol;
  /* the hypothesis margin (confidence) is taken against the other candidates whose maps differ from
   * the returned one: on at least hyp_differ_share (default 0.05) of X's vertices their images lie
   * farther apart than hyp_differ_tol (default 0.1, Euclidean / √area of Y). Two candidates that
   * give the same map are one answer, not a doubt (with landmarks, the landmarks' map and a right
   * landmark-free map agree); 0: every candidate counts */
  double hyp_differ_tol;
  double hyp_differ_share;
  /* a candidate whose whole-map orientation score (ss_autopair_info.hyp_orientation, in [-1, 1]) is
   * below hyp_min_orientation (default 0: the map reverses orientation on most of X) is kept only
   * when no candidate reaches it, and a returned map below it is not confident; both meshes must be
   * wound consistently (outward or inward alike). -1: off */
  double hyp_min_orientation;
  /* a returned map whose whole-map orientation score is below hyp_confident_orientation (default
   * 0.45) is not confident (right maps score above it, mirrored or partly mirrored ones below;
   * docs/tuning.md has the measurements) */
  double hyp_confident_orientation;
  /* the oriented polish of the answer: up to polish_rounds times (default 5; 0: off), a single move
   * of its pairing (two centres exchange their partners, or one moves to an unpaired centre) that
   * lowers the energy is applied when the first orientation test's whole-shape score of the result
   * stays within polish_orient_tol (default 0.1) of the answer's; the answer before the moves stays
   * a hypothesis (docs/tuning.md) */
  int polish_rounds;
  double polish_orient_tol;
  /* landmark-free, one more candidate beside the pairing hypotheses: X's protrusion centres (hyp_keep)
   * and their images under the functional map of the descriptors alone (WKS with the orientation term
   * of weight hyp_descriptor_orient, 0..1e6, default 0.001; no landmark, no segment), mapped as the hypotheses
   * are, when hypotheses > 1. Where the two segmentations differ too much for any pairing to be right
   * (TOSCA_r's dogs curled up), it is the right one (docs/tuning.md). 1 (default): on; 0: off */
  int hyp_descriptor_map;
  double hyp_descriptor_orient;
  /* the hypothesis energy's third term: hyp_w_map (default 0.05; 0: off) · the candidate map's own
   * refinement selection energy (ss_autopair_info.hyp_map_energy; none without SS_REFINE_BEST). A
   * partly swapped map can have the lower distortion and no reversed segment while its functional
   * map is the less orthogonal and its descriptors the worse preserved (docs/tuning.md) */
  double hyp_w_map;
  /* a returned map whose own refinement selection energy (ss_autopair_info.hyp_map_energy) is above
   * hyp_max_map_energy (default 0.37; right maps of the tuning split stay below 0.33) is not
   * confident: a functional map that far from orthogonal, or descriptors that badly kept, is seldom
   * right (docs/tuning.md). Not applied to a map without that energy (no SS_REFINE_BEST). */
  double hyp_max_map_energy;
  /* landmark-free, when the map kept scores below hyp_confident_orientation or a candidate whose map
   * reverses orientation (below hyp_min_orientation) has a lower hypothesis energy than it: each
   * candidate whose map reverses orientation is flipped (the lowest energy first) into one more
   * candidate, mapped as the others are: X's protrusion centres (hyp_keep) and the images under that
   * map of their mirror images on X, the mirror found as the functional map from X to its reflection
   * in a plane with the orientation term of weight hyp_flip_orient (0..1e6, default 1; 0: off). A quadruped
   * whose every hypothesis came out as its mirror image (TOSCA_r's cats, dogs, centaurs), or whose
   * oriented map is worse than its mirror images, gets the right way round (docs/tuning.md) */
  double hyp_flip_orient;
  /* weight of the orientation shortfall in the hypothesis energy: a candidate scores
   * hyp_w_orientation * max(0, hyp_confident_orientation - its orientation score) more, so of two
   * maps of near-equal distortion the one that keeps orientation more clearly wins, while scores
   * above the confident level all count alike (default 0.01; 0: off; TOSCA_r horse14 -> horse7,
   * docs/tuning.md) */
  double hyp_w_orientation;
  /* whose own left-right symmetry turns a mirrored candidate round (hyp_flip_orient): 0 X's (x ->
   * T(S_X(x))), 1 Y's (x -> S_Y(T(x))), 2 both, X's first (default 2: a symmetry map that fails on
   * one shape, a cat curled up, works on the other; docs/tuning.md) */
  int hyp_flip_side;
  /* the map kept, once chosen, refined further as ss_match_refine refines a map: its functional map
   * at the match's ZoomOut size (fmap.zoomout_kmax), then ZoomOut up to hyp_final_kmax
   * eigenfunctions (default 150; 0, or not above fmap.zoomout_kmax: none; not with SS_REFINE_NONE).
   * The hypotheses compete at the match's size (a larger one there changes which map wins); the
   * larger basis then sharpens the winner alone (FAUST_r and TOSCA_r tuning splits, docs/tuning.md).
   * Landmark-free and with landmarks alike (the hypotheses beside them, hyp_landmarks); not in a
   * match that forms no hypotheses. Shapes of fewer eigenpairs (prepared for an earlier default)
   * stop at theirs, with a note. */
  int hyp_final_kmax;
  /* landmark-free, the other direction's hypotheses too (hypotheses > 1): Y's pairing search against
   * X (its answer, mirror and next leaves) and Y's descriptors' own candidate, each turned into X -> Y
   * landmarks (the same centre pairs read the other way; Y's protrusion centres and their images on
   * X) and mapped as the others are, distinct sets only. The pairing search is not symmetric (it
   * starts from the protrusions of the shape it maps), and where it goes wrong from X's side it is
   * often right from Y's. 1 (default): on; 0: off (docs/tuning.md) */
  int hyp_reverse;
  /* the map kept, after hyp_final_kmax, polished on the surfaces (ss_map_polish, its defaults): 1
   * (default) on, 0 off. In a match that forms hypotheses (landmark-free, or beside landmarks), not
   * with SS_REFINE_NONE. The result's C stays the functional map before it (docs/tuning.md) */
  int hyp_final_polish;
  /* landmark-free, when the choice is not confident: the map kept and every candidate within this
   * much of its energy (eligible, as oriented, differing from it) are polished on the surfaces
   * (ss_map_polish) and compared again, each energy with the polished map's distortion in place of
   * its own; the least is kept (mapped again for its whole result; a note says so). The confidence
   * stays that of the first choice. Default 0.05; 0: not. Not with SS_REFINE_NONE (docs/tuning.md) */
  double hyp_recheck_window;
  /* 1: the hypothesis energy's distortion (ss_autopair_info.hyp_distortion) compares X's distances
   * with their images' up to one scale, fitted per map by least squares within [0.5, 2]. Two bodies
   * of different build differ over √area by a common factor that can hide a swapped limb (FAUST_r).
   * 0 (default): the distances over √area as they are. Off by default: the fit also rewards a map
   * that pulls distances together, and on one shape in different poses (TOSCA_r) it made a right
   * map lose, confidently (docs/tuning.md) */
  int hyp_fit_scale;
  /* landmark-free, a candidate is not mapped when the map of an earlier one (mapped, not itself
   * skipped) already sends each of its landmarks within hyp_skip_tol (Euclidean / √area of Y) of the
   * landmark's partner: its map would be that one's, or one near it, at the full cost of a map
   * (ss_autopair_info.hyp_skipped_by). 0 (default): every candidate is mapped. 0.05 costs about 0.8x
   * the CPU of a FAUST_r or TOSCA_r match; off by default because a candidate skipped loses its own
   * energy, which may differ from the earlier map's by more than the margin between distinct maps,
   * and the choice and the confidence may go with it (docs/tuning.md) */
  double hyp_skip_tol;
  /* the map returned is not confident when its images reach fewer than this share of the vertices
   * of the smaller shape (ss_autopair_info.coverage: distinct images / min(X's, Y's vertex count)).
   * A map that slides or folds part of X piles images together and leaves part of Y unreached: on
   * the tuning split its three maps above 5 reach the fewest of all 180 (0.615-0.632; the right maps
   * 0.636-0.875, FAUST_r's from 0.711). Default 0.65; 0: not used. Set on shapes of about equal vertex
   * counts (FAUST_r, TOSCA_r); a right map between a coarse and a fine mesh reaches more, so there it
   * flags less (docs/tuning.md) */
  double hyp_min_coverage;
} ss_autopair_options;

#define SS_MAX_HYPOTHESES 16

/* Fills o with the landmark-free pairing's defaults (the values named in ss_autopair_options).
 *
 * Outputs:
 *   o        every field written
 */
SS_API void ss_autopair_default_options(ss_autopair_options *o);

/* What the pairing needs from one shape (m exact fields and one WKS). */
typedef struct ss_centre_signature {
  int m;              /* centres (segments) */
  int nd;             /* descriptor length */
  int *centers;       /* m input vertices (copy of seg.centers) */
  double *descr;      /* m x nd, row a at descr + a·nd, unit length */
  double *D;          /* m x m scaled geodesic distances (symmetric) */
  double volume_ratio; /* signed volume / area^1.5 (its sign fixes the orientation; |ratio| < 1e-3:
                          orientation undecidable) */
  double orient_sign;  /* +1 / −1: the sign applied to the faces' own orientation (outward) */
  double *normals;     /* nv x 3 outward vertex normals (area-weighted) */
  const ss_shape_prep *prep; /* borrowed: the shape it was computed from (must outlive it) */
  int *sigma;          /* m: the centres' left-right symmetry (identity where none was found) */
  double sigma_score;  /* the orientation score of σ's map (< 0: a mirror; 1: none found) */
  /* the orientation test's probes of this shape, built once (ss_fmap_base_probes with every centre
   * as a landmark, in its first probe_k eigenfunctions (the larger of the two tests' bases; a test
   * with a smaller basis takes the leading block) from probe_descr_k eigenpairs: coefficients
   * probe_A, k x probe_p, and packed operators probe_P); NULL (e.g. a signature read from a
   * prepared-shape file): the pairing builds them itself, to the same effect */
  int probe_k, probe_descr_k, probe_p;
  double *probe_A, *probe_P;
} ss_centre_signature;

/* The landmark-free pairing's signature of one prepared shape: the WKS descriptor of each segment
 * centre, the centre-to-centre geodesic distances, outward normals, the centres' own left-right
 * symmetry and the orientation test's probes.
 *
 * Inputs:
 *   p        a prepared shape with a segmentation and >= min(descr_k, orient_descr_k) eigenpairs
 *            (borrowed: must outlive out)
 *   o        options (NULL: defaults from ss_autopair_default_options)
 * Outputs:
 *   out      the signature (free with ss_centre_signature_free)
 * Errors: SS_ERR_INVALID on bad options or an unprepared shape; errors of the geodesic fields and the
 *   functional maps; SS_ERR_NOMEM.
 */
SS_API ss_status ss_centre_signature_compute(const ss_shape_prep *p, const ss_autopair_options *o,
                                             ss_centre_signature *out, ss_error *err);
/* Frees the arrays of s and zeroes it; safe on a zeroed struct.
 *
 * Inputs:
 *   s        from ss_centre_signature_compute
 */
SS_API void ss_centre_signature_free(ss_centre_signature *s);

/* What the landmark-free pairing (and a match's hypotheses) report: energies, orientation scores and
 * confidence.
 */
typedef struct ss_autopair_info {
  int used;             /* 1: the pairing was landmark-free (then the fields below are set) */
  int exact;            /* 1: exact search, 0: the relaxation */
  double energy;        /* E of the chosen pairing */
  double energy_mirror; /* E of its mirror candidate */
  double energy_other;  /* E₃: the best pairing other than those two (INFINITY: none) */
  double gap;           /* (energy_other − min(energy, energy_mirror)) / that minimum (negative when a near
                         * tie replaced the search's best: energy_other is then the search's best) */
  double mirror;        /* orientation score of the chosen pairing's map */
  double mirror_other;  /* that of the mirror candidate */
  int confident;        /* the pairing: gap ≥ min_gap and (mirror − mirror_other) / 2 ≥ min_mirror; in a
                         * match with several hypotheses: the map's (hyp_margin below) */
  int pairing_confident; /* the pairing's own rule, as above, also in a match */
  double cpu;           /* CPU seconds of the search and the orientation test (signatures excluded) */
  int rechecked;        /* 1: the second orientation test decided (mirror / mirror_other are its scores) */
  double mirror_first, mirror_other_first; /* the first test's scores */
  /* the left / right decision's margin: half the median over the segments of the smaller-count
   * shape of (segment's score under the answer − under its mirror) (rechecked: (mirror −
   * mirror_other) / 2); the confidence rule compares it with min_mirror */
  double mirror_margin;
  int alternatives;     /* near-tie pairings tested beyond the mirror pair (ss_autopair_options.alt_*) */
  int alternative;      /* 1: one of them replaced the search's best (energy: its energy) */
  int polished;         /* moves made by the oriented polish (ss_autopair_options.polish_rounds) */
  /* the hypotheses' refined maps (ss_autopair_options.hypotheses): how many were mapped, the index
   * of the one returned (0: the pairing's own answer), and per hypothesis its pairing energy, the
   * orientation score and the metric distortion of its map, and its hypothesis energy */
  int hypotheses;
  int hypothesis;
  int hyp_descriptor; /* the descriptors' own candidate (hyp_descriptor_map; -1: none) */
  double hyp_pair_energy[SS_MAX_HYPOTHESES];
  double hyp_orientation[SS_MAX_HYPOTHESES];
  double hyp_distortion[SS_MAX_HYPOTHESES];
  double hyp_energy[SS_MAX_HYPOTHESES];
  double hyp_map_energy[SS_MAX_HYPOTHESES]; /* the selection energy of its map (ss_match_result.refine_energy) */
  double hyp_orientation_min[SS_MAX_HYPOTHESES]; /* the least orientation score over X's segments */
  double hyp_reversed[SS_MAX_HYPOTHESES];        /* the share of X's segments below hyp_reversed_below */
  int hyp_landmarks;  /* landmarks of the returned map (its protrusion pairs, hyp_keep) */
  /* E of the best other hypothesis whose map differs (hyp_differ_share) − E of the returned one
   * (INFINITY: none); a match's `confident` is then the map's: hyp_margin >= hyp_min_margin */
  double hyp_margin;
  /* per candidate, the share of X's vertices whose image lies farther than hyp_differ_tol from the
   * returned map's image of it (0 for the returned one) */
  double hyp_differ[SS_MAX_HYPOTHESES];
  /* per candidate, the candidate it is the flip of (hyp_flip_orient), -1 for the others */
  int hyp_flip_of[SS_MAX_HYPOTHESES];
  /* per flipped candidate, 1 when Y's own symmetry turned it round, 0 when X's (hyp_flip_side) */
  int hyp_flip_by_y[SS_MAX_HYPOTHESES];
  /* per candidate, 1 when it came from Y's side (hyp_reverse), 0 otherwise */
  int hyp_from_y[SS_MAX_HYPOTHESES];
  /* the basis size the map kept was refined to after the choice (hyp_final_kmax; 0: not refined
   * further) */
  int hyp_final_k;
  /* 1 when the map kept was polished on the surfaces after the choice (hyp_final_polish) */
  int hyp_final_polished;
  /* candidates polished for the recheck in doubt (hyp_recheck_window; 0: none), and the hypothesis
   * chosen before it (= hypothesis when it stood) */
  int hyp_rechecked, hyp_recheck_from;
  /* per candidate, the scale its distortion was taken at (hyp_fit_scale; 1 without the fit, NaN
   * where no distortion was taken) */
  double hyp_scale[SS_MAX_HYPOTHESES];
  /* per candidate, the earlier candidate whose map already kept its landmarks, so that it was not
   * mapped (hyp_skip_tol; its hyp_* numbers are then NaN, and it is neither chosen nor counted in the
   * margin), -1 for the candidates mapped */
  int hyp_skipped_by[SS_MAX_HYPOTHESES];
  /* the map returned: its distinct images over min(X's, Y's vertex count) (hyp_min_coverage); set by
   * a match that forms hypotheses (landmark-free, or beside landmarks), 0 otherwise */
  double coverage;
} ss_autopair_info;

/* Landmark-free pairing of the segment centres of two shapes (the method above): every centre of the
 * shape with fewer (X on ties) with a distinct centre of the other.
 *
 * Inputs:
 *   X, Y     the shapes' signatures (ss_centre_signature_compute)
 *   o        options (NULL: defaults)
 * Outputs:
 *   out      pairs sorted by sx, energy[p] the pair's own terms (descriptor + its share of the distance
 *            and orientation terms); free with ss_segment_pairs_free
 *   info     (may be NULL) energies, orientation scores and confidence
 * Errors: SS_ERR_INVALID on bad options or signatures; errors of the functional maps; SS_ERR_NOMEM.
 */
SS_API ss_status ss_pair_centres_auto(const ss_centre_signature *X, const ss_centre_signature *Y,
                                      const ss_autopair_options *o, ss_segment_pairs *out, ss_autopair_info *info,
                                      ss_error *err);

/* The pairing hypotheses of ss_pair_centres_auto (ss_autopair_options.hypotheses): hyp[0] its answer,
 * then distinct others (the answer's mirror, then near-best pairings each followed by its mirror).
 *
 * Inputs:
 *   X, Y, o  as ss_pair_centres_auto
 *   maxh     room in hyp, 1..SS_MAX_HYPOTHESES
 * Outputs:
 *   hyp      *nh pairings, filled as ss_pair_centres_auto fills its out (free each with
 *            ss_segment_pairs_free)
 *   nh       how many
 *   info     (may be NULL) as ss_pair_centres_auto
 * Errors: SS_ERR_INVALID on bad options, maxh out of range or bad signatures; SS_ERR_NOMEM.
 */
SS_API ss_status ss_pair_centres_hypotheses(const ss_centre_signature *X, const ss_centre_signature *Y,
                                            const ss_autopair_options *o, int maxh, ss_segment_pairs *hyp, int *nh,
                                            ss_autopair_info *info, ss_error *err);

/* ---- The matching pipeline (match.c; its stages in match_*.c) ----------------------------------- */

typedef enum ss_probe_set {
  SS_PROBES_STD = 0,  /* WKS + landmark wave-kernel maps (NO17) */
  SS_PROBES_ASA = 1,  /* + the paired segments' functions (segment_profile), as they are */
  SS_PROBES_DIFF = 2  /* + the same functions filtered by the wave kernel */
} ss_probe_set;

/* What ss_match_prepared returns (ss_match_options.refine). */
typedef enum ss_refine_mode {
  SS_REFINE_NONE = 0,    /* the point map of the chosen probes' functional map at size k (the paper's
                            STD / ASA / DIFF maps) */
  SS_REFINE_ZOOMOUT = 1, /* ZoomOut of that map up to fmap.zoomout_kmax */
  SS_REFINE_BEST = 2     /* default: the starts STD and, with ASA / DIFF probes and segments paired,
                            the segment-aided map; the one of lower selection energy (both with
                            refine_single 0) refined by ZoomOut up to fmap.zoomout_kmax (default
                            110, step fmap.zoomout_step 5, on fmap.zoomout_samples 1,000 samples of
                            X then once on every vertex: docs/tuning.md); of
                            the starts and their refinements the map with the lowest selection energy
                            ss_p2p_energy (k0 = k, K = max(k, zoomout_kmax), step 1, w_lap =
                            refine_w_lap) + refine_w_descr · ss_p2p_descr_residual (the base probes,
                            at size k) is returned — a refinement only when not above its own start
                            by that energy. No ground truth. */
} ss_refine_mode;

/* Options of the matching pipeline (start from ss_match_default_options or ss_match_paper_options). */
typedef struct ss_match_options {
  ss_probe_set probes;        /* default DIFF */
  ss_fmap_match_options fmap; /* k, WKS, weights, descr_k; fmap.zoomout_kmax: size of the refinement */
  ss_segment_options seg;     /* segmentation of both shapes */
  /* the profile of a paired segment's probe function (ASA and DIFF); default SS_PROFILE_TENT at the
   * default k = 50, SS_PROFILE_SOFT is better for k >= 60 (docs/tuning.md) */
  ss_segment_profile segment_profile;
  ss_pairing_options pairing; /* confidence rules of the pairing (ss_pairing_default_options) */
  ss_refine_mode refine;      /* default SS_REFINE_BEST */
  double refine_w_lap;        /* w_lap of the selection energy (ss_p2p_energy) */
  double refine_w_descr;      /* weight of the descriptor residual in the selection energy */
  /* fmap.descr_k of the segment-aided (ASA / DIFF) map; fmap.descr_k is the STD map's. Default 0
   * (= k, the paper's probes): with descriptors from 100 eigenpairs DIFF got worse (docs/tuning.md). */
  int seg_descr_k;
  /* SS_REFINE_BEST: 1 (default) refines only the start with the lower selection energy (the other
   * start stays a candidate unrefined); 0: refine every start */
  int refine_single;
  /* the landmark-free pairing (used when ss_match_prepared gets no landmarks) */
  ss_autopair_options autopair;
  /* the caller's own descriptors (default none): ndescr columns on each shape, descrX nX x ndescr and
   * descrY nY x ndescr column-major, column j of one corresponding to column j of the other; probes
   * beside the WKS (or instead of it with fmap.no_wks), as ss_fmap_shape.descr; rows of the input
   * meshes' vertices (ss_match keeps the rows of the components it matches) */
  int ndescr;
  const double *descrX, *descrY;
  /* STD probes use no segments, so by default a match with STD and landmarks neither segments its
   * meshes (ss_match) nor pairs the segments (pairs empty); 1: segment and pair them all the same
   * (reported in pairs and centerX / centerY, not used by the map) */
  int std_pairs;
} ss_match_options;

/* Fills p->probe_cache (ss_shape_prep) for matches with options opts, replacing what it held: the WKS
 * columns of each descriptor basis the functional maps use and the triple products for the largest
 * (none with the caller's own descriptors or no_wks). Worth it for a shape matched more than once
 * (specseg prepare, Python Shape).
 *
 * Inputs:
 *   p        a prepared shape (updated in place)
 *   opts     options (NULL: defaults)
 * Errors: SS_ERR_INVALID on bad options or too few eigenpairs; SS_ERR_NOMEM.
 */
SS_API ss_status ss_shape_prep_probe_cache(ss_shape_prep *p, const ss_match_options *opts, ss_error *err);

/* Fills o with the library's defaults: DIFF probes, the refined output (SS_REFINE_BEST), the
 * library's pairing rules, the landmark-free pairing's defaults (values named in the fields above).
 *
 * Outputs:
 *   o        every field written
 */
SS_API void ss_match_default_options(ss_match_options *o);
/* Fills o with the paper's STD / ASA / DIFF as the paper defines them (what specseg eval's Table 1
 * uses): the defaults with descr_k = k, the paper's pairing rule (ss_pairing_paper_options) and no
 * refinement.
 *
 * Outputs:
 *   o        every field written
 */
SS_API void ss_match_paper_options(ss_match_options *o);

/* The result of a match: the point map X -> Y, the functional map, the segment pairs, timings and
 * notes. Free with ss_match_result_free.
 */
typedef struct ss_match_result {
  int nX;           /* vertices of X */
  int *map;         /* nX: map[i] = vertex of Y, image of vertex i of X */
  int kc;           /* C is kc x kc (k, or zoomout_kmax with ZoomOut) */
  double *C;        /* functional map from functions on Y to functions on X (pull-back of map), in the
                       shapes' unit-area bases (ss_shape_prep: C[0] = ±1, whatever the two sizes) */
  ss_segment_pairs pairs;
  int *centerX, *centerY; /* pairs.n: input vertices at the centres of the paired segments */
  /* seconds per stage (t_segment, t_eigs: both shapes' added up) and of the whole call */
  double t_segment, t_eigs, t_pair, t_fmap, t_zoomout, t_total;
  /* SS_REFINE_BEST: the candidate returned (0 STD start, 1 STD refined, 2 segment-aided start,
   * 3 segment-aided refined) and the selection energies of the four (NAN: not computed); -1 and NANs
   * with the other modes */
  int refine_choice;
  double refine_energy[4];
  /* what the caller should know, e.g. that segment probes were not used (empty: nothing) */
  char notes[256];
  /* the landmark-free pairing's energies and confidence (autopair.used = 0 with landmarks) */
  ss_autopair_info autopair;
} ss_match_result;

/* Matches two prepared shapes: probes by opts->probes (STD: WKS + landmarks; ASA / DIFF: + the
 * segments paired through the landmarks), Eq. (1), then the refinement of opts->refine. With STD the
 * segments are not paired (unless opts->std_pairs: then paired and reported, not used; the shapes
 * must be segmented); with fewer than pairing.min_landmarks landmarks, or no segment paired, ASA and
 * DIFF fall back to STD and say so in notes.
 *
 * Inputs:
 *   X, Y     prepared shapes, each with >= ss_match_eigenpairs(opts, nl) eigenpairs
 *   nl       landmarks (<= SS_MAX_LANDMARKS); 0 (lmX, lmY may be NULL): landmark-free, see
 *            ss_match_prepared_auto
 *   lmX, lmY nl corresponding input vertices of X and Y
 *   opts     options (NULL: defaults from ss_match_default_options)
 * Outputs:
 *   out      the result (free with ss_match_result_free)
 * Errors: SS_ERR_INVALID on a NULL output, unprepared shapes, too few eigenpairs, landmarks out of
 *   range or given two partners (ss_landmarks_check), bad options; errors of the stages
 *   (SS_ERR_NUMERIC); SS_ERR_NOMEM.
 */
SS_API ss_status ss_match_prepared(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX, const int *lmY,
                                   const ss_match_options *opts, ss_match_result *out, ss_error *err);

/* ss_match_prepared with the segment pairing given instead of computed (e.g. by
 * ss_pair_critical_points_conf from landmark fields cached per shape, as specseg eval does;
 * opts->pairing is then not used, except min_landmarks and min_map_share). With the pairing
 * ss_match_prepared would compute, the result is the same.
 *
 * Inputs:
 *   X, Y, nl, lmX, lmY, opts  as ss_match_prepared (nl >= 1)
 *   pairs    the pairing (sx < X->seg.m, sy < Y->seg.m), copied into out->pairs (less the pairs the
 *            map check drops)
 * Outputs:
 *   out      the result (free with ss_match_result_free)
 * Errors: as ss_match_prepared; SS_ERR_INVALID also for NULL or out-of-range pairs.
 */
SS_API ss_status ss_match_prepared_pairs(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX,
                                         const int *lmY, const ss_segment_pairs *pairs, const ss_match_options *opts,
                                         ss_match_result *out, ss_error *err);

/* Landmark-free match of two prepared shapes: the segments are paired by ss_pair_centres_auto
 * (opts->autopair), then each pairing hypothesis's paired centres serve as the landmarks and the
 * pairing as the segment pairing of ss_match_prepared (same probes, refinement and selection); the
 * map of least hypothesis energy is returned. When it is not confident notes says so: the map may be
 * wrong (a segment pair or the left-right mirror), never silently. The orientation decision needs
 * both meshes consistently oriented (outward normals after the signed-volume convention).
 *
 * Inputs:
 *   X, Y     prepared shapes with segmentations and enough eigenpairs (ss_match_eigenpairs(opts, 0))
 *   sigX, sigY  their signatures (NULL: computed here)
 *   opts     options (NULL: defaults)
 * Outputs:
 *   out      the result; out->autopair holds the pairing's energies and confidence (free with
 *            ss_match_result_free)
 * Errors: SS_ERR_INVALID on a NULL output, unprepared shapes, bad options; errors of the pairing and
 *   of ss_match_prepared; SS_ERR_NOMEM.
 */
SS_API ss_status ss_match_prepared_auto(const ss_shape_prep *X, const ss_shape_prep *Y, const ss_centre_signature *sigX,
                                        const ss_centre_signature *sigY, const ss_match_options *opts,
                                        ss_match_result *out, ss_error *err);

/* The match's refinement of a given point map X -> Y (another method's map, or a rough one): its
 * functional map at size k (Φ_Xᵀ M_X Π Φ_Y, ss_fmap_from_p2p), then ZoomOut up to zoomout_kmax as
 * ss_match_prepared refines its own maps (on zoomout_samples samples of X, one pass on every
 * vertex at the end). No segmentation and no landmark: ss_shape_prep_compute_spectral's preps do.
 * ZoomOut keeps a map's errors of orientation and of whole parts (a left-right swap stays one); it
 * mends what is local.
 *
 * Inputs:
 *   X, Y     prepared shapes, each with kev >= kz eigenpairs, kz = max(fmap.k, fmap.zoomout_kmax)
 *   map_in   X->mesh->nv vertices of Y (0-based): entry i is the image of vertex i of X
 *   opts     (NULL: ss_match_default_options) reads fmap.k (>= 1), fmap.zoomout_kmax (<= k: no
 *            ZoomOut, the map through its own size-k functional map), fmap.zoomout_step (0: 1) and
 *            fmap.zoomout_samples (0 or >= X's vertices: every vertex); the rest is not used
 * Outputs:
 *   map_out  X->mesh->nv entries, caller-allocated (may be map_in): the refined map
 *   C_out    (may be NULL) kz x kz, column-major, caller-allocated: its functional map (functions on
 *            Y to functions on X, as ss_match_result.C)
 * Errors: SS_ERR_INVALID on NULL or unprepared shapes, NULL maps, a map entry outside 0..Y->mesh->nv-1,
 *   bad sizes or too few eigenpairs; SS_ERR_NOMEM.
 */
SS_API ss_status ss_match_refine(const ss_shape_prep *X, const ss_shape_prep *Y, const int *map_in,
                                 const ss_match_options *opts, int *map_out, double *C_out, ss_error *err);

/* ss_map_polish's parameters (ss_map_polish_default_options gives the defaults named here). */
typedef struct ss_map_polish_options {
  int rounds;                 /* ICP rounds, 0..10000 (default 30; 0: the map is returned as given) */
  int steps;                  /* ARAP local-global steps per round, 1..100 (default 3) */
  /* the surface term's weight in the first and the last round (default 0.1 and 1), the pull towards
   * the given map's images likewise (default 0.3 and 0.001); each moves geometrically in between,
   * all in (0, 1e6], relative to ARAP's rigidity term on shapes scaled to unit area */
  double w_surface_first, w_surface_last;
  double w_map_first, w_map_last;
  int neighbours;             /* nearest vertices of Y examined for one facing the same way, 1..64 (default 16) */
  double min_normal_dot;      /* "facing the same way": normals' dot product above this, [-1, 1) (default 0) */
  /* how far an image may move from the given one, along Y's edges, in units of √(Y's area), (0, 1e6]
   * (default 0.1): where two parts of Y touch, the nearest vertex can lie on the other part */
  double max_move;
  /* 1 (default): then a second pass over each thick region the map turns over (X's faces laid on
   * their images face against Y there; at least 0.5 % of X, and Y at least 0.08 √area thick there:
   * a torso's front sent to its back), which max_move keeps out of the first pass's reach: from the
   * first pass's map, such a region (and 4 rings around it) does not pull and may move anywhere, and
   * the rest's deformation places it; 0: not */
  int mend_mirrored;
} ss_map_polish_options;

/* Fills o with ss_map_polish's defaults (tuned on the FAUST_r and TOSCA_r tuning splits, docs/tuning.md).
 *
 * Outputs:
 *   o        every field written
 */
SS_API void ss_map_polish_default_options(ss_map_polish_options *o);

/* A point map X -> Y fitted to the surfaces: X, deformed as rigidly as possible (ARAP, cotangent
 * weights), is pulled onto Y (point-to-plane ICP against Y's nearest vertex whose normal faces the
 * same way) and, less and less over the rounds, towards the given map's images; each vertex's image
 * is then the nearest vertex of Y facing the same way at its deformed position and within max_move
 * of its given image along Y's edges (the given image when none of `neighbours` is). An outlier of
 * the given map (an image farther from its neighbours' images than 5 times the edges between them,
 * the median over the neighbours) does not pull: its vertex follows its neighbours, and its image
 * stays within max_move of a neighbour's given image. The spectral refinement leaves a map off by about an edge length nearly
 * everywhere where the poses stretch the surface; this spatial step mends much of that (FAUST_r,
 * TOSCA_r: docs/tuning.md). A thick region the map turns over (a torso's front sent to its back)
 * lies beyond max_move: a second pass (mend_mirrored) releases it and lets the rest's deformation
 * place it. It does not mend a part mapped onto another (a left-right swap of limbs).
 * Both shapes are scaled to unit area first, so their scale, position and rotation do not change the
 * result (up to rounding). Each mesh must be consistently oriented; the two may face opposite ways
 * (X's faces laid on their images vote, and Y's normals are turned round when most face against
 * them).
 *
 * Inputs:
 *   X, Y     triangle meshes (nv, nf >= 1, nonzero area, finite coordinates)
 *   map_in   X->nv vertices of Y (0-based): entry i is the image of vertex i of X
 *   opts     NULL: ss_map_polish_default_options
 * Outputs:
 *   map_out  X->nv entries, caller-allocated (may be map_in): the polished map
 * Errors: SS_ERR_INVALID on NULL or empty meshes, a face index or map entry out of range, zero area,
 *   non-finite coordinates, bad options; SS_ERR_NUMERIC if the deformation's system cannot be
 *   factored; SS_ERR_NOMEM.
 */
SS_API ss_status ss_map_polish(const ss_mesh *X, const ss_mesh *Y, const int *map_in, const ss_map_polish_options *opts,
                               int *map_out, ss_error *err);

/* The landmark-free pairing from two meshes: prepare both (opts->seg, max(autopair.descr_k,
 * autopair.orient_k) eigenpairs), their signatures, ss_pair_centres_auto (opts->autopair).
 *
 * Inputs:
 *   X, Y     triangle meshes
 *   opts     options (NULL: defaults)
 * Outputs:
 *   pairs    the pairing (free with ss_segment_pairs_free)
 *   centerX, centerY  (may be NULL) malloc'd pairs->n input vertices at the paired centres (free())
 *   info     (may be NULL) energies and confidence
 * Errors: SS_ERR_INVALID on a NULL output or mesh; those of ss_shape_prep_compute and the pairing;
 *   SS_ERR_NOMEM.
 */
SS_API ss_status ss_pair_auto(const ss_mesh *X, const ss_mesh *Y, const ss_match_options *opts, ss_segment_pairs *pairs,
                              int **centerX, int **centerY, ss_autopair_info *info, ss_error *err);

/* Everything from two meshes: prepare both, then ss_match_prepared (landmark-free:
 * ss_match_prepared_auto). Meshes of several components: the map is only determined on components
 * that hold a landmark, so on each mesh the components with at least one landmark are kept and
 * matched (the body of a scan, without its crumbs; every component when each has a landmark); a
 * vertex of X on a dropped component takes the image of its nearest (Euclidean) kept vertex of X, and
 * no vertex of X maps to a dropped vertex of Y. Landmark-free (nl = 0): the largest component (by
 * area) of each mesh is kept. Unreferenced vertices are refused as for one component. Meshes above
 * 100,000 vertices are matched through coarse proxies (ss_prepared_shape). Threads: when OpenMP gives
 * the call two or more threads and it is not made inside a parallel region, the two shapes'
 * preparations (and their probe caches) run side by side, one thread each; the map is the same bytes
 * as with one thread. Stage times (t_segment, t_eigs) then add up both shapes' work, while t_total is
 * the time the call took.
 *
 * Inputs:
 *   X, Y     triangle meshes
 *   nl       landmarks (0: landmark-free; <= SS_MAX_LANDMARKS)
 *   lmX, lmY nl corresponding vertices of X and Y (checked by ss_landmarks_check)
 *   opts     options (NULL: defaults)
 * Outputs:
 *   out      map, centerX and centerY refer to the input meshes' vertices; C, the basis and pairs
 *            (segment indices) to the kept parts (free with ss_match_result_free)
 * Errors: SS_ERR_INVALID on NULL meshes or output, bad landmarks, bad options, a mesh the pipeline
 *   cannot take; errors of the stages (SS_ERR_UNSUPPORTED, SS_ERR_NUMERIC); SS_ERR_NOMEM.
 */
SS_API ss_status ss_match(const ss_mesh *X, const ss_mesh *Y, int nl, const int *lmX, const int *lmY,
                          const ss_match_options *opts, ss_match_result *out, ss_error *err);
/* ss_match that also says what was dropped: per mesh, the components kept, their share of the
 * vertices and the area, and the dropped ones.
 *
 * Inputs:
 *   X, Y, nl, lmX, lmY, opts  as ss_match
 *   warnings_size  bytes at warnings
 * Outputs:
 *   out      as ss_match
 *   warnings (may be NULL) the summary ("" when nothing)
 * Errors: as ss_match.
 */
SS_API ss_status ss_match_warn(const ss_mesh *X, const ss_mesh *Y, int nl, const int *lmX, const int *lmY,
                               const ss_match_options *opts, ss_match_result *out, char *warnings,
                               size_t warnings_size, ss_error *err);
/* Frees every array of r (map, C, pairs, centres) and zeroes it; safe on a zeroed struct.
 *
 * Inputs:
 *   r        from any match call
 */
SS_API void ss_match_result_free(ss_match_result *r);

/* ---- Prepared shapes and their files (shape_file.c) -------------------------------------------- *
 * What a match needs from one shape, computed once (specseg prepare) and matched many times: the
 * input mesh, its ss_shape_prep (the segmentation with its streamlined work mesh, Ψ, critical
 * points, iVd labels and centre distances; K eigenpairs and masses of the input; the critical
 * points' geodesic fields, so no geodesic is propagated at match time, and the probe cache of the
 * default match's functional maps), the options they were computed with and, for one-component
 * meshes, the landmark-free pairing's centre signature.
 *
 * File format (version SS_PREPARED_SHAPE_VERSION), the design of the eval cache (util/blob.h):
 *   line 1: "specseg-shape VERSION BYTEORDER intN doubleN lib X.Y.Z mesh NV NF HASH kev K
 *            seg FACES NOSTREAM CLEANUP NEIGS CMCF_STEPS CMCF_DT SANITIZE sig 0|1 [AUTOPAIR OPTIONS]"
 *            (HASH: FNV-1a 64 of the mesh's nv, nf, V, F; doubles printed exactly, %.17g);
 *   line 2: "payload BYTES fnv1a64 CHECKSUM" (of line 1 followed by the payload);
 *   then the raw native arrays: mesh, proxy flag, prep (eigenpairs, masses, segmentation, the
 *   critical points' geodesic fields, the probe cache), [proxy mesh, to_proxy, proxy_src, proxy
 *   prep], signature (version 3; version 2 had no probe cache, version 1 neither fields nor proxies).
 * A file of another format version, byte order or type sizes, cut short, longer, with any byte
 * changed (checksum) or with contents out of range is refused with SS_ERR_PARSE and the reason; it is
 * never used partly. */
#define SS_PREPARED_SHAPE_VERSION 3

/* One shape prepared for matching (specseg prepare), as held in memory and in its file (format
 * above). Free with ss_prepared_shape_free.
 */
typedef struct ss_prepared_shape {
  ss_mesh mesh;                 /* the input mesh (owned) */
  ss_shape_prep prep;           /* prep.mesh points to `mesh` */
  ss_segment_options seg;       /* the options prep.seg was computed with */
  int has_signature;            /* 1: sig holds the centre signature, computed with `autopair` */
  ss_autopair_options autopair;
  ss_centre_signature sig;      /* sig.prep points to the matched prep (ss_prepared_shape_matched) */
  /* A mesh above 100,000 vertices (closed, manifold, consistently oriented) is matched through a
   * coarse proxy of about 40,000 faces, as ss_match_warn matches it from the mesh: then has_proxy is
   * 1, `prep` holds the input's own segmentation only (what `segment` reports; kev 0, no spectrum)
   * and the match uses proxy_prep, computed on `proxy`; maps and centres are lifted back through
   * to_proxy / proxy_src. */
  int has_proxy;
  ss_mesh proxy;                /* the coarse mesh (owned); proxy_prep.mesh points to it */
  int *to_proxy;                /* mesh.nv: input vertex -> proxy vertex */
  int *proxy_src;               /* proxy.nv: proxy vertex -> the input vertex it was */
  ss_shape_prep proxy_prep;
} ss_prepared_shape;

/* The ss_shape_prep a match of s uses.
 *
 * Inputs:
 *   s        a prepared shape
 * Returns: &s->proxy_prep with a proxy, else &s->prep.
 */
SS_API const ss_shape_prep *ss_prepared_shape_matched(const ss_prepared_shape *s);

/* Prepares one shape for matching: ss_shape_prep_compute, the critical points' geodesic fields
 * (ss_shape_prep_crit_fields), the default match's probe cache, the landmark-free signature and, for
 * a very large mesh, its proxy (above). Cost: ss_shape_prep_compute's plus m (8 on FAUST) geodesic
 * fields; with a proxy, ss_segment of the input plus ss_shape_prep_compute of the proxy.
 *
 * Inputs:
 *   m        the input mesh (nv vertices, nf faces; copied), as ss_shape_prep_compute takes it (no face
 *            or vertex the sanitizer would drop)
 *   seg_opts segmentation options (NULL: ss_segment_default_options)
 *   kev      eigenpairs, 3 <= kev < nv; a match needs ss_match_eigenpairs (150 for the default
 *            match)
 *   autopair options of the landmark-free pairing's centre signature (NULL: none computed); it is
 *            computed only for a mesh of one component (the landmark-free match of several keeps the
 *            largest one and prepares that)
 * Outputs:
 *   out      filled (free with ss_prepared_shape_free); zeroed on failure
 * Errors: those of ss_shape_prep_compute, ss_shape_prep_crit_fields and ss_centre_signature_compute.
 */
SS_API ss_status ss_prepared_shape_compute(const ss_mesh *m, const ss_segment_options *seg_opts, int kev,
                                           const ss_autopair_options *autopair, ss_prepared_shape *out, ss_error *err);
/* Writes a prepared shape to a file (the format above), through a temporary file renamed into place.
 *
 * Inputs:
 *   path     the file
 *   s        the prepared shape
 * Errors: SS_ERR_INVALID on NULL arguments or a shape that is not prepared; SS_ERR_IO when the file
 *   cannot be written; SS_ERR_NOMEM.
 */
SS_API ss_status ss_prepared_shape_write(const char *path, const ss_prepared_shape *s, ss_error *err);
/* Reads a prepared-shape file; a file of another format version, byte order or type sizes, cut
 * short, longer, damaged or out of range is refused, never used partly.
 *
 * Inputs:
 *   path     the file
 * Outputs:
 *   out      the shape (free with ss_prepared_shape_free); zeroed on failure
 * Errors: SS_ERR_IO (no such file, unreadable); SS_ERR_PARSE (not a prepared shape, another format
 *   version / machine, damaged: the message says which); SS_ERR_NOMEM.
 */
SS_API ss_status ss_prepared_shape_read(const char *path, ss_prepared_shape *out, ss_error *err);
/* ss_prepared_shape_read of size bytes in memory.
 *
 * Inputs:
 *   data, size  the bytes (not kept)
 *   name     stands for the file in messages
 * Outputs:
 *   out      as ss_prepared_shape_read
 * Errors: as ss_prepared_shape_read (SS_ERR_PARSE, SS_ERR_INVALID on NULL arguments, SS_ERR_NOMEM).
 */
SS_API ss_status ss_prepared_shape_read_memory(const void *data, size_t size, const char *name, ss_prepared_shape *out,
                                               ss_error *err);
/* Do the first bytes of a file look like a prepared-shape file?
 *
 * Inputs:
 *   head     the first n bytes of a file
 *   n        their count
 * Returns: 1 when they begin like a prepared-shape file, else 0.
 */
SS_API int ss_is_prepared_shape(const void *head, size_t n);
/* Frees everything s owns (mesh, preps, proxy, signature) and zeroes it; safe on a zeroed struct.
 *
 * Inputs:
 *   s        from ss_prepared_shape_compute / ss_prepared_shape_read
 */
SS_API void ss_prepared_shape_free(ss_prepared_shape *s);

/* Does a match segment its shapes?
 *
 * Inputs:
 *   opts     options (NULL: defaults)
 *   nl       landmarks
 * Returns: 1 when a match with opts and nl landmarks segments its shapes (landmark-free, ASA, DIFF, or
 *   STD with std_pairs); 0 for STD with landmarks, which uses no segments.
 */
SS_API int ss_match_segments(const ss_match_options *opts, int nl);

/* Eigenpairs each shape needs for ss_match_prepared: max(k, ZoomOut's kmax when refining, descr_k,
 * seg_descr_k with segment probes; landmark-free also the pairing's descr_k and orient_k; and
 * autopair.hyp_final_kmax when the match forms hypotheses (landmark-free, or beside landmarks with
 * hyp_landmarks and SS_REFINE_BEST): shapes with fewer but enough for the rest are matched, the map
 * kept refined only as far as their eigenpairs go, with a note).
 *
 * Inputs:
 *   opts     options (NULL: defaults)
 *   nl       landmarks (0: landmark-free)
 * Returns: the count (defaults: 150, with landmarks or without; 110 with hyp_landmarks 0).
 */
SS_API int ss_match_eigenpairs(const ss_match_options *opts, int nl);

/* The most landmarks a match takes: each adds probe functions and, for the segment pairing, a
 * geodesic field (1000 landmarks took over 60 s and 2.3 GB on a 7000-vertex pair). */
#define SS_MAX_LANDMARKS 200
/* Checks the landmark list of a match: no more than SS_MAX_LANDMARKS, no vertex given two partners
 * ("962 1319" and "962 100", or two vertices of X one vertex of Y). An exact repeat is accepted.
 * ss_match, ss_match_warn and ss_match_prepared_shapes check their landmarks with it.
 *
 * Inputs:
 *   nl       landmarks
 *   lmX, lmY nl pairs lmX[i] <-> lmY[i] (in range)
 * Outputs:
 *   a, b     (may be NULL) on a conflict: a < b, the two landmarks (0-based); on success: the first two
 *            occurrences of an exact repeat (-1 when none); more than SS_MAX_LANDMARKS: -1
 * Errors: SS_ERR_INVALID for too many landmarks or a vertex with two partners (the message names
 *   them); SS_ERR_NOMEM.
 */
SS_API ss_status ss_landmarks_check(int nl, const int *lmX, const int *lmY, int *a, int *b, ss_error *err);

/* ss_match_warn on two prepared shapes: the same map, pairs and notes as ss_match_warn(&X->mesh,
 * &Y->mesh, ...) with opts->seg = the shapes' options, when each was prepared with exactly
 * ss_match_eigenpairs(opts, nl) eigenpairs (more: a match in the larger basis, as ss_match_prepared
 * gives it). A shape whose components ss_match_warn would not all keep (several components, some
 * without a landmark; landmark-free: more than one) is prepared again from its mesh, and warnings says
 * so.
 *
 * Inputs:
 *   X, Y     prepared shapes
 *   nl       landmarks (0: landmark-free; the stored signatures are used when computed with
 *            opts->autopair)
 *   lmX, lmY nl input vertices
 *   opts     options (NULL: defaults; opts->seg is not used)
 *   warnings_size  bytes at warnings
 * Outputs:
 *   out      as ss_match (free with ss_match_result_free)
 *   warnings (may be NULL) as ss_match_warn
 * Errors: SS_ERR_INVALID on a NULL output, a shape that is not prepared or has fewer eigenpairs than
 *   the match needs (naming the shape), bad landmarks; errors of ss_match_prepared; SS_ERR_NOMEM.
 */
SS_API ss_status ss_match_prepared_shapes(const ss_prepared_shape *X, const ss_prepared_shape *Y, int nl, const int *lmX,
                                          const int *lmY, const ss_match_options *opts, ss_match_result *out,
                                          char *warnings, size_t warnings_size, ss_error *err);

#ifdef __cplusplus
}
#endif
#endif
