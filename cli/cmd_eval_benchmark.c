/* specseg eval --benchmark DIR: the field's benchmark (FAUST_r, TOSCA_r, any folder of meshes with
 * ground-truth points) for our own maps and external maps folders; eval merge of its shards. A thin
 * shell over ss_benchmark_run / ss_benchmark_write_outputs (specseg/eval.h). */
#include "cli.h"
#include "cmd_eval_benchmark.h"
#include "specseg/eval.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define MAX_MAPS 15

static const char USAGE_HEAD[] =
    "usage: specseg eval --benchmark DIR [--out OUTDIR] [--pairs FILE] [--max-pairs N] [--seed S]\n"
    "                    [--landmarks none|gt:N] [--maps NAME=MAPDIR]... [--no-match] [--cache DIR] [--jobs N]\n"
    "                    [--shard I/N] [--title TEXT] [--quiet] [--json]\n"
    "       specseg eval merge OUTDIR/pairs.csv... --out DIR [--title TEXT] [--json]\n"
    "\n";

static char *usage_text(void) {
  size_t a = strlen(USAGE_HEAD), b = strlen(CLI_EVAL_BENCHMARK_HELP_TEXT);
  char *u = malloc(a + b + 1);
  if (u) memcpy(u, USAGE_HEAD, a), memcpy(u + a, CLI_EVAL_BENCHMARK_HELP_TEXT, b + 1);
  return u;
}

/* ---- the table --------------------------------------------------------------------------------- */

static void fmt_num(char *buf, size_t n, double v, const char *fmt) {
  if (isfinite(v)) snprintf(buf, n, fmt, v);
  else snprintf(buf, n, "-");
}

static void print_stats_row(FILE *f, const char *method, const char *cls, const ss_benchmark_stats *s) {
  char mean[32], med[32], ab[32], sym[32], sec[32];
  fmt_num(mean, sizeof mean, s->mean, "%.2f");
  fmt_num(med, sizeof med, s->median, "%.2f");
  fmt_num(ab, sizeof ab, s->above5, "%.1f");
  fmt_num(sym, sizeof sym, s->sym_mean, "%.2f");
  fmt_num(sec, sizeof sec, s->seconds, "%.2f");
  fprintf(f, "%-16s %-14s %6d %7d %8d %10s %8s %7s %9s %7s %9d\n", method, cls, s->pairs, s->scored, s->skipped, mean, med,
          ab, sym, sec, s->not_confident);
}

static void print_summary(FILE *f, const ss_benchmark_summary *s, const char *title, int pairs_listed) {
  fprintf(f, "\n%s%s", title && *title ? title : "benchmark", pairs_listed >= 0 ? "" : "");
  if (pairs_listed >= 0) fprintf(f, ": %d pairs listed", pairs_listed);
  fprintf(f, " (errors x 100: geodesic / sqrt(area), exact)\n");
  fprintf(f, "%-16s %-14s %6s %7s %8s %10s %8s %7s %9s %7s %9s\n", "method", "class", "pairs", "scored", "skipped",
          "mean x100", "median", ">5 (%)", "sym x100", "s/pair", "not conf.");
  for (int m = 0; m < s->nmethods; m++) {
    const ss_benchmark_method *M = &s->methods[m];
    print_stats_row(f, M->name, "all", &M->all);
    if (M->nclasses > 1)
      for (int c = 0; c < M->nclasses; c++) print_stats_row(f, "", M->classes[c], &M->class_stats[c]);
  }
}

/* the outputs from OUTDIR/pairs.csv (or given rows), then the table or the JSON */
static int finish(const char *outdir, ss_benchmark_row *rows, int n, const char *title, int pairs_listed, int nwarn,
                  char **warnings, int json) {
  ss_benchmark_summary s;
  char *js = NULL;
  ss_error e;
  if (ss_benchmark_write_outputs(outdir, rows, n, title, pairs_listed, nwarn, (const char *const *)warnings, &s, &js, &e))
    return cli_error("%s", e.msg);
  int rc = SS_EXIT_OK;
  if (json) fputs(js, stdout);
  else {
    print_summary(stdout, &s, title, pairs_listed);
    printf("-> %s/pairs.csv, %s/summary.json, %s/curves.png\n", outdir, outdir, outdir);
  }
  if (fflush(stdout)) rc = cli_error("cannot write to standard output");
  free(js);
  ss_benchmark_summary_free(&s);
  return rc;
}

