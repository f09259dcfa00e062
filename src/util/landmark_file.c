/* Landmark files: one landmark a line, "i" (the same vertex on both shapes) or "i j" (i on the first
 * shape, j on the second) — the format `specseg match` and `specseg render --landmarks` take. */
#include <limits.h>
#include <stdlib.h>

#include "specseg/io.h"
#include "util/io_text.h"

ss_status ss_read_landmarks(const char *path, int **lx, int **ly, int *n, int *columns, ss_error *err) {
  return ss_read_landmarks_lines(path, lx, ly, NULL, n, columns, err);
}

/* The landmarks of [buf, buf + len); `path` names the input in messages. Outputs are reset by the callers. */
static ss_status parse_landmarks(const char *path, const char *buf, size_t len, int **lx, int **ly, int **lines,
                                 int *n, int *columns, ss_error *err) {
  ss_status st = SS_OK;
  io_text t;
  io_text_init(&t, buf, len);
  io_ivec a = {0}, b = {0}, ln = {0};
  const char *lb, *le, *p, *tb;
  size_t tl;
  char show[48];
  int cols = 0;
  while (!st && io_text_line(&t, &lb, &le)) {
    p = lb;
    long long v[2];
    int k = 0;
    while (!st && io_token(&p, le, 1, &tb, &tl)) {
      if (k == 2) {
        st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "more than two vertex indices on the line");
        break;
      }
      if (io_parse_ll(tb, tl, &v[k]) || v[k] < 0 || v[k] > INT_MAX)
        st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "'%s' is not a vertex index",
                          io_tok_show(tb, tl, show, sizeof show));
      k++;
    }
    if (st || k == 0) continue;
    if (k > cols) cols = k;
    if (io_ivec_push(&a, (int)v[0]) || io_ivec_push(&b, (int)(k == 2 ? v[1] : v[0])) ||
        (lines && io_ivec_push(&ln, t.line > INT_MAX ? INT_MAX : (int)t.line)))
      st = io_fail_line(err, SS_ERR_NOMEM, path, t.line, "out of memory");
    else if (a.n >= INT_MAX)
      st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "too many landmarks");
  }
  if (!st && a.n == 0) st = ss_fail(err, SS_ERR_PARSE, "%s: no landmark", path);
  if (st) {
    free(a.a);
    free(b.a);
    free(ln.a);
    return st;
  }
  *lx = a.a;
  *ly = b.a;
  if (lines) *lines = ln.a;
  *n = (int)a.n;
  if (columns) *columns = cols;
  return SS_OK;
}

/* Resets the outputs; -1 when a required one is NULL. */
static int reset_outputs(int **lx, int **ly, int **lines, int *n, int *columns) {
  if (!lx || !ly || !n) return -1;
  *lx = *ly = NULL;
  if (lines) *lines = NULL;
  *n = 0;
  if (columns) *columns = 0;
  return 0;
}

ss_status ss_read_landmarks_lines(const char *path, int **lx, int **ly, int **lines, int *n, int *columns,
                                  ss_error *err) {
  if (reset_outputs(lx, ly, lines, n, columns)) return ss_fail(err, SS_ERR_INVALID, "landmarks: NULL output");
  char *buf;
  size_t len;
  ss_status st = io_slurp(path, &buf, &len, err);
  if (st) return st;
  st = parse_landmarks(path, buf, len, lx, ly, lines, n, columns, err);
  free(buf);
  return st;
}

ss_status ss_read_landmarks_memory(const void *buf, size_t len, const char *name, int **lx, int **ly, int **lines,
                                   int *n, int *columns, ss_error *err) {
  if (reset_outputs(lx, ly, lines, n, columns)) return ss_fail(err, SS_ERR_INVALID, "landmarks: NULL output");
  if (!name) name = "<memory>";
  if (!buf && len > 0) return ss_fail(err, SS_ERR_INVALID, "%s: NULL buffer", name);
  return parse_landmarks(name, buf ? (const char *)buf : "", len, lx, ly, lines, n, columns, err);
}
