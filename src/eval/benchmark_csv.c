/* pairs.csv of `specseg eval --benchmark`: one row per (method, pair), written as it finishes, read
 * back for resume, merge and the summary. */
#include "benchmark_internal.h"
#include "util/c_locale.h"
#include "csv_file.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NCOL 13
static const char *const COLS[NCOL] = {"method",  "x",      "y",      "mean",   "median", "sym_mean", "seconds",
                                       "confident", "notes", "status", "points", "sym_points", "cum"};

const char *ss_benchmark_csv_header(void) {
  return "method,x,y,mean,median,sym_mean,seconds,confident,notes,status,points,sym_points,cum";
}

void bm_note(char *notes, size_t size, const char *fmt, ...) {
  size_t len = strlen(notes);
  if (len + 1 >= size) return;
  if (len) snprintf(notes + len, size - len, "; "), len = strlen(notes);
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(notes + len, size - len, fmt, ap);
  va_end(ap);
  for (char *p = notes; *p; p++)
    if (*p == '\n' || *p == '\r') *p = ' ';
}

int bm_method_cmp(const char *a, const char *b) {
  int sa = !strncmp(a, "specseg", 7), sb = !strncmp(b, "specseg", 7);
  if (sa != sb) return sa ? -1 : 1;
  int c = strcmp(a, b);
  return (c > 0) - (c < 0);
}

int bm_row_cmp(const ss_benchmark_row *a, const ss_benchmark_row *b) {
  int c = bm_method_cmp(a->method, b->method);
  if (!c) c = bm_name_cmp(a->x, b->x);
  if (!c) c = bm_name_cmp(a->y, b->y);
  return c;
}

/* a field, quoted when it holds a comma, a quote or a blank at an end (always for notes) */
static size_t put_field(char *buf, size_t size, size_t pos, const char *s, int always_quote) {
  int q = always_quote || strpbrk(s, ",\"") || (s[0] == ' ') || (*s && s[strlen(s) - 1] == ' ');
  if (pos + 1 < size && q) buf[pos++] = '"';
  for (const char *p = s; *p && pos + 2 < size; p++) {
    if (*p == '"') buf[pos++] = '"';
    buf[pos++] = *p;
  }
  if (pos + 1 < size && q) buf[pos++] = '"';
  buf[pos < size ? pos : size - 1] = 0;
  return pos;
}

