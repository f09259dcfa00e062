/* The benchmark runner: a folder of meshes with ground-truth points, our own map per pair and any
 * number of external maps folders, every map scored by the same code (ss_benchmark_score).
 *
 * Phase 1 reads, in parallel, every shape the shard's pairs need (mesh, points, mirror points) and,
 * for our own maps, prepares it once (ss_prepared_shape_compute, through the cache folder): a file
 * that is missing or does not read is reported once and its pairs become skipped rows. Phase 2 runs
 * the pairs in parallel: per pair our match (ss_match_prepared_shapes, the map `specseg match X Y`
 * writes) and each external map, scored, one row per (method, pair) appended to OUT/pairs.csv and
 * flushed as it finishes; scored rows already there are not recomputed (resume). */
#include "benchmark_internal.h"
#include "csv_file.h"
#include "specseg/io.h"
#include "specseg/match.h"
#include "specseg/version.h"
#include "util/blob.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#define MAX_LM 64 /* --landmarks gt:N, N at most */

void ss_benchmark_default_options(ss_benchmark_options *o) {
  memset(o, 0, sizeof *o);
  o->seed = 1;
  o->match = 1;
  o->shard_i = 0, o->shard_n = 1;
}

void ss_benchmark_method_name(const ss_benchmark_options *o, char *name, size_t n) {
  if (o && o->landmarks > 0) snprintf(name, n, "specseg_gt%d", o->landmarks);
  else snprintf(name, n, "specseg");
}

void ss_benchmark_info_free(ss_benchmark_info *info) {
  if (!info) return;
  for (int i = 0; i < info->nwarnings; i++) free(info->warnings[i]);
  free(info->warnings);
  memset(info, 0, sizeof *info);
}

/* one shape of the run */
typedef struct bshape {
  int need;           /* 1: some pair of the shard needs it; 2: and our maps do (prepare it) */
  int ok;             /* mesh and points read */
  char why[1200];     /* why not (the note of its pairs' rows) */
  ss_mesh mesh;
  int *vts, nvts;     /* 0-based */
  int *sym, nsym;     /* 0-based; NULL: none */
  int prepared;       /* ps is there */
  char prep_why[1200]; /* why not, when it was wanted */
  int from_cache;
  ss_prepared_shape ps;
} bshape;

/* the run's state: the options, info, messages and the lock around them and the CSV, then what run's
 * stages build in turn */
typedef struct brun {
  const ss_benchmark_options *o;
  ss_benchmark_info *info;
#ifdef _OPENMP
  omp_lock_t lock;
#endif
  ss_match_options mo;
  const ss_autopair_options *ap; /* mo's: the prepared shapes' pairing signature */
  int kev;                       /* the prepared shapes' eigenpairs */
  char ours[SS_BENCH_METHOD];    /* our maps' method name */
  int NM;                        /* methods: ours (when o->match, first), then each maps folder's */
  const char **mname;
  ss_benchmark_set B;
  int p0, p1;                   /* the shard: pairs p0..p1-1 of B */
  char *csv, *mapdir;           /* OUT/pairs.csv, OUT/maps */
  int have_header;              /* pairs.csv is there (resume) */
  ss_benchmark_row *old;        /* its rows */
  char **keys, **skeys;         /* the scored rows' keys; the skipped rows' keys with their notes (sorted) */
  int nkeys, nskeys;
  int *todo, ntodo;             /* the shard's pairs with a row to compute */
  int *need_m;                  /* ntodo x NM: whether pair todo[t] needs method m's row */
  bshape *sh;                   /* per shape of B */
  int lm[MAX_LM], nlm;          /* --landmarks gt:N: the ground-truth points used */
  int nthreads;
} brun;

static void lock(brun *R) {
#ifdef _OPENMP
  omp_set_lock(&R->lock);
#else
  (void)R;
#endif
}
static void unlock(brun *R) {
#ifdef _OPENMP
  omp_unset_lock(&R->lock);
#else
  (void)R;
#endif
}

