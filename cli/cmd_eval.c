/* specseg eval: reproduce the paper's evaluation (Table 1, §5 coherency, §5 timings, Figures 3, 9–11). */
#include "cli.h"
#include "cmd_eval_benchmark.h"
#include "specseg/eval.h"
#include "specseg/io.h"
#include "specseg/match.h"
#include "specseg/render.h"

#include <dirent.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

static const char USAGE[] =
    "usage: specseg eval --table1 --data DIR [--pairs N] [--seed S] [--out RESULTS.csv] [--jobs N]\n"
    "                    [--cache DIR] [--shard I/N] [--error-samples N] [--k K]\n"
    "                    [--policies random,subj,pose] [--landmarks best,gt,fps,none] [--methods std,asa,diff,refined]\n"
    "                    [--quiet] [--json]\n"
    "       specseg eval --table1 --manifest FILE [--out RESULTS.csv] [--landmarks best,gt,fps,none]\n"
    "                    [--pairing paper|confident] [--methods ...] [--cache DIR] [--shard I/N] ...\n"
    "       specseg eval merge CSV... [--out ALL.csv] [--manifest FILE]\n"
    "       specseg eval --benchmark DIR [--out OUTDIR] [--maps NAME=MAPDIR]... [--landmarks none|gt:N] ...\n"
    "                    (the field's benchmark, FAUST_r / TOSCA_r: options at the end)\n"
    "       specseg eval --coherency --data DIR [--jobs N]\n"
    "       specseg eval --timings --data DIR [--shapes N]\n"
    "       specseg eval --figures OUTDIR --data DIR [--landmarks best,gt,fps] [--pair X,Y | --candidates N]\n"
    "                    [--size WxH] [--gallery-count N | --gallery-only] [--seed S] [--k K] [--cache DIR]\n"
    "\n"
    "The paper's evaluation on the FAUST / TOSCA data under DIR: Table 1 (mean geodesic errors of STD,\n"
    "ASA and DIFF maps, one CSV row per map, resumable and shardable), the section 5 coherency and\n"
    "timings, Figures 3 and 9-11 as PNGs. One mode per run:\n"
    "  --table1            Table 1: rows appended to the CSV (rows already there are kept), then the table\n"
    "  --coherency         section 5 coherency of the segmentations, with and without streamlining\n"
    "  --timings           section 5 per-stage timings (medians over FAUST shapes)\n"
    "  --figures OUTDIR    Figure 3 (segment gallery) and Figures 9-11 (maps, BEST / GT / FPS landmarks)\n"
    "  merge CSV...        merge (shard) CSVs into one table\n"
    "Options:\n"
    "  --data DIR          the data folder, with faust/ (and tosca/) (required unless --manifest)\n"
    "  --manifest FILE     --table1 (and merge): any data set described by a manifest (its format:\n"
    "                      docs/evaluation.md) instead of FAUST: its groups, ground truth, landmarks and\n"
    "                      pairs; the table per group. Landmark\n"
    "                      sets: best = its landmark files, gt = FPS on each group's reference carried by\n"
    "                      the ground truth, fps = each mesh's own FPS (default: those it has)\n"
    "  --pairing RULE      segment pairing of the ASA / DIFF rows: paper (default, the paper's rule) or\n"
    "                      confident (the library's safeguards: ratio test, at least 4 landmarks, the\n"
    "                      STD map's check of each pair); use another --out for each rule\n"
    "  --out, -o FILE      --table1: the CSV, also the resume state (default specseg_table1.csv);\n"
    "                      merge: the merged CSV (default: none written; - writes it to standard output)\n"
    "  --pairs N           shape pairs per pairing policy, 1..900 (default 100)\n"
    "  --seed S            seed of the pair and FPS draws, >= 0 (default 1)\n"
    "  --jobs N            parallel work units, 1..1024 (default: the OpenMP default)\n"
    "  --cache DIR         cache per-shape preparations in DIR (default: in memory only)\n"
    "  --shard I/N         compute only the I-th of N interleaved parts, 1 <= I <= N (default 1/1)\n"
    "  --error-samples N   mean errors over N sampled vertices, 0..3000 (default 0: every vertex)\n"
    "  --k K               functional map basis size, 3..1000 (default 50)\n"
    "  --policies LIST     pairing policies, comma list of random,subj,pose (default all)\n"
    "  --landmarks LIST    landmark sets, comma list of best,gt,fps,none (default best,gt,fps; --figures:\n"
    "                      best). none: landmark-free rows (segments paired automatically, the paired\n"
    "                      centres as landmarks; 100 eigenpairs per shape) and the pairing's accuracy\n"
    "  --methods LIST      comma list of std,asa,diff (the paper's maps), refined (the default output of\n"
    "                      specseg match) (default std,asa,diff)\n"
    "  --quiet             no progress bar or stage messages\n"
    "  --shapes N          --timings: FAUST shapes to time, 1..100 (default 100)\n"
    "  --pair X,Y          --figures: this FAUST pair (shape numbers 0..99) instead of the showcase pair\n"
    "  --candidates N      --figures: the showcase pair of each map figure is the one of median error\n"
    "                      (mean of its STD, ASA and DIFF errors) among the first N pairs its policy\n"
    "                      draws under the seed, 1..100 (default 9; 1: the first pair drawn)\n"
    "  --json              --table1, --figures: a JSON summary on standard output (the table, or the\n"
    "                      figures with their pairs, rule and errors; output paths, seconds, errors)\n"
    "  --size WxH          --figures: panel size, 16..4096 each (default 360x720 gallery, 300x600 maps)\n"
    "  --gallery-count N   --figures: shapes in the gallery, 0..100 (default 10)\n"
    "  --gallery-only      --figures: the gallery only, no map figures\n"
    "\n";


