/* The results CSV of `specseg eval --table1` and the Table 1 aggregation. */
#include "specseg/eval.h"
#include "util/c_locale.h"
#include "csv_file.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const lm_names[4] = {"best", "gt", "fps", "none"};
static const char *const method_names[SS_EVAL_NMETHODS] = {"std", "asa", "diff", "refined"};

const char *ss_lm_set_name(ss_lm_set s) { return (unsigned)s < 4 ? lm_names[s] : "?"; }
const char *ss_eval_method_name(ss_eval_method m) { return (unsigned)m < SS_EVAL_NMETHODS ? method_names[m] : "?"; }
int ss_lm_set_parse(const char *s) {
  for (int i = 0; i < 4; i++)
    if (s && !strcmp(s, lm_names[i])) return i;
  return -1;
}
int ss_eval_method_parse(const char *s) {
  for (int i = 0; i < SS_EVAL_NMETHODS; i++)
    if (s && !strcmp(s, method_names[i])) return i;
  return -1;
}

const double ss_table1_paper[12][3] = {
    {0.027, 0.027, 0.020}, {0.032, 0.030, 0.026}, {0.189, 0.190, 0.188}, /* FAUST */
    {0.018, 0.018, 0.014}, {0.021, 0.018, 0.015}, {0.185, 0.184, 0.184}, /* subj */
    {0.021, 0.020, 0.014}, {0.026, 0.023, 0.020}, {0.080, 0.079, 0.063}, /* pose */
    {0.027, 0.026, 0.020}, {0.032, 0.030, 0.026}, {0.189, 0.189, 0.188}, /* sym */
};
const char *const ss_table1_row_names[12] = {
    "FAUST BEST",      "FAUST GT",      "FAUST FPS",      "FAUST subj BEST", "FAUST subj GT", "FAUST subj FPS",
    "FAUST pose BEST", "FAUST pose GT", "FAUST pose FPS", "FAUST sym BEST",  "FAUST sym GT",  "FAUST sym FPS"};

#define NCOLS 12
static const char *const col_names[NCOLS] = {"policy",     "landmarks",  "method", "x",      "y",       "error",
                                             "error_sym", "segments_x", "segments_y", "paired", "seconds", "samples"};

const char *ss_eval_csv_header(void) {
  return "policy,landmarks,method,x,y,error,error_sym,segments_x,segments_y,paired,seconds,samples,cpu_seconds,pairing";
}

void ss_eval_csv_format_row(const ss_eval_row *r, char *buf, size_t size) {
  ssi_snprintf_c(buf, size, "%s,%s,%s,%d,%d,%.17g,%.17g,%d,%d,%d,%.6f,%d,%.6f,%d", ss_pair_policy_name(r->policy),
           ss_lm_set_name(r->landmarks), ss_eval_method_name(r->method), r->x, r->y, r->error, r->error_sym,
           r->segments_x, r->segments_y, r->paired, r->seconds, r->samples, r->cpu_seconds, r->pairing);
}

/* splits `line` at commas in place; returns the field count (at most max) */
static int split(char *line, char **f, int max) {
  int n = 0;
  char *p = line;
  while (n < max) {
    f[n++] = p;
    char *c = strchr(p, ',');
    if (!c) break;
    *c = 0;
    p = c + 1;
  }
  return n;
}

static int parse_int(const char *s, int *v) { return ssi_csv_parse_int(s, v); }
static int parse_dbl(const char *s, double *v) { return ssi_csv_parse_real(s, 0, v); }