static void say(brun *R, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void say(brun *R, const char *fmt, ...) {
  if (!R->o->log) return;
  char line[1400];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(line, sizeof line, fmt, ap);
  va_end(ap);
  R->o->log(R->o->user, line);
}

/* a warning: to the caller and into info (the caller holds the lock or runs single-threaded) */
static void warn(brun *R, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void warn(brun *R, const char *fmt, ...) {
  char line[1400];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(line, sizeof line, fmt, ap);
  va_end(ap);
  if (R->o->warn) R->o->warn(R->o->user, line);
  ss_benchmark_info *I = R->info;
  char **g = realloc(I->warnings, sizeof *g * (size_t)(I->nwarnings + 1));
  if (!g) return;
  I->warnings = g;
  if ((g[I->nwarnings] = bm_strdup(line))) I->nwarnings++;
}

static void progress(brun *R, int sd, int st, int pd, int pt, double t0) {
  if (!R->o->progress) return;
  ss_benchmark_progress p = {sd, st, pd, pt, ss_time() - t0};
  R->o->progress(R->o->user, &p);
}

/* 1-based points of a mesh of nv vertices -> 0-based; the file and line of the first bad one in why */
static ss_status read_points(const char *path, int nv, int **out, int *n, char *why, size_t nwhy) {
  ss_error e;
  int *lines = NULL;
  *out = NULL, *n = 0;
  if (ss_read_ints_lines(path, out, &lines, n, &e)) {
    snprintf(why, nwhy, "%.1000s", e.msg);
    return SS_ERR_PARSE;
  }
  ss_status st = SS_OK;
  if (*n < 1) {
    snprintf(why, nwhy, "%s: no points", path);
    st = SS_ERR_PARSE;
  }
  for (int k = 0; k < *n && !st; k++) {
    if ((*out)[k] < 1 || (*out)[k] > nv) {
      snprintf(why, nwhy, "%s:%d: vertex %d is not a 1-based vertex of its mesh (1..%d)", path, lines[k], (*out)[k], nv);
      st = SS_ERR_PARSE;
    }
    (*out)[k]--;
  }
  free(lines);
  if (st) free(*out), *out = NULL, *n = 0;
  return st;
}

/* the cache file of a shape: NAME (blanks and slashes replaced) and a key of what it depends on */
static void cache_path(const char *dir, const char *name, const ss_mesh *m, int kev, int sig, char *path, size_t n) {
  char key[256];
  snprintf(key, sizeof key, "specseg-benchmark-shape 1 lib %s kev %d sig %d mesh %016llx", ss_version(), kev, sig,
           (unsigned long long)ssi_mesh_hash(m));
  uint64_t h = ssi_fnv1a(SSI_FNV_INIT, key, strlen(key));
  char safe[SS_BENCH_NAME];
  snprintf(safe, sizeof safe, "%s", name);
  for (char *p = safe; *p; p++)
    if (*p == '/' || *p == ' ' || *p == '\\') *p = '_';
  snprintf(path, n, "%s/%s_%016llx.sss", dir, safe, (unsigned long long)h);
}

static int same_mesh(const ss_mesh *a, const ss_mesh *b) {
  return a->nv == b->nv && a->nf == b->nf && !memcmp(a->V, b->V, sizeof(double) * 3 * (size_t)a->nv) &&
         !memcmp(a->F, b->F, sizeof(int) * 3 * (size_t)a->nf);
}

/* phase 1 for one shape: mesh, points, mirror points; prepared when our maps need it */
static void load_shape(brun *R, const ss_benchmark_shape *d, bshape *s, int kev, const ss_autopair_options *ap,
                       const char *corres) {
  ss_error e;
  if (!d->mesh) {
    snprintf(s->why, sizeof s->why, "%s: no mesh file", d->name);
    return;
  }
  if (ss_read_mesh(d->mesh, &s->mesh, &e)) {
    snprintf(s->why, sizeof s->why, "%.1000s", e.msg);
    return;
  }
  if (!d->vts) {
    snprintf(s->why, sizeof s->why, "%s/%s.vts: no such file", corres, d->name);
    return;
  }
  if (read_points(d->vts, s->mesh.nv, &s->vts, &s->nvts, s->why, sizeof s->why)) return;
  if (d->sym) {
    char why[1200];
    if (read_points(d->sym, s->mesh.nv, &s->sym, &s->nsym, why, sizeof why)) {
      lock(R);
      warn(R, "%s: not used (no symmetric error for pairs onto %s)", why, d->name);
      unlock(R);
    }
  }
  s->ok = 1;
  if (s->need < 2) return;
  /* prepared once: from the cache when its entry is this mesh's */
  char path[4400] = "";
  const char *cache = R->o->cache_dir;
  if (cache) {
    cache_path(cache, d->name, &s->mesh, kev, ap != NULL, path, sizeof path);
    if (access(path, F_OK) == 0) {
      char why[1200] = "";
      if (ss_prepared_shape_read(path, &s->ps, &e)) snprintf(why, sizeof why, "%.1000s", e.msg);
      else if (!same_mesh(&s->ps.mesh, &s->mesh)) snprintf(why, sizeof why, "written for another mesh");
      else if (ss_prepared_shape_matched(&s->ps)->kev != kev && !s->ps.has_proxy)
        snprintf(why, sizeof why, "%d eigenpairs, %d wanted", ss_prepared_shape_matched(&s->ps)->kev, kev);
      /* a signature read from a file has no orientation-test probes, which every match would then
       * build for itself (~1 s a FAUST_r pair): computed again once here, as preparing it did */
      if (!why[0] && ap && R->o->landmarks == 0 && s->ps.has_signature) {
        ss_centre_signature_free(&s->ps.sig);
        if (ss_centre_signature_compute(ss_prepared_shape_matched(&s->ps), ap, &s->ps.sig, &e)) {
          snprintf(why, sizeof why, "its pairing signature: %.1000s", e.msg);
          s->ps.has_signature = 0;
        }
      }
      if (!why[0]) {
        s->prepared = s->from_cache = 1;
        return;
      }
      ss_prepared_shape_free(&s->ps);
      lock(R);
      say(R, "benchmark cache: %s: %s; not used, recomputing", path, why);
      unlock(R);
    }
  }
  if (ss_prepared_shape_compute(&s->mesh, NULL, kev, ap, &s->ps, &e)) {
    snprintf(s->prep_why, sizeof s->prep_why, "%.100s: not prepared: %.1000s", d->name, e.msg);
    return;
  }
  s->prepared = 1;
  if (cache && ss_prepared_shape_write(path, &s->ps, &e)) {
    lock(R);
    warn(R, "benchmark cache: %s", e.msg);
    unlock(R);
  }
}

/* Euclidean farthest-point sampling over the points of shape s from its point 0: nl point indices */
static int fps_points(const bshape *s, int nl, int *pick) {
  const int n = s->nvts;
  if (nl > n) nl = n;
  double *d = malloc(sizeof(double) * (size_t)n);
  if (!d) return 0;
  for (int k = 0; k < n; k++) d[k] = INFINITY;
  int cur = 0;
  for (int j = 0; j < nl; j++) {
    pick[j] = cur;
    const double *c = s->mesh.V + 3 * (size_t)s->vts[cur];
    int best = -1;
    double bd = -1;
    for (int k = 0; k < n; k++) {
      const double *p = s->mesh.V + 3 * (size_t)s->vts[k];
      double dx = p[0] - c[0], dy = p[1] - c[1], dz = p[2] - c[2], q = sqrt(dx * dx + dy * dy + dz * dz);
      if (q < d[k]) d[k] = q;
      if (d[k] > bd) bd = d[k], best = k; /* ties: the lower index */
    }
    cur = best;
  }
  free(d);
  return nl;
}

/* the keys of rows already scored: "method\tx\ty", sorted */
static int str_cmp(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }
static void row_key(const char *m, const char *x, const char *y, char *buf, size_t n) { snprintf(buf, n, "%s\t%s\t%s", m, x, y); }
static int is_done(char **keys, int n, const char *m, const char *x, const char *y) {
  if (n <= 0) return 0;
  char k[SS_BENCH_METHOD + 2 * SS_BENCH_NAME + 4], *kp = k;
  row_key(m, x, y, k, sizeof k);
  return bsearch(&kp, keys, (size_t)n, sizeof *keys, str_cmp) != NULL;
}


static int valid_method_name(const char *s) {
  if (!*s || strlen(s) >= SS_BENCH_METHOD) return 0;
  for (const char *p = s; *p; p++)
    if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') || *p == '_' || *p == '-' ||
          *p == '.'))
      return 0;
  return 1;
}