/* the help text: the paper's evaluation, then the benchmark's (cmd_eval_benchmark.h) */
static const char *full_usage(void) {
  static char buf[sizeof USAGE + sizeof CLI_EVAL_BENCHMARK_HELP_TEXT];
  if (!buf[0]) snprintf(buf, sizeof buf, "%s%s", USAGE, CLI_EVAL_BENCHMARK_HELP_TEXT);
  return buf;
}

/* "a,b,c" of names → bit set; -1 on an unknown name */
static int parse_set(const char *s, int (*parse)(const char *)) {
  char buf[256];
  snprintf(buf, sizeof buf, "%s", s);
  int mask = 0;
  for (char *t = strtok(buf, ","); t; t = strtok(NULL, ",")) {
    int v = parse(t);
    if (v < 0) return -1;
    mask |= 1 << v;
  }
  return mask ? mask : -1;
}
static int parse_policy(const char *s) { return ss_pair_policy_parse(s); }
static int parse_lm(const char *s) { return ss_lm_set_parse(s); }
static int parse_method(const char *s) { return ss_eval_method_parse(s); }

/* --policies, --landmarks, --methods: a comma list into a bit set (given: set to 1, when not NULL) */
typedef struct set_opt {
  int *mask, *given;
  int (*parse)(const char *);
  const char *msg;
} set_opt;

static int take_set(cli_args *A, const cli_opt *o, const char *v) {
  const set_opt *s = o->dest;
  if (s->given) *s->given = 1;
  if ((*s->mask = parse_set(v, s->parse)) < 0) return cli_bad(A, "%s", s->msg);
  return -1;
}

/* --pair X,Y: two different FAUST shape numbers */
static int take_pair(cli_args *A, const cli_opt *o, const char *v) {
  char buf[64], *c;
  snprintf(buf, sizeof buf, "%s", v);
  if (!(c = strchr(buf, ','))) return cli_bad(A, "--pair: X,Y (FAUST shape numbers 0..99)");
  *c = 0;
  int *x = o->dest, *y = o->dest2;
  if (cli_parse_int(buf, 0, 99, x) || cli_parse_int(c + 1, 0, 99, y) || *x == *y)
    return cli_bad(A, "--pair: X,Y (two different FAUST shape numbers 0..99)");
  return -1;
}

/* Table 1 in the paper's layout, ours beside the paper's, the refined default's column when there
 * are such rows, and the ordering checks. */
static void print_table(const ss_table1 *t, FILE *f) {
  int ref = 0;
  for (int i = 0; i < 12; i++) ref += t->count[i][SS_METHOD_REFINED];
  fprintf(f, "\n%-17s %17s %17s %17s", "Table 1", "STD", "ASA", "DIFF");
  if (ref) fprintf(f, " %9s", "REFINED");
  fprintf(f, "  %5s  %s\n", "pairs", "checks");
  fprintf(f, "%-17s %17s %17s %17s%s\n", "scenario", "ours (paper)", "ours (paper)", "ours (paper)", ref ? "      ours" : "");
  for (int i = 0; i < 12; i++) {
    if (t->count[i][0] + t->count[i][1] + t->count[i][2] + t->count[i][3] == 0) continue;
    fprintf(f, "%-17s", ss_table1_row_names[i]);
    int n = 0;
    for (int c = 0; c < 3; c++) {
      if (t->count[i][c]) fprintf(f, "   %7.4f (%.3f)", t->mean[i][c], ss_table1_paper[i][c]);
      else fprintf(f, "   %7s (%.3f)", "-", ss_table1_paper[i][c]);
      if (t->count[i][c] > n) n = t->count[i][c];
    }
    if (ref) {
      if (t->count[i][3]) fprintf(f, "   %7.4f", t->mean[i][3]);
      else fprintf(f, "   %7s", "-");
      if (t->count[i][3] > n) n = t->count[i][3];
    }
    fprintf(f, "  %5d", n);
    if (t->count[i][0] && t->count[i][1] && t->count[i][2]) {
      const double *m = t->mean[i];
      fprintf(f, "  %s%s", m[2] <= m[1] && m[1] <= m[0] ? "DIFF<=ASA<=STD" : "order differs",
              (i % 3 != 2) ? (m[2] <= 0.8 * m[0] ? ", DIFF<=0.8STD" : ", DIFF>0.8STD") : "");
    }
    if (t->count[i][0] && t->count[i][2] && t->count[i][3]) {
      const double *m = t->mean[i];
      fprintf(f, "%s%s", t->count[i][1] ? ", " : "  ", m[3] <= fmin(m[0], m[2]) ? "REFINED<=min(STD,DIFF)" : "REFINED>min(STD,DIFF)");
    }
    fputc('\n', f);
  }
}