ss_status ss_eval_csv_read(const char *path, ss_eval_row **rows, int *nrows, ss_error *err) {
  *rows = NULL;
  *nrows = 0;
  FILE *f = fopen(path, "rb");
  if (!f) return ss_fail(err, SS_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
  char line[4096], *fld[64];
  int idx[NCOLS], cap = 0, n = 0, lineno = 0;
  ss_eval_row *out = NULL;
  ss_status st = SS_OK;
  if (!fgets(line, sizeof line, f)) { st = ss_fail(err, SS_ERR_PARSE, "%s:1: empty file (no header)", path); goto done; }
  lineno = 1;
  line[strcspn(line, "\r\n")] = 0;
  int nh = split(line, fld, 64);
  for (int c = 0; c < NCOLS; c++) {
    idx[c] = -1;
    for (int h = 0; h < nh; h++)
      if (!strcmp(fld[h], col_names[c])) idx[c] = h;
    if (idx[c] < 0) { st = ss_fail(err, SS_ERR_PARSE, "%s:1: no column '%s' in the header", path, col_names[c]); goto done; }
  }
  int icpu = -1, ipair = -1; /* optional columns */
  for (int h = 0; h < nh; h++) {
    if (!strcmp(fld[h], "cpu_seconds")) icpu = h;
    if (!strcmp(fld[h], "pairing")) ipair = h;
  }
  int complete;
  while (ssi_csv_next_line(f, line, (int)(sizeof line), &complete, &lineno)) {
    int nf = split(line, fld, 64);
    ss_eval_row r;
    memset(&r, 0, sizeof r);
    r.pairing = -1;
    int bad = nf < nh;
    if (!bad) {
      r.policy = ss_pair_policy_parse(fld[idx[0]]);
      r.landmarks = ss_lm_set_parse(fld[idx[1]]);
      r.method = ss_eval_method_parse(fld[idx[2]]);
      bad = r.policy < 0 || r.landmarks < 0 || r.method < 0 || parse_int(fld[idx[3]], &r.x) ||
            parse_int(fld[idx[4]], &r.y) || parse_dbl(fld[idx[5]], &r.error) || parse_dbl(fld[idx[6]], &r.error_sym) ||
            parse_int(fld[idx[7]], &r.segments_x) || parse_int(fld[idx[8]], &r.segments_y) ||
            parse_int(fld[idx[9]], &r.paired) || parse_dbl(fld[idx[10]], &r.seconds) ||
            parse_int(fld[idx[11]], &r.samples) || (icpu >= 0 && parse_dbl(fld[icpu], &r.cpu_seconds)) ||
            (ipair >= 0 && (parse_int(fld[ipair], &r.pairing) || r.pairing < -1 || r.pairing > 2));
    }
    if (bad) {
      /* an interrupted run leaves at most a partial last line: drop it */
      if (!complete && feof(f)) break;
      st = ss_fail(err, SS_ERR_PARSE, "%s:%d: malformed results row", path, lineno);
      goto done;
    }
    if (n == cap) {
      int nc = cap ? 2 * cap : 256;
      ss_eval_row *g = realloc(out, sizeof *out * (size_t)nc);
      if (!g) { st = ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", path); goto done; }
      out = g;
      cap = nc;
    }
    out[n++] = r;
  }
done:
  fclose(f);
  if (st) { free(out); return st; }
  *rows = out;
  *nrows = n;
  return SS_OK;
}

static int key_cmp(const void *pa, const void *pb) {
  const ss_eval_row *a = pa, *b = pb;
  int ka[5] = {a->policy, a->landmarks, a->method, a->x, a->y}, kb[5] = {b->policy, b->landmarks, b->method, b->x, b->y};
  for (int i = 0; i < 5; i++)
    if (ka[i] != kb[i]) return ka[i] < kb[i] ? -1 : 1;
  return 0;
}

ss_status ss_eval_rows_canonical(ss_eval_row *rows, int *n, ss_error *err) {
  if (*n <= 0) return SS_OK;
  qsort(rows, (size_t)*n, sizeof *rows, key_cmp);
  int m = 1;
  for (int i = 1; i < *n; i++) {
    if (key_cmp(&rows[i], &rows[m - 1])) { rows[m++] = rows[i]; continue; }
    /* the same work unit twice (overlapping shards, re-run): results must agree (timings may not) */
    const ss_eval_row *a = &rows[i], *b = &rows[m - 1];
    if (memcmp(&a->error, &b->error, sizeof a->error) || memcmp(&a->error_sym, &b->error_sym, sizeof a->error) ||
        a->paired != b->paired || a->segments_x != b->segments_x || a->segments_y != b->segments_y ||
        a->samples != b->samples || a->pairing != b->pairing)
      return ss_fail(err, SS_ERR_INVALID, "conflicting results for %s,%s,%s,%d,%d (%.17g vs %.17g)",
                     ss_pair_policy_name(a->policy), ss_lm_set_name(a->landmarks), ss_eval_method_name(a->method), a->x,
                     a->y, a->error, b->error);
  }
  *n = m;
  return SS_OK;
}

/* A canonical copy of rows (sorted, duplicates dropped: ss_eval_rows_canonical) for the
 * aggregations; *r is malloc'd (free it) whenever the rows were valid. */
static ss_status canonical_copy(const ss_eval_row *rows, int *n, ss_eval_row **r, ss_error *err) {
  *r = NULL;
  if (*n < 0 || (*n > 0 && !rows)) return ss_fail(err, SS_ERR_INVALID, "table: bad rows");
  *r = malloc(sizeof **r * (size_t)(*n > 0 ? *n : 1));
  if (!*r) return ss_fail(err, SS_ERR_NOMEM, "table: out of memory");
  if (*n > 0) memcpy(*r, rows, sizeof **r * (size_t)*n);
  return ss_eval_rows_canonical(*r, n, err);
}

ss_status ss_table1_aggregate(const ss_eval_row *rows, int n, ss_table1 *t, ss_error *err) {
  memset(t, 0, sizeof *t);
  ss_eval_row *r;
  ss_status st = canonical_copy(rows, &n, &r, err);
  if (!st) {
    double sum[12][SS_EVAL_NMETHODS] = {{0}};
    for (int i = 0; i < n; i++) {
      if (r[i].landmarks == SS_LM_NONE) continue; /* ss_table1_none_aggregate */
      int row = 3 * r[i].policy + r[i].landmarks, c = r[i].method;
      sum[row][c] += r[i].error;
      t->count[row][c]++;
      if (r[i].policy == SS_POLICY_RANDOM) {
        sum[9 + r[i].landmarks][c] += r[i].error_sym;
        t->count[9 + r[i].landmarks][c]++;
      }
    }
    for (int i = 0; i < 12; i++)
      for (int c = 0; c < SS_EVAL_NMETHODS; c++) t->mean[i][c] = t->count[i][c] ? sum[i][c] / t->count[i][c] : NAN;
  }
  free(r);
  return st;
}

ss_status ss_table1_none_aggregate(const ss_eval_row *rows, int n, ss_table1_none *t, ss_error *err) {
  memset(t, 0, sizeof *t);
  ss_eval_row *r;
  ss_status st = canonical_copy(rows, &n, &r, err);
  if (!st) {
    double sum[4][SS_EVAL_NMETHODS] = {{0}};
    int all[3] = {0}, mir[3] = {0}, tot[3] = {0};
    for (int i = 0; i < n; i++) {
      if (r[i].landmarks != SS_LM_NONE) continue;
      int p = r[i].policy, c = r[i].method;
      sum[p][c] += r[i].error;
      t->count[p][c]++;
      if (p == SS_POLICY_RANDOM) sum[3][c] += r[i].error_sym, t->count[3][c]++;
      /* every paper-method row of a shape pair carries the same pairing (refined rows alone carry -1):
       * the fractions over those rows are those over pairs */
      if (r[i].pairing >= 0) tot[p]++, all[p] += r[i].pairing == 2, mir[p] += r[i].pairing >= 1;
    }
    for (int i = 0; i < 4; i++)
      for (int c = 0; c < SS_EVAL_NMETHODS; c++) t->mean[i][c] = t->count[i][c] ? sum[i][c] / t->count[i][c] : NAN;
    for (int p = 0; p < 3; p++) {
      for (int c = 0; c < SS_EVAL_NMETHODS; c++) t->pairs[p] = t->count[p][c] > t->pairs[p] ? t->count[p][c] : t->pairs[p];
      t->all_right[p] = tot[p] ? (double)all[p] / tot[p] : NAN;
      t->mirror_right[p] = tot[p] ? (double)mir[p] / tot[p] : NAN;
    }
  }
  free(r);
  return st;
}
