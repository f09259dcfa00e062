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
  double *evals;        /* kev */
  double *evecs;        /* nv x kev, column-major, M-orthonormal */
  double *M;            /* nv barycentric lumped masses */
  double area;
  double t_segment, t_eigs; /* seconds */
} ss_shape_prep;

/* Segments `m` (seg_opts may be NULL) and computes its first kev Laplace–Beltrami eigenpairs. The
 * result depends only on the shape, so it can be computed once and reused across pairs. Fails with
 * SS_ERR_INVALID on a mesh the sanitizer would change (non-manifold or degenerate input): repair it
 * first (its vertex indices are what landmarks and maps refer to). */
SS_API ss_status ss_shape_prep_compute(const ss_mesh *m, const ss_segment_options *seg_opts, int kev, ss_shape_prep *out,
                                       ss_error *err);
SS_API void ss_shape_prep_free(ss_shape_prep *p);

/* ---- The matching pipeline (match.c) ------------------------------------------------------------ */

typedef enum ss_probe_set {
  SS_PROBES_STD = 0,  /* WKS + landmark wave-kernel maps (NO17) */
  SS_PROBES_ASA = 1,  /* + the paired segments' functions (segment_profile), as they are */
  SS_PROBES_DIFF = 2  /* + the same functions filtered by the wave kernel */
} ss_probe_set;

typedef struct ss_match_options {
  ss_probe_set probes;        /* default DIFF */
  ss_fmap_match_options fmap; /* k, WKS, weights; fmap.zoomout_kmax > k enables ZoomOut */
  ss_segment_options seg;     /* segmentation of both shapes */
  /* the profile of a paired segment's probe function (ASA and DIFF); default SS_PROFILE_TENT at the
   * default k = 50, SS_PROFILE_SOFT is better for k >= 60 (docs/tuning.md) */
  ss_segment_profile segment_profile;
  /* the caller's own descriptors (default none): ndescr columns on each shape, descrX nX x ndescr and
   * descrY nY x ndescr column-major, column j of one corresponding to column j of the other; probes
   * beside the WKS (or instead of it with fmap.no_wks), as ss_fmap_shape.descr */
  int ndescr;
  const double *descrX, *descrY;
} ss_match_options;

SS_API void ss_match_default_options(ss_match_options *o);

typedef struct ss_match_result {
  int nX;           /* vertices of X */
  int *map;         /* nX: map[i] = vertex of Y, image of vertex i of X */
  int kc;           /* C is kc x kc (k, or zoomout_kmax with ZoomOut) */
  double *C;        /* functional map from functions on Y to functions on X (pull-back of map) */
  ss_segment_pairs pairs;
  int *centerX, *centerY; /* pairs.n: input vertices at the centres of the paired segments */
  /* seconds per stage */
  double t_segment, t_eigs, t_pair, t_fmap, t_zoomout, t_total;
} ss_match_result;

/* Matches two prepared shapes (each with ≥ max(k, zoomout_kmax) eigenpairs). lmX/lmY: nl input
 * vertices. With STD the pairing is still computed (and reported) but not used. */
SS_API ss_status ss_match_prepared(const ss_shape_prep *X, const ss_shape_prep *Y, int nl, const int *lmX, const int *lmY,
                                   const ss_match_options *opts, ss_match_result *out, ss_error *err);

/* Everything from two meshes: prepare both, then ss_match_prepared. opts may be NULL. */
SS_API ss_status ss_match(const ss_mesh *X, const ss_mesh *Y, int nl, const int *lmX, const int *lmY,
                          const ss_match_options *opts, ss_match_result *out, ss_error *err);
SS_API void ss_match_result_free(ss_match_result *r);

#ifdef __cplusplus
}
#endif
#endif
