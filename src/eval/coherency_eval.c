/* §5 coherency of a whole set of shapes with its first shape, with and without streamlining
 * (reuses ss_segment and ss_coherency). */
#include "specseg/eval.h"
#include "specseg/io.h"
#include "specseg/segment.h"

#ifdef _OPENMP
#include <omp.h>
#endif
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

ss_status ss_eval_coherency_set(const char *name, int n, const char *const *paths, int jobs,
                                ss_coherency_result *res, ss_error *err) {
  if (!res || n < 2 || !paths) return ss_fail(err, SS_ERR_INVALID, "coherency: need at least two shapes");
  memset(res, 0, sizeof *res);
  snprintf(res->name, sizeof res->name, "%s", name ? name : "");
  res->nshapes = n;
  ss_segmentation *seg = calloc((size_t)n * 2, sizeof *seg);
  int *nvs = calloc((size_t)n, sizeof(int));
  if (!seg || !nvs) { free(seg); free(nvs); return ss_fail(err, SS_ERR_NOMEM, "coherency: out of memory"); }
  int failed = 0;
  ss_error ferr = {{0}};
  omp_lock_t err_lock;
  omp_init_lock(&err_lock);
  /* one task per (shape, with/without streamlining) */
  int nth = jobs > 0 ? jobs : 1;
#ifdef _OPENMP
  if (jobs <= 0) nth = omp_get_max_threads();
#endif
#pragma omp parallel for schedule(dynamic, 1) num_threads(nth)
  for (int t = 0; t < 2 * n; t++) {
    if (failed) continue;
    int i = t / 2, w = t % 2;
    ss_mesh m = {0};
    ss_segment_options o;
    ss_segment_default_options(&o);
    o.no_streamline = w;
    ss_error e;
    ss_status s1 = ss_read_mesh(paths[i], &m, &e);
    if (!s1) s1 = ss_segment(&m, &o, &seg[2 * i + w], &e);
    if (s1) {
      omp_set_lock(&err_lock);
      if (!failed) failed = s1, snprintf(ferr.msg, sizeof ferr.msg, "%.300s: %.700s", paths[i], e.msg);
      omp_unset_lock(&err_lock);
    }
    nvs[i] = m.nv;
    ss_mesh_free(&m);
  }
  omp_destroy_lock(&err_lock);
  ss_status st = SS_OK;
  if (failed) st = ss_fail(err, (ss_status)failed, "coherency: %s", ferr.msg);
  for (int w = 0; w < 2 && !st; w++) {
    double sum = 0, mn = 1;
    const ss_segmentation *s0 = &seg[w];
    for (int i = 0; i < n && !st; i++) {
      const ss_segmentation *s = &seg[2 * i + w];
      res->hist[w][s->m < 31 ? s->m : 31]++;
      if (i == 0) continue;
      double c;
      if ((st = ss_coherency(s0->labels, s0->nv, s->labels, s->centers, s->m, s->nv, NULL, &c, err))) break;
      sum += c;
      if (c < mn) mn = c;
    }
    res->coherency[w] = sum / (n - 1);
    res->min_coherency[w] = mn;
  }
  for (int t = 0; t < 2 * n; t++) ss_segmentation_free(&seg[t]);
  free(seg);
  free(nvs);
  return st;
}