/* an external map X -> Y: MAPDIR/X__Y.txt or .npy, nx lines of vertices of Y; NULL with why */
static int *read_ext_map(const char *dir, const char *x, const char *y, int nx, int ny, char *why, size_t nwhy,
                         int *missing) {
  char path[4400];
  snprintf(path, sizeof path, "%s/%s__%s.txt", dir, x, y);
  int npy = 0;
  if (access(path, F_OK)) {
    snprintf(path, sizeof path, "%s/%s__%s.npy", dir, x, y);
    if (access(path, F_OK)) {
      snprintf(why, nwhy, "%s/%s__%s.txt (or .npy): no such file", dir, x, y);
      *missing = 1;
      return NULL;
    }
    npy = 1;
  }
  int *map = NULL, n = 0, rows = 0, cols = 0;
  ss_error e;
  if (npy) {
    if (ss_read_npy_ints(path, &map, &rows, &cols, &e)) {
      /* float64 arrays of whole numbers too (NumPy's default dtype) */
      double *a = NULL;
      if (ss_read_npy(path, &a, &rows, &cols, NULL)) {
        snprintf(why, nwhy, "%.1000s", e.msg);
        return NULL;
      }
      map = malloc(sizeof(int) * (size_t)(rows > 0 ? rows : 1) * (size_t)(cols > 0 ? cols : 1));
      for (long i = 0; map && i < (long)rows * cols; i++) {
        if (a[i] != floor(a[i]) || !(fabs(a[i]) < 2e9)) {
          snprintf(why, nwhy, "%.700s: entry %ld (%g) is not a vertex index", path, i + 1, a[i]);
          free(a), free(map);
          return NULL;
        }
        map[i] = (int)a[i];
      }
      free(a);
      if (!map) { snprintf(why, nwhy, "out of memory"); return NULL; }
    }
    if (cols != 1 && rows != 1) {
      snprintf(why, nwhy, "%.700s: a %d x %d array; a map is one column", path, rows, cols);
      free(map);
      return NULL;
    }
    n = rows * cols;
  } else if (ss_read_ints(path, &map, &n, &e)) {
    snprintf(why, nwhy, "%.1000s", e.msg);
    return NULL;
  }
  if (n != nx) {
    snprintf(why, nwhy, "%.700s: %d lines, but %s has %d vertices", path, n, x, nx);
    free(map);
    return NULL;
  }
  for (int i = 0; i < n; i++)
    if (map[i] < 0 || map[i] >= ny) {
      snprintf(why, nwhy, "%.700s:%d: vertex %d is not on %s (0..%d)", path, i + 1, map[i], y, ny - 1);
      free(map);
      return NULL;
    }
  return map;
}

/* The run's methods: our own maps (when o->match, first) and each maps folder's; a folder name that is
 * not a valid method name, not a folder, or given twice is refused. Sets ours, NM, mname. */
