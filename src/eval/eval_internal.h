/* Internals of the Table 1 runner: one prepared FAUST shape and the single place where the
 * evaluation calls the matching pipeline (eval_match.c). */
#ifndef SS_EVAL_INTERNAL_H
#define SS_EVAL_INTERNAL_H

#include "specseg/eval.h"
#include "specseg/match.h"

#define EV_NL 5 /* landmarks per set (paper: 5) */

/* Everything a shape contributes to a match, computed once per shape. When loaded from the disk
 * cache, prep.seg holds only nv, m, labels and centers (no work mesh). */
typedef struct ev_shape {
  int id;
  ss_mesh mesh;
  ss_shape_prep prep;
  int from_cache;
  int fps[EV_NL];          /* this shape's own FPS landmarks (input vertices) */
  double *lmd[3];          /* per landmark set: m x EV_NL scaled distances landmark → critical point */
  ss_fmap_probes base[3];  /* per landmark set: WKS + landmark probes (ev_shape_probes; p = 0 until then) */
  double t_prep;
  /* the refined method's view of the shape (ctx->kref > 0): prep's segmentation and masses (borrowed)
   * with its own kref eigenpairs (computed with that count, so the paper methods' k eigenpairs stay
   * exactly what they were; both sets live in the same cache entry) */
  ss_shape_prep rprep;
} ev_shape;

typedef struct ev_context {
  int best[EV_NL], gt[EV_NL];
  int kev;
  ss_match_options mopt;
  /* the refined method (SS_METHOD_REFINED): its options (ss_match_default_options with the run's k)
   * and eigenpairs per shape; kref = 0: not run */
  int kref;
  ss_match_options ropt;
} ev_context;

void ev_shape_free(ev_shape *s);
/* Reads tr_reg_<id>.off, prepares it (segmentation, eigenpairs, FPS landmarks, landmark fields at
 * the critical points; with ctx->kref also the refined method's eigenpairs), through the cache folder
 * when cache_dir is not NULL (format and checks in eval_shape.c; an entry without the refined
 * eigenpairs gets them added). note (nnote bytes, may be NULL) receives one line when a cache entry
 * was there but not used (damaged, truncated, written for another key): the caller reports it; else "". */
ss_status ev_shape_load(const char *data_dir, const char *cache_dir, int id, const ev_context *ctx, ev_shape *s,
                        char *note, size_t nnote, ss_error *err);

/* The same for a shape whose mesh (s->mesh, s->id) is already set: segmentation + eigenpairs
 * (ss_shape_prep_compute), FPS landmarks seeded at vertex 0, landmark fields, and with ctx->kref the
 * refined method's eigenpairs (ev_shape_refined). On failure s->mesh is kept and everything else
 * released. */
ss_status ev_shape_prepare(ev_shape *s, const ev_context *ctx, ss_error *err);

/* GT landmarks (§6.1): FPS of EV_NL points, seeded at Ψ(seed_vertex), on the streamlined version of
 * `m` (exact geodesics), mapped back to input vertices. */
ss_status ev_fps_landmarks(const ss_mesh *m, const ss_segmentation *seg, const ss_segment_options *so, int seed_vertex,
                           int *lm, ss_error *err);

/* The adapter: matches X → Y with the landmark set `lmset` and `method`, map[X.nv]. Uses the
 * landmark fields cached in the shapes and the library's pairing + functional-map calls; the result
 * equals ss_match_prepared's (tests/test_eval.c checks it). paired receives the number of paired
 * segments. */
ss_status ev_match(const ev_context *ctx, const ev_shape *X, const ev_shape *Y, int lmset, int method, int *map,
                   int *paired, ss_error *err);
/* The same for several methods of one pair and landmark set (bit 1 << method of methods_mask), sharing
 * the pairing, the base probes and the assembled normal equations: maps[method] (X.nv each) is
 * written for every method in the mask, with the CPU seconds of its own solve + point map plus an
 * equal share of the shared part in cpu[method] (may be NULL). Identical maps to ev_match. The
 * refined method is ss_match_prepared_pairs on the shapes' rprep with the confident pairing of ctx->ropt
 * from the cached landmark fields (its own CPU only; the paper methods' share excludes it). paired
 * (may be NULL): segments paired, per method (the refined one pairs with its own confidence rule). */
ss_status ev_match_methods(const ev_context *ctx, const ev_shape *X, const ev_shape *Y, int lmset, int methods_mask,
                           int *const maps[SS_EVAL_NMETHODS], double cpu[SS_EVAL_NMETHODS],
                           int paired[SS_EVAL_NMETHODS], ss_error *err);

/* Exact error sums of nmaps maps onto one target (ground truth identity): sum[r] = Σ_x d(maps[r][x], x),
 * sum_sym[r] = Σ_x min(d(maps[r][x], x), d(maps[r][x], sym[x])), every distinct (image, vertex) pair
 * queried once (batch_errors.c). */
ss_status ev_batch_errors(const ss_geodesic_mesh *gm, int nv, const int *sym, int nmaps, const int *const *maps,
                          double *sum, double *sum_sym, ss_error *err);

/* s->rprep for ctx->kref > 0: ctx->kref eigenpairs of the mesh (ss_mesh_eigs), the segmentation and
 * masses of s->prep. No-op when already there or kref = 0. */
ss_status ev_shape_refined(ev_shape *s, const ev_context *ctx, ss_error *err);

/* Builds s->base[set] for the landmark sets in lm_mask (once per shape, not cached on disk). */
ss_status ev_shape_probes(ev_shape *s, const ev_context *ctx, int lm_mask, ss_error *err);

/* Landmarks of a set on shape s (input vertices). */
const int *ev_landmarks(const ev_context *ctx, const ev_shape *s, int lmset);

/* GT landmarks for a seed (gt_landmarks.c): FPS on the seeded-random FAUST shape *shape, seeded at
 * vertex 0 (the Table 1 runner's and the figures' GT set). */
ss_status ev_gt_landmarks(const char *data_dir, uint64_t seed, const ev_context *ctx, int *gt, int *shape,
                          ss_error *err);

#endif