static size_t put_text(char *buf, size_t size, size_t pos, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
static size_t put_text(char *buf, size_t size, size_t pos, const char *fmt, ...) {
  if (pos >= size) return pos;
  va_list ap;
  va_start(ap, fmt);
  int n = ssi_vsnprintf_c(buf + pos, size - pos, fmt, ap);
  va_end(ap);
  return n < 0 ? pos : pos + (size_t)n >= size ? size - 1 : pos + (size_t)n;
}

static size_t put_real(char *buf, size_t size, size_t pos, double v, const char *fmt) {
  if (!isfinite(v)) return pos;
  return put_text(buf, size, pos, fmt, v);
}

void ss_benchmark_csv_format_row(const ss_benchmark_row *r, char *buf, size_t size) {
  if (!buf || size == 0) return;
  buf[0] = 0;
  size_t p = 0;
  p = put_field(buf, size, p, r->method, 0);
  p = put_text(buf, size, p, ",");
  p = put_field(buf, size, p, r->x, 0);
  p = put_text(buf, size, p, ",");
  p = put_field(buf, size, p, r->y, 0);
  p = put_text(buf, size, p, ",");
  if (r->ok) p = put_real(buf, size, p, r->mean, "%.17g");
  p = put_text(buf, size, p, ",");
  if (r->ok) p = put_real(buf, size, p, r->median, "%.17g");
  p = put_text(buf, size, p, ",");
  if (r->ok) p = put_real(buf, size, p, r->sym_mean, "%.17g");
  p = put_text(buf, size, p, ",");
  p = put_real(buf, size, p, r->seconds, "%.6f");
  p = put_text(buf, size, p, ",");
  if (r->confident >= 0) p = put_text(buf, size, p, "%d", r->confident ? 1 : 0);
  p = put_text(buf, size, p, ",");
  p = put_field(buf, size, p, r->notes, 1);
  p = put_text(buf, size, p, ",%s,%d,%d,", r->ok ? "ok" : "skipped", r->ok ? r->points : 0, r->ok ? r->sym_points : 0);
  if (r->ok)
    for (int j = 0; j < SS_BENCH_CURVE_N; j++) p = put_text(buf, size, p, j ? " %d" : "%d", r->cum[j]);
}

/* splits a CSV line in place (quoted fields with "" escapes); returns the field count or -1 on an
 * unterminated quote */
static int split_csv(char *line, char **f, int max) {
  int n = 0;
  char *p = line;
  for (;;) {
    if (n == max) return n;
    char *w = p;
    f[n++] = w;
    if (*p == '"') {
      p++;
      for (;;) {
        if (!*p) return -1;
        if (*p == '"') {
          if (p[1] == '"') { *w++ = '"'; p += 2; continue; }
          p++;
          break;
        }
        *w++ = *p++;
      }
      /* after the closing quote: a comma or the end */
      if (*p && *p != ',') return -1;
    } else {
      while (*p && *p != ',') *w++ = *p++;
    }
    int end = !*p;
    *w = 0;
    if (end) return n;
    p++;
  }
}

static int parse_int(const char *s, int *v) { return ssi_csv_parse_int(s, v); }
static int parse_real(const char *s, double *v) { return ssi_csv_parse_real(s, 1, v); } /* "" = NAN */

ss_status ss_benchmark_csv_read(const char *path, ss_benchmark_row **rows, int *nrows, ss_error *err) {
  *rows = NULL, *nrows = 0;
  FILE *f = fopen(path, "rb");
  if (!f) return ss_fail(err, SS_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
  char *line = malloc(2 * SS_BENCH_CSV_LINE);
  ss_benchmark_row *out = NULL;
  int cap = 0, n = 0, ln = 1, idx[NCOL];
  ss_status st = SS_OK;
  char *fld[64];
  if (!line) { fclose(f); return ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); }
  if (!fgets(line, 2 * SS_BENCH_CSV_LINE, f)) { st = ss_fail(err, SS_ERR_PARSE, "%s:1: empty file (no header)", path); goto done; }
  line[strcspn(line, "\r\n")] = 0;
  int nh = split_csv(line, fld, 64);
  for (int c = 0; c < NCOL; c++) {
    idx[c] = -1;
    for (int h = 0; h < nh; h++)
      if (!strcmp(fld[h], COLS[c])) idx[c] = h;
    if (idx[c] < 0) {
      st = ss_fail(err, SS_ERR_PARSE, "%s:1: no column '%s' in the header: not a benchmark pairs.csv", path, COLS[c]);
      goto done;
    }
  }
  int complete;
  while (ssi_csv_next_line(f, line, (int)(2 * SS_BENCH_CSV_LINE), &complete, &ln)) {
    int nf = split_csv(line, fld, 64);
    ss_benchmark_row r;
    memset(&r, 0, sizeof r);
    const char *why = NULL;
    if (nf < nh) why = "too few fields";
    else {
      const char *m = fld[idx[0]], *x = fld[idx[1]], *y = fld[idx[2]], *status = fld[idx[9]];
      if (!*m || !*x || !*y) why = "empty method or shape name";
      else if (strlen(m) >= SS_BENCH_METHOD || strlen(x) >= SS_BENCH_NAME || strlen(y) >= SS_BENCH_NAME) why = "name too long";
      else if (strcmp(status, "ok") && strcmp(status, "skipped")) why = "status is neither ok nor skipped";
      else {
        snprintf(r.method, sizeof r.method, "%s", m);
        snprintf(r.x, sizeof r.x, "%s", x);
        snprintf(r.y, sizeof r.y, "%s", y);
        snprintf(r.notes, sizeof r.notes, "%s", fld[idx[8]]);
        r.ok = !strcmp(status, "ok");
        const char *conf = fld[idx[7]];
        r.confident = !*conf ? -1 : !strcmp(conf, "1") ? 1 : !strcmp(conf, "0") ? 0 : -2;
        if (r.confident == -2) why = "confident is not 1, 0 or empty";
        else if (parse_real(fld[idx[3]], &r.mean) || parse_real(fld[idx[4]], &r.median) ||
                 parse_real(fld[idx[5]], &r.sym_mean) || parse_real(fld[idx[6]], &r.seconds) ||
                 parse_int(fld[idx[10]], &r.points) || parse_int(fld[idx[11]], &r.sym_points))
          why = "a number does not read";
        else if (r.ok) {
          if (!(r.points > 0) || !isfinite(r.mean) || !isfinite(r.median) || r.sym_points < 0 ||
              (r.sym_points > 0) != !!isfinite(r.sym_mean))
            why = "a scored row without points, mean or median";
          char *c = fld[idx[12]], *end;
          for (int j = 0; j < SS_BENCH_CURVE_N && !why; j++) {
            errno = 0;
            long v = strtol(c, &end, 10);
            if (end == c || errno || v < 0 || v > r.points || (j && v < r.cum[j - 1])) why = "the cumulative counts do not read";
            else r.cum[j] = (int)v, c = end;
          }
          while (!why && *c == ' ') c++;
          if (!why && *c) why = "more cumulative counts than the curve's grid";
        } else {
          r.mean = r.median = r.sym_mean = NAN, r.points = r.sym_points = 0;
        }
      }
    }
    if (why) {
      if (!complete) break; /* the cut last line of an interrupted run */
      st = ss_fail(err, SS_ERR_PARSE, "%s:%d: %s", path, ln, why);
      goto done;
    }
    if (n == cap) {
      cap = cap ? 2 * cap : 256;
      ss_benchmark_row *g = realloc(out, sizeof *g * (size_t)cap);
      if (!g) { st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); goto done; }
      out = g;
    }
    out[n++] = r;
  }
  if (ferror(f)) st = ss_fail(err, SS_ERR_IO, "%s: read error", path);
done:
  fclose(f);
  free(line);
  if (st) { free(out); return st; }
  *rows = out, *nrows = n;
  return SS_OK;
}