static ss_status check_methods(brun *R, ss_error *err) {
  const ss_benchmark_options *o = R->o;
  ss_benchmark_method_name(o, R->ours, sizeof R->ours);
  R->NM = (o->match ? 1 : 0) + o->nmaps;
  if (!(R->mname = calloc((size_t)R->NM, sizeof *R->mname)))
    return ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory");
  int k = 0;
  if (o->match) R->mname[k++] = R->ours;
  for (int i = 0; i < o->nmaps; i++) R->mname[k++] = o->map_names[i];
  const char **mname = R->mname;
  for (int i = o->match; i < R->NM; i++) {
    if (!valid_method_name(mname[i]))
      return ss_fail(err, SS_ERR_INVALID,
                     "benchmark: method name '%s': letters, digits, '_', '-' and '.' only, at most %d", mname[i],
                     SS_BENCH_METHOD - 1);
    if (!bm_is_dir(o->map_dirs[i - o->match]))
      return ss_fail(err, SS_ERR_IO, "benchmark: %s: maps folder %s is not a folder", mname[i],
                     o->map_dirs[i - o->match]);
    for (int j = 0; j < i; j++)
      if (!strcmp(mname[i], mname[j]))
        return ss_fail(err, SS_ERR_INVALID, "benchmark: method '%s' given twice%s", mname[i],
                       j == 0 && o->match ? " (our own maps' name)" : "");
  }
  return SS_OK;
}

/* The output folder and its paths (csv, mapdir); pairs.csv's rows already there: the scored ones' keys
 * (keys: not run again) and the skipped ones' keys with their notes (skeys: retried, but not written
 * again when skipped for the same reason), each sorted */
static ss_status read_resume(brun *R, ss_error *err) {
  const char *dir = R->o->out_dir;
  if (mkdir(dir, 0755) && errno != EEXIST)
    return ss_fail(err, SS_ERR_IO, "%s: cannot create: %s", dir, strerror(errno));
  if (!bm_is_dir(dir)) return ss_fail(err, SS_ERR_IO, "%s: not a folder", dir);
  R->csv = bm_join(dir, "pairs.csv"), R->mapdir = bm_join(dir, "maps");
  if (!R->csv || !R->mapdir) return ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory");
  R->have_header = ssi_csv_repair_tail(R->csv);
  if (!R->have_header) return SS_OK;
  ss_status st;
  int nold = 0;
  if ((st = ss_benchmark_csv_read(R->csv, &R->old, &nold, err))) return st;
  R->keys = malloc(sizeof *R->keys * (size_t)(nold > 0 ? nold : 1));
  R->skeys = malloc(sizeof *R->skeys * (size_t)(nold > 0 ? nold : 1));
  if (!R->keys || !R->skeys) return ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory");
  for (int i = 0; i < nold; i++) {
    const ss_benchmark_row *w = &R->old[i];
    char k[SS_BENCH_METHOD + 2 * SS_BENCH_NAME + 4 + sizeof w->notes];
    row_key(w->method, w->x, w->y, k, sizeof k);
    if (!w->ok) {
      size_t L = strlen(k);
      snprintf(k + L, sizeof k - L, "\t%s", w->notes);
      if (!(R->skeys[R->nskeys] = bm_strdup(k))) return ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory");
      R->nskeys++;
      continue;
    }
    if (!(R->keys[R->nkeys] = bm_strdup(k))) return ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory");
    R->info->rows_kept++;
    R->nkeys++;
  }
  qsort(R->keys, (size_t)R->nkeys, sizeof *R->keys, str_cmp);
  qsort(R->skeys, (size_t)R->nskeys, sizeof *R->skeys, str_cmp);
  return SS_OK;
}

/* Our maps' folder, marked with the method whose maps it holds (another method needs another --out),
 * and the cache folder */
static ss_status make_map_folders(brun *R, ss_error *err) {
  const ss_benchmark_options *o = R->o;
  if (!o->match) return SS_OK;
  const char *mapdir = R->mapdir;
  if (mkdir(mapdir, 0755) && errno != EEXIST)
    return ss_fail(err, SS_ERR_IO, "%s: cannot create: %s", mapdir, strerror(errno));
  char omark[4400], was[SS_BENCH_METHOD] = "";
  snprintf(omark, sizeof omark, "%s/.method", mapdir);
  FILE *mf = fopen(omark, "rb");
  if (mf) {
    if (!fgets(was, sizeof was, mf)) was[0] = 0;
    fclose(mf);
    was[strcspn(was, "\r\n")] = 0;
  }
  if (was[0] && strcmp(was, R->ours))
    return ss_fail(err, SS_ERR_INVALID, "%s: its maps/ hold %s's maps; %s needs another --out", o->out_dir, was,
                   R->ours);
  if (!was[0]) {
    mf = fopen(omark, "wb");
    if (!mf || fprintf(mf, "%s\n", R->ours) < 0 || fclose(mf))
      return ss_fail(err, SS_ERR_IO, "%s: cannot write", omark);
  }
  if (o->cache_dir && mkdir(o->cache_dir, 0755) && errno != EEXIST)
    return ss_fail(err, SS_ERR_IO, "%s: cannot create the cache folder: %s", o->cache_dir, strerror(errno));
  return SS_OK;
}

/* The shard's pairs with a method to run (todo, need_m: which methods) and what each shape is needed
 * for (sh[].need); *rows_total: the rows to compute */
