/* PLY reader: ascii, binary_little_endian and binary_big_endian. Vertex x y z of any numeric type;
 * faces from the list property vertex_indices (or vertex_index) with any integer count and index
 * types; every other property (scalar or list) and every other element is skipped. Elements may come
 * in any order. Declared counts are only loop bounds: arrays grow as data is actually read, and
 * binary lists whose declared length exceeds the bytes left fail at once. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/io_internal.h"
#include "specseg/io.h"

enum { T_I8, T_U8, T_I16, T_U16, T_I32, T_U32, T_F32, T_F64, T_NONE };
static const struct {
  const char *name, *alias;
  int size;
} ply_types[] = {{"char", "int8", 1},   {"uchar", "uint8", 1},  {"short", "int16", 2},    {"ushort", "uint16", 2},
                 {"int", "int32", 4},   {"uint", "uint32", 4},  {"float", "float32", 4}, {"double", "float64", 8}};

static int type_from_token(const char *tb, size_t tl) {
  for (int i = 0; i < T_NONE; i++)
    if (io_tok_eq(tb, tl, ply_types[i].name) || io_tok_eq(tb, tl, ply_types[i].alias)) return i;
  return T_NONE;
}
static int type_is_int(int t) { return t <= T_U32; }

#define PLY_MAX_ELEMENTS 64
#define PLY_MAX_PROPS 64

typedef struct {
  int type;      /* scalar type, or item type of a list */
  int list;      /* 1 when "property list COUNT ITEM name" */
  int count_type;
  char name[64];
} ply_prop;

typedef struct {
  char name[64];
  long long count;
  int nprops;
  ply_prop props[PLY_MAX_PROPS];
} ply_elem;

enum { F_ASCII, F_LE, F_BE };

/* Value source: ascii token stream (line-tracked) or binary bytes. */
typedef struct {
  const char *path;
  int fmt;
  const char *buf;
  size_t len, pos; /* binary: next byte */
  io_text t;       /* ascii: line scanner */
  const char *p, *e; /* ascii: rest of the current line */
} ply_in;

static ss_status in_fail(ply_in *in, ss_error *err, ss_status code, const char *what) {
  if (in->fmt == F_ASCII) return io_fail_line(err, code, in->path, in->t.line, "%s", what);
  return io_fail_byte(err, code, in->path, in->pos, "%s", what);
}

/* ascii: next token across lines; 0 at end of input */
static int next_tok(ply_in *in, const char **tb, size_t *tl) {
  for (;;) {
    if (in->p && io_token(&in->p, in->e, 0, tb, tl)) return 1;
    if (!io_text_line(&in->t, &in->p, &in->e)) return 0;
  }
}

/* Names a value for messages ("face 12 vertex_indices"); only formatted when something fails, since
 * this sits on the per-value path. */
typedef struct {
  const char *elem;
  long long row;
  const char *prop;
} ply_where;

/* Reads one value of type `type` as a double, or as an integer when want_int (then a floating-point
 * type is an error). */
