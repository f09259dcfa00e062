/* STL reader, ASCII and binary, our own (it was assimp's, whose ASCII reader throws out of malformed
 * input and leaks what it has made: three such paths in three fuzz runs). Binary: an 80-byte header,
 * a little-endian uint32 facet count, then 50 bytes a facet (normal, three corners as float32, a
 * uint16 attribute), and nothing else. ASCII: "solid NAME", facets of "facet normal x y z / outer
 * loop / vertex x y z (three) / endloop / endfacet", "endsolid NAME"; several solids may follow each
 * other. Keywords are read in either case (exporters write "FACET NORMAL"). The normals are checked as
 * numbers and ignored: the corners' order gives the orientation. Corners are welded by exact
 * coordinates (ssi_mesh_weld), which joins the facets into one surface. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/io_internal.h"
#include "specseg/io.h"

/* binary STL: the facet count its header declares when the length is exactly 84 + 50 n, else -1 */
static int64_t binary_facets(const char *buf, size_t len) {
  if (len < 84) return -1;
  const unsigned char *u = (const unsigned char *)buf + 80;
  uint64_t nf = (uint64_t)u[0] | (uint64_t)u[1] << 8 | (uint64_t)u[2] << 16 | (uint64_t)u[3] << 24;
  return 84 + 50 * nf == len ? (int64_t)nf : -1;
}

static int word_is(const char *tb, size_t tl, const char *kw) {
  size_t n = strlen(kw);
  if (tl != n) return 0;
  for (size_t i = 0; i < n; i++) {
    char c = tb[i];
    if ((c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c) != kw[i]) return 0;
  }
  return 1;
}

/* text beginning (after blank space) with the word "solid" */
static int starts_solid(const char *buf, size_t len) {
  size_t i = 0;
  while (i < len && (buf[i] == ' ' || buf[i] == '\t' || buf[i] == '\r' || buf[i] == '\n')) i++;
  size_t j = i;
  while (j < len && buf[j] != ' ' && buf[j] != '\t' && buf[j] != '\r' && buf[j] != '\n') j++;
  return word_is(buf + i, j - i, "solid");
}

int io_stl_sniff(const char *buf, size_t len) {
  if (binary_facets(buf, len) > 0) return 1;
  if (!starts_solid(buf, len)) return 0;
  size_t lim = len < 4096 ? len : 4096;
  for (size_t j = 5; j + 5 <= lim; j++)
    if (!memcmp(buf + j, "facet", 5) || !memcmp(buf + j, "FACET", 5)) return 1;
  return 0;
}

static ss_status push_corner(io_dvec *V, io_ivec *F, const double *p, const char *path, ss_error *err) {
  if (F->n >= (size_t)IO_MAX_ELEMENTS)
    return ss_fail(err, SS_ERR_PARSE, "%s: more than %d facet corners", path, IO_MAX_ELEMENTS);
  if (io_dvec_push(V, p[0]) || io_dvec_push(V, p[1]) || io_dvec_push(V, p[2]) || io_ivec_push(F, (int)(V->n / 3 - 1)))
    return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", path);
  return SS_OK;
}

static float f32le(const unsigned char *u) {
  uint32_t b = (uint32_t)u[0] | (uint32_t)u[1] << 8 | (uint32_t)u[2] << 16 | (uint32_t)u[3] << 24;
  float f;
  memcpy(&f, &b, sizeof f);
  return f;
}

static ss_status parse_binary(const char *path, const char *buf, int64_t nf, io_dvec *V, io_ivec *F, ss_error *err) {
  if (nf == 0) return ss_fail(err, SS_ERR_PARSE, "%s: binary STL without facets", path);
  if (nf > IO_MAX_ELEMENTS / 3)
    return ss_fail(err, SS_ERR_PARSE, "%s: binary STL of %lld facets, more than this reader takes (%d)", path,
                   (long long)nf, IO_MAX_ELEMENTS / 3);
  ss_status st = SS_OK;
  for (int64_t t = 0; t < nf && !st; t++) {
    const unsigned char *rec = (const unsigned char *)buf + 84 + 50 * t + 12; /* past the normal */
    for (int c = 0; c < 3 && !st; c++) {
      double p[3];
      for (int d = 0; d < 3; d++) p[d] = (double)f32le(rec + 12 * c + 4 * d);
      st = push_corner(V, F, p, path, err);
    }
  }
  return st;
}

/* ASCII: a token stream over the lines, for messages "PATH:LINE: what" */
typedef struct stl_in {
  io_text t;
  const char *p, *e; /* the rest of the current line */
  const char *tb;    /* the token last read */
  size_t tl;
  const char *path;
} stl_in;

static int next_word(stl_in *in) {
  for (;;) {
    if (in->p && io_token(&in->p, in->e, 0, &in->tb, &in->tl)) return 1;
    if (!io_text_line(&in->t, &in->p, &in->e)) return 0;
  }
}

static void skip_line(stl_in *in) { in->p = in->e; }

static ss_status expect_word(stl_in *in, const char *kw, const char *where, ss_error *err) {
  char show[48];
  if (!next_word(in)) return io_fail_line(err, SS_ERR_PARSE, in->path, in->t.line, "the file ends %s", where);
  if (!word_is(in->tb, in->tl, kw))
    return io_fail_line(err, SS_ERR_PARSE, in->path, in->t.line, "'%s' where '%s' was expected",
                        io_tok_show(in->tb, in->tl, show, sizeof show), kw);
  return SS_OK;
}

