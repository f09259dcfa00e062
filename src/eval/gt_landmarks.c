/* The GT landmark set of §6.1 for a seed: FPS (Appendix A) on one seeded-random FAUST shape, seeded
 * at its head vertex 0, carried to every shape by the ground truth (FAUST: identity). The same
 * definition as the Table 1 runner's, so the figures show the rows' landmarks. */
#include "eval_internal.h"
#include "specseg/io.h"

#include <stdio.h>
#include <string.h>

ss_status ev_fps_file(const char *path, int seed_vertex, const ev_context *ctx, int *lm, ss_error *err) {
  ss_mesh m = {0};
  ss_segmentation seg;
  memset(&seg, 0, sizeof seg);
  ss_status st = ss_read_mesh(path, &m, err);
  if (!st) st = ss_segment(&m, &ctx->mopt.seg, &seg, err);
  if (!st) st = ev_fps_landmarks(&m, &seg, &ctx->mopt.seg, seed_vertex, lm, err);
  ss_segmentation_free(&seg);
  ss_mesh_free(&m);
  return st;
}

ss_status ev_gt_landmarks(const char *data_dir, uint64_t seed, const ev_context *ctx, int *gt, int *shape,
                          ss_error *err) {
  ss_rng r;
  ss_rng_seed(&r, seed ^ 0x6A09E667F3BCC909ull);
  *shape = ss_rng_below(&r, 100); /* FAUST: 10 subjects x 10 poses */
  char path[4096];
  snprintf(path, sizeof path, "%s/faust/tr_reg_%03d.off", data_dir, *shape);
  return ev_fps_file(path, 0, ctx, gt, err);
}