static ss_status read_value(ply_in *in, int type, int want_int, double *d, long long *ll, ply_where w, ss_error *err) {
  char msg[256], show[48], what[160];
#define WHAT() (snprintf(what, sizeof what, "%s %lld %s", w.elem, w.row, w.prop), what)
  if (in->fmt == F_ASCII) {
    const char *tb;
    size_t tl;
    if (!next_tok(in, &tb, &tl)) {
      snprintf(msg, sizeof msg, "unexpected end of file reading %s", WHAT());
      return in_fail(in, err, SS_ERR_PARSE, msg);
    }
    if (want_int || type_is_int(type)) {
      long long v;
      if (io_parse_ll(tb, tl, &v)) {
        snprintf(msg, sizeof msg, "%s: '%s' is not an integer", WHAT(), io_tok_show(tb, tl, show, sizeof show));
        return in_fail(in, err, SS_ERR_PARSE, msg);
      }
      if (ll) *ll = v;
      if (d) *d = (double)v;
    } else {
      double v;
      if (io_parse_double(tb, tl, &v)) {
        snprintf(msg, sizeof msg, "%s: '%s' is not a number", WHAT(), io_tok_show(tb, tl, show, sizeof show));
        return in_fail(in, err, SS_ERR_PARSE, msg);
      }
      if (d) *d = v;
    }
    return SS_OK;
  }
  if (want_int && !type_is_int(type)) { /* the header checks make this unreachable; kept as a guard */
    snprintf(msg, sizeof msg, "%s has a floating-point type", WHAT());
    return in_fail(in, err, SS_ERR_PARSE, msg);
  }
  int sz = ply_types[type].size;
  if (in->len - in->pos < (size_t)sz) {
    snprintf(msg, sizeof msg, "unexpected end of file reading %s", WHAT());
    return in_fail(in, err, SS_ERR_PARSE, msg);
  }
  const unsigned char *q = (const unsigned char *)in->buf + in->pos;
  uint64_t u = 0;
  for (int i = 0; i < sz; i++) {
    int k = in->fmt == F_LE ? sz - 1 - i : i; /* most significant byte first */
    u = (u << 8) | q[k];
  }
  in->pos += (size_t)sz;
  long long iv = 0;
  double dv = 0;
  switch (type) {
    case T_I8: iv = (int8_t)(uint8_t)u; dv = (double)iv; break;
    case T_U8: iv = (long long)u; dv = (double)iv; break;
    case T_I16: iv = (int16_t)(uint16_t)u; dv = (double)iv; break;
    case T_U16: iv = (long long)u; dv = (double)iv; break;
    case T_I32: iv = (int32_t)(uint32_t)u; dv = (double)iv; break;
    case T_U32: iv = (long long)u; dv = (double)iv; break;
    case T_F32: {
      uint32_t bits = (uint32_t)u;
      float f;
      memcpy(&f, &bits, 4);
      dv = f;
      break;
    }
    default: {
      memcpy(&dv, &u, 8);
      break;
    }
  }
#undef WHAT
  if (ll) *ll = iv;
  if (d) *d = dv;
  return SS_OK;
}

/* Skips one property instance (scalar or list) of an element we do not use. */
static ss_status skip_prop(ply_in *in, const char *elem, long long row, const ply_prop *pr, ss_error *err) {
  ply_where w = {elem, row, pr->name};
  if (!pr->list) return read_value(in, pr->type, 0, NULL, NULL, w, err);
  long long k;
  ss_status st = read_value(in, pr->count_type, 1, NULL, &k, w, err);
  if (st) return st;
  if (k < 0) return in_fail(in, err, SS_ERR_PARSE, "negative list length");
  if (in->fmt != F_ASCII && (unsigned long long)k > (in->len - in->pos) / (size_t)ply_types[pr->type].size)
    return in_fail(in, err, SS_ERR_PARSE, "list length exceeds the rest of the file (truncated?)");
  for (long long j = 0; j < k; j++)
    if ((st = read_value(in, pr->type, 0, NULL, NULL, w, err))) return st;
  return SS_OK;
}