/* ---- progress ---------------------------------------------------------------------------------- */

typedef struct bench_out {
  int bar, quiet, on_line;
} bench_out;

static void bench_progress(void *user, const ss_benchmark_progress *p) {
  bench_out *o = user;
  if (!o->bar) return;
  if (p->shapes_done < p->shapes_total || p->pairs_total == 0) {
    fprintf(stderr, "\r  reading / preparing shapes %d/%d  %.0fs      ", p->shapes_done, p->shapes_total, p->seconds);
  } else {
    char eta[32] = "--", bar[64];
    if (p->pairs_done > 0) {
      double r = p->seconds / p->pairs_done * (p->pairs_total - p->pairs_done);
      snprintf(eta, sizeof eta, "%dm%02ds", (int)(r / 60), (int)fmod(r, 60));
    }
    int w = 30, fill = p->pairs_total ? (int)((long)w * p->pairs_done / p->pairs_total) : w;
    for (int i = 0; i < w; i++) bar[i] = i < fill ? '#' : '.';
    bar[w] = 0;
    fprintf(stderr, "\r  [%s] %d/%d pairs  %.0fs elapsed  ETA %s   ", bar, p->pairs_done, p->pairs_total, p->seconds, eta);
  }
  o->on_line = 1;
  fflush(stderr);
}

static void bench_log(void *user, const char *line) {
  bench_out *o = user;
  if (o->quiet) return;
  fprintf(stderr, "%s%s\n", o->on_line ? "\n" : "", line);
  o->on_line = 0;
}

static void bench_warn(void *user, const char *line) {
  bench_out *o = user;
  if (o->on_line) fputc('\n', stderr), o->on_line = 0;
  cli_warn("%s", line);
}

/* DIR's name (without a trailing vtx_5k/, off/ or shapes/) */
static void default_title(const char *dir, char *t, size_t n) {
  char buf[4096];
  snprintf(buf, sizeof buf, "%s", dir);
  for (;;) {
    size_t L = strlen(buf);
    while (L > 1 && buf[L - 1] == '/') buf[--L] = 0;
    char *b = strrchr(buf, '/');
    const char *base = b ? b + 1 : buf;
    if (b && (!strcmp(base, "vtx_5k") || !strcmp(base, "off") || !strcmp(base, "shapes"))) {
      *b = 0;
      continue;
    }
    snprintf(t, n, "%s", base);
    return;
  }
}

/* --landmarks none|gt:N */
static int take_landmarks(cli_args *A, const cli_opt *o, const char *v) {
  int *n = o->dest;
  if (!strcmp(v, "none")) *n = 0;
  else if (strncmp(v, "gt:", 3) || cli_parse_int(v + 3, 1, 64, n)) return cli_bad(A, "--landmarks: none or gt:N with N in 1..64");
  return -1;
}

/* the --maps NAME=MAPDIR given (each a copy, cut at its '=') */
typedef struct maps_opt {
  const char *names[MAX_MAPS], *dirs[MAX_MAPS];
  char *args[MAX_MAPS];
  int n;
} maps_opt;

static int take_maps(cli_args *A, const cli_opt *o, const char *v) {
  maps_opt *M = o->dest;
  const char *eq = strchr(v, '=');
  if (!eq || eq == v || !eq[1]) return cli_bad(A, "--maps: NAME=MAPDIR");
  if (M->n == MAX_MAPS) return cli_bad(A, "--maps: at most %d folders", MAX_MAPS);
  char *c = malloc(strlen(v) + 1);
  if (!c) return cli_error("out of memory");
  strcpy(c, v);
  c[eq - v] = 0;
  M->args[M->n] = c, M->names[M->n] = c, M->dirs[M->n] = c + (eq - v) + 1, M->n++;
  return -1;
}

