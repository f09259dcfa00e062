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

/* One Table 1 run's state: the options and locks, then what table1_run's stages build in turn */
typedef struct t1run {
  const ss_table1_options *o;
  run_locks *locks;
  const ss_manifest *man; /* NULL: FAUST in o->data_dir */
  int nsh;                /* shapes */
  ev_context ctx;
  unit *U;                 /* the units; after t1_resume the first nwork are those with rows to do */
  int nu, u0, u1, nwork;   /* units, this shard's slice u0..u1-1, those to do */
  int *px, *py, *lmb;      /* a policy's pairs; BEST landmarks */
  done_set done;           /* rows already in the output */
  ss_eval_row *old;
  int nold, have_header;
  long total_rows;         /* rows to do */
  ev_manifest_data md;
  ss_mesh m0;              /* FAUST: tr_reg_000, whose symmetry map (sym) serves every shape */
  int *sym, nv;            /* nv: vertices of the largest shape */
  int *need, *list, nneed; /* the shapes the units need */
  ev_shape *shapes;
  int **symv, **gtmaps, *nvs; /* per shape: symmetry map; per unit: ground-truth map (NULL: identity) */
  int nthreads;
  double t_start;
  int failed; /* a worker's first error (perr), under locks->err */
  ss_error perr;
} t1run;

/* The match options of the paper's methods (and of the refined rows) at size o->k, and the eigenpairs
 * prepared */
static void t1_context(t1run *R) {
  const ss_table1_options *o = R->o;
  ev_context *ctx = &R->ctx;
  ss_match_paper_options(&ctx->mopt); /* Table 1: the paper's STD / ASA / DIFF */
  ctx->mopt.fmap.k = o->k;
  ctx->kev = o->k;
  if (o->confident_pairing) ss_pairing_default_options(&ctx->mopt.pairing); /* the paper methods' rows: safeguarded */
  if (o->methods_mask >> SS_METHOD_REFINED & 1) { /* and the library's default output, at the same k */
    ss_match_default_options(&ctx->ropt);
    ctx->ropt.autopair.hyp_landmarks = 0; /* Table 1's refined rows: the landmarks' own map, as defined */
    ctx->ropt.fmap.k = o->k;
    if (ctx->ropt.fmap.zoomout_kmax < o->k) ctx->ropt.fmap.zoomout_kmax = o->k;
    if (ctx->ropt.fmap.descr_k < o->k) ctx->ropt.fmap.descr_k = 0;
    const int zk = ctx->ropt.fmap.zoomout_kmax, dk = ctx->ropt.fmap.descr_k;
    ctx->kref = zk > dk ? zk : dk;
    if (ctx->kref < o->k) ctx->kref = o->k;
  }
  /* the landmark-free rows' pairing uses descriptors from 100 eigenpairs */
  if ((o->lm_mask >> SS_LM_NONE & 1) && ctx->kev < ctx->mopt.autopair.descr_k) ctx->kev = ctx->mopt.autopair.descr_k;
}