static ss_status plan_pairs(brun *R, long *rows_total, ss_error *err) {
  const ss_benchmark_set *B = &R->B;
  const int NM = R->NM, np = R->p1 - R->p0 > 0 ? R->p1 - R->p0 : 1;
  R->todo = malloc(sizeof(int) * (size_t)np);
  R->need_m = calloc((size_t)np * NM, sizeof(int));
  R->sh = calloc((size_t)B->nshapes, sizeof *R->sh);
  if (!R->todo || !R->need_m || !R->sh) return ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory");
  bshape *sh = R->sh;
  *rows_total = 0;
  for (int p = R->p0; p < R->p1; p++) {
    int any = 0;
    for (int m = 0; m < NM; m++) {
      int t = !is_done(R->keys, R->nkeys, R->mname[m], B->shapes[B->px[p]].name, B->shapes[B->py[p]].name);
      R->need_m[(size_t)R->ntodo * NM + m] = t;
      any |= t;
      *rows_total += t;
      if (t && R->o->match && m == 0) sh[B->px[p]].need = sh[B->py[p]].need = 2;
    }
    if (!any) continue;
    if (!sh[B->px[p]].need) sh[B->px[p]].need = 1;
    if (!sh[B->py[p]].need) sh[B->py[p]].need = 1;
    R->todo[R->ntodo++] = p;
  }
  return SS_OK;
}

/* --landmarks gt:N: farthest-point sampling on the first shape whose mesh and points read */
static ss_status pick_landmarks(brun *R, ss_error *err) {
  const ss_benchmark_set *B = &R->B;
  ss_benchmark_info *I = R->info;
  for (int s = 0; s < B->nshapes && !R->nlm; s++) { /* read on its own (cheap), whatever the shard needs */
    bshape tmp = {0};
    tmp.need = 1;
    load_shape(R, &B->shapes[s], &tmp, R->kev, R->ap, B->corres_dir);
    if (tmp.ok) {
      R->nlm = fps_points(&tmp, R->o->landmarks, R->lm);
      snprintf(I->landmark_shape, sizeof I->landmark_shape, "%s", B->shapes[s].name);
    }
    ss_mesh_free(&tmp.mesh);
    free(tmp.vts), free(tmp.sym);
  }
  if (!R->nlm) return ss_fail(err, SS_ERR_INVALID, "benchmark: --landmarks: no shape whose mesh and points read");
  I->nlandmarks = R->nlm;
  memcpy(I->landmarks, R->lm, sizeof(int) * (size_t)R->nlm);
  char list[600] = "";
  for (int j = 0; j < R->nlm; j++) snprintf(list + strlen(list), sizeof list - strlen(list), " %d", R->lm[j]);
  say(R, "benchmark: landmarks: %d ground-truth points by farthest-point sampling on %s from its point 0:%s", R->nlm,
      I->landmark_shape, list);
  if (R->nlm < R->o->landmarks)
    warn(R, "--landmarks gt:%d: %s has only %d points: %d landmarks", R->o->landmarks, I->landmark_shape, R->nlm,
         R->nlm);
  return SS_OK;
}

/* What did not read, once per shape with the pairs it skips; points files of unequal length (the most
 * common length, and each file that differs); the shapes prepared and cached counted in info */
static ss_status report_shapes(brun *R, ss_error *err) {
  const ss_benchmark_set *B = &R->B;
  const bshape *sh = R->sh;
  ss_benchmark_info *I = R->info;
  int *npairs = calloc((size_t)B->nshapes, sizeof(int)), *mode = NULL;
  if (!npairs) return ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory");
  for (int t = 0; t < R->ntodo; t++) {
    const int p = R->todo[t];
    npairs[B->px[p]]++, npairs[B->py[p]] += B->px[p] != B->py[p];
  }
  int nok = 0;
  for (int s = 0; s < B->nshapes; s++) {
    if (!sh[s].need) continue;
    if (!sh[s].ok)
      warn(R, "%s: its %d pair%s skipped", sh[s].why, npairs[s], npairs[s] == 1 ? "" : "s");
    else if (sh[s].need == 2 && !sh[s].prepared)
      warn(R, "%s: its %d pair%s skipped for %s", sh[s].prep_why, npairs[s], npairs[s] == 1 ? "" : "s", R->ours);
    if (sh[s].ok) {
      nok++;
      I->shapes_prepared += sh[s].prepared && !sh[s].from_cache;
      I->shapes_cached += sh[s].from_cache;
    }
  }
  if (!(mode = malloc(sizeof(int) * (size_t)(nok > 0 ? nok : 1)))) {
    free(npairs);
    return ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory");
  }
  int k = 0;
  for (int s = 0; s < B->nshapes; s++)
    if (sh[s].need && sh[s].ok) mode[k++] = sh[s].nvts;
  int best = 0, bestc = 0;
  for (int a = 0; a < k; a++) {
    int c = 0;
    for (int b = 0; b < k; b++) c += mode[b] == mode[a];
    if (c > bestc || (c == bestc && mode[a] > best)) bestc = c, best = mode[a];
  }
  for (int s = 0; s < B->nshapes; s++) {
    if (!sh[s].need || !sh[s].ok) continue;
    if (sh[s].nvts != best)
      warn(R, "%s: %d points where the others have %d: its pairs use the points both files have", B->shapes[s].vts,
           sh[s].nvts, best);
    if (sh[s].sym && sh[s].nsym != sh[s].nvts)
      warn(R, "%s: %d mirror points for %d points: the symmetric error of pairs onto %s uses the first %d",
           B->shapes[s].sym, sh[s].nsym, sh[s].nvts, B->shapes[s].name,
           sh[s].nsym < sh[s].nvts ? sh[s].nsym : sh[s].nvts);
  }
  free(mode), free(npairs);
  return SS_OK;
}