typedef struct idx_row {
  const ss_benchmark_row *r;
  int i;
} idx_row;
static int idx_cmp(const void *a, const void *b) {
  const idx_row *p = a, *q = b;
  int c = bm_row_cmp(p->r, q->r);
  return c ? c : (p->i > q->i) - (p->i < q->i);
}

static int same_bits(double a, double b) { return (isnan(a) && isnan(b)) || !memcmp(&a, &b, sizeof a); }

ss_status ss_benchmark_rows_canonical(ss_benchmark_row *rows, int *n, ss_error *err) {
  const int m = *n;
  if (m <= 0) return SS_OK;
  idx_row *ix = malloc(sizeof *ix * (size_t)m);
  ss_benchmark_row *tmp = malloc(sizeof *tmp * (size_t)m);
  if (!ix || !tmp) { free(ix), free(tmp); return ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); }
  for (int i = 0; i < m; i++) ix[i].r = &rows[i], ix[i].i = i;
  qsort(ix, (size_t)m, sizeof *ix, idx_cmp);
  int k = 0;
  for (int a = 0, b; a < m; a = b) {
    for (b = a + 1; b < m && !bm_row_cmp(ix[a].r, ix[b].r);) b++;
    /* a scored row wins; among skipped ones the last (a later run's) */
    int pick = b - 1;
    for (int i = a; i < b; i++)
      if (ix[i].r->ok) { pick = i; break; }
    for (int i = a; i < b; i++) {
      const ss_benchmark_row *p = ix[pick].r, *q = ix[i].r;
      if (i == pick || !q->ok || !p->ok) continue;
      if (p->points != q->points || !same_bits(p->mean, q->mean) || !same_bits(p->median, q->median) ||
          !same_bits(p->sym_mean, q->sym_mean)) {
        ss_status st = ss_fail(err, SS_ERR_INVALID, "benchmark rows: %s %s -> %s twice with different results (%.17g, %.17g)",
                               p->method, p->x, p->y, p->mean, q->mean);
        free(ix), free(tmp);
        return st;
      }
    }
    tmp[k++] = *ix[pick].r;
  }
  memcpy(rows, tmp, sizeof *tmp * (size_t)k);
  *n = k;
  free(ix), free(tmp);
  return SS_OK;
}
