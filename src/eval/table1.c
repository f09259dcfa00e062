/* The Table 1 runner (paper §6): pairing policies × landmark sets × methods on FAUST.
 *
 * Work unit = (policy, pair, landmark set): its three method rows share the pairing. The full unit
 * list is fixed by the seed and sorted by target shape, so a shard is a contiguous slice (shards
 * rarely share a target) and stays the same across resumed runs. Each needed shape is prepared once
 * (in parallel); then units run in parallel grouped by target shape, whose exact error fields are
 * computed once per group. Rows are appended (and flushed) as they finish. */
#include "csv_file.h"
#include "eval_internal.h"
#include "specseg/io.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#define NSUBJ 10
#define NPOSE 10
#define NSHAPES (NSUBJ * NPOSE)

void ss_table1_default_options(ss_table1_options *o) {
  memset(o, 0, sizeof *o);
  o->npairs = 100;
  o->seed = 1;
  o->shard_i = 0;
  o->shard_n = 1;
  o->error_samples = 0; /* exact mean over every vertex, as the paper defines the error */
  o->k = 50;
  o->policies_mask = o->lm_mask = o->methods_mask = 7;
}

typedef struct unit {
  int policy, x, y, lmset, pair;
} unit;

static int unit_cmp(const void *pa, const void *pb) {
  const unit *a = pa, *b = pb;
  int ka[4] = {a->y, a->policy, a->pair, a->lmset}, kb[4] = {b->y, b->policy, b->pair, b->lmset};
  for (int i = 0; i < 4; i++)
    if (ka[i] != kb[i]) return ka[i] < kb[i] ? -1 : 1;
  return 0;
}

/* rows already in the CSV: sorted keys ((policy*4+lm)*NM+method)*nsh² + x*nsh + y, nsh shapes */
#define NM SS_EVAL_NMETHODS
static uint64_t row_key(int policy, int lm, int method, int x, int y, int nsh) {
  return ((uint64_t)((policy * 4 + lm) * NM + method) * (uint64_t)nsh + (uint64_t)x) * (uint64_t)nsh + (uint64_t)y;
}
static int u64_cmp(const void *a, const void *b) {
  uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return (x > y) - (x < y);
}
typedef struct done_set {
  uint64_t *k;
  int n, nsh;
} done_set;
static int is_done(const done_set *d, int policy, int lm, int method, int x, int y) {
  uint64_t key = row_key(policy, lm, method, x, y, d->nsh);
  return d->n > 0 && bsearch(&key, d->k, (size_t)d->n, sizeof key, u64_cmp) != NULL;
}


/* The caller's progress callback, if any (called inside a critical section: one call at a time). */
static void report(const ss_table1_options *o, double t0, long done, long total, int shapes_done, int shapes_total) {
  if (!o->progress) return;
  ss_table1_progress p = {shapes_done, shapes_total, done, total, ss_time() - t0};
  o->progress(o->user, &p);
}

