/* Figures 9–11: one FAUST pair matched with STD, ASA and DIFF the way the Table 1 rows are (same
 * shape preparation, landmark sets and ev_match), drawn as the paper does: the top row shows the target
 * Y coloured by its coordinates and X pulled back through each map (colour transfer), the bottom row X
 * coloured by each map's per-vertex exact geodesic error on one shared heat scale; on the right the
 * segments of X and Y, paired segments in the same colour. The bottom-left panel is X pulled back
 * through the ground truth (identity): what a perfect map would show above. The drawing is the
 * library's ss_render_map_comparison; this file computes what it shows. */
#include "eval_internal.h"
#include "specseg/io.h"
#include "specseg/render.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The matching context of the figures: the Table 1 runner's options at basis size k, the BEST set from
 * the data folder and the GT set of `seed` (always, as a full Table 1 run has it: the per-shape cache
 * key then matches its files). */
static ss_status figure_context(const char *data_dir, uint64_t seed, int k, ev_context *ctx, ss_error *err) {
  memset(ctx, 0, sizeof *ctx);
  ss_match_paper_options(&ctx->mopt); /* Table 1: the paper's STD / ASA / DIFF */
  ctx->mopt.fmap.k = k;
  ctx->kev = k;
  int *lmb = NULL, nlmb = 0, gt_shape;
  char path[4096];
  snprintf(path, sizeof path, "%s/faust/landmarks_best.txt", data_dir);
  ss_status st = ss_read_ints(path, &lmb, &nlmb, err);
  if (!st && nlmb != EV_NL) st = ss_fail(err, SS_ERR_PARSE, "%s: %d landmarks, %d expected", path, nlmb, EV_NL);
  if (!st) memcpy(ctx->best, lmb, sizeof ctx->best);
  free(lmb);
  if (!st) st = ev_gt_landmarks(data_dir, seed, ctx, ctx->gt, &gt_shape, err);
  return st;
}

ss_status ss_eval_showcase_pair(const char *data_dir, const char *cache_dir, uint64_t seed, int k, ss_lm_set lmset,
                                ss_pair_policy policy, int ncand, int *x, int *y, int *index, int *xs, int *ys,
                                double *scores, ss_error *err) {
  if (!data_dir || !x || !y || lmset < 0 || lmset > 2 || ncand < 1 || ncand > 100 || k < 3)
    return ss_fail(err, SS_ERR_INVALID, "showcase: bad arguments (landmarks %d, %d candidates, k %d)", lmset, ncand, k);
  int cx[100], cy[100];
  ss_status st = ss_eval_pairs(policy, 10, 10, ncand, seed, cx, cy, err);
  if (st) return st;
  double sc[100];
  ev_context ctx;
  ev_shape *sh = calloc(100, sizeof *sh); /* each shape prepared once, by id */
  char *loaded = calloc(100, 1);
  int *maps[SS_EVAL_NMETHODS] = {NULL}; /* STD, ASA, DIFF (not the refined method) */
  if (!sh || !loaded) { st = ss_fail(err, SS_ERR_NOMEM, "showcase: out of memory"); goto done; }
  if (ncand > 1 && (st = figure_context(data_dir, seed, k, &ctx, err))) goto done;
  for (int c = 0; c < ncand && ncand > 1; c++) {
    const int ids[2] = {cx[c], cy[c]};
    for (int s = 0; s < 2; s++)
      if (!loaded[ids[s]]) {
        if ((st = ev_shape_load(data_dir, cache_dir, ids[s], &ctx, &sh[ids[s]], NULL, 0, err))) goto done;
        loaded[ids[s]] = 1;
      }
    const ev_shape *X = &sh[cx[c]], *Y = &sh[cy[c]];
    for (int m = 0; m < 3; m++)
      if (!maps[m] && !(maps[m] = malloc(sizeof(int) * (size_t)X->mesh.nv))) {
        st = ss_fail(err, SS_ERR_NOMEM, "showcase: out of memory");
        goto done;
      }
    int paired[SS_EVAL_NMETHODS];
    if ((st = ev_match_methods(&ctx, X, Y, lmset, 7, maps, NULL, paired, err))) goto done;
    double sum = 0;
    for (int m = 0; m < 3; m++) {
      double mean;
      if ((st = ss_map_geodesic_error(&Y->mesh, X->mesh.nv, maps[m], NULL, NULL, NULL, &mean, err))) goto done;
      sum += mean;
    }
    sc[c] = sum / 3;
  }
  /* the median of the candidates' scores: the (ncand + 1) / 2-th smallest, ties in draw order */
  int order[100];
  for (int c = 0; c < ncand; c++) order[c] = c;
  for (int a = 1; a < ncand; a++)
    for (int b = a; b > 0 && (sc[order[b]] < sc[order[b - 1]] || (sc[order[b]] == sc[order[b - 1]] && order[b] < order[b - 1])); b--) {
      int t = order[b];
      order[b] = order[b - 1], order[b - 1] = t;
    }
  int pick = ncand > 1 ? order[(ncand - 1) / 2] : 0;
  *x = cx[pick], *y = cy[pick];
  if (index) *index = pick;
  for (int c = 0; c < ncand; c++) {
    if (xs) xs[c] = cx[c];
    if (ys) ys[c] = cy[c];
    if (scores) scores[c] = ncand > 1 ? sc[c] : 0.0;
  }
done:
  for (int i = 0; sh && loaded && i < 100; i++)
    if (loaded[i]) ev_shape_free(&sh[i]);
  free(sh), free(loaded);
  for (int m = 0; m < 3; m++) free(maps[m]);
  return st;
}

