/* Text vectors: one value a line, '#' comments and blank lines skipped. Used for labels, maps,
 * landmark lists and per-vertex fields. Doubles are written with %.17g (exact round trip). */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "specseg/io.h"
#include "util/c_locale.h"
#include "util/io_text.h"
#include "util/out_file.h"

/* Shared parser: one value per content line of [buf, buf + len) into a growing array of doubles or
 * ints; `path` names the input in messages. */
static ss_status parse_values(const char *path, const char *buf, size_t len, int as_int, void **out, int **lines,
                              int *n, ss_error *err) {
  ss_status st = SS_OK;
  io_text t;
  io_text_init(&t, buf, len);
  io_dvec dv = {0};
  io_ivec iv = {0}, ln = {0}; /* ln: line numbers, when wanted */
  const char *b, *e, *p, *tb;
  size_t tl;
  char show[48];
  while (!st && io_text_line(&t, &b, &e)) {
    p = b;
    if (!io_token(&p, e, 1, &tb, &tl)) continue;
    size_t count = as_int ? iv.n : dv.n;
    if (count >= INT_MAX) {
      st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "too many values");
      break;
    }
    if (as_int) {
      long long v;
      if (io_parse_ll(tb, tl, &v) || v < INT_MIN || v > INT_MAX)
        st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "'%s' is not an integer in range", io_tok_show(tb, tl, show, sizeof show));
      else if (io_ivec_push(&iv, (int)v) || (lines && io_ivec_push(&ln, t.line > INT_MAX ? INT_MAX : (int)t.line)))
        st = io_fail_line(err, SS_ERR_NOMEM, path, t.line, "out of memory");
    } else {
      double v;
      if (io_parse_double(tb, tl, &v))
        st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "'%s' is not a number", io_tok_show(tb, tl, show, sizeof show));
      else if (io_dvec_push(&dv, v))
        st = io_fail_line(err, SS_ERR_NOMEM, path, t.line, "out of memory");
    }
    if (!st && !io_line_blank(p, e, 1))
      st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "more than one value on the line");
  }
  if (st) {
    free(dv.a);
    free(iv.a);
    free(ln.a);
    return st;
  }
  void *a = as_int ? (void *)iv.a : (void *)dv.a;
  size_t cnt = as_int ? iv.n : dv.n;
  if (!a) a = malloc(sizeof(double)); /* a valid (empty) array even for an empty file */
  if (lines && !ln.a) ln.a = malloc(sizeof(int));
  if (!a || (lines && !ln.a)) {
    free(a);
    free(ln.a);
    return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", path);
  }
  *out = a;
  if (lines) *lines = ln.a;
  *n = (int)cnt;
  return SS_OK;
}

static ss_status read_values(const char *path, int as_int, void **out, int *n, ss_error *err) {
  *out = NULL;
  *n = 0;
  char *buf;
  size_t len;
  ss_status st = io_slurp(path, &buf, &len, err);
  if (st) return st;
  st = parse_values(path, buf, len, as_int, out, NULL, n, err);
  free(buf);
  return st;
}

/* out and n are checked by the callers; name NULL: "<memory>" */
static ss_status read_values_memory(const void *buf, size_t len, const char *name, int as_int, void **out, int *n,
                                    ss_error *err) {
  *out = NULL;
  *n = 0;
  if (!buf && len > 0) return ss_fail(err, SS_ERR_INVALID, "%s: NULL buffer", name);
  return parse_values(name, buf ? (const char *)buf : "", len, as_int, out, NULL, n, err);
}

ss_status ss_read_ints_memory(const void *buf, size_t len, const char *name, int **out, int *n, ss_error *err) {
  if (!name) name = "<memory>";
  if (!out || !n) return ss_fail(err, SS_ERR_INVALID, "%s: NULL output", name);
  void *a;
  ss_status st = read_values_memory(buf, len, name, 1, &a, n, err);
  *out = st ? NULL : (int *)a;
  return st;
}

ss_status ss_read_doubles_memory(const void *buf, size_t len, const char *name, double **out, int *n, ss_error *err) {
  if (!name) name = "<memory>";
  if (!out || !n) return ss_fail(err, SS_ERR_INVALID, "%s: NULL output", name);
  void *a;
  ss_status st = read_values_memory(buf, len, name, 0, &a, n, err);
  *out = st ? NULL : (double *)a;
  return st;
}

ss_status ss_read_ints(const char *path, int **out, int *n, ss_error *err) {
  void *a;
  ss_status st = read_values(path, 1, &a, n, err);
  *out = st ? NULL : (int *)a;
  return st;
}

ss_status ss_read_ints_lines(const char *path, int **out, int **lines, int *n, ss_error *err) {
  if (!out || !lines || !n) return ss_fail(err, SS_ERR_INVALID, "%s: NULL output", path ? path : "<null>");
  *out = NULL, *lines = NULL, *n = 0;
  char *buf;
  size_t len;
  ss_status st = io_slurp(path, &buf, &len, err);
  if (st) return st;
  void *a;
  st = parse_values(path, buf, len, 1, &a, lines, n, err);
  free(buf);
  if (!st) *out = a;
  return st;
}

ss_status ss_read_ints_lines_memory(const void *buf, size_t len, const char *name, int **out, int **lines, int *n,
                                    ss_error *err) {
  if (!name) name = "<memory>";
  if (!out || !lines || !n) return ss_fail(err, SS_ERR_INVALID, "%s: NULL output", name);
  *out = NULL, *lines = NULL, *n = 0;
  if (!buf && len > 0) return ss_fail(err, SS_ERR_INVALID, "%s: NULL buffer", name);
  void *a;
  ss_status st = parse_values(name, buf ? (const char *)buf : "", len, 1, &a, lines, n, err);
  if (!st) *out = a;
  return st;
}

ss_status ss_read_doubles(const char *path, double **out, int *n, ss_error *err) {
  void *a;
  ss_status st = read_values(path, 0, &a, n, err);
  *out = st ? NULL : (double *)a;
  return st;
}

static ss_status write_values(const char *path, const int *iv, const double *dv, int n, ss_error *err) {
  if (n < 0 || (n > 0 && !iv && !dv)) return ss_fail(err, SS_ERR_INVALID, "%s: invalid vector (n = %d)", path, n);
  ssi_out o; /* whole or not at all: a map cut at a line boundary would look complete */
  ss_status st = ssi_out_open(&o, path, err);
  if (st) return st;
  for (int i = 0; i < n && !ferror(o.f); i++) {
    if (iv) fprintf(o.f, "%d\n", iv[i]);
    else ssi_fprintf_c(o.f, "%.17g\n", dv[i]);
  }
  return ssi_out_commit(&o, path, err);
}

ss_status ss_write_ints(const char *path, const int *v, int n, ss_error *err) { return write_values(path, v, NULL, n, err); }
ss_status ss_write_doubles(const char *path, const double *v, int n, ss_error *err) {
  return write_values(path, NULL, v, n, err);
}