static ss_status parse_header(ply_in *in, ply_elem *el, int *nel, ss_error *err) {
  const char *b, *e, *p, *tb;
  size_t tl;
  char show[48];
  const char *path = in->path;
  io_text *t = &in->t;
  if (!io_text_line(t, &b, &e)) return io_fail_line(err, SS_ERR_PARSE, path, 1, "empty file");
  p = b;
  if (!io_token(&p, e, 0, &tb, &tl) || !io_tok_eq(tb, tl, "ply") || !io_line_blank(p, e, 0))
    return io_fail_line(err, SS_ERR_PARSE, path, 1, "not a PLY file (first line must be 'ply')");
  int have_format = 0;
  *nel = 0;
  for (;;) {
    if (!io_text_line(t, &b, &e)) return io_fail_line(err, SS_ERR_PARSE, path, t->line, "unexpected end of file in header (no end_header)");
    p = b;
    if (!io_token(&p, e, 0, &tb, &tl)) continue;
    if (io_tok_eq(tb, tl, "comment") || io_tok_eq(tb, tl, "obj_info")) continue;
    if (io_tok_eq(tb, tl, "end_header")) break;
    if (io_tok_eq(tb, tl, "format")) {
      if (!io_token(&p, e, 0, &tb, &tl)) return io_fail_line(err, SS_ERR_PARSE, path, t->line, "format line without a format");
      if (io_tok_eq(tb, tl, "ascii")) in->fmt = F_ASCII;
      else if (io_tok_eq(tb, tl, "binary_little_endian")) in->fmt = F_LE;
      else if (io_tok_eq(tb, tl, "binary_big_endian")) in->fmt = F_BE;
      else return io_fail_line(err, SS_ERR_UNSUPPORTED, path, t->line, "unknown PLY format '%s'", io_tok_show(tb, tl, show, sizeof show));
      have_format = 1;
      continue;
    }
    if (io_tok_eq(tb, tl, "element")) {
      if (*nel >= PLY_MAX_ELEMENTS) return io_fail_line(err, SS_ERR_UNSUPPORTED, path, t->line, "more than %d elements", PLY_MAX_ELEMENTS);
      ply_elem *E = &el[*nel];
      memset(E, 0, sizeof *E);
      if (!io_token(&p, e, 0, &tb, &tl)) return io_fail_line(err, SS_ERR_PARSE, path, t->line, "element without a name");
      if (tl >= sizeof E->name) return io_fail_line(err, SS_ERR_PARSE, path, t->line, "element name too long");
      memcpy(E->name, tb, tl);
      if (!io_token(&p, e, 0, &tb, &tl) || io_parse_ll(tb, tl, &E->count))
        return io_fail_line(err, SS_ERR_PARSE, path, t->line, "element '%s' has no integer count", E->name);
      if (E->count < 0 || E->count > INT32_MAX)
        return io_fail_line(err, SS_ERR_PARSE, path, t->line, "element '%s' count %lld out of range", E->name, E->count);
      for (int i = 0; i < *nel; i++)
        if (!strcmp(el[i].name, E->name)) return io_fail_line(err, SS_ERR_PARSE, path, t->line, "element '%s' declared twice", E->name);
      (*nel)++;
      continue;
    }
    if (io_tok_eq(tb, tl, "property")) {
      if (*nel == 0) return io_fail_line(err, SS_ERR_PARSE, path, t->line, "property before any element");
      ply_elem *E = &el[*nel - 1];
      if (E->nprops >= PLY_MAX_PROPS) return io_fail_line(err, SS_ERR_UNSUPPORTED, path, t->line, "more than %d properties", PLY_MAX_PROPS);
      ply_prop *P = &E->props[E->nprops];
      memset(P, 0, sizeof *P);
      if (!io_token(&p, e, 0, &tb, &tl)) return io_fail_line(err, SS_ERR_PARSE, path, t->line, "property without a type");
      if (io_tok_eq(tb, tl, "list")) {
        P->list = 1;
        if (!io_token(&p, e, 0, &tb, &tl) || (P->count_type = type_from_token(tb, tl)) == T_NONE)
          return io_fail_line(err, SS_ERR_PARSE, path, t->line, "list property without a valid count type");
        if (!type_is_int(P->count_type)) return io_fail_line(err, SS_ERR_PARSE, path, t->line, "list count type must be an integer type");
        if (!io_token(&p, e, 0, &tb, &tl)) return io_fail_line(err, SS_ERR_PARSE, path, t->line, "list property without an item type");
      }
      if ((P->type = type_from_token(tb, tl)) == T_NONE)
        return io_fail_line(err, SS_ERR_PARSE, path, t->line, "unknown property type '%s'", io_tok_show(tb, tl, show, sizeof show));
      if (!io_token(&p, e, 0, &tb, &tl)) return io_fail_line(err, SS_ERR_PARSE, path, t->line, "property without a name");
      if (tl >= sizeof P->name) return io_fail_line(err, SS_ERR_PARSE, path, t->line, "property name too long");
      memcpy(P->name, tb, tl);
      E->nprops++;
      continue;
    }
    return io_fail_line(err, SS_ERR_PARSE, path, t->line, "unknown header keyword '%s'", io_tok_show(tb, tl, show, sizeof show));
  }
  if (!have_format) return io_fail_line(err, SS_ERR_PARSE, path, t->line, "header has no format line");
  return SS_OK;
}

static int find_prop(const ply_elem *E, const char *name) {
  for (int i = 0; i < E->nprops; i++)
    if (!strcmp(E->props[i].name, name)) return i;
  return -1;
}

/* A vertex colour channel: "red" (or "diffuse_red", "r"), likewise green and blue; -1 when absent. */
static int find_channel(const ply_elem *E, const char *name) {
  char alt[32];
  int k = find_prop(E, name);
  if (k < 0) {
    snprintf(alt, sizeof alt, "diffuse_%s", name);
    k = find_prop(E, alt);
  }
  if (k < 0) {
    alt[0] = name[0], alt[1] = '\0';
    k = find_prop(E, alt);
  }
  return k >= 0 && !E->props[k].list ? k : -1;
}

/* A colour channel value as a byte: integer types as they are (clamped to 0..255), floating-point
 * ones in [0, 1] scaled by 255. */
static unsigned char channel_byte(int type, double v) {
  if (!type_is_int(type)) v *= 255.0;
  if (!(v > 0)) return 0;
  if (v >= 255) return 255;
  return (unsigned char)(v + (type_is_int(type) ? 0 : 0.5));
}