/* 1. landmarks, pairs, the unit list (sorted by target) and this shard's slice */
static ss_status t1_units(t1run *R, ss_error *err) {
  const ss_table1_options *o = R->o;
  const ss_manifest *man = R->man;
  const int npairs_all = man ? man->npairs : o->npairs;
  R->px = malloc(sizeof(int) * (size_t)npairs_all);
  R->py = malloc(sizeof(int) * (size_t)npairs_all);
  R->U = malloc(sizeof(unit) * (size_t)npairs_all * 12);
  if (!R->px || !R->py || !R->U) return ss_fail(err, SS_ERR_NOMEM, "table1: out of memory");
  ss_status st;
  if (man) { /* a manifest's pairs, policy "random" */
    if (o->error_samples > 0)
      for (int g = 0; g < man->ngroups; g++)
        if (man->groups[g].gt_maps)
          return ss_fail(err, SS_ERR_INVALID,
                         "table1: --error-samples needs identity ground truth (group '%s' has maps)",
                         man->groups[g].name);
    for (int i = 0; i < man->npairs; i++)
      for (int l = 0; l < 4; l++)
        if (o->lm_mask >> l & 1) R->U[R->nu++] = (unit){0, man->px[i], man->py[i], l, i};
  } else {
    char path[4096];
    int nlmb = 0;
    snprintf(path, sizeof path, "%s/faust/landmarks_best.txt", o->data_dir);
    if ((st = ss_read_ints(path, &R->lmb, &nlmb, err))) return st;
    if (nlmb != EV_NL) return ss_fail(err, SS_ERR_PARSE, "%s: %d landmarks, %d expected", path, nlmb, EV_NL);
    memcpy(R->ctx.best, R->lmb, sizeof R->ctx.best);
    for (int p = 0; p < 3; p++) {
      if (!(o->policies_mask >> p & 1)) continue;
      if ((st = ss_eval_pairs((ss_pair_policy)p, NSUBJ, NPOSE, o->npairs, o->seed, R->px, R->py, err))) return st;
      for (int i = 0; i < o->npairs; i++)
        for (int l = 0; l < 4; l++)
          if (o->lm_mask >> l & 1) R->U[R->nu++] = (unit){p, R->px[i], R->py[i], l, i};
    }
  }
  qsort(R->U, (size_t)R->nu, sizeof *R->U, unit_cmp);
  R->u0 = (int)((long)R->nu * o->shard_i / o->shard_n), R->u1 = (int)((long)R->nu * (o->shard_i + 1) / o->shard_n);
  return SS_OK;
}

/* 2. resume: the rows already in the output are skipped; the slice's units with rows to do first in U */
static ss_status t1_resume(t1run *R, ss_error *err) {
  const ss_table1_options *o = R->o;
  const int nsh = R->nsh;
  R->have_header = ssi_csv_repair_tail(o->out_csv);
  if (R->have_header) {
    ss_status st = ss_eval_csv_read(o->out_csv, &R->old, &R->nold, err);
    if (st) return st;
    R->done.k = malloc(sizeof(uint64_t) * (size_t)(R->nold > 0 ? R->nold : 1));
    if (!R->done.k) return ss_fail(err, SS_ERR_NOMEM, "table1: out of memory");
    for (int i = 0; i < R->nold; i++) {
      const ss_eval_row *w = &R->old[i];
      if (w->x >= 0 && w->x < nsh && w->y >= 0 && w->y < nsh)
        R->done.k[R->done.n++] = row_key(w->policy, w->landmarks, w->method, w->x, w->y, nsh);
    }
    qsort(R->done.k, (size_t)R->done.n, sizeof *R->done.k, u64_cmp);
  }
  for (int u = R->u0; u < R->u1; u++) {
    int todo = 0;
    for (int mth = 0; mth < NM; mth++)
      if ((o->methods_mask >> mth & 1) && !is_done(&R->done, R->U[u].policy, R->U[u].lmset, mth, R->U[u].x, R->U[u].y))
        todo++;
    if (todo) R->U[R->nwork++] = R->U[u], R->total_rows += todo;
  }
  say(o, "table1: shard %d/%d: %d units, %d to do (%ld rows), %d rows already in %s", o->shard_i + 1, o->shard_n,
      R->u1 - R->u0, R->nwork, R->total_rows, R->nold, o->out_csv);
  return SS_OK;
}