/* Phase 1: every shape the pairs need read (and prepared for our maps), in parallel, then reported */
static ss_status load_shapes(brun *R, ss_error *err) {
  const ss_benchmark_set *B = &R->B;
  int *list = malloc(sizeof(int) * (size_t)B->nshapes), nlist = 0;
  if (!list) return ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory");
  for (int s = 0; s < B->nshapes; s++)
    if (R->sh[s].need) list[nlist++] = s;
  int loaded = 0;
  double t1 = ss_time();
  progress(R, 0, nlist, 0, R->ntodo, t1);
#pragma omp parallel for schedule(dynamic, 1) num_threads(R->nthreads)
  for (int i = 0; i < nlist; i++) {
    load_shape(R, &B->shapes[list[i]], &R->sh[list[i]], R->kev, R->ap, B->corres_dir);
    lock(R);
    loaded++;
    progress(R, loaded, nlist, 0, R->ntodo, t1);
    unlock(R);
  }
  free(list);
  ss_status st = report_shapes(R, err);
  if (st) return st;
  say(R, "benchmark: shapes read%s in %.1f s (%d prepared, %d from the cache)", R->o->match ? " and prepared" : "",
      ss_time() - t1, R->info->shapes_prepared, R->info->shapes_cached);
  return SS_OK;
}

/* Phase 2's shared state: the CSV open for appending, the first write error, the maps folders' missing
 * files (counted per method, the first named), the pairs done */
typedef struct {
  FILE *out;
  int werr;
  ss_error wmsg;
  int *nmissing;
  char (*first_missing)[1200];
  int done_pairs;
  double t0;
} bpairs;

/* The write error e, unless one came first (the caller holds no lock) */
static void write_failed(brun *R, bpairs *P, ss_status code, const ss_error *e) {
  lock(R);
  if (!P->werr) P->werr = code, P->wmsg = *e;
  unlock(R);
}

/* Our own map of pair (x, y) (X, Y read and prepared), written to maps/X__Y.txt: returned (malloc'd),
 * with its seconds and confidence in r; NULL when not made, the reason in r's notes (or, for a write
 * error, in P) */
static int *our_map(brun *R, bpairs *P, const bshape *X, const bshape *Y, const char *xn, const char *yn, int K,
                    ss_benchmark_row *r) {
  if (!X->prepared || !Y->prepared) {
    bm_note(r->notes, sizeof r->notes, "%s", !X->prepared ? X->prep_why : Y->prep_why);
    return NULL;
  }
  int lx[MAX_LM], ly[MAX_LM], nl = 0;
  for (int j = 0; j < R->nlm; j++)
    if (R->lm[j] < K) lx[nl] = X->vts[R->lm[j]], ly[nl] = Y->vts[R->lm[j]], nl++;
  if (R->o->landmarks > 0 && nl < R->nlm)
    bm_note(r->notes, sizeof r->notes, "%d of the %d landmarks (the others beyond point %d)", nl, R->nlm, K);
  if (R->o->landmarks > 0 && nl == 0) {
    bm_note(r->notes, sizeof r->notes, "no landmark among the points both shapes have");
    return NULL;
  }
  ss_error e;
  ss_match_result res = {0};
  char wbuf[1024] = "";
  double ts = ss_time();
  if (ss_match_prepared_shapes(&X->ps, &Y->ps, nl, lx, ly, NULL, &res, wbuf, sizeof wbuf, &e)) {
    bm_note(r->notes, sizeof r->notes, "match failed: %s", e.msg);
    ss_match_result_free(&res);
    return NULL;
  }
  r->seconds = ss_time() - ts;
  if (res.autopair.used || res.autopair.hypotheses > 1) r->confident = res.autopair.confident;
  if (res.notes[0]) bm_note(r->notes, sizeof r->notes, "%s", res.notes);
  if (wbuf[0]) bm_note(r->notes, sizeof r->notes, "%s", wbuf);
  char mp[4400];
  snprintf(mp, sizeof mp, "%s/%s__%s.txt", R->mapdir, xn, yn);
  int *map = NULL;
  if (ss_write_ints(mp, res.map, res.nX, &e))
    write_failed(R, P, SS_ERR_IO, &e);
  else
    map = res.map, res.map = NULL;
  ss_match_result_free(&res);
  return map;
}