/* The landmark-free rows (landmark set "none"), when there are any. */
static void print_none_table(const ss_eval_row *rows, int n, FILE *f) {
  ss_table1_none t;
  if (ss_table1_none_aggregate(rows, n, &t, NULL)) return;
  if (!t.pairs[0] && !t.pairs[1] && !t.pairs[2]) return;
  static const char *names[4] = {"FAUST NONE", "FAUST subj NONE", "FAUST pose NONE", "FAUST sym NONE"};
  fprintf(f, "\n%-17s %9s %9s %9s %9s  %5s  %s\n", "landmark-free", "STD", "ASA", "DIFF", "REFINED", "pairs",
          "segment pairing: all right / up to the mirror");
  for (int i = 0; i < 4; i++) {
    if (t.count[i][0] + t.count[i][1] + t.count[i][2] + t.count[i][3] == 0) continue;
    fprintf(f, "%-17s", names[i]);
    int np = 0;
    for (int c = 0; c < SS_EVAL_NMETHODS; c++) {
      if (t.count[i][c]) fprintf(f, " %9.4f", t.mean[i][c]);
      else fprintf(f, " %9s", "-");
      if (t.count[i][c] > np) np = t.count[i][c];
    }
    fprintf(f, "  %5d", np);
    if (i < 3 && t.all_right[i] == t.all_right[i])
      fprintf(f, "  %5.1f%% / %5.1f%%", 100 * t.all_right[i], 100 * t.mirror_right[i]);
    fputc('\n', f);
  }
}

/* A manifest's table: per group and landmark set, the methods' mean errors (and symmetric ones when
 * the group has symmetry maps), and the DIFF <= 1.02 STD check. */
static int print_manifest_table(const ss_manifest *m, const ss_eval_row *rows, int n, FILE *f) {
  const int NM = SS_EVAL_NMETHODS, cells = m->ngroups * 4 * NM;
  double *mean = malloc(sizeof(double) * (size_t)cells), *msym = malloc(sizeof(double) * (size_t)cells);
  int *count = malloc(sizeof(int) * (size_t)cells);
  ss_error e;
  if (!mean || !msym || !count) { free(mean), free(msym), free(count); return cli_error("out of memory"); }
  if (ss_manifest_aggregate(m, rows, n, mean, msym, count, &e)) {
    free(mean), free(msym), free(count);
    return cli_error("%s", e.msg);
  }
  fprintf(f, "\n%-20s %-5s %9s %9s %9s %9s  %5s  %s\n", "group", "lm", "STD", "ASA", "DIFF", "REFINED", "pairs", "checks");
  for (int g = 0; g < m->ngroups; g++)
    for (int l = 0; l < 4; l++) {
      const int *c = count + (g * 4 + l) * NM;
      const double *a = mean + (g * 4 + l) * NM;
      int np = 0;
      for (int k = 0; k < NM; k++) np = c[k] > np ? c[k] : np;
      if (!np) continue;
      for (int sy = 0; sy < 1 + (m->groups[g].symmetry != NULL); sy++) {
        const double *v = sy ? msym + (g * 4 + l) * NM : a;
        char name[40];
        snprintf(name, sizeof name, "%.15s%s", m->groups[g].name, sy ? " sym" : "");
        fprintf(f, "%-20s %-5s", name, ss_lm_set_name((ss_lm_set)l));
        for (int k = 0; k < NM; k++)
          if (c[k]) fprintf(f, " %9.4f", v[k]);
          else fprintf(f, " %9s", "-");
        fprintf(f, "  %5d", np);
        if (c[SS_METHOD_STD] && c[SS_METHOD_DIFF])
          fprintf(f, "  DIFF/STD %.3f%s", v[SS_METHOD_DIFF] / v[SS_METHOD_STD],
                  v[SS_METHOD_DIFF] <= 1.02 * v[SS_METHOD_STD] ? "" : " (> 1.02)");
        if (c[SS_METHOD_STD] && c[SS_METHOD_REFINED])
          fprintf(f, "%sREFINED/STD %.3f", c[SS_METHOD_DIFF] ? ", " : "  ", v[SS_METHOD_REFINED] / v[SS_METHOD_STD]);
        fputc('\n', f);
      }
    }
  free(mean), free(msym), free(count);
  return SS_EXIT_OK;
}


/* The table as a JSON array: one object per scenario with rows (ours, the paper's, the pair count;
 * the refined method has no paper value). */
static void json_table(const ss_table1 *t, cli_job *J) {
  char *buf = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  if (!f) return;
  static const char *const M[SS_EVAL_NMETHODS] = {"std", "asa", "diff", "refined"};
  fputc('[', f);
  int first = 1;
  for (int i = 0; i < 12; i++) {
    int any = 0;
    for (int c = 0; c < SS_EVAL_NMETHODS; c++) any += t->count[i][c];
    if (!any) continue;
    fprintf(f, "%s{\"scenario\": ", first ? "" : ", ");
    first = 0;
    cli_json_str(f, ss_table1_row_names[i]);
    for (int c = 0; c < SS_EVAL_NMETHODS; c++) {
      fprintf(f, ", \"%s\": ", M[c]);
      if (t->count[i][c]) cli_json_num(f, t->mean[i][c]);
      else fputs("null", f);
      fprintf(f, ", \"%s_pairs\": %d", M[c], t->count[i][c]);
      if (c < 3) { /* the paper has no refined column */
        fprintf(f, ", \"%s_paper\": ", M[c]);
        cli_json_num(f, ss_table1_paper[i][c]);
      }
    }
    fputc('}', f);
  }
  fputc(']', f);
  fclose(f);
  cli_job_json(J, "table", buf);
  free(buf);
}

static int print_csv_table(const char *path, const ss_manifest *man, cli_job *J) {
  ss_eval_row *rows;
  int n;
  ss_error e;
  if (ss_eval_csv_read(path, &rows, &n, &e)) return cli_error("%s", e.msg);
  if (man) {
    int rc = print_manifest_table(man, rows, n, stdout);
    free(rows);
    return rc;
  }
  ss_table1 t;
  ss_status st = ss_table1_aggregate(rows, n, &t, &e);
  if (st) {
    free(rows);
    return cli_error("%s", e.msg);
  }
  if (J) {
    cli_job_int(J, "rows", n);
    json_table(&t, J);
  } else {
    print_table(&t, stdout);
    print_none_table(rows, n, stdout);
  }
  free(rows);
  return SS_EXIT_OK;
}