static ss_status read_numbers(stl_in *in, const char *what, double *p, ss_error *err) {
  char show[48];
  for (int d = 0; d < 3; d++) {
    if (!next_word(in)) return io_fail_line(err, SS_ERR_PARSE, in->path, in->t.line, "the file ends inside a %s", what);
    if (io_parse_double(in->tb, in->tl, p + d))
      return io_fail_line(err, SS_ERR_PARSE, in->path, in->t.line, "a %s coordinate is not a number ('%s')", what,
                          io_tok_show(in->tb, in->tl, show, sizeof show));
  }
  return SS_OK;
}

/* one facet after its "facet" keyword */
static ss_status parse_facet(stl_in *in, io_dvec *V, io_ivec *F, ss_error *err) {
  double p[3];
  ss_status st;
  char show[48];
  if ((st = expect_word(in, "normal", "inside a facet", err)) || (st = read_numbers(in, "normal", p, err)) ||
      (st = expect_word(in, "outer", "inside a facet", err)) || (st = expect_word(in, "loop", "inside a facet", err)))
    return st;
  const long first = in->t.line;
  int corners = 0;
  for (;;) {
    if (!next_word(in)) return io_fail_line(err, SS_ERR_PARSE, in->path, in->t.line, "the file ends inside a facet");
    if (word_is(in->tb, in->tl, "endloop")) break;
    if (!word_is(in->tb, in->tl, "vertex"))
      return io_fail_line(err, SS_ERR_PARSE, in->path, in->t.line, "'%s' where 'vertex' or 'endloop' was expected",
                          io_tok_show(in->tb, in->tl, show, sizeof show));
    if ((st = read_numbers(in, "vertex", p, err))) return st;
    if (++corners > 3) break;
    if ((st = push_corner(V, F, p, in->path, err))) return st;
  }
  if (corners != 3)
    return io_fail_line(err, SS_ERR_PARSE, in->path, first, "a facet with %s vertices (STL facets are triangles)",
                        corners > 3 ? "more than 3" : corners == 2 ? "2" : corners == 1 ? "1" : "no");
  return expect_word(in, "endfacet", "inside a facet", err);
}

static ss_status parse_ascii(const char *path, const char *buf, size_t len, io_dvec *V, io_ivec *F, ss_error *err) {
  stl_in in;
  memset(&in, 0, sizeof in);
  io_text_init(&in.t, buf, len);
  in.path = path;
  char show[48];
  ss_status st;
  int solids = 0;
  while (next_word(&in)) { /* at a solid's "solid" */
    if (!word_is(in.tb, in.tl, "solid"))
      return io_fail_line(err, SS_ERR_PARSE, path, in.t.line, "'%s' where %s was expected",
                          io_tok_show(in.tb, in.tl, show, sizeof show), solids ? "'solid' or the end of the file" : "'solid'");
    solids++;
    skip_line(&in); /* its name */
    for (;;) {
      if (!next_word(&in)) return io_fail_line(err, SS_ERR_PARSE, path, in.t.line, "the file ends before 'endsolid'");
      if (word_is(in.tb, in.tl, "endsolid")) break;
      if (!word_is(in.tb, in.tl, "facet"))
        return io_fail_line(err, SS_ERR_PARSE, path, in.t.line, "'%s' where 'facet' or 'endsolid' was expected",
                            io_tok_show(in.tb, in.tl, show, sizeof show));
      if ((st = parse_facet(&in, V, F, err))) return st;
    }
    skip_line(&in); /* its name again */
  }
  if (!solids) return io_fail_line(err, SS_ERR_PARSE, path, 1, "empty file");
  if (F->n == 0) return ss_fail(err, SS_ERR_PARSE, "%s: ASCII STL without facets", path);
  return SS_OK;
}

ss_status io_parse_stl(const char *path, const char *buf, size_t len, ss_mesh *m, ss_error *err) {
  memset(m, 0, sizeof *m);
  io_dvec V = {0};
  io_ivec F = {0};
  const int64_t nf = binary_facets(buf, len);
  ss_status st;
  if (nf >= 0) st = parse_binary(path, buf, nf, &V, &F, err);
  else if (starts_solid(buf, len)) st = parse_ascii(path, buf, len, &V, &F, err);
  else if (len >= 84) {
    const unsigned char *u = (const unsigned char *)buf + 80;
    uint64_t n = (uint64_t)u[0] | (uint64_t)u[1] << 8 | (uint64_t)u[2] << 16 | (uint64_t)u[3] << 24;
    st = ss_fail(err, SS_ERR_PARSE,
                 "%s: not an STL file: not text beginning with 'solid', and not binary (its header declares %llu facets, "
                 "which take %llu bytes; the file has %zu)",
                 path, (unsigned long long)n, (unsigned long long)(84 + 50 * n), len);
  } else
    st = ss_fail(err, SS_ERR_PARSE, "%s: not an STL file: not text beginning with 'solid', and %zu bytes, shorter than a "
                 "binary STL's 84-byte header", path, len);
  if (!st) st = io_finish_mesh(&V, &F, m, path, err);
  if (!st) st = ssi_mesh_weld(m, NULL, err);
  free(V.a), free(F.a);
  if (st) ss_mesh_free(m);
  return st;
}

ss_status ss_read_stl(const char *path, ss_mesh *m, ss_error *err) {
  if (!m) return ss_fail(err, SS_ERR_INVALID, "read STL: NULL output");
  if (!path) {
    memset(m, 0, sizeof *m);
    return ss_fail(err, SS_ERR_INVALID, "read STL: NULL path");
  }
  return io_read_with(path, io_parse_stl, m, err);
}