static int run_benchmark(int argc, char **argv) {
  ss_benchmark_options o;
  ss_benchmark_default_options(&o);
  const char *title = NULL;
  maps_opt maps = {{0}, {0}, {0}, 0};
  int quiet = 0, json = 0;
  o.out_dir = "specseg_benchmark";
  char *usage = usage_text();
  if (!usage) return cli_error("out of memory");
  const cli_opt opts[] = {
      CLI_OPT_STR("--benchmark", &o.dir),
      CLI_OPT_STR("--out|-o", &o.out_dir),
      CLI_OPT_STR("--pairs", &o.pairs_file),
      CLI_OPT_INT("--max-pairs", &o.max_pairs, 1, 2000000000, "--max-pairs: positive integer"),
      CLI_OPT_UINT64("--seed", &o.seed, "--seed: non-negative integer"),
      CLI_OPT_CALL("--landmarks", take_landmarks, &o.landmarks, NULL),
      CLI_OPT_CALL("--maps", take_maps, &maps, NULL),
      CLI_OPT_FLAG("--no-match", &o.match, 0),
      CLI_OPT_STR("--cache", &o.cache_dir),
      CLI_OPT_INT("--jobs", &o.jobs, 1, 1024, "--jobs: positive integer"),
      CLI_OPT_SHARD(&o.shard_i, &o.shard_n),
      CLI_OPT_STR("--title", &title),
      CLI_OPT_FLAG("--quiet", &quiet, 1),
      CLI_OPT_FLAG("--json", &json, 1),
      CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, usage, opts);
  A.cmd = "eval --benchmark";
  int rc = cli_parse(&A);
  const int nmaps = maps.n;
  if (rc < 0) {
    const char *fold[3] = {o.dir, o.out_dir, o.cache_dir};
    if (!o.dir) rc = cli_bad(&A, "--benchmark DIR is required");
    else if (cli_count_std(fold, 3) || (o.pairs_file && cli_is_std(o.pairs_file)))
      rc = cli_bad(&A, "--benchmark, --out, --cache and --pairs take files or folders, not '-'");
    else if (!o.match && !nmaps) rc = cli_bad(&A, "--no-match needs at least one --maps NAME=MAPDIR");
  }
  if (rc >= 0) goto done;
  rc = SS_EXIT_OK;
  {
    o.nmaps = nmaps, o.map_names = maps.names, o.map_dirs = maps.dirs;
    char tbuf[256];
    if (!title) default_title(o.dir, tbuf, sizeof tbuf), title = tbuf;
    bench_out bo = {!quiet && isatty(2), quiet, 0};
    o.progress = bench_progress, o.log = bench_log, o.warn = bench_warn, o.user = &bo;
    ss_benchmark_info info;
    ss_error e;
    ss_status st = ss_benchmark_run(&o, &info, &e);
    if (bo.on_line) fputc('\n', stderr);
    if (st) {
      rc = cli_error("%s", e.msg);
      ss_benchmark_info_free(&info);
      goto done;
    }
    if (!quiet)
      fprintf(stderr, "eval: %d new rows (%d kept) in %.1f s -> %s\n", info.rows_new, info.rows_kept, info.seconds, o.out_dir);
    /* the summary of everything in pairs.csv (earlier runs' rows included) */
    char csv[4200];
    snprintf(csv, sizeof csv, "%s/pairs.csv", o.out_dir);
    ss_benchmark_row *rows = NULL;
    int n = 0;
    if (access(csv, F_OK) && info.pairs_shard == 0) {
      rc = cli_error("%s: shard %d/%d has no pairs (%d listed)", o.dir, o.shard_i + 1, o.shard_n, info.pairs_listed);
    } else if (ss_benchmark_csv_read(csv, &rows, &n, &e)) {
      rc = cli_error("%s", e.msg);
    } else {
      rc = finish(o.out_dir, rows, n, title, info.pairs_listed, info.nwarnings, info.warnings, json);
    }
    free(rows);
    ss_benchmark_info_free(&info);
  }
done:
  for (int i = 0; i < maps.n; i++) free(maps.args[i]);
  free(usage);
  return rc;
}

int cli_is_benchmark_csv(const char *path) {
  struct stat st;
  if (!stat(path, &st) && S_ISDIR(st.st_mode)) return 1;
  FILE *f = fopen(path, "rb");
  if (!f) return 0;
  char line[512] = "";
  if (!fgets(line, sizeof line, f)) line[0] = 0;
  fclose(f);
  return !strncmp(line, "method,x,y,", 11);
}

/* the "title" of a shard's summary.json (what this program wrote: {"title": "...", ...}) */
static void shard_title(const char *csv, char *t, size_t n) {
  char path[4200];
  snprintf(path, sizeof path, "%s", csv);
  char *s = strrchr(path, '/');
  if (s) snprintf(s + 1, sizeof path - (size_t)(s + 1 - path), "summary.json");
  else snprintf(path, sizeof path, "summary.json");
  FILE *f = fopen(path, "rb");
  if (!f) return;
  char buf[512] = "";
  size_t k = fread(buf, 1, sizeof buf - 1, f);
  fclose(f);
  buf[k] = 0;
  const char *p = strstr(buf, "{\"title\": \"");
  if (p != buf) return;
  p += 11;
  size_t j = 0;
  for (; *p && *p != '"' && j + 1 < n; p++) {
    if (*p == '\\' && p[1]) p++;
    t[j++] = *p;
  }
  if (*p == '"') t[j] = 0;
  else t[0] = 0;
}