ss_status io_parse_ply(const char *path, const char *buf, size_t len, ss_mesh *m, ss_error *err) {
  return io_parse_ply_rgb(path, buf, len, m, NULL, err);
}

ss_status io_parse_ply_rgb(const char *path, const char *buf, size_t len, ss_mesh *m, unsigned char **rgb,
                           ss_error *err) {
  memset(m, 0, sizeof *m);
  if (rgb) *rgb = NULL;
  io_bvec C = {0};
  ply_in in;
  memset(&in, 0, sizeof in);
  in.path = path;
  in.buf = buf;
  in.len = len;
  io_text_init(&in.t, buf, len);
  if (len == 0) return io_fail_line(err, SS_ERR_PARSE, path, 1, "empty file");
  ply_elem *el = malloc(sizeof(ply_elem) * PLY_MAX_ELEMENTS);
  if (!el) return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", path);
  int nel = 0;
  ss_status st = parse_header(&in, el, &nel, err);
  io_dvec V = {0};
  io_ivec F = {0};
  int vi = -1, fi = -1, px = -1, py = -1, pz = -1, pf = -1, pc[3] = {-1, -1, -1};
  long header_lines = in.t.line;
  if (!st) {
    for (int i = 0; i < nel; i++) {
      if (!strcmp(el[i].name, "vertex")) vi = i;
      if (!strcmp(el[i].name, "face")) fi = i;
    }
    if (vi < 0) st = io_fail_line(err, SS_ERR_PARSE, path, header_lines, "no 'vertex' element in header");
    else if (fi < 0) st = io_fail_line(err, SS_ERR_PARSE, path, header_lines, "no 'face' element in header");
  }
  if (!st) {
    px = find_prop(&el[vi], "x");
    py = find_prop(&el[vi], "y");
    pz = find_prop(&el[vi], "z");
    if (px < 0 || py < 0 || pz < 0 || el[vi].props[px].list || el[vi].props[py].list || el[vi].props[pz].list)
      st = io_fail_line(err, SS_ERR_PARSE, path, header_lines, "vertex element lacks scalar x, y, z properties");
    if (rgb) {
      pc[0] = find_channel(&el[vi], "red");
      pc[1] = find_channel(&el[vi], "green");
      pc[2] = find_channel(&el[vi], "blue");
      if (pc[0] < 0 || pc[1] < 0 || pc[2] < 0) pc[0] = pc[1] = pc[2] = -1; /* all three or none */
    }
    pf = find_prop(&el[fi], "vertex_indices");
    if (pf < 0) pf = find_prop(&el[fi], "vertex_index");
    if (!st && (pf < 0 || !el[fi].props[pf].list))
      st = io_fail_line(err, SS_ERR_PARSE, path, header_lines, "face element lacks a vertex_indices list");
    else if (!st && !type_is_int(el[fi].props[pf].type))
      st = io_fail_line(err, SS_ERR_PARSE, path, header_lines, "face vertex_indices must have an integer item type");
    else if (!st && el[fi].count == 0)
      st = io_fail_line(err, SS_ERR_PARSE, path, header_lines, "mesh has no faces");
    else if (!st && (el[vi].count > IO_MAX_ELEMENTS || el[fi].count > IO_MAX_ELEMENTS))
      st = io_fail_line(err, SS_ERR_PARSE, path, header_lines, "declared vertex/face count out of range");
  }
  in.pos = in.t.pos; /* binary body starts right after the end_header line */

  long long nv_decl = vi >= 0 ? el[vi].count : 0;
  long long max_idx = -1;
  size_t max_loc = 0; /* line (ascii) or byte offset (binary) of the largest index */
  for (int ie = 0; ie < nel && !st; ie++) {
    const ply_elem *E = &el[ie];
    if (E->nprops == 0) continue; /* nothing stored: a huge count must not spin */
    for (long long r = 0; r < E->count && !st; r++) {
      double xyz[3] = {0, 0, 0}, col[3] = {0, 0, 0};
      for (int ip = 0; ip < E->nprops && !st; ip++) {
        const ply_prop *P = &E->props[ip];
        if (ie == vi && (ip == px || ip == py || ip == pz)) {
          ply_where w = {"vertex", r, P->name};
          st = read_value(&in, P->type, 0, &xyz[ip == px ? 0 : ip == py ? 1 : 2], NULL, w, err);
        } else if (ie == vi && pc[0] >= 0 && (ip == pc[0] || ip == pc[1] || ip == pc[2])) {
          ply_where w = {"vertex", r, P->name};
          int c = ip == pc[0] ? 0 : ip == pc[1] ? 1 : 2;
          if (!(st = read_value(&in, P->type, 0, &col[c], NULL, w, err))) col[c] = channel_byte(P->type, col[c]);
        } else if (ie == fi && ip == pf) {
          long long k;
          char what[128];
          ply_where wc = {"face", r, "vertex count"}, wi = {"face", r, "vertex index"};
          if ((st = read_value(&in, P->count_type, 1, NULL, &k, wc, err))) break;
          if (k < 3) {
            snprintf(what, sizeof what, "face %lld has %lld vertices (at least 3 needed)", r, k);
            st = in_fail(&in, err, SS_ERR_PARSE, what);
            break;
          }
          if (in.fmt != F_ASCII && (unsigned long long)k > (in.len - in.pos) / (size_t)ply_types[P->type].size) {
            snprintf(what, sizeof what, "face %lld: %lld indices exceed the rest of the file", r, k);
            st = in_fail(&in, err, SS_ERR_PARSE, what);
            break;
          }
          int first = -1, prev = -1;
          for (long long j = 0; j < k && !st; j++) {
            long long idx;
            size_t at = in.pos; /* binary: report the offset where the index starts */
            if ((st = read_value(&in, P->type, 1, NULL, &idx, wi, err))) break;
            if (idx < 0 || idx >= nv_decl) {
              char msg[128];
              snprintf(msg, sizeof msg, "face %lld: vertex index %lld out of range [0, %lld)", r, idx, nv_decl);
              in.pos = at;
              st = in_fail(&in, err, SS_ERR_PARSE, msg);
              break;
            }
            if (idx > max_idx) {
              max_idx = idx;
              max_loc = in.fmt == F_ASCII ? (size_t)in.t.line : at;
            }
            if (j == 0) first = (int)idx;
            else if (j == 1) prev = (int)idx;
            else {
              if (F.n / 3 >= (size_t)IO_MAX_ELEMENTS) st = in_fail(&in, err, SS_ERR_PARSE, "too many triangles");
              else if (io_ivec_push(&F, first) || io_ivec_push(&F, prev) || io_ivec_push(&F, (int)idx))
                st = in_fail(&in, err, SS_ERR_NOMEM, "out of memory");
              prev = (int)idx;
            }
          }
        } else {
          st = skip_prop(&in, E->name, r, P, err);
        }
      }
      if (!st && ie == vi)
        for (int d = 0; d < 3 && !st; d++)
          if (io_dvec_push(&V, xyz[d]) || (pc[0] >= 0 && io_bvec_push(&C, (unsigned char)col[d])))
            st = in_fail(&in, err, SS_ERR_NOMEM, "out of memory");
    }
  }
  /* leftover data means the declared counts are wrong (trailing blank space is tolerated) */
  if (!st) {
    if (in.fmt == F_ASCII) {
      const char *tb;
      size_t tl;
      if (next_tok(&in, &tb, &tl)) st = in_fail(&in, err, SS_ERR_PARSE, "data after the last declared element (wrong counts?)");
    } else {
      size_t q = in.pos;
      while (q < in.len && (buf[q] == '\n' || buf[q] == '\r' || buf[q] == ' ' || buf[q] == '\t')) q++;
      if (q < in.len) st = in_fail(&in, err, SS_ERR_PARSE, "data after the last declared element (wrong counts?)");
    }
  }
  /* Indices were checked against the declared vertex count; that count is only trusted once the
   * vertices were all actually read, which the loop above guarantees (or it failed). */
  if (!st && max_idx >= (long long)(V.n / 3)) {
    if (in.fmt == F_ASCII) st = io_fail_line(err, SS_ERR_PARSE, path, (long)max_loc, "vertex index %lld out of range", max_idx);
    else st = io_fail_byte(err, SS_ERR_PARSE, path, max_loc, "vertex index %lld out of range", max_idx);
  }
  if (!st) st = io_finish_mesh(&V, &F, m, path, err);
  if (!st && rgb && pc[0] >= 0) {
    *rgb = C.a; /* 3 nv bytes: one colour per vertex read */
    C.a = NULL;
  }
  free(V.a);
  free(F.a);
  free(C.a);
  free(el);
  return st;
}

ss_status ss_read_ply(const char *path, ss_mesh *m, ss_error *err) {
  return io_read_with(path, io_parse_ply, m, err);
}