/* 3. shared inputs: GT landmarks and the symmetry map (error samples are drawn per target later) */
static ss_status t1_shared_inputs(t1run *R, ss_error *err) {
  const ss_table1_options *o = R->o;
  const ss_manifest *man = R->man;
  ev_context *ctx = &R->ctx;
  ss_status st;
  if (man) {
    /* the manifest's landmark files, GT landmarks (FPS on each group's reference) and symmetry maps */
    if ((st = ev_manifest_data_load(man, ctx, o->lm_mask, &R->md, err))) return st;
    for (int g = 0; g < man->ngroups; g++)
      if (o->lm_mask >> SS_LM_GT & 1) {
        const int *gl = R->md.gt[man->groups[g].reference];
        say(o, "table1: group %s: GT landmarks from %s: %d %d %d %d %d", man->groups[g].name,
            man->meshes[man->groups[g].reference].name, gl[0], gl[1], gl[2], gl[3], gl[4]);
      }
    return SS_OK;
  }
  /* without GT rows the GT landmarks are never used (they stay 0, which the cache key records) */
  int gt_shape = -1;
  if ((o->lm_mask >> SS_LM_GT & 1) && (st = ev_gt_landmarks(o->data_dir, o->seed, ctx, ctx->gt, &gt_shape, err)))
    return st;
  if (gt_shape >= 0)
    say(o, "table1: GT landmarks from tr_reg_%03d: %d %d %d %d %d", gt_shape, ctx->gt[0], ctx->gt[1], ctx->gt[2],
        ctx->gt[3], ctx->gt[4]);
  char path[4096];
  snprintf(path, sizeof path, "%s/faust/tr_reg_000.off", o->data_dir);
  if ((st = ss_read_mesh(path, &R->m0, err))) return st;
  R->nv = R->m0.nv;
  if (!(R->sym = malloc(sizeof(int) * (size_t)R->nv))) return ss_fail(err, SS_ERR_NOMEM, "table1: out of memory");
  /* BEST order: head, left hand, left foot, right foot, right hand */
  int mir[EV_NL] = {ctx->best[0], ctx->best[4], ctx->best[3], ctx->best[2], ctx->best[1]};
  ss_symmetry_stats ss;
  if ((st = ss_symmetry_map(&R->m0, EV_NL, ctx->best, mir, R->sym, &ss, err))) return st;
  say(o, "table1: symmetry map of tr_reg_000: involution on %.1f%% of vertices, %d refined", 100 * ss.involution,
      ss.refined);
  return SS_OK;
}

/* Manifest runs: the vertex counts (identity ground truth needs equal ones), the symmetry maps and the
 * ground-truth maps checked against them; FAUST: one symmetry map for all */
static ss_status t1_symmetry_and_truth(t1run *R, ss_error *err) {
  const ss_manifest *man = R->man;
  if (!man) {
    for (int s = 0; s < R->nsh; s++) R->symv[s] = R->sym;
    return SS_OK;
  }
  if (!(R->nvs = calloc((size_t)R->nsh, sizeof(int)))) return ss_fail(err, SS_ERR_NOMEM, "table1: out of memory");
  int *nvs = R->nvs;
  for (int s = 0; s < R->nsh; s++)
    if (R->need[s]) nvs[s] = R->shapes[s].mesh.nv, R->nv = nvs[s] > R->nv ? nvs[s] : R->nv;
  ss_status st;
  if ((st = ev_manifest_symmetry(man, nvs, &R->md, err))) return st;
  for (int s = 0; s < R->nsh; s++) R->symv[s] = R->md.sym[s];
  for (int u = 0; u < R->nwork; u++) {
    const int x = R->U[u].x, y = R->U[u].y;
    if (man->groups[man->meshes[x].group].gt_maps) {
      if ((st = ev_manifest_gt_map(man, x, y, nvs[x], nvs[y], &R->gtmaps[u], err))) return st;
    } else if (nvs[x] != nvs[y])
      return ss_fail(err, SS_ERR_INVALID,
                     "table1: group '%s' has identity ground truth but '%s' has %d vertices and '%s' %d "
                     "(use 'gt maps')",
                     man->groups[man->meshes[x].group].name, man->meshes[x].name, nvs[x], man->meshes[y].name, nvs[y]);
  }
  return SS_OK;
}

