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
 *    in its notes); the pairing itself is still computed and reported. */
typedef struct ss_pairing_options {
  double min_ratio;
  int mutual;
  double max_rel_energy;
  int min_landmarks;
} ss_pairing_options;

SS_API void ss_pairing_default_options(ss_pairing_options *o);
/* The paper's rule: every confidence test off, min_landmarks 1. */
SS_API void ss_pairing_paper_options(ss_pairing_options *o);

/* §6.1. lmX/lmY: nl corresponding landmarks given as INPUT vertices (< X->nv, < Y->nv); Ψ carries
 * them to the work meshes. Exact (VTP) fields from each landmark on both work meshes, each divided
 * by √area(work). For every critical point x of the shape with fewer of them (X on ties) the
 * critical point y* of the other shape minimising ‖(d_X^i(x) − d_Y^i(y))_i‖₂; when several x choose
 * the same y*, only the one with the smallest energy keeps it (the paper's conservative rule).
 * Output pairs sorted by sx. Needs nl ≥ 1. Segmentations must come from ss_segment on an input that
 * its sanitizer left unchanged (psi indexed by input vertex). Free with ss_segment_pairs_free. */
SS_API ss_status ss_pair_segments(const ss_segmentation *X, const ss_segmentation *Y, int nl, const int *lmX,
                                  const int *lmY, ss_segment_pairs *out, ss_error *err);
/* The same from precomputed landmark fields at the critical points: dX (mx x nl, column-major,
 * dX[s + mx·i] = scaled distance from landmark i to critical point s of X), likewise dY (my x nl). */
SS_API ss_status ss_pair_critical_points(int mx, int my, int nl, const double *dX, const double *dY,
                                         ss_segment_pairs *out, ss_error *err);
/* The same two with the confidence rules of po (NULL: the paper's rule, as the calls above). */
SS_API ss_status ss_pair_critical_points_conf(int mx, int my, int nl, const double *dX, const double *dY,
                                              const ss_pairing_options *po, ss_segment_pairs *out, ss_error *err);
SS_API ss_status ss_pair_segments_conf(const ss_segmentation *X, const ss_segmentation *Y, int nl, const int *lmX,
                                       const int *lmY, const ss_pairing_options *po, ss_segment_pairs *out,
                                       ss_error *err);
SS_API void ss_segment_pairs_free(ss_segment_pairs *p);

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

/* The probe functions of paired segments on one shape: E (malloc'd, sg->nv x npairs, column-major),
 * column p is segment seg[p] of sg in the given profile. The tent needs the segmentation's distances
 * (work_dist, psi), the soft profile its work mesh and critical points (m graph Dijkstras). */
SS_API ss_status ss_segment_probes(const ss_segmentation *sg, int npairs, const int *seg, ss_segment_profile profile,
                                   double **E, ss_error *err);

/* ---- Per-shape preparation (shape_prep.c) ------------------------------------------------------- */

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
} ss_shape_prep;

/* Segments `m` (seg_opts may be NULL) and computes its first kev Laplace–Beltrami eigenpairs (then
 * scaled to unit area, above). The result depends only on the shape, so it can be computed once and
 * reused across pairs. Fails with SS_ERR_INVALID on a mesh the sanitizer would change (non-manifold or
 * degenerate input): repair it first (its vertex indices are what landmarks and maps refer to). */
SS_API ss_status ss_shape_prep_compute(const ss_mesh *m, const ss_segment_options *seg_opts, int kev, ss_shape_prep *out,
                                       ss_error *err);
SS_API void ss_shape_prep_free(ss_shape_prep *p);
/* In place: eigenpairs (kev, eigenvectors nv x kev) and masses (nv) of a shape of the given area become
 * those of the shape scaled to unit area (λ·area, φ·√area, M/area); any pointer may be NULL. What
 * ss_shape_prep_compute applies, for callers that fill an ss_shape_prep themselves (more eigenpairs of
 * the same shape: scale them with the prep's `area`). */
SS_API void ss_shape_prep_unit_area(double area, int nv, int kev, double *evals, double *evecs, double *M);