ss_status ss_eval_map_figure(const char *data_dir, const char *cache_dir, uint64_t seed, int k, ss_lm_set lmset, int x,
                             int y, const ss_render_options *o, const char *png, ss_map_figure *info, ss_error *err) {
  if (!data_dir || !o || !png || lmset < 0 || lmset > 2 || x < 0 || x > 99 || y < 0 || y > 99 || x == y || k < 3)
    return ss_fail(err, SS_ERR_INVALID, "figure: bad arguments (pair %d, %d, landmarks %d, k %d)", x, y, lmset, k);
  ev_context ctx;
  ev_shape X, Y;
  memset(&X, 0, sizeof X), memset(&Y, 0, sizeof Y);
  int *map[3] = {NULL, NULL, NULL}, *ident = NULL;
  double *errs = NULL, mean[3] = {0};
  unsigned char *img = NULL;
  ss_segment_pairs pr;
  memset(&pr, 0, sizeof pr);
  ss_status st = figure_context(data_dir, seed, k, &ctx, err);
  if (st) goto done;
  if ((st = ev_shape_load(data_dir, cache_dir, x, &ctx, &X, NULL, 0, err))) goto done;
  if ((st = ev_shape_load(data_dir, cache_dir, y, &ctx, &Y, NULL, 0, err))) goto done;
  const int nx = X.mesh.nv, ny = Y.mesh.nv;
  if (nx > ny) { st = ss_fail(err, SS_ERR_INVALID, "figure: tr_reg_%03d has more vertices than tr_reg_%03d", x, y); goto done; }

  /* the three maps and their per-vertex errors (all vertices, exact geodesics: the rows' measure) */
  errs = malloc(sizeof(double) * 3 * (size_t)nx);
  ident = malloc(sizeof(int) * (size_t)nx);
  if (!errs || !ident) { st = ss_fail(err, SS_ERR_NOMEM, "figure: out of memory"); goto done; }
  for (int i = 0; i < nx; i++) ident[i] = i;
  int paired = 0;
  for (int m = 0; m < 3; m++) {
    if (!(map[m] = malloc(sizeof(int) * (size_t)nx))) { st = ss_fail(err, SS_ERR_NOMEM, "figure: out of memory"); goto done; }
    if ((st = ev_match(&ctx, &X, &Y, lmset, m, map[m], &paired, err))) goto done;
    if ((st = ss_map_geodesic_error(&Y.mesh, nx, map[m], NULL, NULL, errs + (size_t)m * nx, &mean[m], err))) goto done;
  }

  /* the segment pairing of this landmark set, as ev_match computes it */
  if ((st = ss_pair_critical_points(X.prep.seg.m, Y.prep.seg.m, EV_NL, X.lmd[lmset], Y.lmd[lmset], &pr, err))) goto done;
  /* pairs the ground truth (identity) confirms: most of X's segment lies in Y's paired segment */
  int agree = 0;
  for (int p = 0; p < pr.n; p++) {
    long in = 0, both = 0;
    for (int i = 0; i < nx; i++)
      if (X.prep.seg.labels[i] == pr.sx[p]) in++, both += Y.prep.seg.labels[i] == pr.sy[p];
    agree += 2 * both > in;
  }

  /* the picture: the three maps against the ground truth (identity), the segments paired as above */
  static const char *const NAME[3] = {"STD", "ASA", "DIFF"}, *const LM[3] = {"BEST", "GT", "FPS"};
  char xname[16], yname[16], heading[160];
  snprintf(xname, sizeof xname, "tr_reg_%03d", x);
  snprintf(yname, sizeof yname, "tr_reg_%03d", y);
  snprintf(heading, sizeof heading, "FAUST %s landmarks: tr_reg_%03d to tr_reg_%03d, %d segment pairs (%d right)",
           LM[lmset], x, y, pr.n, agree);
  ss_map_comparison fig;
  ss_map_comparison_init(&fig, &X.mesh, &Y.mesh);
  fig.x_name = xname, fig.y_name = yname, fig.heading = heading;
  fig.nmaps = 3;
  for (int m = 0; m < 3; m++)
    fig.map[m] = map[m], fig.error[m] = errs + (size_t)m * nx, fig.mean_error[m] = mean[m], fig.method[m] = NAME[m];
  fig.gt = ident;
  fig.nlandmarks = EV_NL;
  fig.landmarks_x = ev_landmarks(&ctx, &X, lmset), fig.landmarks_y = ev_landmarks(&ctx, &Y, lmset);
  fig.segments_x = X.prep.seg.m, fig.segments_y = Y.prep.seg.m;
  fig.labels_x = X.prep.seg.labels, fig.labels_y = Y.prep.seg.labels;
  fig.centers_x = X.prep.seg.centers, fig.centers_y = Y.prep.seg.centers;
  fig.npairs = pr.n, fig.pair_x = pr.sx, fig.pair_y = pr.sy;
  int w, h;
  double hi;
  if ((st = ss_render_map_comparison(&fig, o, &img, &w, &h, &hi, err))) goto done;
  if ((st = ss_write_png(png, img, w, h, err))) goto done;
  if (info) {
    memset(info, 0, sizeof *info);
    info->x = x, info->y = y, info->lmset = lmset;
    for (int m = 0; m < 3; m++) info->mean_error[m] = mean[m];
    info->error_scale = hi;
    info->paired = pr.n, info->paired_right = agree, info->segments_x = X.prep.seg.m, info->segments_y = Y.prep.seg.m;
    info->width = w, info->height = h;
  }
done:
  ev_shape_free(&X);
  ev_shape_free(&Y);
  ss_segment_pairs_free(&pr);
  for (int m = 0; m < 3; m++) free(map[m]);
  free(ident), free(errs), free(img);
  return st;
}