/* the rows of the CSVs merged so far */
typedef struct merge_rows {
  ss_eval_row *all;
  int n, nin;
} merge_rows;

/* a CSV argument of eval merge: its rows appended */
static int merge_csv(cli_args *A, const cli_opt *o, const char *path) {
  merge_rows *M = o->dest;
  ss_error e;
  if (cli_is_std(path)) return cli_bad(A, "merge reads CSV files, not standard input ('-')");
  ss_eval_row *r;
  int m;
  if (ss_eval_csv_read(path, &r, &m, &e)) return cli_error("%s", e.msg);
  ss_eval_row *g = realloc(M->all, sizeof *M->all * (size_t)(M->n + m + 1));
  if (!g) { free(r); return cli_error("out of memory"); }
  M->all = g;
  if (m) memcpy(M->all + M->n, r, sizeof *r * (size_t)m);
  M->n += m;
  M->nin++;
  free(r);
  return -1;
}

static int cmd_merge(int argc, char **argv) {
  const char *out = NULL, *mpath = NULL;
  merge_rows M = {NULL, 0, 0};
  ss_error e;
  const cli_opt opts[] = {CLI_OPT_POS_FN("CSV", merge_csv, &M), CLI_OPT_STR("--out|-o", &out),
                          CLI_OPT_STR("--manifest", &mpath), CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, full_usage(), opts);
  A.cmd = "eval merge";
  int rc = cli_parse(&A);
  ss_eval_row *all = M.all;
  int n = M.n, nin = M.nin;
  if (rc >= 0) { free(all); return rc; }
  if (!nin) { free(all); return cli_bad(&A, "merge needs at least one CSV"); }
  if (ss_eval_rows_canonical(all, &n, &e)) { free(all); return cli_error("%s", e.msg); }
  FILE *report = cli_is_std(out) ? stderr : stdout; /* the table beside a CSV on stdout goes to stderr */
  if (out) {
    FILE *f = cli_open_out(out);
    if (!f) { free(all); return cli_error("%s: cannot write: %s", out, strerror(errno)); }
    fprintf(f, "%s\n", ss_eval_csv_header());
    char line[512];
    for (int i = 0; i < n; i++) {
      ss_eval_csv_format_row(&all[i], line, sizeof line);
      fprintf(f, "%s\n", line);
    }
    if (cli_close_out(f)) { free(all); return cli_error("%s: write error: %s", cli_out_name(out), strerror(errno)); }
  }
  ss_table1 t;
  ss_status st = ss_table1_aggregate(all, n, &t, &e);
  if (st) {
    free(all);
    return cli_error("%s", e.msg);
  }
  fprintf(report, "merged %d rows from %d files%s%s\n", n, nin, out ? " into " : "", out ? cli_out_name(out) : "");
  rc = SS_EXIT_OK;
  if (mpath) {
    ss_manifest man;
    if (ss_manifest_read(mpath, &man, &e)) rc = cli_error("%s", e.msg);
    else rc = print_manifest_table(&man, all, n, report), ss_manifest_free(&man);
  } else {
    print_table(&t, report);
    print_none_table(all, n, report);
  }
  free(all);
  return rc;
}

/* ---- §5 coherency ------------------------------------------------------------------------------ */

static int name_cmp(const void *a, const void *b) {
  const char *x = *(const char *const *)a, *y = *(const char *const *)b;
  /* class prefix, then the number: cat2 < cat10 */
  size_t i = 0;
  while (x[i] && x[i] == y[i] && !(x[i] >= '0' && x[i] <= '9')) i++;
  if ((x[i] >= '0' && x[i] <= '9') && (y[i] >= '0' && y[i] <= '9')) {
    long p = strtol(x + i, NULL, 10), q = strtol(y + i, NULL, 10);
    if (p != q) return p < q ? -1 : 1;
  }
  return strcmp(x, y);
}

static void print_coherency(const ss_coherency_result *r) {
  printf("%-9s %3d shapes  coherency with streamlining %.3f (min %.3f)   without %.3f (min %.3f)\n", r->name,
         r->nshapes, r->coherency[0], r->min_coherency[0], r->coherency[1], r->min_coherency[1]);
  for (int w = 0; w < 2; w++) {
    printf("          segments %s:", w ? "without" : "with   ");
    for (int k = 0; k < 32; k++)
      if (r->hist[w][k]) printf(" %d%s x%d", k, k == 31 ? "+" : "", r->hist[w][k]);
    putchar('\n');
  }
}