/* Pair t's rows, one per method it needs (rows[m]): the map (ours, or method m's file), scored */
static void score_pair(brun *R, bpairs *P, int t, ss_benchmark_row *rows) {
  const ss_benchmark_options *o = R->o;
  const ss_benchmark_set *B = &R->B;
  const int p = R->todo[t], x = B->px[p], y = B->py[p];
  const bshape *X = &R->sh[x], *Y = &R->sh[y];
  const char *xn = B->shapes[x].name, *yn = B->shapes[y].name;
  const int K = X->ok && Y->ok ? (X->nvts < Y->nvts ? X->nvts : Y->nvts) : 0;
  const int NS = Y->ok && Y->sym ? Y->nsym : 0;
  for (int m = 0; m < R->NM; m++) {
    ss_benchmark_row *r = &rows[m];
    snprintf(r->method, sizeof r->method, "%s", R->mname[m]);
    snprintf(r->x, sizeof r->x, "%s", xn);
    snprintf(r->y, sizeof r->y, "%s", yn);
    r->mean = r->median = r->sym_mean = r->seconds = NAN;
    r->confident = -1;
    if (!R->need_m[(size_t)t * R->NM + m]) continue;
    if (!X->ok || !Y->ok) {
      bm_note(r->notes, sizeof r->notes, "%s", !X->ok ? X->why : Y->why);
      continue;
    }
    if (X->nvts != Y->nvts)
      bm_note(r->notes, sizeof r->notes, "the first %d points (%s has %d, %s %d)", K, xn, X->nvts, yn, Y->nvts);
    int *map;
    if (o->match && m == 0)
      map = our_map(R, P, X, Y, xn, yn, K, r);
    else {
      char why[1200];
      int missing = 0;
      map = read_ext_map(o->map_dirs[m - o->match], xn, yn, X->mesh.nv, Y->mesh.nv, why, sizeof why, &missing);
      if (!map) {
        bm_note(r->notes, sizeof r->notes, "%s", why);
        lock(R);
        if (!missing)
          warn(R, "%s: %s -> %s skipped: %s", R->mname[m], xn, yn, why);
        else if (!P->nmissing[m]++)
          snprintf(P->first_missing[m], sizeof P->first_missing[m], "%s", why);
        unlock(R);
      }
    }
    if (!map) continue;
    ss_error e;
    if (ss_benchmark_score(&Y->mesh, X->mesh.nv, map, K, X->vts, Y->vts, Y->sym, NS, r, NULL, &e))
      bm_note(r->notes, sizeof r->notes, "not scored: %s", e.msg);
    else
      r->ok = 1;
    free(map);
  }
}

/* Pair t's rows appended to pairs.csv and flushed, but a row skipped for the same reason as before
 * (the caller holds the lock) */
static void write_rows(brun *R, bpairs *P, int t, const ss_benchmark_row *rows) {
  ss_benchmark_info *I = R->info;
  for (int m = 0; m < R->NM && !P->werr; m++) {
    if (!R->need_m[(size_t)t * R->NM + m]) continue;
    if (!rows[m].ok && R->nskeys > 0) {
      char k[SS_BENCH_METHOD + 2 * SS_BENCH_NAME + 4 + sizeof rows[m].notes], *kp = k;
      row_key(rows[m].method, rows[m].x, rows[m].y, k, sizeof k);
      size_t L = strlen(k);
      snprintf(k + L, sizeof k - L, "\t%s", rows[m].notes);
      if (bsearch(&kp, R->skeys, (size_t)R->nskeys, sizeof *R->skeys, str_cmp)) {
        I->rows_same_skip++;
        continue;
      }
    }
    char line[SS_BENCH_CSV_LINE];
    ss_benchmark_csv_format_row(&rows[m], line, sizeof line);
    if (fprintf(P->out, "%s\n", line) < 0)
      P->werr = SS_ERR_IO, snprintf(P->wmsg.msg, sizeof P->wmsg.msg, "%s: write error", R->csv);
    I->rows_new++;
  }
  fflush(P->out);
}

/* Phase 2: the pairs, in parallel, each pair's rows written as it finishes */
static ss_status score_pairs(brun *R, ss_error *err) {
  bpairs P;
  memset(&P, 0, sizeof P);
  if (!(P.out = fopen(R->csv, R->have_header ? "ab" : "wb")))
    return ss_fail(err, SS_ERR_IO, "%s: cannot open for writing: %s", R->csv, strerror(errno));
  if (!R->have_header) fprintf(P.out, "%s\n", ss_benchmark_csv_header());
  fflush(P.out);
  ss_status st = SS_OK;
  P.nmissing = calloc((size_t)R->NM, sizeof(int));
  P.first_missing = calloc((size_t)R->NM, sizeof *P.first_missing);
  if (!P.nmissing || !P.first_missing) {
    st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory");
    goto done;
  }
  P.t0 = ss_time();
  progress(R, 1, 1, 0, R->ntodo, P.t0);
#pragma omp parallel for schedule(dynamic, 1) num_threads(R->nthreads)
  for (int t = 0; t < R->ntodo; t++) {
    if (P.werr) continue;
    ss_benchmark_row *rows = calloc((size_t)R->NM, sizeof *rows);
    if (!rows) {
      ss_error e;
      snprintf(e.msg, sizeof e.msg, "benchmark: out of memory");
      write_failed(R, &P, SS_ERR_NOMEM, &e);
      continue;
    }
    score_pair(R, &P, t, rows);
    lock(R);
    write_rows(R, &P, t, rows);
    P.done_pairs++;
    progress(R, 1, 1, P.done_pairs, R->ntodo, P.t0);
    unlock(R);
    free(rows);
  }
  for (int m = 0; m < R->NM; m++)
    if (P.nmissing[m])
      warn(R, "%s: %d of the %d pairs have no map file (%s): skipped", R->mname[m], P.nmissing[m], R->ntodo,
           P.first_missing[m]);
  if (P.werr)
    st = ss_fail(err, (ss_status)P.werr, "%s", P.wmsg.msg);
  else
    say(R, "benchmark: %d rows of %d pairs in %.1f s", R->info->rows_new, R->ntodo, ss_time() - P.t0);
done:
  if (fclose(P.out) && !st) st = ss_fail(err, SS_ERR_IO, "%s: write error: %s", R->csv, strerror(errno));
  free(P.nmissing), free(P.first_missing);
  return st;
}

