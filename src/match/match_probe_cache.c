/* The probe cache of a match: the shape-only parts of the functional map's base probes for a
 * match's options, computed once on a prepared shape (ss_shape_prep_probe_cache), or by a match for
 * a shape that does not carry them (the same function, so both give the same map). */
#include "specseg/match.h"
#include "fmap/fmap_options.h"
#include "match/match_internal.h"
#include "util/side_by_side.h"

#include <stdlib.h>
#include <string.h>

/* The fmap options of a match's two starts: [0] STD, [1] the segment-aided one (its own descriptor
 * basis); returns how many differ in what a probe cache holds (1 or 2). */
int ssi_match_start_options(const ss_match_options *o, ss_fmap_match_options fo[2]) {
  fo[0] = fo[1] = o->fmap;
  fo[0].zoomout_kmax = fo[1].zoomout_kmax = 0;
  fo[1].descr_k = o->seg_descr_k;
  return o->probes != SS_PROBES_STD && ssi_fmap_descr_k(&fo[1]) != ssi_fmap_descr_k(&fo[0]) ? 2 : 1;
}

/* the probe cache entries of a match with options o on prep p (*n 0: none applies) */
static ss_status probe_caches(const ss_shape_prep *p, const ss_match_options *o, ss_fmap_probe_cache **out, int *n,
                              ss_error *err) {
  *out = NULL, *n = 0;
  if (o->ndescr > 0 || o->fmap.no_wks) return SS_OK;
  ss_fmap_match_options fo[2];
  const int ns = ssi_match_start_options(o, fo);
  int kt = 0;
  for (int c = 0; c < ns; c++) kt = ssi_fmap_descr_k(&fo[c]) > kt ? ssi_fmap_descr_k(&fo[c]) : kt;
  if (kt > p->kev) return SS_OK; /* the match reports the missing eigenpairs */
  ss_fmap_probe_cache *c = calloc((size_t)ns, sizeof *c);
  if (!c) return ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
  ss_fmap_shape fs = {p->mesh, p->M, p->evals, p->evecs, p->kev, NULL, 0, NULL, 0};
  ss_status st = SS_OK;
  for (int i = 0; i < ns && !st; i++) st = ss_fmap_probe_cache_compute(&fs, &fo[i], i == 0, kt, &c[i], err);
  if (st) {
    for (int i = 0; i < ns; i++) ss_fmap_probe_cache_free(&c[i]);
    free(c);
    return st;
  }
  *out = c, *n = ns;
  return SS_OK;
}

/* do p's cache entries serve every base probe set of a match with options o? */
static int caches_cover(const ss_shape_prep *p, const ss_match_options *o) {
  ss_fmap_match_options fo[2];
  const int ns = ssi_match_start_options(o, fo);
  ss_fmap_shape fs = {p->mesh, p->M, p->evals, p->evecs, p->kev, NULL, 0, p->probe_cache, p->nprobe_cache};
  for (int c = 0; c < ns; c++)
    if (!ssi_fmap_cache_covers(&fs, &fo[c], o->fmap.w_dcomm > 0)) return 0;
  return 1;
}

/* One shape's probe cache entries for ssi_match_probe_caches_both (nothing when the shape carries them). */
typedef struct cache_task {
  const ss_shape_prep *p;
  const ss_match_options *o;
  ss_fmap_probe_cache **c;
  int *n, need;
} cache_task;
static ss_status cache_task_run(void *arg, ss_error *err) {
  cache_task *t = arg;
  return t->need ? probe_caches(t->p, t->o, t->c, t->n, err) : SS_OK;
}

/* The probe cache entries of both shapes that the shapes do not carry (NULL, 0 where they do), side
 * by side when both need them (ssi_run_both); X's error first. */
ss_status ssi_match_probe_caches_both(const ss_shape_prep *X, const ss_shape_prep *Y, const ss_match_options *o,
                                      ss_fmap_probe_cache **cx, int *nx, ss_fmap_probe_cache **cy, int *ny,
                                      ss_error *err) {
  *cx = *cy = NULL, *nx = *ny = 0;
  cache_task tx = {X, o, cx, nx, !caches_cover(X, o)}, ty = {Y, o, cy, ny, !caches_cover(Y, o)};
  return ssi_run_both(cache_task_run, &tx, cache_task_run, &ty, tx.need && ty.need, err);
}

ss_status ss_shape_prep_probe_cache(ss_shape_prep *p, const ss_match_options *opts, ss_error *err) {
  if (!p || !p->mesh || !p->evecs) return ss_fail(err, SS_ERR_INVALID, "probe cache: shape not prepared");
  ss_match_options d;
  if (!opts) ss_match_default_options(&d), opts = &d;
  ss_fmap_probe_cache *c;
  int n;
  ss_status st = probe_caches(p, opts, &c, &n, err);
  if (st) return st;
  for (int i = 0; i < p->nprobe_cache && p->probe_cache; i++) ss_fmap_probe_cache_free(&p->probe_cache[i]);
  free(p->probe_cache);
  p->probe_cache = c, p->nprobe_cache = n;
  return SS_OK;
}