static int run_coherency(const char *dir, int jobs) {
  char path[4096];
  ss_error e;
  /* FAUST: X0 = tr_reg_000 */
  char *fp[100];
  int nf = 0;
  for (int i = 0; i < 100; i++) {
    snprintf(path, sizeof path, "%s/faust/tr_reg_%03d.off", dir, i);
    if (access(path, R_OK)) break;
    fp[nf++] = strdup(path);
  }
  printf("§5 coherency (X0 = first shape of each set; paper FAUST: 0.92 with streamlining, 0.68 without)\n");
  int rc = SS_EXIT_OK;
  if (nf >= 2) {
    ss_coherency_result r;
    if (ss_eval_coherency_set("faust", nf, (const char *const *)fp, jobs, &r, &e)) rc = cli_error("%s", e.msg);
    else print_coherency(&r);
  } else cli_warn("no FAUST shapes under %s/faust", dir);
  for (int i = 0; i < nf; i++) free(fp[i]);
  /* TOSCA: one set per class (file name without its number), X0 = the lowest number */
  snprintf(path, sizeof path, "%s/tosca", dir);
  DIR *d = opendir(path);
  if (!d) { cli_warn("no TOSCA folder %s", path); return rc; }
  char *names[512];
  int nn = 0;
  struct dirent *de;
  while ((de = readdir(d)) && nn < 512) {
    size_t L = strlen(de->d_name);
    if (L > 4 && !strcmp(de->d_name + L - 4, ".off")) names[nn++] = strdup(de->d_name);
  }
  closedir(d);
  qsort(names, (size_t)nn, sizeof *names, name_cmp);
  for (int i = 0; i < nn;) {
    char cls[64];
    size_t L = strcspn(names[i], "0123456789.");
    snprintf(cls, sizeof cls, "%.*s", (int)L, names[i]);
    int j = i;
    char *paths[512];
    while (j < nn && strcspn(names[j], "0123456789.") == L && !strncmp(names[j], cls, L)) {
      char p2[4200];
      snprintf(p2, sizeof p2, "%s/tosca/%s", dir, names[j]);
      paths[j - i] = strdup(p2);
      j++;
    }
    if (j - i >= 2) {
      ss_coherency_result r;
      if (ss_eval_coherency_set(cls, j - i, (const char *const *)paths, jobs, &r, &e)) cli_warn("%s: %s", cls, e.msg);
      else print_coherency(&r);
    }
    for (int k = 0; k < j - i; k++) free(paths[k]);
    i = j;
  }
  for (int i = 0; i < nn; i++) free(names[i]);
  return rc;
}

/* ---- §5 timings -------------------------------------------------------------------------------- */

static int dbl_cmp(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}
static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, dbl_cmp);
  return n ? (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2])) : NAN;
}

static int run_timings(const char *dir, int nshapes) {
  char path[4096];
  ss_error e;
  int *lm = NULL, nlm = 0;
  snprintf(path, sizeof path, "%s/faust/landmarks_best.txt", dir);
  if (ss_read_ints(path, &lm, &nlm, &e)) return cli_error("%s", e.msg);
  double *t[5], *pcpu = calloc((size_t)nshapes, sizeof(double));
  for (int k = 0; k < 5; k++) t[k] = calloc((size_t)nshapes, sizeof(double));
  ss_segmentation prev;
  memset(&prev, 0, sizeof prev);
  ss_mesh mprev = {0};
  int n = 0, np = 0, rc = SS_EXIT_OK;
  for (int i = 0; i < nshapes; i++) {
    snprintf(path, sizeof path, "%s/faust/tr_reg_%03d.off", dir, i);
    ss_mesh m = {0};
    ss_segmentation s;
    clock_t c0 = clock();
    if (ss_read_mesh(path, &m, &e) || ss_segment(&m, NULL, &s, &e)) {
      rc = cli_error("%s", e.msg);
      ss_mesh_free(&m);
      break;
    }
    t[0][n] = s.t_smooth;
    t[1][n] = s.t_remesh + s.t_psi;
    t[2][n] = s.t_spectrum + s.t_critical + s.t_ivd;
    t[4][n] = (double)(clock() - c0) / CLOCKS_PER_SEC;
    n++;
    if (i > 0) { /* pairing with the previous shape, BEST landmarks (fields on both work meshes) */
      ss_segment_pairs pr;
      double t0 = ss_time();
      clock_t c1 = clock();
      if (ss_pair_segments(&prev, &s, nlm, lm, lm, &pr, &e)) rc = cli_error("%s", e.msg);
      else t[3][np] = ss_time() - t0, pcpu[np++] = (double)(clock() - c1) / CLOCKS_PER_SEC, ss_segment_pairs_free(&pr);
    }
    ss_segmentation_free(&prev);
    ss_mesh_free(&mprev);
    prev = s;
    mprev = m;
    fprintf(stderr, "\r  timings: %d/%d shapes", i + 1, nshapes);
  }
  fputc('\n', stderr);
  ss_segmentation_free(&prev);
  ss_mesh_free(&mprev);
  static const char *names[4] = {"CMCF", "remeshing (+ Psi)", "Fiedler + critical + iVd", "pairing"};
  static const double paper[4] = {0.14, 0.84, 0.36, 0.57};
  printf("§5 per-stage timings, medians over %d FAUST shapes (%d pairings)\n", n, np);
  printf("%-26s %9s %9s %7s\n", "stage", "ours [s]", "paper [s]", "ratio");
  double tot = 0, ptot = 0;
  for (int k = 0; k < 4; k++) {
    double med = median(t[k], k == 3 ? np : n);
    tot += med, ptot += paper[k];
    printf("%-26s %9.3f %9.2f %7.2f\n", names[k], med, paper[k], paper[k] / med);
  }
  double seg = tot - median(t[3], np);
  printf("%-26s %9.3f %9.2f %7.2f   (the paper's 1.34 s: the first three stages)\n", "segmentation", seg, 1.34,
         1.34 / seg);
  printf("%-26s %9.3f %9.2f %7.2f   (ratio = paper / ours; wall clock, noisy on a shared machine)\n", "with pairing",
         tot, ptot, ptot / tot);
  printf("process CPU medians: segmentation %.3f s, pairing %.3f s (all threads; on a busy machine a better guide)\n",
         median(t[4], n), median(pcpu, np));
  for (int k = 0; k < 5; k++) free(t[k]);
  free(pcpu);
  free(lm);
  return rc;
}