/* the rows of the shards merged so far; the title from the first one's summary.json unless --title came
 * before it */
typedef struct shard_rows {
  ss_benchmark_row *all;
  int n, nin;
  const char **title;
  char *tbuf; /* 256 bytes */
} shard_rows;

/* a pairs.csv (or its shard folder) argument of eval merge: its rows appended */
static int merge_shard(cli_args *A, const cli_opt *o, const char *arg) {
  shard_rows *M = o->dest;
  ss_error e;
  if (cli_is_std(arg)) return cli_bad(A, "merge reads pairs.csv files, not standard input ('-')");
  char path[4200];
  struct stat st;
  if (!stat(arg, &st) && S_ISDIR(st.st_mode)) snprintf(path, sizeof path, "%s/pairs.csv", arg);
  else snprintf(path, sizeof path, "%s", arg);
  ss_benchmark_row *r;
  int m;
  if (ss_benchmark_csv_read(path, &r, &m, &e)) return cli_error("%s", e.msg);
  ss_benchmark_row *g = realloc(M->all, sizeof *M->all * (size_t)(M->n + m + 1));
  if (!g) { free(r); return cli_error("out of memory"); }
  M->all = g;
  if (m) memcpy(M->all + M->n, r, sizeof *r * (size_t)m);
  M->n += m;
  free(r);
  if (!M->nin++ && !*M->title) shard_title(path, M->tbuf, 256);
  return -1;
}

int cmd_eval_benchmark_merge(int argc, char **argv) {
  const char *out = NULL, *title = NULL;
  int json = 0, nin = 0, n = 0;
  ss_benchmark_row *all = NULL;
  char tbuf[256] = "";
  ss_error e;
  char *usage = usage_text();
  if (!usage) return cli_error("out of memory");
  shard_rows M = {NULL, 0, 0, &title, tbuf};
  const cli_opt opts[] = {CLI_OPT_POS_FN("CSV", merge_shard, &M), CLI_OPT_STR("--out|-o", &out),
                          CLI_OPT_STR("--title", &title), CLI_OPT_FLAG("--json", &json, 1), CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, usage, opts);
  A.cmd = "eval merge";
  int rc = cli_parse(&A);
  all = M.all, n = M.n, nin = M.nin;
  if (rc < 0 && !nin) rc = cli_bad(&A, "merge needs at least one pairs.csv (or shard folder)");
  if (rc < 0 && !out) rc = cli_bad(&A, "--out DIR: the folder of the merged pairs.csv, summary.json and curves.png");
  if (rc < 0 && cli_is_std(out)) rc = cli_bad(&A, "--out takes a folder, not '-'");
  if (rc >= 0) goto done;
  rc = SS_EXIT_OK;
  if (ss_benchmark_rows_canonical(all, &n, &e)) { rc = cli_error("%s", e.msg); goto done; }
  if (mkdir(out, 0755) && errno != EEXIST) { rc = cli_error("%s: cannot create: %s", out, strerror(errno)); goto done; }
  {
    char path[4200], tmp[4300];
    snprintf(path, sizeof path, "%s/pairs.csv", out);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "wb");
    if (!f) { rc = cli_error("%s: cannot write: %s", tmp, strerror(errno)); goto done; }
    fprintf(f, "%s\n", ss_benchmark_csv_header());
    char line[SS_BENCH_CSV_LINE];
    for (int i = 0; i < n; i++) {
      ss_benchmark_csv_format_row(&all[i], line, sizeof line);
      fprintf(f, "%s\n", line);
    }
    if (fclose(f) || rename(tmp, path)) { remove(tmp); rc = cli_error("%s: write error", path); goto done; }
    if (!json) fprintf(stdout, "merged %d rows from %d files into %s\n", n, nin, path);
  }
  rc = finish(out, all, n, title ? title : tbuf, -1, 0, NULL, json);
done:
  free(all);
  free(usage);
  return rc;
}

int cmd_eval_benchmark(int argc, char **argv) { return run_benchmark(argc, argv); }