/* 4. every shape the units need prepared once, in parallel; then the symmetry and ground-truth maps */
static ss_status t1_prepare_shapes(t1run *R, ss_error *err) {
  const ss_table1_options *o = R->o;
  const ss_manifest *man = R->man;
  const int nsh = R->nsh;
  R->need = calloc((size_t)nsh, sizeof(int));
  R->list = malloc(sizeof(int) * (size_t)nsh);
  R->shapes = calloc((size_t)nsh, sizeof(ev_shape));
  R->symv = calloc((size_t)nsh, sizeof(int *));
  R->gtmaps = calloc((size_t)R->nwork, sizeof(int *));
  if (!R->need || !R->list || !R->shapes || !R->symv || !R->gtmaps)
    return ss_fail(err, SS_ERR_NOMEM, "table1: out of memory");
  for (int u = 0; u < R->nwork; u++) R->need[R->U[u].x] = R->need[R->U[u].y] = 1;
  for (int s = 0; s < nsh; s++)
    if (R->need[s]) R->list[R->nneed++] = s;
  if (o->cache_dir) mkdir(o->cache_dir, 0755);
  /* parallelism is over shapes and pairs (the caller should run BLAS single-threaded: OpenBLAS's own
   * pthreads would oversubscribe the cores) */
  int prepared = 0;
#pragma omp parallel for schedule(dynamic, 1) num_threads(R->nthreads)
  for (int i = 0; i < R->nneed; i++) {
    if (R->failed) continue;
    ss_error e;
    char note[1024];
    const int id = R->list[i];
    ev_shape *sh = &R->shapes[id];
    ss_status ws = man ? ev_shape_load_file(man->meshes[id].path, man->meshes[id].name, o->cache_dir, id,
                                            R->md.best[id], R->md.gt[id], &R->ctx, sh, note, sizeof note, &e)
                       : ev_shape_load(o->data_dir, o->cache_dir, id, &R->ctx, sh, note, sizeof note, &e);
    if (note[0]) {
      omp_set_lock(&R->locks->progress);
      say(o, "%s", note);
      omp_unset_lock(&R->locks->progress);
    }
    if (!ws && (o->methods_mask & 7)) ws = ev_shape_probes(sh, &R->ctx, o->lm_mask, &e);
    if (!ws && (o->lm_mask >> SS_LM_NONE & 1)) ws = ev_shape_signature(sh, &R->ctx, &e);
    if (ws) {
      omp_set_lock(&R->locks->err);
      if (!R->failed) R->failed = ws, R->perr = e;
      omp_unset_lock(&R->locks->err);
      continue;
    }
    omp_set_lock(&R->locks->progress);
    prepared++;
    report(o, R->t_start, 0, R->total_rows, prepared, R->nneed);
    omp_unset_lock(&R->locks->progress);
  }
  if (R->failed) return ss_fail(err, (ss_status)R->failed, "table1: preparing shapes: %s", R->perr.msg);
  say(o, "table1: %d shapes prepared in %.1f s", R->nneed, ss_time() - R->t_start);
  return t1_symmetry_and_truth(R, err);
}

/* One worker's buffers for the groups it scores: up to maxrows maps of nv vertices and their rows,
 * and the error samples' fields (S samples and their mirrors) */
typedef struct {
  int S, ns, maxrows;
  int *mapbuf, *scratch, *samples, *sympos, *runit;
  double *fields, *sum, *sum_sym;
  ss_eval_row *rows;
  const int **rmap;
} t1bufs;

static int t1bufs_alloc(t1bufs *b, int S, int maxrows, int nv) {
  memset(b, 0, sizeof *b);
  b->S = S, b->maxrows = maxrows;
  b->mapbuf = malloc(sizeof(int) * (size_t)maxrows * nv), b->scratch = malloc(sizeof(int) * (size_t)nv);
  b->samples = malloc(sizeof(int) * (2 * (size_t)S + 1)), b->sympos = malloc(sizeof(int) * (2 * (size_t)S + 1));
  b->fields = malloc(sizeof(double) * (size_t)nv * (2 * (size_t)S + 1));
  b->rows = malloc(sizeof(ss_eval_row) * (size_t)maxrows);
  b->rmap = malloc(sizeof(int *) * (size_t)maxrows);
  b->runit = malloc(sizeof(int) * (size_t)maxrows);
  b->sum = malloc(sizeof(double) * (size_t)maxrows), b->sum_sym = malloc(sizeof(double) * (size_t)maxrows);
  return b->mapbuf && b->scratch && b->samples && b->sympos && b->fields && b->rows && b->rmap && b->runit && b->sum &&
         b->sum_sym;
}