/* ---- Figures 3 and 9–11 ------------------------------------------------------------------------ */

static double cpu_now(void) { return (double)clock() / CLOCKS_PER_SEC; }

/* Figure 3 (gallery), then one map figure per landmark set: Figure 9 (BEST), 10 (GT), 11 (FPS), each
 * for the showcase pair of the policy the paper's figure shows (random, subj, pose): the median-score
 * pair of the first `ncand` pairs that policy draws under the seed (ss_eval_showcase_pair), unless
 * --pair fixes it. With json, a JSON summary instead of the lines. */
static int run_figures(const char *data, const char *outdir, const char *cache, int lm_mask, int px, int py,
                       int width, int height, int gallery, int maps, uint64_t seed, int k, int ncand, int json) {
  if (mkdir(outdir, 0755) && errno != EEXIST) return cli_error("%s: cannot create: %s", outdir, strerror(errno));
  char path[4096];
  ss_error e;
  ss_render_options ro;
  ss_render_default_options(&ro);
  cli_job J;
  cli_job_begin(&J, NULL);
  FILE *rep = json ? stderr : stdout;
  char *fj = NULL;
  size_t fjn = 0;
  FILE *figs = open_memstream(&fj, &fjn); /* the "figures" array of the JSON */
  if (!figs) return cli_job_end(&J, "eval", cli_error("out of memory"), json);
  fputc('[', figs);
  int nfig = 0, rc = SS_EXIT_OK;
  if (gallery > 0) {
    ro.width = width > 0 ? width : 360, ro.height = height > 0 ? height : 720;
    snprintf(path, sizeof path, "%s/faust_gallery.png", outdir);
    int seg[100];
    double c0 = cpu_now(), t0 = ss_time();
    if (ss_eval_faust_gallery(data, gallery, &ro, path, seg, &e)) { rc = cli_error("%s", e.msg); goto done; }
    fprintf(rep, "%s: Figure 3, segmentations of tr_reg_000..%03d, segments", path, gallery - 1);
    for (int i = 0; i < gallery; i++) fprintf(rep, " %d", seg[i]);
    fprintf(rep, " (%.1f s CPU, %.1f s)\n", cpu_now() - c0, ss_time() - t0);
    fflush(rep);
    cli_job_output(&J, path, NULL);
    fprintf(figs, "%s{\"figure\": 3, \"path\": ", nfig++ ? ", " : "");
    cli_json_str(figs, path);
    fprintf(figs, ", \"segments\": [");
    for (int i = 0; i < gallery; i++) fprintf(figs, "%s%d", i ? ", " : "", seg[i]);
    fprintf(figs, "]}");
  }
  if (!maps) goto done;
  static const int figno[3] = {9, 10, 11};
  static const ss_pair_policy policy[3] = {SS_POLICY_RANDOM, SS_POLICY_SUBJ, SS_POLICY_POSE};
  ro.width = width > 0 ? width : 300, ro.height = height > 0 ? height : 600;
  for (int l = 0; l < 3; l++) {
    if (!(lm_mask >> l & 1)) continue;
    int x = px, y = py, pick = -1, cx[100], cy[100];
    double sc[100];
    char rule[160];
    double c0 = cpu_now(), t0 = ss_time();
    if (x < 0) {
      if (ss_eval_showcase_pair(data, cache, seed, k, (ss_lm_set)l, policy[l], ncand, &x, &y, &pick, cx, cy, sc, &e)) {
        rc = cli_error("%s", e.msg);
        goto done;
      }
      if (ncand > 1)
        snprintf(rule, sizeof rule, "%s pair of median error (mean of STD/ASA/DIFF) among the first %d drawn, #%d",
                 ss_pair_policy_name(policy[l]), ncand, pick + 1);
      else
        snprintf(rule, sizeof rule, "first %s pair drawn", ss_pair_policy_name(policy[l]));
    } else {
      snprintf(rule, sizeof rule, "given pair");
    }
    snprintf(path, sizeof path, "%s/figure%d_%03d_%03d.png", outdir, figno[l], x, y);
    ss_map_figure f;
    if (ss_eval_map_figure(data, cache, seed, k, l, x, y, &ro, path, &f, &e)) { rc = cli_error("%s", e.msg); goto done; }
    fprintf(rep, "%s: Figure %d, FAUST %s landmarks, %s: tr_reg_%03d -> tr_reg_%03d: mean error STD %.4f ASA %.4f "
                 "DIFF %.4f; %d of %d/%d segments paired (%d right); heat scale 0..%g (%.1f s CPU, %.1f s)\n",
            path, figno[l], ss_lm_set_name((ss_lm_set)l), rule, x, y, f.mean_error[0], f.mean_error[1], f.mean_error[2],
            f.paired, f.segments_x, f.segments_y, f.paired_right, f.error_scale, cpu_now() - c0, ss_time() - t0);
    if (pick >= 0 && ncand > 1) {
      fprintf(rep, "  candidates (x -> y: mean error):");
      for (int c = 0; c < ncand; c++) fprintf(rep, " %d->%d: %.4f%s", cx[c], cy[c], sc[c], c == pick ? " *" : "");
      fputc('\n', rep);
    }
    fflush(rep);
    cli_job_output(&J, path, NULL);
    fprintf(figs, "%s{\"figure\": %d, \"path\": ", nfig++ ? ", " : "", figno[l]);
    cli_json_str(figs, path);
    fprintf(figs, ", \"landmarks\": \"%s\", \"x\": %d, \"y\": %d, \"rule\": ", ss_lm_set_name((ss_lm_set)l), x, y);
    cli_json_str(figs, rule);
    fprintf(figs, ", \"mean_error\": {\"std\": ");
    cli_json_num(figs, f.mean_error[0]);
    fprintf(figs, ", \"asa\": ");
    cli_json_num(figs, f.mean_error[1]);
    fprintf(figs, ", \"diff\": ");
    cli_json_num(figs, f.mean_error[2]);
    fprintf(figs, "}, \"paired\": %d, \"paired_right\": %d", f.paired, f.paired_right);
    if (pick >= 0 && ncand > 1) {
      fprintf(figs, ", \"candidates\": [");
      for (int c = 0; c < ncand; c++) {
        fprintf(figs, "%s{\"x\": %d, \"y\": %d, \"score\": ", c ? ", " : "", cx[c], cy[c]);
        cli_json_num(figs, sc[c]);
        fputc('}', figs);
      }
      fputc(']', figs);
    }
    fputc('}', figs);
  }
done:
  fputc(']', figs);
  fclose(figs);
  cli_job_json(&J, "figures", fj);
  free(fj);
  return cli_job_end(&J, "eval", rc, json);
}