/* The caller's log callback, if any: one line, printf-style. */
static void say(const ss_table1_options *o, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void say(const ss_table1_options *o, const char *fmt, ...) {
  if (!o->log) return;
  char line[1200];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(line, sizeof line, fmt, ap);
  va_end(ap);
  o->log(o->user, line);
}

static int int_cmp(const void *a, const void *b) { return *(const int *)a - *(const int *)b; }

/* The vertices the error of a map onto shape y averages over: S seeded-random vertices and their
 * mirrors, sorted, without repeats (≤ 2S). A different sample for every target shape, so the
 * sampling error is independent across targets and averages out over the pairs (one sample shared
 * by all pairs would bias every row the same way). sympos[i]: position of sym(samples[i]). perm:
 * nv scratch ints. Returns the count. */
static int error_samples(uint64_t seed, int y, int S, int nv, const int *sym, int *perm, int *samples, int *sympos) {
  ss_rng r;
  ss_rng_seed(&r, seed ^ 0xBB67AE8584CAA73Bull ^ (0x3C6EF372FE94F82Bull * (uint64_t)(y + 1)));
  if (S > nv) S = nv;
  int ns = 0;
  for (int i = 0; i < nv; i++) perm[i] = i;
  for (int i = 0; i < S; i++) {
    int j = i + ss_rng_below(&r, nv - i), t = perm[i];
    perm[i] = perm[j], perm[j] = t;
    samples[ns++] = perm[i];
    samples[ns++] = sym[perm[i]];
  }
  qsort(samples, (size_t)ns, sizeof(int), int_cmp);
  int k = 0;
  for (int i = 0; i < ns; i++)
    if (!k || samples[i] != samples[k - 1]) samples[k++] = samples[i];
  /* the set is closed under sym by construction */
  for (int i = 0; i < k; i++) {
    int *f = bsearch(&sym[samples[i]], samples, (size_t)k, sizeof(int), int_cmp);
    sympos[i] = f ? (int)(f - samples) : i;
  }
  return k;
}

/* The locks of one run (worker errors; output and progress), local to the call. */
typedef struct run_locks {
  omp_lock_t err, progress;
} run_locks;

static ss_status table1_run(const ss_table1_options *o, int *new_rows, run_locks *locks, ss_error *err) {
  if (new_rows) *new_rows = 0;
  if (!o || (!o->data_dir && !o->manifest) || !o->out_csv)
    return ss_fail(err, SS_ERR_INVALID, "table1: data folder (or manifest) and output needed");
  const ss_manifest *man = o->manifest;
  if (man && (man->nmeshes < 1 || man->npairs < 1)) return ss_fail(err, SS_ERR_INVALID, "table1: empty manifest");
  const int nsh = man ? man->nmeshes : NSHAPES;
  if (o->npairs < 1 || o->shard_n < 1 || o->shard_i < 0 || o->shard_i >= o->shard_n || o->k < 3 ||
      o->error_samples < 0 || o->error_samples > 3000)
    return ss_fail(err, SS_ERR_INVALID, "table1: bad options (pairs %d, shard %d/%d, k %d, samples %d)", o->npairs,
                   o->shard_i + 1, o->shard_n, o->k, o->error_samples);
  ss_status st = SS_OK;
  ev_context ctx;
  memset(&ctx, 0, sizeof ctx);
  ss_match_paper_options(&ctx.mopt); /* Table 1: the paper's STD / ASA / DIFF */
  ctx.mopt.fmap.k = o->k;
  ctx.kev = o->k;
  if (o->confident_pairing) ss_pairing_default_options(&ctx.mopt.pairing); /* the paper methods' rows: safeguarded */
  if (o->methods_mask >> SS_METHOD_REFINED & 1) { /* and the library's default output, at the same k */
    ss_match_default_options(&ctx.ropt);
    ctx.ropt.autopair.hyp_landmarks = 0; /* Table 1's refined rows: the landmarks' own map, as defined */
    ctx.ropt.fmap.k = o->k;
    if (ctx.ropt.fmap.zoomout_kmax < o->k) ctx.ropt.fmap.zoomout_kmax = o->k;
    if (ctx.ropt.fmap.descr_k < o->k) ctx.ropt.fmap.descr_k = 0;
    ctx.kref = ctx.ropt.fmap.zoomout_kmax > ctx.ropt.fmap.descr_k ? ctx.ropt.fmap.zoomout_kmax : ctx.ropt.fmap.descr_k;
    if (ctx.kref < o->k) ctx.kref = o->k;
  }
  /* the landmark-free rows' pairing uses descriptors from 100 eigenpairs */
  if ((o->lm_mask >> SS_LM_NONE & 1) && ctx.kev < ctx.mopt.autopair.descr_k) ctx.kev = ctx.mopt.autopair.descr_k;
  unit *U = NULL;
  int *px = NULL, *py = NULL, *lmb = NULL, *sym = NULL, *need = NULL, *list = NULL, *nvs = NULL;
  int **symv = NULL, **gtmaps = NULL;
  done_set done = {NULL, 0, nsh};
  ev_manifest_data md = {0};
  ev_shape *shapes = NULL;
  ss_eval_row *old = NULL;
  FILE *out = NULL;
  ss_mesh m0 = {0};
  int nlmb = 0, nold = 0, nwork = 0;
  char path[4096];

  /* 1. landmarks, pairs, the unit list and this shard's slice */
  const int npairs_all = man ? man->npairs : o->npairs;
  px = malloc(sizeof(int) * (size_t)npairs_all);
  py = malloc(sizeof(int) * (size_t)npairs_all);
  U = malloc(sizeof(unit) * (size_t)npairs_all * 12);
  if (!px || !py || !U) { st = ss_fail(err, SS_ERR_NOMEM, "table1: out of memory"); goto done; }
  int nu = 0;
  if (man) { /* a manifest's pairs, policy "random" */
    if (o->error_samples > 0)
      for (int g = 0; g < man->ngroups; g++)
        if (man->groups[g].gt_maps) {
          st = ss_fail(err, SS_ERR_INVALID, "table1: --error-samples needs identity ground truth (group '%s' has maps)",
                       man->groups[g].name);
          goto done;
        }
    for (int i = 0; i < man->npairs; i++)
      for (int l = 0; l < 4; l++)
        if (o->lm_mask >> l & 1) U[nu++] = (unit){0, man->px[i], man->py[i], l, i};
  } else {
    snprintf(path, sizeof path, "%s/faust/landmarks_best.txt", o->data_dir);
    if ((st = ss_read_ints(path, &lmb, &nlmb, err))) goto done;
    if (nlmb != EV_NL) { st = ss_fail(err, SS_ERR_PARSE, "%s: %d landmarks, %d expected", path, nlmb, EV_NL); goto done; }
    memcpy(ctx.best, lmb, sizeof ctx.best);
    for (int p = 0; p < 3; p++) {
      if (!(o->policies_mask >> p & 1)) continue;
      if ((st = ss_eval_pairs((ss_pair_policy)p, NSUBJ, NPOSE, o->npairs, o->seed, px, py, err))) goto done;
      for (int i = 0; i < o->npairs; i++)
        for (int l = 0; l < 4; l++)
          if (o->lm_mask >> l & 1) U[nu++] = (unit){p, px[i], py[i], l, i};
    }
  }
  qsort(U, (size_t)nu, sizeof *U, unit_cmp);
  int u0 = (int)((long)nu * o->shard_i / o->shard_n), u1 = (int)((long)nu * (o->shard_i + 1) / o->shard_n);

  /* 2. resume: rows already in the output are skipped */
  int have_header = ssi_csv_repair_tail(o->out_csv);
  if (have_header) {
    if ((st = ss_eval_csv_read(o->out_csv, &old, &nold, err))) goto done;
    done.k = malloc(sizeof(uint64_t) * (size_t)(nold > 0 ? nold : 1));
    if (!done.k) { st = ss_fail(err, SS_ERR_NOMEM, "table1: out of memory"); goto done; }
    for (int i = 0; i < nold; i++)
      if (old[i].x >= 0 && old[i].x < nsh && old[i].y >= 0 && old[i].y < nsh)
        done.k[done.n++] = row_key(old[i].policy, old[i].landmarks, old[i].method, old[i].x, old[i].y, nsh);
    qsort(done.k, (size_t)done.n, sizeof *done.k, u64_cmp);
  }
  long total_rows = 0;
  for (int u = u0; u < u1; u++) {
    int todo = 0;
    for (int mth = 0; mth < NM; mth++)
      if ((o->methods_mask >> mth & 1) && !is_done(&done, U[u].policy, U[u].lmset, mth, U[u].x, U[u].y)) todo++;
    if (todo) U[nwork++] = U[u], total_rows += todo;
  }
  say(o, "table1: shard %d/%d: %d units, %d to do (%ld rows), %d rows already in %s", o->shard_i + 1, o->shard_n,
      u1 - u0, nwork, total_rows, nold, o->out_csv);
  if (nwork == 0) goto done;

  /* 3. shared inputs: GT landmarks and the symmetry map (error samples are drawn per target below) */
  double t_start = ss_time();
  int gt_shape = -1;
  int nv = 0; /* vertices of the largest shape */
  if (man) {
    /* the manifest's landmark files, GT landmarks (FPS on each group's reference) and symmetry maps */
    if ((st = ev_manifest_data_load(man, &ctx, o->lm_mask, &md, err))) goto done;
    for (int g = 0; g < man->ngroups; g++)
      if (o->lm_mask >> SS_LM_GT & 1) {
        const int *gl = md.gt[man->groups[g].reference];
        say(o, "table1: group %s: GT landmarks from %s: %d %d %d %d %d", man->groups[g].name,
            man->meshes[man->groups[g].reference].name, gl[0], gl[1], gl[2], gl[3], gl[4]);
      }
  } else {
    /* without GT rows the GT landmarks are never used (they stay 0, which the cache key records) */
    if ((o->lm_mask >> SS_LM_GT & 1) && (st = ev_gt_landmarks(o->data_dir, o->seed, &ctx, ctx.gt, &gt_shape, err))) goto done;
    if (gt_shape >= 0)
      say(o, "table1: GT landmarks from tr_reg_%03d: %d %d %d %d %d", gt_shape, ctx.gt[0], ctx.gt[1], ctx.gt[2], ctx.gt[3],
          ctx.gt[4]);
    snprintf(path, sizeof path, "%s/faust/tr_reg_000.off", o->data_dir);
    if ((st = ss_read_mesh(path, &m0, err))) goto done;
    nv = m0.nv;
    sym = malloc(sizeof(int) * (size_t)nv);
    if (!sym) { st = ss_fail(err, SS_ERR_NOMEM, "table1: out of memory"); goto done; }
    {
      /* BEST order: head, left hand, left foot, right foot, right hand */
      int mir[EV_NL] = {ctx.best[0], ctx.best[4], ctx.best[3], ctx.best[2], ctx.best[1]};
      ss_symmetry_stats ss;
      if ((st = ss_symmetry_map(&m0, EV_NL, ctx.best, mir, sym, &ss, err))) goto done;
      say(o, "table1: symmetry map of tr_reg_000: involution on %.1f%% of vertices, %d refined", 100 * ss.involution,
          ss.refined);
    }
  }
  /* 4. prepare every shape this slice needs, once, in parallel */
  need = calloc((size_t)nsh, sizeof(int));
  list = malloc(sizeof(int) * (size_t)nsh);
  shapes = calloc((size_t)nsh, sizeof(ev_shape));
  symv = calloc((size_t)nsh, sizeof(int *));
  gtmaps = calloc((size_t)nwork, sizeof(int *));
  if (!need || !list || !shapes || !symv || !gtmaps) { st = ss_fail(err, SS_ERR_NOMEM, "table1: out of memory"); goto done; }
  for (int u = 0; u < nwork; u++) need[U[u].x] = need[U[u].y] = 1;
  int nneed = 0;
  for (int s = 0; s < nsh; s++)
    if (need[s]) list[nneed++] = s;
  if (o->cache_dir) mkdir(o->cache_dir, 0755);
  /* parallelism is over shapes and pairs (the caller should run BLAS single-threaded: OpenBLAS's own
   * pthreads would oversubscribe the cores) */
  int failed = 0, prepared = 0;
  ss_error perr = {{0}};
  int nthreads = ssi_eval_threads(o->jobs);
#pragma omp parallel for schedule(dynamic, 1) num_threads(nthreads)
  for (int i = 0; i < nneed; i++) {
    if (failed) continue;
    ss_error e;
    char note[1024];
    const int id = list[i];
    ss_status ws = man ? ev_shape_load_file(man->meshes[id].path, man->meshes[id].name, o->cache_dir, id, md.best[id],
                                            md.gt[id], &ctx, &shapes[id], note, sizeof note, &e)
                       : ev_shape_load(o->data_dir, o->cache_dir, id, &ctx, &shapes[id], note, sizeof note, &e);
    if (note[0]) {
      omp_set_lock(&locks->progress);
      say(o, "%s", note);
      omp_unset_lock(&locks->progress);
    }
    if (!ws && (o->methods_mask & 7)) ws = ev_shape_probes(&shapes[list[i]], &ctx, o->lm_mask, &e);
    if (!ws && (o->lm_mask >> SS_LM_NONE & 1)) ws = ev_shape_signature(&shapes[list[i]], &ctx, &e);
    if (ws) {
      omp_set_lock(&locks->err);
      if (!failed) failed = ws, perr = e;
      omp_unset_lock(&locks->err);
      continue;
    }
    omp_set_lock(&locks->progress);
    {
      prepared++;
      report(o, t_start, 0, total_rows, prepared, nneed);
    }
    omp_unset_lock(&locks->progress);
  }
  if (failed) {
    st = ss_fail(err, (ss_status)failed, "table1: preparing shapes: %s", perr.msg);
    goto done;
  }
  say(o, "table1: %d shapes prepared in %.1f s", nneed, ss_time() - t_start);
  if (man) {
    /* vertex counts: identity ground truth needs equal ones; symmetry maps and ground-truth maps
     * checked against them */
    nvs = calloc((size_t)nsh, sizeof(int));
    if (!nvs) { st = ss_fail(err, SS_ERR_NOMEM, "table1: out of memory"); goto done; }
    for (int s = 0; s < nsh; s++)
      if (need[s]) nvs[s] = shapes[s].mesh.nv, nv = nvs[s] > nv ? nvs[s] : nv;
    if ((st = ev_manifest_symmetry(man, nvs, &md, err))) goto done;
    for (int s = 0; s < nsh; s++) symv[s] = md.sym[s];
    for (int u = 0; u < nwork; u++) {
      const int x = U[u].x, y = U[u].y;
      if (man->groups[man->meshes[x].group].gt_maps) {
        if ((st = ev_manifest_gt_map(man, x, y, nvs[x], nvs[y], &gtmaps[u], err))) goto done;
      } else if (nvs[x] != nvs[y]) {
        st = ss_fail(err, SS_ERR_INVALID,
                     "table1: group '%s' has identity ground truth but '%s' has %d vertices and '%s' %d (use 'gt maps')",
                     man->groups[man->meshes[x].group].name, man->meshes[x].name, nvs[x], man->meshes[y].name, nvs[y]);
        goto done;
      }
    }
  } else
    for (int s = 0; s < nsh; s++) symv[s] = sym;

  /* 5. the units, in parallel, grouped by target shape */
  out = fopen(o->out_csv, have_header ? "ab" : "wb");
  if (!out) { st = ss_fail(err, SS_ERR_IO, "%s: cannot open for writing: %s", o->out_csv, strerror(errno)); goto done; }
  if (!have_header) fprintf(out, "%s\n", ss_eval_csv_header());
  fflush(out);
  int ngroups = 0, *gstart = malloc(sizeof(int) * ((size_t)nwork + 1));
  if (!gstart) { st = ss_fail(err, SS_ERR_NOMEM, "table1: out of memory"); goto done; }
  for (int u = 0; u < nwork; u++)
    if (!u || U[u].y != U[u - 1].y) gstart[ngroups++] = u;
  gstart[ngroups] = nwork;
  int maxgroup = 0; /* units in the largest group: its maps are held until their errors are known */
  for (int g = 0; g < ngroups; g++) maxgroup = gstart[g + 1] - gstart[g] > maxgroup ? gstart[g + 1] - gstart[g] : maxgroup;
  long rows_done = 0;
  double t_rows = ss_time();
#pragma omp parallel num_threads(nthreads)
  {
    int S = o->error_samples < nv ? o->error_samples : nv, ns = 0;
    int maxrows = NM * (maxgroup > 0 ? maxgroup : 1);
    int *mapbuf = malloc(sizeof(int) * (size_t)maxrows * nv), *scratch = malloc(sizeof(int) * (size_t)nv);
    int *samples = malloc(sizeof(int) * (2 * (size_t)S + 1)), *sympos = malloc(sizeof(int) * (2 * (size_t)S + 1));
    double *fields = malloc(sizeof(double) * (size_t)nv * (2 * (size_t)S + 1));
    ss_eval_row *rows = malloc(sizeof(ss_eval_row) * (size_t)maxrows);
    const int **rmap = malloc(sizeof(int *) * (size_t)maxrows);
    int *runit = malloc(sizeof(int) * (size_t)maxrows);
    double *sum = malloc(sizeof(double) * (size_t)maxrows), *sum_sym = malloc(sizeof(double) * (size_t)maxrows);
    if (!mapbuf || !scratch || !samples || !sympos || !fields || !rows || !rmap || !runit || !sum || !sum_sym) {
      omp_set_lock(&locks->err);
      if (!failed) failed = SS_ERR_NOMEM, snprintf(perr.msg, sizeof perr.msg, "out of memory");
      omp_unset_lock(&locks->err);
    }
#pragma omp for schedule(dynamic, 1)
    for (int g = 0; g < ngroups; g++) {
      if (failed) continue;
      ss_error e;
      const ev_shape *Y = &shapes[U[gstart[g]].y];
      ss_geodesic_mesh *gm = NULL;
      ss_status s2 = ss_geodesic_mesh_build(&Y->mesh, &gm, &e);
      const int nvy = Y->mesh.nv, *symy = symv[Y->id];
      if (S > 0) ns = error_samples(o->seed, Y->id, S < nvy ? S : nvy, nvy, symy, scratch, samples, sympos);
      if (!s2 && ns > 0) s2 = ss_geodesic_fields(gm, samples, ns, 0, fields, &e);
      const double scale = 1.0 / sqrt(ss_mesh_area(&Y->mesh));
      /* a. every map of this target: the units' methods share pairing, probes and normal equations */
      int nr = 0;
      for (int u = gstart[g]; u < gstart[g + 1] && !s2; u++) {
        const unit *w = &U[u];
        const ev_shape *X = &shapes[w->x];
        int mask = 0, paired[NM] = {0};
        for (int mth = 0; mth < NM; mth++)
          if ((o->methods_mask >> mth & 1) && !is_done(&done, w->policy, w->lmset, mth, w->x, w->y)) mask |= 1 << mth;
        if (!mask) continue;
        int *maps[NM];
        for (int mth = 0; mth < NM; mth++) maps[mth] = mapbuf + (size_t)nv * (nr + mth);
        double cpu[NM], t0 = ss_time();
        ss_segment_pairs pr = {0};
        const int want_pr = w->lmset == SS_LM_NONE && (mask & 7);
        if ((s2 = ev_match_methods_pairs(&ctx, X, Y, w->lmset, mask, maps, cpu, paired, want_pr ? &pr : NULL, &e))) break;
        int pairing = -1;
        if (want_pr) { /* against the ground truth and its mirror */
          int right = 0, mright = 0;
          for (int q = 0; q < pr.n; q++) {
            int cx = X->prep.seg.centers[pr.sx[q]];
            if (gtmaps[u]) cx = gtmaps[u][cx];
            right += Y->prep.seg.labels[cx] == pr.sy[q];
            mright += Y->prep.seg.labels[symy[cx]] == pr.sy[q];
          }
          pairing = pr.n > 0 && right == pr.n ? 2 : pr.n > 0 && mright == pr.n ? 1 : 0;
          ss_segment_pairs_free(&pr);
        }
        const double wall = (ss_time() - t0) / __builtin_popcount(mask);
        int slot = 0;
        for (int mth = 0; mth < NM; mth++) {
          if (!(mask >> mth & 1)) continue;
          if (maps[mth] != mapbuf + (size_t)nv * (nr + slot))
            memcpy(mapbuf + (size_t)nv * (nr + slot), maps[mth], sizeof(int) * (size_t)nv);
          ss_eval_row *r = &rows[nr + slot];
          memset(r, 0, sizeof *r);
          r->paired = paired[mth], r->seconds = wall, r->cpu_seconds = cpu[mth], r->pairing = pairing;
          r->policy = w->policy, r->landmarks = w->lmset, r->method = mth, r->x = w->x, r->y = w->y;
          r->segments_x = X->prep.seg.m, r->segments_y = Y->prep.seg.m;
          rmap[nr + slot] = mapbuf + (size_t)nv * (nr + slot);
          runit[nr + slot] = u;
          slot++;
        }
        nr += slot;
      }
      /* b. their errors: exact over every vertex, each distinct (image, vertex) pair of the target's
       * maps queried once; or over the target's seeded sample */
      if (!s2 && nr > 0) {
        if (ns > 0) {
          for (int i = 0; i < nr; i++) {
            double se = 0, ss2 = 0;
            for (int j = 0; j < ns; j++) {
              double a = fields[rmap[i][samples[j]] + (size_t)nvy * j], b = fields[rmap[i][samples[j]] + (size_t)nvy * sympos[j]];
              se += a;
              ss2 += a < b ? a : b;
            }
            sum[i] = se, sum_sym[i] = ss2;
            rows[i].samples = ns;
          }
        } else {
          /* maps with the same ground truth together (identity: all of this target's) */
          for (int i0 = 0, i1; i0 < nr && !s2; i0 = i1) {
            const int *gt = gtmaps[runit[i0]];
            for (i1 = i0 + 1; i1 < nr && gt && runit[i1] == runit[i0];) i1++;
            if (!gt) i1 = nr;
            const int nvx = shapes[rows[i0].x].mesh.nv;
            s2 = ev_batch_errors(gm, nvx, symy, gt, i1 - i0, rmap + i0, sum + i0, sum_sym + i0, &e);
            for (int i = i0; i < i1; i++) rows[i].samples = nvx;
          }
        }
      }
      for (int i = 0; i < nr && !s2; i++) {
        rows[i].error = sum[i] / rows[i].samples * scale;
        rows[i].error_sym = sum_sym[i] / rows[i].samples * scale;
        char line[512];
        ss_eval_csv_format_row(&rows[i], line, sizeof line);
        omp_set_lock(&locks->progress);
        {
          fprintf(out, "%s\n", line);
          fflush(out);
          rows_done++;
          report(o, t_rows, rows_done, total_rows, 1, 1);
        }
        omp_unset_lock(&locks->progress);
      }
      ss_geodesic_mesh_free(gm);
      if (s2) {
        omp_set_lock(&locks->err);
        if (!failed) failed = s2, perr = e;
        omp_unset_lock(&locks->err);
      }
    }
    free(mapbuf), free(scratch), free(samples), free(sympos), free(fields), free(rows), free(rmap), free(runit), free(sum),
        free(sum_sym);
  }
  free(gstart);
  if (new_rows) *new_rows = (int)rows_done;
  say(o, "table1: %ld rows in %.1f s (%.1f s total)", rows_done, ss_time() - t_rows, ss_time() - t_start);
  if (failed) st = ss_fail(err, (ss_status)failed, "table1: %s", perr.msg);
done:
  if (out && fclose(out) && !st) st = ss_fail(err, SS_ERR_IO, "%s: write error: %s", o->out_csv, strerror(errno));
  if (shapes)
    for (int s = 0; s < nsh; s++) ev_shape_free(&shapes[s]);
  if (gtmaps)
    for (int u = 0; u < nwork; u++) free(gtmaps[u]);
  free(shapes), free(need), free(list), free(nvs), free(U), free(px), free(py), free(lmb), free(sym), free(symv), free(gtmaps);
  free(done.k), free(old);
  ev_manifest_data_free(&md);
  ss_mesh_free(&m0);
  return st;
}

ss_status ss_table1_run(const ss_table1_options *o, int *new_rows, ss_error *err) {
  run_locks locks;
  omp_init_lock(&locks.err);
  omp_init_lock(&locks.progress);
  ss_status st = table1_run(o, new_rows, &locks, err);
  omp_destroy_lock(&locks.err);
  omp_destroy_lock(&locks.progress);
  return st;
}