static void t1bufs_free(t1bufs *b) {
  free(b->mapbuf), free(b->scratch), free(b->samples), free(b->sympos), free(b->fields), free(b->rows), free(b->rmap);
  free(b->runit), free(b->sum), free(b->sum_sym);
}

/* a. the maps of units u0..u1-1 (one target): each unit's methods share pairing, probes and normal
 * equations; their rows in b (errors not yet known). Returns the rows made (*nr). */
static ss_status t1_group_maps(t1run *R, int u0, int u1, t1bufs *b, int *nr_out, ss_error *e) {
  const ss_table1_options *o = R->o;
  const int nv = R->nv;
  int nr = 0;
  ss_status s2 = SS_OK;
  for (int u = u0; u < u1 && !s2; u++) {
    const unit *w = &R->U[u];
    const ev_shape *X = &R->shapes[w->x], *Y = &R->shapes[w->y];
    const int *symy = R->symv[Y->id];
    int mask = 0, paired[NM] = {0};
    for (int mth = 0; mth < NM; mth++)
      if ((o->methods_mask >> mth & 1) && !is_done(&R->done, w->policy, w->lmset, mth, w->x, w->y)) mask |= 1 << mth;
    if (!mask) continue;
    int *maps[NM];
    for (int mth = 0; mth < NM; mth++) maps[mth] = b->mapbuf + (size_t)nv * (nr + mth);
    double cpu[NM], t0 = ss_time();
    ss_segment_pairs pr = {0};
    const int want_pr = w->lmset == SS_LM_NONE && (mask & 7);
    if ((s2 = ev_match_methods_pairs(&R->ctx, X, Y, w->lmset, mask, maps, cpu, paired, want_pr ? &pr : NULL, e))) break;
    int pairing = -1;
    if (want_pr) { /* against the ground truth and its mirror */
      int right = 0, mright = 0;
      for (int q = 0; q < pr.n; q++) {
        int cx = X->prep.seg.centers[pr.sx[q]];
        if (R->gtmaps[u]) cx = R->gtmaps[u][cx];
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
      int *dst = b->mapbuf + (size_t)nv * (nr + slot);
      if (maps[mth] != dst) memcpy(dst, maps[mth], sizeof(int) * (size_t)nv);
      ss_eval_row *r = &b->rows[nr + slot];
      memset(r, 0, sizeof *r);
      r->paired = paired[mth], r->seconds = wall, r->cpu_seconds = cpu[mth], r->pairing = pairing;
      r->policy = w->policy, r->landmarks = w->lmset, r->method = mth, r->x = w->x, r->y = w->y;
      r->segments_x = X->prep.seg.m, r->segments_y = Y->prep.seg.m;
      b->rmap[nr + slot] = dst;
      b->runit[nr + slot] = u;
      slot++;
    }
    nr += slot;
  }
  *nr_out = nr;
  return s2;
}

/* b. the nr maps' error sums on target Y: exact over every vertex, each distinct (image, vertex) pair
 * of the target's maps queried once; or over the target's seeded sample (b->ns fields) */
static ss_status t1_group_errors(t1run *R, const ss_geodesic_mesh *gm, int nvy, const int *symy, int nr, t1bufs *b,
                                 ss_error *e) {
  if (b->ns > 0) {
    for (int i = 0; i < nr; i++) {
      double se = 0, ss2 = 0;
      for (int j = 0; j < b->ns; j++) {
        const int img = b->rmap[i][b->samples[j]];
        double a = b->fields[img + (size_t)nvy * j], c = b->fields[img + (size_t)nvy * b->sympos[j]];
        se += a;
        ss2 += a < c ? a : c;
      }
      b->sum[i] = se, b->sum_sym[i] = ss2;
      b->rows[i].samples = b->ns;
    }
    return SS_OK;
  }
  /* maps with the same ground truth together (identity: all of this target's) */
  ss_status s2 = SS_OK;
  for (int i0 = 0, i1; i0 < nr && !s2; i0 = i1) {
    const int *gt = R->gtmaps[b->runit[i0]];
    for (i1 = i0 + 1; i1 < nr && gt && b->runit[i1] == b->runit[i0];) i1++;
    if (!gt) i1 = nr;
    const int nvx = R->shapes[b->rows[i0].x].mesh.nv;
    s2 = ev_batch_errors(gm, nvx, symy, gt, i1 - i0, b->rmap + i0, b->sum + i0, b->sum_sym + i0, e);
    for (int i = i0; i < i1; i++) b->rows[i].samples = nvx;
  }
  return s2;
}

/* Group g (units gstart[g]..gstart[g+1]-1, one target): maps, errors, rows written as they are known */
static ss_status t1_group(t1run *R, const int *gstart, int g, t1bufs *b, FILE *out, long *rows_done, double t_rows,
                          ss_error *e) {
  const ss_table1_options *o = R->o;
  const ev_shape *Y = &R->shapes[R->U[gstart[g]].y];
  ss_geodesic_mesh *gm = NULL;
  ss_status s2 = ss_geodesic_mesh_build(&Y->mesh, &gm, e);
  const int nvy = Y->mesh.nv, *symy = R->symv[Y->id];
  if (b->S > 0)
    b->ns = error_samples(o->seed, Y->id, b->S < nvy ? b->S : nvy, nvy, symy, b->scratch, b->samples, b->sympos);
  if (!s2 && b->ns > 0) s2 = ss_geodesic_fields(gm, b->samples, b->ns, 0, b->fields, e);
  const double scale = 1.0 / sqrt(ss_mesh_area(&Y->mesh));
  int nr = 0;
  if (!s2) s2 = t1_group_maps(R, gstart[g], gstart[g + 1], b, &nr, e);
  if (!s2 && nr > 0) s2 = t1_group_errors(R, gm, nvy, symy, nr, b, e);
  for (int i = 0; i < nr && !s2; i++) {
    ss_eval_row *r = &b->rows[i];
    r->error = b->sum[i] / r->samples * scale;
    r->error_sym = b->sum_sym[i] / r->samples * scale;
    char line[512];
    ss_eval_csv_format_row(r, line, sizeof line);
    omp_set_lock(&R->locks->progress);
    fprintf(out, "%s\n", line);
    fflush(out);
    (*rows_done)++;
    report(o, t_rows, *rows_done, R->total_rows, 1, 1);
    omp_unset_lock(&R->locks->progress);
  }
  ss_geodesic_mesh_free(gm);
  return s2;
}

/* 5. the units, in parallel, grouped by target shape; rows appended to the output. *rows_done: written */
static ss_status t1_score_units(t1run *R, FILE *out, long *rows_done) {
  const ss_table1_options *o = R->o;
  const int nwork = R->nwork;
  int ngroups = 0, *gstart = malloc(sizeof(int) * ((size_t)nwork + 1));
  if (!gstart) {
    R->failed = SS_ERR_NOMEM, snprintf(R->perr.msg, sizeof R->perr.msg, "out of memory");
    return R->failed;
  }
  for (int u = 0; u < nwork; u++)
    if (!u || R->U[u].y != R->U[u - 1].y) gstart[ngroups++] = u;
  gstart[ngroups] = nwork;
  int maxgroup = 0; /* units in the largest group: its maps are held until their errors are known */
  for (int g = 0; g < ngroups; g++)
    maxgroup = gstart[g + 1] - gstart[g] > maxgroup ? gstart[g + 1] - gstart[g] : maxgroup;
  const double t_rows = ss_time();
#pragma omp parallel num_threads(R->nthreads)
  {
    t1bufs b;
    const int S = o->error_samples < R->nv ? o->error_samples : R->nv;
    if (!t1bufs_alloc(&b, S, NM * (maxgroup > 0 ? maxgroup : 1), R->nv)) {
      omp_set_lock(&R->locks->err);
      if (!R->failed) R->failed = SS_ERR_NOMEM, snprintf(R->perr.msg, sizeof R->perr.msg, "out of memory");
      omp_unset_lock(&R->locks->err);
    }
#pragma omp for schedule(dynamic, 1)
    for (int g = 0; g < ngroups; g++) {
      if (R->failed) continue;
      ss_error e;
      ss_status s2 = t1_group(R, gstart, g, &b, out, rows_done, t_rows, &e);
      if (s2) {
        omp_set_lock(&R->locks->err);
        if (!R->failed) R->failed = s2, R->perr = e;
        omp_unset_lock(&R->locks->err);
      }
    }
    t1bufs_free(&b);
  }
  free(gstart);
  say(o, "table1: %ld rows in %.1f s (%.1f s total)", *rows_done, ss_time() - t_rows, ss_time() - R->t_start);
  return R->failed;
}

static void t1run_free(t1run *R) {
  if (R->shapes)
    for (int s = 0; s < R->nsh; s++) ev_shape_free(&R->shapes[s]);
  if (R->gtmaps)
    for (int u = 0; u < R->nwork; u++) free(R->gtmaps[u]);
  free(R->shapes), free(R->need), free(R->list), free(R->nvs), free(R->U), free(R->px), free(R->py), free(R->lmb);
  free(R->sym), free(R->symv), free(R->gtmaps), free(R->done.k), free(R->old);
  ev_manifest_data_free(&R->md);
  ss_mesh_free(&R->m0);
}

static ss_status table1_run(const ss_table1_options *o, int *new_rows, run_locks *locks, ss_error *err) {
  if (new_rows) *new_rows = 0;
  if (!o || (!o->data_dir && !o->manifest) || !o->out_csv)
    return ss_fail(err, SS_ERR_INVALID, "table1: data folder (or manifest) and output needed");
  const ss_manifest *man = o->manifest;
  if (man && (man->nmeshes < 1 || man->npairs < 1)) return ss_fail(err, SS_ERR_INVALID, "table1: empty manifest");
  if (o->npairs < 1 || o->shard_n < 1 || o->shard_i < 0 || o->shard_i >= o->shard_n || o->k < 3 ||
      o->error_samples < 0 || o->error_samples > 3000)
    return ss_fail(err, SS_ERR_INVALID, "table1: bad options (pairs %d, shard %d/%d, k %d, samples %d)", o->npairs,
                   o->shard_i + 1, o->shard_n, o->k, o->error_samples);
  t1run R;
  memset(&R, 0, sizeof R);
  R.o = o, R.locks = locks, R.man = man, R.nsh = man ? man->nmeshes : NSHAPES;
  R.done.nsh = R.nsh;
  t1_context(&R);
  FILE *out = NULL;
  ss_status st;
  if ((st = t1_units(&R, err)) || (st = t1_resume(&R, err))) goto done;
  if (R.nwork == 0) goto done;
  R.t_start = ss_time();
  R.nthreads = ssi_eval_threads(o->jobs);
  if ((st = t1_shared_inputs(&R, err)) || (st = t1_prepare_shapes(&R, err))) goto done;
  if (!(out = fopen(o->out_csv, R.have_header ? "ab" : "wb"))) {
    st = ss_fail(err, SS_ERR_IO, "%s: cannot open for writing: %s", o->out_csv, strerror(errno));
    goto done;
  }
  if (!R.have_header) fprintf(out, "%s\n", ss_eval_csv_header());
  fflush(out);
  long rows_done = 0;
  if (t1_score_units(&R, out, &rows_done)) st = ss_fail(err, (ss_status)R.failed, "table1: %s", R.perr.msg);
  if (new_rows) *new_rows = (int)rows_done;
done:
  if (out && fclose(out) && !st) st = ss_fail(err, SS_ERR_IO, "%s: write error: %s", o->out_csv, strerror(errno));
  t1run_free(&R);
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
