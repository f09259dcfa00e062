/* OFF reader: optional (C|N|ST...)OFF header, '#' comments, "nv nf [ne]" counts, one vertex a line
 * (extra values such as colours or normals ignored), one polygon a line ("k i1 .. ik [colour]"),
 * polygons fan-triangulated. Line-based because per-element colours make token streams ambiguous. */
#include <stdlib.h>
#include <string.h>

#include "mesh/io_internal.h"
#include "specseg/io.h"

/* Header keywords we read as plain OFF: [ST][C][N]OFF. 4OFF / nOFF (other dimensions) are refused. */
static int off_header_kind(const char *tb, size_t tl) {
  if (tl < 3 || memcmp(tb + tl - 3, "OFF", 3) != 0) return 0; /* not a header */
  size_t i = 0, n = tl - 3;
  if (n - i >= 2 && tb[i] == 'S' && tb[i + 1] == 'T') i += 2;
  if (i < n && tb[i] == 'C') i++;
  if (i < n && tb[i] == 'N') i++;
  return i == n ? 1 : -1; /* 1: supported header, -1: an OFF variant we do not read */
}

/* Next non-blank, non-comment line; 0 at end of input. */
static int next_content_line(io_text *t, const char **b, const char **e) {
  while (io_text_line(t, b, e))
    if (!io_line_blank(*b, *e, 1)) return 1;
  return 0;
}

ss_status io_parse_off(const char *path, const char *buf, size_t len, ss_mesh *m, ss_error *err) {
  memset(m, 0, sizeof *m);
  io_text t;
  io_text_init(&t, buf, len);
  const char *b, *e, *p, *tb;
  size_t tl;
  char show[48];
  if (!next_content_line(&t, &b, &e)) return io_fail_line(err, SS_ERR_PARSE, path, t.line + 1, "empty file");

  p = b;
  io_token(&p, e, 1, &tb, &tl);
  int kind = off_header_kind(tb, tl);
  if (kind < 0)
    return io_fail_line(err, SS_ERR_UNSUPPORTED, path, t.line, "unsupported OFF variant '%s'", io_tok_show(tb, tl, show, sizeof show));
  if (kind == 1) {
    const char *q = p;
    if (io_token(&q, e, 1, &tb, &tl) && io_tok_eq(tb, tl, "BINARY"))
      return io_fail_line(err, SS_ERR_UNSUPPORTED, path, t.line, "binary OFF is not supported");
    /* Counts may share the header line ("OFF 8 6 0"); otherwise they are on the next content line. */
    if (io_line_blank(p, e, 1)) {
      if (!next_content_line(&t, &b, &e))
        return io_fail_line(err, SS_ERR_PARSE, path, t.line + 1, "unexpected end of file: missing vertex/face counts");
      p = b;
    }
  } else {
    long long probe;
    if (io_parse_ll(tb, tl, &probe))
      return io_fail_line(err, SS_ERR_PARSE, path, t.line, "not an OFF file: expected 'OFF' or counts, got '%s'",
                          io_tok_show(tb, tl, show, sizeof show));
    p = b; /* header omitted: this line holds the counts */
  }

  long long cnt[2];
  for (int k = 0; k < 2; k++) {
    if (!io_token(&p, e, 1, &tb, &tl))
      return io_fail_line(err, SS_ERR_PARSE, path, t.line, "expected vertex and face counts");
    if (io_parse_ll(tb, tl, &cnt[k]))
      return io_fail_line(err, SS_ERR_PARSE, path, t.line, "%s count '%s' is not an integer", k ? "face" : "vertex",
                          io_tok_show(tb, tl, show, sizeof show));
    if (cnt[k] < 0 || cnt[k] > IO_MAX_ELEMENTS)
      return io_fail_line(err, SS_ERR_PARSE, path, t.line, "%s count %lld out of range [0, %d]", k ? "face" : "vertex", cnt[k],
                          IO_MAX_ELEMENTS);
  }
  if (cnt[1] == 0) return io_fail_line(err, SS_ERR_PARSE, path, t.line, "mesh has no faces");
  long long nv = cnt[0], nf = cnt[1];

  io_dvec V = {0};
  io_ivec F = {0};
  ss_status st = SS_OK;
  for (long long i = 0; i < nv && !st; i++) {
    if (!next_content_line(&t, &b, &e)) {
      st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "unexpected end of file: %lld of %lld vertices read", i, nv);
      break;
    }
    p = b;
    for (int d = 0; d < 3 && !st; d++) {
      double x;
      if (!io_token(&p, e, 1, &tb, &tl))
        st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "vertex %lld has %d coordinates, expected 3", i, d);
      else if (io_parse_double(tb, tl, &x))
        st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "vertex %lld: '%s' is not a number", i, io_tok_show(tb, tl, show, sizeof show));
      else if (io_dvec_push(&V, x))
        st = io_fail_line(err, SS_ERR_NOMEM, path, t.line, "out of memory");
    }
  }
  for (long long f = 0; f < nf && !st; f++) {
    if (!next_content_line(&t, &b, &e)) {
      st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "unexpected end of file: %lld of %lld faces read", f, nf);
      break;
    }
    p = b;
    long long k;
    if (!io_token(&p, e, 1, &tb, &tl) || io_parse_ll(tb, tl, &k)) {
      st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "face %lld: vertex count '%s' is not an integer", f,
                        io_tok_show(tb, tl, show, sizeof show));
      break;
    }
    if (k < 3) {
      st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "face %lld has %lld vertices (at least 3 needed)", f, k);
      break;
    }
    int first = -1, prev = -1;
    for (long long j = 0; j < k && !st; j++) {
      long long idx;
      if (!io_token(&p, e, 1, &tb, &tl))
        st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "face %lld declares %lld vertices but the line has %lld", f, k, j);
      else if (io_parse_ll(tb, tl, &idx))
        st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "face %lld: index '%s' is not an integer", f, io_tok_show(tb, tl, show, sizeof show));
      else if (idx < 0 || idx >= nv)
        st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "face %lld: vertex index %lld out of range [0, %lld)", f, idx, nv);
      else if (j == 0)
        first = (int)idx;
      else if (j == 1)
        prev = (int)idx;
      else {
        if (F.n / 3 >= (size_t)IO_MAX_ELEMENTS)
          st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "too many triangles");
        else if (io_ivec_push(&F, first) || io_ivec_push(&F, prev) || io_ivec_push(&F, (int)idx))
          st = io_fail_line(err, SS_ERR_NOMEM, path, t.line, "out of memory");
        prev = (int)idx;
      }
    }
  }
  /* content after the declared faces means the counts are wrong: refuse rather than guess */
  if (!st && next_content_line(&t, &b, &e))
    st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "data after the %lld declared faces (wrong face count?)", nf);
  if (!st) st = io_finish_mesh(&V, &F, m, path, err);
  free(V.a);
  free(F.a);
  return st;
}

ss_status ss_read_off(const char *path, ss_mesh *m, ss_error *err) {
  return io_read_with(path, io_parse_off, m, err);
}
