/* The hypothesis energy of a landmark-free map (hypotheses.c). */
#ifndef SS_MATCH_HYPOTHESES_H
#define SS_MATCH_HYPOTHESES_H

#include "specseg/geodesic.h"
#include "specseg/match.h"

/* X's sources and their distance fields, computed once per match; Y's graph */
typedef struct ssi_hyp_ctx {
  const ss_mesh *X, *Y;
  ss_graph gX, gY;
  int nsrc;
  int *src;           /* nsrc farthest-point sources on X */
  double *dX;         /* nX x nsrc edge-graph distances from them */
  double *dY;         /* scratch, nY */
  double *dB;         /* scratch, nX x nsrc: the images' distances over √area of Y */
  double sX, sY;      /* √area of each mesh */
  int fit_scale;      /* 1: distances compared up to one scale (ssi_hyp_distortion) */
  double scale;       /* the scale of the last ssi_hyp_distortion (1 without fit_scale) */
} ssi_hyp_ctx;

ss_status ssi_hyp_ctx_new(const ss_mesh *X, const ss_mesh *Y, int nsrc, int fit_scale, ssi_hyp_ctx *c,
                          ss_error *err);
void ssi_hyp_ctx_free(ssi_hyp_ctx *c);

/* Metric distortion of map (X's nv entries, vertices of Y): mean over the sources s and X's vertices
 * v of |d_X(s, v)/√area_X − σ d_Y(map s, map v)/√area_Y| (edge-graph distances). σ = 1, or with
 * c->fit_scale the least-squares scale of the two distance sets, clamped to [0.5, 2] (c->scale): two
 * people of different build have limbs of about the same length and torsos of different area, so
 * over √area their distances differ by a common factor that hides the difference between a right
 * map and a swapped one (docs/tuning.md). The clamp keeps a map that collapses X from being scaled
 * up to fit. */
ss_status ssi_hyp_distortion(ssi_hyp_ctx *c, const int *map, double *out, ss_error *err);

/* X's left-right self-symmetry as a vertex map (match_hypotheses.c; the flipped candidates of
 * ss_autopair_options.hyp_flip_orient): S[v] is the mirror image of vertex v of X (an
 * orientation-reversing self-isometry), from the functional map of X to its reflection in a plane with
 * the orientation term of weight w (> 0) and the match's ZoomOut (o->fmap).
 *
 * Inputs:
 *   X        a prepared shape (kev >= 20 for both candidate sizes)
 *   o        the match's options (o->fmap: descriptors and ZoomOut)
 *   w        weight of the orientation term
 * Outputs:
 *   S        X->mesh->nv entries (caller-allocated)
 * Errors: those of ss_fmap_match; SS_ERR_NOMEM. */
ss_status ssi_symmetry_map(const ss_shape_prep *X, const ss_match_options *o, double w, int *S, ss_error *err);

/* ss_match_prepared with the shapes' centre signatures when the caller has them (NULL: computed):
 * landmark-free, the hypotheses' map; with landmarks and ss_autopair_options.hyp_landmarks, the
 * given landmarks' map against the pairing hypotheses that agree with them (match_hypotheses.c). */
ss_status ssi_match_prepared_signed(const ss_shape_prep *X, const ss_shape_prep *Y, const ss_centre_signature *sigX,
                                    const ss_centre_signature *sigY, int nl, const int *lmX, const int *lmY,
                                    const ss_match_options *opts, ss_match_result *out, ss_error *err);
#endif