/* ---- The matching pipeline (match.c) ------------------------------------------------------------ */

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
                            the segment-aided map; each refined by ZoomOut up to fmap.zoomout_kmax
                            (default 120, step fmap.zoomout_step 5, on fmap.zoomout_samples 2,000
                            samples of X then once on every vertex: docs/tuning.md); of
                            the starts and their refinements the map with the lowest selection energy
                            ss_p2p_energy (k0 = k, K = max(k, zoomout_kmax), step 1, w_lap =
                            refine_w_lap) + refine_w_descr · ss_p2p_descr_residual (the base probes,
                            at size k) is returned — a refinement only when not above its own start
                            by that energy. No ground truth. */
} ss_refine_mode;

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
  /* SS_REFINE_BEST: refine only the start with the lower selection energy (the other start stays a
   * candidate unrefined); 0: refine every start */
  int refine_single;
} ss_match_options;

SS_API void ss_match_default_options(ss_match_options *o);
/* The paper's STD / ASA / DIFF as the paper defines them (what specseg eval's Table 1 uses): the
 * defaults with descr_k = k, the paper's pairing rule (ss_pairing_paper_options) and no refinement. */
SS_API void ss_match_paper_options(ss_match_options *o);

typedef struct ss_match_result {
  int nX;           /* vertices of X */
  int *map;         /* nX: map[i] = vertex of Y, image of vertex i of X */
  int kc;           /* C is kc x kc (k, or zoomout_kmax with ZoomOut) */
  double *C;        /* functional map from functions on Y to functions on X (pull-back of map), in the
                       shapes' unit-area bases (ss_shape_prep: C[0] = ±1, whatever the two sizes) */
  ss_segment_pairs pairs;
  int *centerX, *centerY; /* pairs.n: input vertices at the centres of the paired segments */
  /* seconds per stage */
  double t_segment, t_eigs, t_pair, t_fmap, t_zoomout, t_total;
  /* SS_REFINE_BEST: the candidate returned (0 STD start, 1 STD refined, 2 segment-aided start,
   * 3 segment-aided refined) and the selection energies of the four (NAN: not computed); -1 and NANs
   * with the other modes */
  int refine_choice;
  double refine_energy[4];
  /* what the caller should know, e.g. that segment probes were not used (empty: nothing) */
  char notes[256];
} ss_match_result;

/* Matches two prepared shapes (each with ≥ max(k, zoomout_kmax, descr_k) eigenpairs; zoomout_kmax
 * only with refinement). lmX/lmY: nl input vertices. With STD the pairing is still computed (and
 * reported) but not used; with fewer than pairing.min_landmarks landmarks, or no segment paired, ASA
 * and DIFF fall back to STD and say so in notes. */
SS_API ss_status ss_match_prepared(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX, const int *lmY,
                                   const ss_match_options *opts, ss_match_result *out, ss_error *err);

/* The same with the pairing given instead of computed (e.g. by ss_pair_critical_points_conf from
 * landmark fields cached per shape, as specseg eval does; opts->pairing is then not used, except
 * min_landmarks): pairs (sx < X->seg.m, sy < Y->seg.m) is copied into out->pairs. With the pairing
 * ss_match_prepared would compute, the result is the same. */
SS_API ss_status ss_match_prepared_pairs(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX,
                                         const int *lmY, const ss_segment_pairs *pairs, const ss_match_options *opts,
                                         ss_match_result *out, ss_error *err);

/* Everything from two meshes: prepare both, then ss_match_prepared. opts may be NULL.
 * Meshes of several components: the map is only determined on components that hold a landmark, so
 * on each mesh the components with at least one landmark are kept and matched (the body of a scan,
 * without its crumbs; every component when each has a landmark); a vertex of X on a dropped
 * component takes the image of its nearest (Euclidean) kept vertex of X, and no vertex of X maps to
 * a dropped vertex of Y. map, centerX and centerY refer to the input meshes' vertices; C, the basis
 * and pairs (segment indices) to the kept parts. Unreferenced vertices are refused as for one
 * component. */
SS_API ss_status ss_match(const ss_mesh *X, const ss_mesh *Y, int nl, const int *lmX, const int *lmY,
                          const ss_match_options *opts, ss_match_result *out, ss_error *err);
/* The same, with what was dropped in `warnings` (warnings_size bytes, may be NULL; "" when nothing):
 * per mesh, the components kept, their share of the vertices and the area, and the dropped ones. */
SS_API ss_status ss_match_warn(const ss_mesh *X, const ss_mesh *Y, int nl, const int *lmX, const int *lmY,
                               const ss_match_options *opts, ss_match_result *out, char *warnings,
                               size_t warnings_size, ss_error *err);
SS_API void ss_match_result_free(ss_match_result *r);

#ifdef __cplusplus
}
#endif
#endif