/* The run's state freed (not R's options, info and lock) */
static void run_free(brun *R) {
  if (R->sh)
    for (int s = 0; s < R->B.nshapes; s++) {
      ss_mesh_free(&R->sh[s].mesh);
      free(R->sh[s].vts), free(R->sh[s].sym);
      if (R->sh[s].prepared) ss_prepared_shape_free(&R->sh[s].ps);
    }
  for (int i = 0; i < R->nkeys; i++) free(R->keys[i]);
  for (int i = 0; i < R->nskeys; i++) free(R->skeys[i]);
  free(R->keys), free(R->skeys), free(R->sh), free(R->todo), free(R->need_m), free(R->old), free(R->csv);
  free(R->mapdir), free(R->mname);
  ss_benchmark_set_free(&R->B);
}

static ss_status run(brun *R, ss_error *err) {
  const ss_benchmark_options *o = R->o;
  ss_benchmark_info *I = R->info;
  if (!o->dir || !o->out_dir) return ss_fail(err, SS_ERR_INVALID, "benchmark: folder and output folder needed");
  if (o->shard_n < 1 || o->shard_i < 0 || o->shard_i >= o->shard_n || o->landmarks < 0 || o->landmarks > MAX_LM ||
      o->nmaps < 0 || o->max_pairs < 0 || (o->nmaps > 0 && (!o->map_names || !o->map_dirs)))
    return ss_fail(err, SS_ERR_INVALID, "benchmark: bad options (shard %d/%d, landmarks %d, maps %d)", o->shard_i + 1,
                   o->shard_n, o->landmarks, o->nmaps);
  if (!o->match && o->nmaps == 0)
    return ss_fail(err, SS_ERR_INVALID, "benchmark: no method (our maps off and no maps folder)");
  /* the landmark-free match's eigenpairs and pairing signature, also for --landmarks runs (a match with
   * landmarks never needs more eigenpairs; the signature is unused there, ~0.2 s a shape): one cache
   * entry serves both */
  ss_match_default_options(&R->mo);
  R->kev = ss_match_eigenpairs(NULL, 0), R->ap = &R->mo.autopair;
  double t0 = ss_time();
  ss_status st;
  long rows_total = 0;
  if ((st = check_methods(R, err))) goto done;
  if ((st = ss_benchmark_open(o->dir, o->pairs_file, o->max_pairs, o->seed, &R->B, err))) goto done;
  const ss_benchmark_set *B = &R->B;
  I->pairs_listed = B->npairs;
  R->p0 = (int)((long)B->npairs * o->shard_i / o->shard_n),
  R->p1 = (int)((long)B->npairs * (o->shard_i + 1) / o->shard_n);
  I->pairs_shard = R->p1 - R->p0;
  if ((st = read_resume(R, err)) || (st = make_map_folders(R, err)) || (st = plan_pairs(R, &rows_total, err)))
    goto done;
  say(R,
      "benchmark: %s: %d shapes (meshes in %s), %d pairs (%s%s)%s: shard %d/%d: %d pairs, %d to do (%ld rows), %d "
      "rows already in %s",
      o->dir, B->nshapes, B->mesh_dir, B->npairs, B->pairs_file ? B->pairs_file : "all ordered pairs",
      B->npairs < B->nall ? ", sampled" : "", "", o->shard_i + 1, o->shard_n, R->p1 - R->p0, R->ntodo, rows_total,
      I->rows_kept, R->csv);
  if (R->ntodo == 0) goto done;
  if (o->match && o->landmarks > 0 && (st = pick_landmarks(R, err))) goto done;
  R->nthreads = ssi_eval_threads(o->jobs);
  if ((st = load_shapes(R, err))) goto done;
  st = score_pairs(R, err);
done:
  run_free(R);
  I->seconds = ss_time() - t0;
  return st;
}

static int warn_cmp(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

ss_status ss_benchmark_run(const ss_benchmark_options *o, ss_benchmark_info *info, ss_error *err) {
  ss_benchmark_info local;
  if (!info) info = &local;
  memset(info, 0, sizeof *info);
  if (!o) return ss_fail(err, SS_ERR_INVALID, "benchmark: no options");
  brun R;
  memset(&R, 0, sizeof R);
  R.o = o, R.info = info;
#ifdef _OPENMP
  omp_init_lock(&R.lock);
#endif
  ss_status st = run(&R, err);
#ifdef _OPENMP
  omp_destroy_lock(&R.lock);
#endif
  /* warnings in a fixed order (threads finish in any) */
  if (info->nwarnings > 1) qsort(info->warnings, (size_t)info->nwarnings, sizeof *info->warnings, warn_cmp);
  if (info == &local) ss_benchmark_info_free(&local);
  return st;
}