/* The progress bar on a terminal and the stage messages of a Table 1 run (the library prints nothing). */
typedef struct eval_output {
  int bar;     /* draw the bar (stderr is a terminal) */
  int on_line; /* the cursor is on a bar line */
} eval_output;

static void eval_progress(void *user, const ss_table1_progress *p) {
  eval_output *out = user;
  if (!out->bar) return;
  double el = p->seconds;
  if (p->shapes_done < p->shapes_total) {
    fprintf(stderr, "\r  preparing shapes %d/%d  %.0fs      ", p->shapes_done, p->shapes_total, el);
  } else {
    char eta[32] = "--", bar[64];
    if (p->rows_done > 0) {
      double r = el / p->rows_done * (p->rows_total - p->rows_done);
      snprintf(eta, sizeof eta, "%dm%02ds", (int)(r / 60), (int)fmod(r, 60));
    }
    int w = 30, fill = p->rows_total ? (int)(w * p->rows_done / p->rows_total) : w;
    for (int i = 0; i < w; i++) bar[i] = i < fill ? '#' : '.';
    bar[w] = 0;
    fprintf(stderr, "\r  [%s] %ld/%ld rows  %.0fs elapsed  ETA %s   ", bar, p->rows_done, p->rows_total, el, eta);
  }
  out->on_line = 1;
  fflush(stderr);
}

static void eval_log(void *user, const char *line) {
  eval_output *out = user;
  fprintf(stderr, "%s%s\n", out->on_line ? "\n" : "", line);
  out->on_line = 0;
}

static int run_table1(ss_table1_options *o, int quiet, const ss_manifest *man, int json) {
#ifdef __GLIBC__
  /* every match allocates and frees tens of MB of probe / operator buffers: keep them in the heap
   * instead of mmap/munmap-ing them each time (page faults were ~20 % of the run's CPU) */
  mallopt(M_MMAP_THRESHOLD, 512 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
  eval_output eo = {!quiet && isatty(2), 0};
  if (!quiet) {
    o->progress = eval_progress;
    o->log = eval_log;
    o->user = &eo;
  }
  ss_error e;
  int nnew = 0;
  double t0 = ss_time();
  ss_status st = ss_table1_run(o, &nnew, &e);
  if (eo.on_line) fputc('\n', stderr);
  if (st) return cli_error("%s", e.msg);
  if (!quiet) fprintf(stderr, "eval: %d new rows in %.1f s -> %s\n", nnew, ss_time() - t0, o->out_csv);
  if (!json || man) return print_csv_table(o->out_csv, man, NULL);
  cli_job J;
  cli_job_begin(&J, NULL);
  cli_job_output(&J, o->out_csv, NULL);
  cli_job_int(&J, "new_rows", nnew);
  cli_job_num(&J, "t_run", ss_time() - t0);
  return cli_job_end(&J, "eval", print_csv_table(o->out_csv, NULL, &J), 1);
}

/* --table1 --manifest: the landmark sets default to those the manifest has (best only when every
 * mesh has landmark files) */
static int run_manifest(ss_table1_options *o, const char *path, int lm_given, int quiet, int json) {
  ss_manifest man;
  ss_error e;
  if (o->cache_dir && cli_is_std(o->cache_dir)) return cli_error("--cache takes a folder, not '-'");
  if (cli_is_std(o->out_csv)) return cli_error("--out: the Table 1 CSV is also the resume state and is read back; give a file name");
  if (ss_manifest_read(path, &man, &e)) return cli_error("%s", e.msg);
  if (!lm_given) {
    int best = 1;
    for (int i = 0; i < man.nmeshes; i++) best &= man.meshes[i].landmarks || man.groups[man.meshes[i].group].landmarks;
    o->lm_mask = (best ? 1 << SS_LM_BEST : 0) | 1 << SS_LM_GT | 1 << SS_LM_FPS;
  }
  o->manifest = &man;
  int rc = run_table1(o, quiet, &man, json);
  ss_manifest_free(&man);
  return rc;
}

/* eval merge of benchmark shards: a folder argument, or a CSV with the benchmark's header (option
 * values skipped) */
static int merge_is_benchmark(int argc, char **argv) {
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "--out") || !strcmp(a, "-o") || !strcmp(a, "--manifest") || !strcmp(a, "--title")) {
      i++;
      continue;
    }
    if (a[0] == '-' && a[1]) continue;
    if (cli_is_benchmark_csv(a)) return 1;
  }
  return 0;
}

