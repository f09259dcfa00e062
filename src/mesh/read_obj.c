/* Wavefront OBJ reader: "v x y z [w | r g b]" and "f a b c ..." with a, a/t, a//n or a/t/n corners;
 * 1-based indices, negative ones relative to the vertices read so far; polygons fan-triangulated;
 * every other statement (vt, vn, g, o, s, usemtl, l, p, ...) ignored. */
#include <stdlib.h>
#include <string.h>

#include "mesh/io_internal.h"
#include "specseg/io.h"

ss_status io_parse_obj(const char *path, const char *buf, size_t len, ss_mesh *m, ss_error *err) {
  memset(m, 0, sizeof *m);
  if (len == 0) return io_fail_line(err, SS_ERR_PARSE, path, 1, "empty file");
  io_text t;
  io_text_init(&t, buf, len);
  const char *b, *e, *p, *tb;
  size_t tl;
  char show[48];
  io_dvec V = {0};
  io_ivec F = {0};
  ss_status st = SS_OK;
  /* Positive indices may legally point past the vertices read so far (some writers emit faces
   * first); the largest such index is checked once all vertices are known. */
  long long max_fwd = -1;
  long max_fwd_line = 0;
  while (!st && io_text_line(&t, &b, &e)) {
    p = b;
    if (!io_token(&p, e, 1, &tb, &tl)) continue;
    if (io_tok_eq(tb, tl, "v")) {
      if (V.n / 3 >= (size_t)IO_MAX_ELEMENTS) {
        st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "too many vertices");
        break;
      }
      for (int d = 0; d < 3 && !st; d++) {
        double x;
        if (!io_token(&p, e, 1, &tb, &tl))
          st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "vertex has %d coordinates, expected 3", d);
        else if (io_parse_double(tb, tl, &x))
          st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "vertex coordinate '%s' is not a number", io_tok_show(tb, tl, show, sizeof show));
        else if (io_dvec_push(&V, x))
          st = io_fail_line(err, SS_ERR_NOMEM, path, t.line, "out of memory");
      }
    } else if (io_tok_eq(tb, tl, "f")) {
      long long nvnow = (long long)(V.n / 3);
      int first = -1, prev = -1, k = 0;
      while (!st && io_token(&p, e, 1, &tb, &tl)) {
        /* the vertex index is the part before the first '/' */
        size_t il = 0;
        while (il < tl && tb[il] != '/') il++;
        long long idx;
        if (io_parse_ll(tb, il, &idx)) {
          st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "face corner '%s' has no integer vertex index", io_tok_show(tb, tl, show, sizeof show));
          break;
        }
        if (idx == 0) {
          st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "vertex index 0 is invalid (OBJ indices start at 1)");
          break;
        }
        if (idx < 0) {
          if (-idx > nvnow) {
            st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "relative vertex index %lld reaches before the first vertex (%lld read so far)", idx, nvnow);
            break;
          }
          idx = nvnow + idx;
        } else {
          if (idx > IO_MAX_ELEMENTS) {
            st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "vertex index %lld out of range", idx);
            break;
          }
          idx -= 1;
          if (idx >= nvnow && idx > max_fwd) {
            max_fwd = idx;
            max_fwd_line = t.line;
          }
        }
        if (k == 0) first = (int)idx;
        else if (k == 1) prev = (int)idx;
        else {
          if (F.n / 3 >= (size_t)IO_MAX_ELEMENTS)
            st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "too many triangles");
          else if (io_ivec_push(&F, first) || io_ivec_push(&F, prev) || io_ivec_push(&F, (int)idx))
            st = io_fail_line(err, SS_ERR_NOMEM, path, t.line, "out of memory");
          prev = (int)idx;
        }
        k++;
      }
      if (!st && k < 3) st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "face has %d vertices (at least 3 needed)", k);
    }
    /* anything else: ignored */
  }
  if (!st && max_fwd >= (long long)(V.n / 3))
    st = io_fail_line(err, SS_ERR_PARSE, path, max_fwd_line, "vertex index %lld out of range (file has %zu vertices)", max_fwd + 1, V.n / 3);
  if (!st && F.n == 0) st = io_fail_line(err, SS_ERR_PARSE, path, t.line, "no faces ('f' lines) in file");
  if (!st) st = io_finish_mesh(&V, &F, m, path, err);
  free(V.a);
  free(F.a);
  return st;
}

ss_status ss_read_obj(const char *path, ss_mesh *m, ss_error *err) {
  return io_read_with(path, io_parse_obj, m, err);
}