int cmd_eval(int argc, char **argv) {
  if (argc >= 2 && !strcmp(argv[1], "merge"))
    return merge_is_benchmark(argc - 1, argv + 1) ? cmd_eval_benchmark_merge(argc - 1, argv + 1) : cmd_merge(argc - 1, argv + 1);
  for (int i = 1; i < argc; i++)
    if (!strcmp(argv[i], "--benchmark") || !strncmp(argv[i], "--benchmark=", 12)) return cmd_eval_benchmark(argc, argv);
  const char *usage = full_usage();
  ss_table1_options o;
  ss_table1_default_options(&o);
  o.out_csv = "specseg_table1.csv";
  int table1 = 0, coherency = 0, timings = 0, quiet = 0, nshapes = 100, json = 0;
  const char *figures = NULL;
  int lm_given = 0, pair_x = -1, pair_y = -1, fig_w = 0, fig_h = 0, gallery = 10, gallery_only = 0, ncand = 9;
  const char *mpath = NULL;
  set_opt sets[3] = {{&o.policies_mask, NULL, parse_policy, "--policies: comma list of random,subj,pose"},
                     {&o.lm_mask, &lm_given, parse_lm, "--landmarks: comma list of best,gt,fps,none"},
                     {&o.methods_mask, NULL, parse_method, "--methods: comma list of std,asa,diff,refined"}};
  const cli_opt opts[] = {
      CLI_OPT_FLAG("--table1", &table1, 1),
      CLI_OPT_FLAG("--coherency", &coherency, 1),
      CLI_OPT_FLAG("--timings", &timings, 1),
      CLI_OPT_FLAG("--quiet", &quiet, 1),
      CLI_OPT_FLAG("--json", &json, 1),
      CLI_OPT_STR("--figures", &figures),
      CLI_OPT_FLAG("--gallery-only", &gallery_only, 1),
      CLI_OPT_INT("--candidates", &ncand, 1, 100, "--candidates: integer in [1,100]"),
      CLI_OPT_INT("--gallery-count", &gallery, 0, 100, "--gallery-count: integer in [0,100]"),
      CLI_OPT_CALL("--pair", take_pair, &pair_x, &pair_y),
      CLI_OPT_WXH("--size", &fig_w, &fig_h, 16, 4096, "--size: WxH per panel, each between 16 and 4096"),
      CLI_OPT_STR("--data", &o.data_dir),
      CLI_OPT_STR("--manifest", &mpath),
      CLI_OPT_CHOICE("--pairing", &o.confident_pairing, "paper|confident", NULL, "--pairing: paper or confident"),
      CLI_OPT_STR("--out|-o", &o.out_csv),
      CLI_OPT_STR("--cache", &o.cache_dir),
      CLI_OPT_INT("--pairs", &o.npairs, 1, 900, "--pairs: integer in [1,900]"),
      CLI_OPT_INT("--jobs", &o.jobs, 1, 1024, "--jobs: positive integer"),
      CLI_OPT_INT("--k", &o.k, 3, 1000, "--k: integer in [3,1000]"),
      CLI_OPT_INT("--shapes", &nshapes, 1, 100, "--shapes: integer in [1,100]"),
      CLI_OPT_INT("--error-samples", &o.error_samples, 0, 3000, "--error-samples: integer in [0,3000] (0 = every vertex)"),
      CLI_OPT_UINT64("--seed", &o.seed, "--seed: non-negative integer"),
      CLI_OPT_SHARD(&o.shard_i, &o.shard_n),
      CLI_OPT_CALL("--policies", take_set, &sets[0], NULL),
      CLI_OPT_CALL("--landmarks", take_set, &sets[1], NULL),
      CLI_OPT_CALL("--methods", take_set, &sets[2], NULL),
      CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, usage, opts);
  int rc = cli_parse(&A);
  if (rc >= 0) return rc;
  if (table1 + coherency + timings + !!figures != 1)
    return cli_bad(&A, "choose one of --table1, --coherency, --timings, --figures");
  if (mpath && !table1) return cli_bad(&A, "--manifest works with --table1 (and merge)");
  if (mpath && o.data_dir) return cli_bad(&A, "--manifest and --data: one data set per run");
  if (!o.data_dir && !mpath) return cli_bad(&A, "--data DIR (or --manifest FILE) is required");
  if (mpath && cli_is_std(mpath)) return cli_bad(&A, "--manifest: a file (its folder anchors the paths in it), not '-'");
  if (json && !table1 && !figures) return cli_bad(&A, "--json is for --table1 and --figures");
  if (mpath && json) return cli_bad(&A, "--json: not with --manifest (its per-group table is text only)");
  if (mpath) return run_manifest(&o, mpath, lm_given, quiet, json);
  const char *dirs[3] = {o.data_dir, figures, o.cache_dir};
  if (cli_count_std(dirs, 3)) return cli_bad(&A, "--data, --figures and --cache take folders, not '-'");
  if (table1 && cli_is_std(o.out_csv))
    return cli_bad(&A, "--out: the Table 1 CSV is also the resume state and is read back; give a file name");
  if (figures) /* map figures: BEST (Figure 9) unless --landmarks says otherwise */
    return run_figures(o.data_dir, figures, o.cache_dir, lm_given ? o.lm_mask : 1 << SS_LM_BEST, pair_x, pair_y, fig_w,
                       fig_h, gallery_only && gallery == 0 ? 10 : gallery, !gallery_only, o.seed, o.k, ncand, json);
  if (coherency) return run_coherency(o.data_dir, o.jobs);
  if (timings) return run_timings(o.data_dir, nshapes);
  return run_table1(&o, quiet, NULL, json);
}
