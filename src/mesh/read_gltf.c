/* glTF 2.0 reader, our own (it was assimp's, whose importer crashed and leaked on malformed input).
 * .gltf is JSON; .glb a 12-byte header ("glTF", version 2, total length) and chunks (length, type),
 * JSON first, an optional BIN chunk second. A small strict JSON parser (RFC 8259, UTF-8 checked,
 * nesting at most 64 deep; a duplicate key: the last one wins) builds a tree; the glTF reading walks
 * it, checking every reference and every byte range before touching data.
 *
 * What is read: the triangles (modes TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN; points and lines are
 * dropped) of every mesh instance of the scene (`scene`, else scenes[0]; without scenes every mesh
 * once, untransformed), each placed by its node's world transform (parent * local, double precision),
 * in depth-first node order, concatenated, then welded by exact coordinates like the other readers.
 * Buffers: base64 data URIs, a GLB's BIN chunk, or files beside the .gltf (only when reading by path).
 * Refused with a message: sparse accessors, accessors without bufferView (all zeros), extensions
 * required other than KHR_mesh_quantization (integer positions), glTF 1.0, instancing out of
 * proportion to the file (GLTF_MAX_COPIES below). Skins and morph targets are ignored (the mesh as
 * stored). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/io_internal.h"
#include "util/c_locale.h"
#include "specseg/io.h"

/* ---- JSON ---------------------------------------------------------------------------------------- */

enum { J_NULL, J_FALSE, J_TRUE, J_NUM, J_STR, J_ARR, J_OBJ };

typedef struct jv {
  unsigned char t;
  size_t off;    /* the value's byte offset in the JSON text */
  size_t ko, kn; /* an object member's key: offset and length in the string pool */
  double num;
  size_t a, n; /* string: pool offset and length; array / object: first entry in items[] and count */
} jv;

typedef struct jdoc {
  jv *v;
  size_t nv, cv;
  size_t *items; /* the entries of each array / object, contiguous */
  size_t ni, ci;
  size_t *stk; /* entries of the containers being parsed */
  size_t ns, cs;
  char *pool; /* decoded strings, each followed by a NUL */
  size_t np, cp;
} jdoc;

#define JSON_MAX_DEPTH 64

typedef struct jparse {
  const unsigned char *s;
  size_t len, pos;
  jdoc *d;
  size_t epos; /* where the error is */
  const char *emsg;
} jparse;

static void jdoc_free(jdoc *d) {
  free(d->v), free(d->items), free(d->stk), free(d->pool);
  memset(d, 0, sizeof *d);
}

/* room for `more` further elements of size sz in *p (capacity *cap, used n): 0, or -1 out of memory */
static int grow(void **p, size_t *cap, size_t n, size_t more, size_t sz) {
  if (more <= *cap - n) return 0;
  size_t c = *cap ? *cap : 16;
  while (c - n < more) {
    if (c > SIZE_MAX / 2 / sz) return -1;
    c *= 2;
  }
  void *q = realloc(*p, c * sz);
  if (!q) return -1;
  *p = q, *cap = c;
  return 0;
}

static int jfail(jparse *p, size_t at, const char *msg) {
  p->epos = at, p->emsg = msg;
  return -1;
}

static void jskip_ws(jparse *p) {
  while (p->pos < p->len) {
    unsigned char c = p->s[p->pos];
    if (c != ' ' && c != '\t' && c != '\n' && c != '\r') break;
    p->pos++;
  }
}

static int jpool_put(jparse *p, const void *b, size_t n) {
  if (grow((void **)&p->d->pool, &p->d->cp, p->d->np, n, 1)) return jfail(p, p->pos, "out of memory");
  memcpy(p->d->pool + p->d->np, b, n);
  p->d->np += n;
  return 0;
}

static int hex4(const unsigned char *s, unsigned *out) {
  unsigned v = 0;
  for (int i = 0; i < 4; i++) {
    unsigned c = s[i], d;
    if (c >= '0' && c <= '9')
      d = c - '0';
    else if (c >= 'a' && c <= 'f')
      d = c - 'a' + 10;
    else if (c >= 'A' && c <= 'F')
      d = c - 'A' + 10;
    else
      return -1;
    v = v << 4 | d;
  }
  *out = v;
  return 0;
}

/* length of the valid UTF-8 sequence at s (n bytes left), 0 when invalid (overlong, surrogate, > U+10FFFF) */
static size_t utf8_len(const unsigned char *s, size_t n) {
  unsigned c = s[0];
  size_t k;
  unsigned lo = 0x80, hi = 0xBF;
  if (c >= 0xC2 && c <= 0xDF)
    k = 2;
  else if (c >= 0xE0 && c <= 0xEF) {
    k = 3;
    if (c == 0xE0) lo = 0xA0;
    if (c == 0xED) hi = 0x9F;
  } else if (c >= 0xF0 && c <= 0xF4) {
    k = 4;
    if (c == 0xF0) lo = 0x90;
    if (c == 0xF4) hi = 0x8F;
  } else
    return 0;
  if (n < k || s[1] < lo || s[1] > hi) return 0;
  for (size_t i = 2; i < k; i++)
    if (s[i] < 0x80 || s[i] > 0xBF) return 0;
  return k;
}

/* a string at the opening quote into the pool; *o, *n its place there */
static int jstring(jparse *p, size_t *o, size_t *n) {
  const size_t start = p->pos++;
  *o = p->d->np;
  for (;;) {
    if (p->pos >= p->len) return jfail(p, start, "unterminated string");
    size_t run = p->pos; /* plain bytes copied in runs */
    while (p->pos < p->len && p->s[p->pos] != '"' && p->s[p->pos] != '\\' && p->s[p->pos] >= 0x20) {
      if (p->s[p->pos] < 0x80)
        p->pos++;
      else {
        size_t k = utf8_len(p->s + p->pos, p->len - p->pos);
        if (!k) return jfail(p, p->pos, "invalid UTF-8 in a string");
        p->pos += k;
      }
    }
    if (p->pos > run && jpool_put(p, p->s + run, p->pos - run)) return -1;
    if (p->pos >= p->len) return jfail(p, start, "unterminated string");
    unsigned char c = p->s[p->pos];
    if (c == '"') {
      p->pos++;
      break;
    }
    if (c < 0x20) return jfail(p, p->pos, "control character in a string (must be escaped)");
    /* an escape */
    if (p->pos + 1 >= p->len) return jfail(p, start, "unterminated string");
    unsigned char e = p->s[p->pos + 1];
    const char *simple = strchr("\"\\/bfnrt", e);
    if (e && simple) {
      static const char out[] = "\"\\/\b\f\n\r\t";
      if (jpool_put(p, out + (simple - "\"\\/bfnrt"), 1)) return -1;
      p->pos += 2;
      continue;
    }
    if (e != 'u') return jfail(p, p->pos, "invalid escape in a string");
    unsigned u, u2;
    if (p->len - p->pos < 6 || hex4(p->s + p->pos + 2, &u))
      return jfail(p, p->pos, "invalid \\u escape (4 hex digits expected)");
    p->pos += 6;
    if (u >= 0xDC00 && u <= 0xDFFF) return jfail(p, p->pos - 6, "unpaired low surrogate in a \\u escape");
    if (u >= 0xD800 && u <= 0xDBFF) {
      if (p->len - p->pos < 6 || p->s[p->pos] != '\\' || p->s[p->pos + 1] != 'u' || hex4(p->s + p->pos + 2, &u2) ||
          u2 < 0xDC00 || u2 > 0xDFFF)
        return jfail(p, p->pos - 6, "high surrogate in a \\u escape without its low surrogate");
      p->pos += 6;
      u = 0x10000 + ((u - 0xD800) << 10 | (u2 - 0xDC00));
    }
    unsigned char b[4];
    size_t k;
    if (u < 0x80)
      b[0] = (unsigned char)u, k = 1;
    else if (u < 0x800)
      b[0] = (unsigned char)(0xC0 | u >> 6), b[1] = (unsigned char)(0x80 | (u & 63)), k = 2;
    else if (u < 0x10000)
      b[0] = (unsigned char)(0xE0 | u >> 12), b[1] = (unsigned char)(0x80 | (u >> 6 & 63)),
      b[2] = (unsigned char)(0x80 | (u & 63)), k = 3;
    else
      b[0] = (unsigned char)(0xF0 | u >> 18), b[1] = (unsigned char)(0x80 | (u >> 12 & 63)),
      b[2] = (unsigned char)(0x80 | (u >> 6 & 63)), b[3] = (unsigned char)(0x80 | (u & 63)), k = 4;
    if (jpool_put(p, b, k)) return -1;
  }
  *n = p->d->np - *o;
  return jpool_put(p, "", 1);
}

static int isdig(unsigned char c) { return c >= '0' && c <= '9'; }

static int jnumber(jparse *p, double *out) {
  const size_t start = p->pos;
  size_t i = p->pos;
  const unsigned char *s = p->s;
  if (i < p->len && s[i] == '-') i++;
  if (i >= p->len || !isdig(s[i])) return jfail(p, start, "invalid number");
  if (s[i] == '0')
    i++;
  else
    while (i < p->len && isdig(s[i])) i++;
  if (i < p->len && s[i] == '.') {
    i++;
    if (i >= p->len || !isdig(s[i])) return jfail(p, start, "invalid number (a digit must follow '.')");
    while (i < p->len && isdig(s[i])) i++;
  }
  if (i < p->len && (s[i] == 'e' || s[i] == 'E')) {
    i++;
    if (i < p->len && (s[i] == '+' || s[i] == '-')) i++;
    if (i >= p->len || !isdig(s[i])) return jfail(p, start, "invalid number (a digit must follow the exponent)");
    while (i < p->len && isdig(s[i])) i++;
  }
  /* strtod on a NUL-terminated copy: the text need not end after the number */
  const size_t n = i - start;
  char small[128], *t = n < sizeof small ? small : malloc(n + 1);
  if (!t) return jfail(p, start, "out of memory");
  memcpy(t, s + start, n);
  t[n] = '\0';
  char *end;
  double v = ssi_strtod_c(t, &end);
  const int whole = end == t + n;
  if (t != small) free(t);
  if (!whole) return jfail(p, start, "number not readable");
  if (!isfinite(v)) return jfail(p, start, "number out of range");
  *out = v;
  p->pos = i;
  return 0;
}

static int jlit(jparse *p, const char *w) {
  size_t n = strlen(w);
  if (p->len - p->pos < n || memcmp(p->s + p->pos, w, n)) return jfail(p, p->pos, "unexpected character");
  p->pos += n;
  return 0;
}

static int jnew(jparse *p, unsigned char t, size_t off, size_t *idx) {
  jdoc *d = p->d;
  if (grow((void **)&d->v, &d->cv, d->nv, 1, sizeof *d->v)) return jfail(p, off, "out of memory");
  jv *v = d->v + d->nv;
  memset(v, 0, sizeof *v);
  v->t = t, v->off = off, v->ko = SIZE_MAX;
  *idx = d->nv++;
  return 0;
}

static int jpush_stk(jparse *p, size_t idx) {
  jdoc *d = p->d;
  if (grow((void **)&d->stk, &d->cs, d->ns, 1, sizeof *d->stk)) return jfail(p, p->pos, "out of memory");
  d->stk[d->ns++] = idx;
  return 0;
}

/* moves a container's entries (the top n of the stack) into items[] */
static int jclose(jparse *p, size_t idx, size_t n) {
  jdoc *d = p->d;
  if (grow((void **)&d->items, &d->ci, d->ni, n, sizeof *d->items)) return jfail(p, p->pos, "out of memory");
  if (n) memcpy(d->items + d->ni, d->stk + d->ns - n, n * sizeof *d->items); /* empty: items may still be NULL */
  d->v[idx].a = d->ni, d->v[idx].n = n;
  d->ni += n, d->ns -= n;
  return 0;
}

static int jvalue(jparse *p, int depth, size_t *idx) {
  jskip_ws(p);
  if (p->pos >= p->len) return jfail(p, p->pos, "unexpected end of the JSON text");
  const size_t at = p->pos;
  unsigned char c = p->s[at];
  if (c == '{' || c == '[') {
    if (depth >= JSON_MAX_DEPTH) return jfail(p, at, "nested deeper than 64 levels");
    const int obj = c == '{';
    size_t me, n = 0;
    if (jnew(p, obj ? J_OBJ : J_ARR, at, &me)) return -1;
    p->pos++;
    jskip_ws(p);
    if (p->pos < p->len && p->s[p->pos] == (obj ? '}' : ']')) {
      p->pos++;
      *idx = me;
      return jclose(p, me, 0);
    }
    for (;;) {
      size_t ko = 0, kn = 0, child;
      if (obj) {
        jskip_ws(p);
        if (p->pos >= p->len) return jfail(p, at, "unterminated object");
        if (p->s[p->pos] != '"') return jfail(p, p->pos, "a member name (a string) expected");
        if (jstring(p, &ko, &kn)) return -1;
        jskip_ws(p);
        if (p->pos >= p->len || p->s[p->pos] != ':') return jfail(p, p->pos, "':' expected after a member name");
        p->pos++;
      }
      if (jvalue(p, depth + 1, &child)) return -1;
      if (obj) p->d->v[child].ko = ko, p->d->v[child].kn = kn;
      if (jpush_stk(p, child)) return -1;
      n++;
      jskip_ws(p);
      if (p->pos >= p->len) return jfail(p, at, obj ? "unterminated object" : "unterminated array");
      c = p->s[p->pos++];
      if (c == ',') continue;
      if (c == (obj ? '}' : ']')) break;
      return jfail(p, p->pos - 1, obj ? "',' or '}' expected in an object" : "',' or ']' expected in an array");
    }
    *idx = me;
    return jclose(p, me, n);
  }
  if (c == '"') {
    size_t o, n;
    if (jnew(p, J_STR, at, idx) || jstring(p, &o, &n)) return -1;
    p->d->v[*idx].a = o, p->d->v[*idx].n = n;
    return 0;
  }
  if (c == '-' || isdig(c)) {
    double x;
    if (jnumber(p, &x) || jnew(p, J_NUM, at, idx)) return -1;
    p->d->v[*idx].num = x;
    return 0;
  }
  if (c == 't') return jlit(p, "true") || jnew(p, J_TRUE, at, idx);
  if (c == 'f') return jlit(p, "false") || jnew(p, J_FALSE, at, idx);
  if (c == 'n') return jlit(p, "null") || jnew(p, J_NULL, at, idx);
  return jfail(p, at, "unexpected character");
}

/* the whole text as one value; 0 or -1 with p->emsg, p->epos */
static int json_parse(jparse *p, const unsigned char *s, size_t len, jdoc *d) {
  memset(d, 0, sizeof *d);
  p->s = s, p->len = len, p->pos = 0, p->d = d, p->emsg = NULL;
  if (len >= 3 && s[0] == 0xEF && s[1] == 0xBB && s[2] == 0xBF) p->pos = 3; /* a BOM is tolerated */
  size_t root;
  if (jvalue(p, 0, &root)) return -1;
  jskip_ws(p);
  if (p->pos < p->len) return jfail(p, p->pos, "text after the JSON value");
  return 0;
}

static const jv *jget(const jdoc *d, const jv *o, const char *key) {
  if (!o || o->t != J_OBJ) return NULL;
  const size_t kn = strlen(key);
  const jv *hit = NULL; /* the last of duplicate keys wins */
  for (size_t i = 0; i < o->n; i++) {
    const jv *m = d->v + d->items[o->a + i];
    if (m->kn == kn && !memcmp(d->pool + m->ko, key, kn)) hit = m;
  }
  return hit;
}

static const jv *jat(const jdoc *d, const jv *a, size_t i) { return d->v + d->items[a->a + i]; }

/* a string value as a C string (NULL when it holds a NUL) */
static const char *jstr(const jdoc *d, const jv *v) {
  if (!v || v->t != J_STR || strlen(d->pool + v->a) != v->n) return NULL;
  return d->pool + v->a;
}

/* ---- the glTF document ----------------------------------------------------------------------------- */

#define MAX_EXACT 9007199254740992.0 /* 2^53: larger integers are not exact in a JSON number */
#define GLB_JSON 0x4E4F534Au
#define GLB_BIN 0x004E4942u
/* A scene may place a mesh once per node that names it, and one accessor may serve many meshes: a
 * file of a few kilobytes could ask for hundreds of millions of vertices (many GB) before any other
 * limit applies. Past GLTF_FLOOR vertices the scene may place its stored vertices (each POSITION
 * accessor counted once) at most GLTF_MAX_COPIES times over, so that memory stays in proportion to
 * the file; a shape to match is one body, not a crowd of copies. */
#define GLTF_FLOOR ((size_t)1 << 20)
#define GLTF_MAX_COPIES 64

typedef struct gbuf {
  const unsigned char *p;
  size_t n; /* byteLength (checked against the data) */
  unsigned char *own;
  int loaded;
} gbuf;

typedef struct gl {
  const char *name, *path;
  ss_error *err;
  jdoc d;
  const jv *root, *buffers, *views, *accessors, *meshes, *nodes;
  const unsigned char *bin; /* a GLB's BIN chunk */
  size_t binlen;
  int glb, has_bin, quant;
  gbuf *bufs;
  unsigned char *state; /* per node: 0 not seen, 1 on the path from the root, 2 done */
  unsigned char *placed; /* per accessor: 1 once some primitive placed its vertices */
  size_t stored;         /* the vertices of the POSITION accessors placed, each accessor once */
  io_dvec V;
  io_ivec F;
  long dropped, prims;
} gl;

static uint32_t u32le(const unsigned char *u) {
  return (uint32_t)u[0] | (uint32_t)u[1] << 8 | (uint32_t)u[2] << 16 | (uint32_t)u[3] << 24;
}

/* a top-level array (absent: NULL, which counts as empty) */
static ss_status top_array(gl *g, const char *key, const jv **out) {
  const jv *a = jget(&g->d, g->root, key);
  if (a && a->t != J_ARR) return ss_fail(g->err, SS_ERR_PARSE, "%s: '%s' is not an array", g->name, key);
  *out = a;
  return SS_OK;
}

static size_t alen(const jv *a) { return a ? a->n : 0; }

/* An integer member ctx.key in [lo, hi]; absent: def when !required. */
static ss_status get_int(gl *g, const jv *obj, const char *ctx, const char *key, int required, double def, double lo,
                         double hi, double *out) {
  const jv *v = jget(&g->d, obj, key);
  if (!v) {
    if (required) return ss_fail(g->err, SS_ERR_PARSE, "%s: %s: '%s' is missing", g->name, ctx, key);
    *out = def;
    return SS_OK;
  }
  if (v->t != J_NUM || v->num != floor(v->num))
    return ss_fail(g->err, SS_ERR_PARSE, "%s: %s.%s is not an integer", g->name, ctx, key);
  if (v->num < lo || v->num > hi)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: %s.%s: %.17g is out of range (%.17g to %.17g)", g->name, ctx, key, v->num,
                   lo, hi);
  *out = v->num;
  return SS_OK;
}

/* A reference ctx.key into the top-level array arr (named what); absent: -1 when !required. */
static ss_status get_ref(gl *g, const jv *obj, const char *ctx, const char *key, int required, const jv *arr,
                         const char *what, long *out) {
  const jv *v = jget(&g->d, obj, key);
  if (!v) {
    if (required) return ss_fail(g->err, SS_ERR_PARSE, "%s: %s: '%s' is missing", g->name, ctx, key);
    *out = -1;
    return SS_OK;
  }
  if (v->t != J_NUM || v->num != floor(v->num) || v->num < 0)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: %s.%s is not an index (a non-negative integer)", g->name, ctx, key);
  if (v->num >= (double)alen(arr))
    return ss_fail(g->err, SS_ERR_PARSE, "%s: %s.%s: %.17g, but '%s' has %zu entries", g->name, ctx, key, v->num, what,
                   alen(arr));
  *out = (long)v->num;
  return SS_OK;
}

static ss_status get_bool(gl *g, const jv *obj, const char *ctx, const char *key, int *out) {
  const jv *v = jget(&g->d, obj, key);
  *out = 0;
  if (!v) return SS_OK;
  if (v->t != J_TRUE && v->t != J_FALSE)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: %s.%s is not true or false", g->name, ctx, key);
  *out = v->t == J_TRUE;
  return SS_OK;
}

/* An array member of exactly n finite numbers into x; *present 0 when absent. */
static ss_status get_numbers(gl *g, const jv *obj, const char *ctx, const char *key, int n, double *x, int *present) {
  const jv *v = jget(&g->d, obj, key);
  *present = v != NULL;
  if (!v) return SS_OK;
  if (v->t != J_ARR || v->n != (size_t)n)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: %s.%s is not an array of %d numbers", g->name, ctx, key, n);
  for (int i = 0; i < n; i++) {
    const jv *e = jat(&g->d, v, (size_t)i);
    if (e->t != J_NUM) return ss_fail(g->err, SS_ERR_PARSE, "%s: %s.%s[%d] is not a number", g->name, ctx, key, i);
    x[i] = e->num;
  }
  return SS_OK;
}

/* an object entry of a top-level array */
static ss_status entry(gl *g, const jv *arr, const char *what, long i, const jv **out) {
  const jv *e = jat(&g->d, arr, (size_t)i);
  if (e->t != J_OBJ) return ss_fail(g->err, SS_ERR_PARSE, "%s: %s[%ld] is not an object", g->name, what, i);
  *out = e;
  return SS_OK;
}

/* ---- buffers ---- */

static int b64val(unsigned char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

/* Strict base64: the alphabet only (no blanks), a length that is a multiple of 4, '=' padding only at
 * the end. The decoded size is at most 3/4 of the text's, which lies in memory already. */
static ss_status base64_decode(gl *g, long bi, const char *s, size_t n, unsigned char **out, size_t *outn) {
  if (n % 4)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: buffers[%ld].uri: base64 data of %zu characters (not a multiple of 4)",
                   g->name, bi, n);
  size_t pad = n >= 1 && s[n - 1] == '=' ? (n >= 2 && s[n - 2] == '=' ? 2 : 1) : 0;
  unsigned char *o = malloc(n / 4 * 3 + 1);
  if (!o) return ss_fail(g->err, SS_ERR_NOMEM, "%s: out of memory", g->name);
  size_t k = 0;
  for (size_t i = 0; i < n; i += 4) {
    uint32_t v = 0;
    for (size_t j = 0; j < 4; j++) {
      int c = i + j >= n - pad ? 0 : b64val((unsigned char)s[i + j]);
      if (c < 0) {
        free(o);
        return ss_fail(g->err, SS_ERR_PARSE, "%s: buffers[%ld].uri: invalid base64 character at position %zu", g->name,
                       bi, i + j);
      }
      v = v << 6 | (uint32_t)c;
    }
    o[k++] = (unsigned char)(v >> 16), o[k++] = (unsigned char)(v >> 8), o[k++] = (unsigned char)v;
  }
  *out = o, *outn = k - pad;
  return SS_OK;
}

static int lower_eq(const char *a, size_t n, const char *b) {
  if (strlen(b) != n) return 0;
  for (size_t i = 0; i < n; i++) {
    char c = a[i];
    if ((c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c) != b[i]) return 0;
  }
  return 1;
}

static int hexval(char c) {
  return c >= '0' && c <= '9'   ? c - '0'
         : c >= 'a' && c <= 'f' ? c - 'a' + 10
         : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                : -1;
}

/* an external buffer: the uri percent-decoded, relative to the .gltf's folder (absolute paths as given) */
static ss_status read_external(gl *g, long bi, const char *uri, unsigned char **out, size_t *outn) {
  char show[48];
  if (!g->path)
    return ss_fail(
        g->err, SS_ERR_UNSUPPORTED,
        "%s: buffers[%ld]: the external file '%s' cannot be read from memory (read the .gltf by its path, or "
        "embed the buffer)",
        g->name, bi, io_tok_show(uri, strlen(uri), show, sizeof show));
  const char *slash = uri[0] == '/' ? NULL : strrchr(g->path, '/');
  const size_t dir = slash ? (size_t)(slash - g->path) + 1 : 0, un = strlen(uri);
  char *full = malloc(dir + un + 1);
  if (!full) return ss_fail(g->err, SS_ERR_NOMEM, "%s: out of memory", g->name);
  memcpy(full, g->path, dir);
  size_t k = dir;
  for (size_t i = 0; i < un; i++) {
    if (uri[i] != '%') {
      full[k++] = uri[i];
      continue;
    }
    int a = i + 1 < un ? hexval(uri[i + 1]) : -1, b = i + 2 < un ? hexval(uri[i + 2]) : -1;
    if (a < 0 || b < 0 || (a == 0 && b == 0)) {
      free(full);
      return ss_fail(g->err, SS_ERR_PARSE, "%s: buffers[%ld].uri: invalid percent escape in '%s'", g->name, bi,
                     io_tok_show(uri, un, show, sizeof show));
    }
    full[k++] = (char)(a * 16 + b);
    i += 2;
  }
  full[k] = '\0';
  char *data;
  size_t len;
  ss_error e2 = {{0}};
  ss_status st = io_slurp(full, &data, &len, &e2);
  free(full);
  if (st) return ss_fail(g->err, st, "%s: buffers[%ld]: %s", g->name, bi, e2.msg);
  *out = (unsigned char *)data, *outn = len;
  return SS_OK;
}

static ss_status get_buffer(gl *g, long bi, const unsigned char **p, size_t *n) {
  gbuf *b = g->bufs + bi;
  if (b->loaded) {
    *p = b->p, *n = b->n;
    return SS_OK;
  }
  char ctx[48], show[48];
  snprintf(ctx, sizeof ctx, "buffers[%ld]", bi);
  const jv *o = NULL;
  double blen = 0;
  ss_status st;
  if ((st = entry(g, g->buffers, "buffers", bi, &o)) ||
      (st = get_int(g, o, ctx, "byteLength", 1, 0, 1, MAX_EXACT, &blen)))
    return st;
  const jv *u = jget(&g->d, o, "uri");
  const unsigned char *data = NULL;
  size_t have = 0;
  if (!u) {
    if (!g->glb || bi != 0)
      return ss_fail(g->err, SS_ERR_PARSE, "%s: %s has no uri (only a GLB's first buffer, its BIN chunk, may lack one)",
                     g->name, ctx);
    if (!g->has_bin)
      return ss_fail(g->err, SS_ERR_PARSE, "%s: %s refers to the GLB's BIN chunk, which is missing", g->name, ctx);
    data = g->bin, have = g->binlen;
  } else {
    const char *uri = jstr(&g->d, u);
    if (!uri) return ss_fail(g->err, SS_ERR_PARSE, "%s: %s.uri is not a string", g->name, ctx);
    const size_t un = strlen(uri);
    size_t sch = 0; /* a scheme: a letter, then letters, digits, '+', '-', '.', then ':' */
    if ((uri[0] | 32) >= 'a' && (uri[0] | 32) <= 'z')
      for (sch = 1;
           uri[sch] && (((uri[sch] | 32) >= 'a' && (uri[sch] | 32) <= 'z') || (uri[sch] >= '0' && uri[sch] <= '9') ||
                        uri[sch] == '+' || uri[sch] == '-' || uri[sch] == '.');)
        sch++;
    if (sch && uri[sch] == ':') {
      if (!lower_eq(uri, sch, "data"))
        return ss_fail(g->err, SS_ERR_UNSUPPORTED, "%s: %s.uri '%s': only data: URIs and relative file paths are read",
                       g->name, ctx, io_tok_show(uri, un, show, sizeof show));
      const char *comma = strchr(uri, ',');
      const size_t hl = comma ? (size_t)(comma - uri) : 0;
      if (!comma || (!lower_eq(uri, hl, "data:application/octet-stream;base64") &&
                     !lower_eq(uri, hl, "data:application/gltf-buffer;base64")))
        return ss_fail(g->err, SS_ERR_PARSE,
                       "%s: %s.uri '%s': a data URI must be data:application/octet-stream;base64,... or "
                       "data:application/gltf-buffer;base64,...",
                       g->name, ctx, io_tok_show(uri, comma ? hl : un, show, sizeof show));
      if ((st = base64_decode(g, bi, comma + 1, un - hl - 1, &b->own, &have))) return st;
    } else if ((st = read_external(g, bi, uri, &b->own, &have)))
      return st;
    data = b->own;
  }
  if (blen > (double)have)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: %s.byteLength %.17g, but its data has %zu bytes", g->name, ctx, blen,
                   have);
  b->p = data, b->n = (size_t)blen, b->loaded = 1;
  *p = b->p, *n = b->n;
  return SS_OK;
}

/* ---- accessors ---- */

typedef struct acc {
  const unsigned char *p; /* the first element */
  size_t count, stride;
  int ctype, ncomp, csize, norm;
} acc;

static int comp_size(int ct) {
  switch (ct) {
    case 5120:
    case 5121: return 1;
    case 5122:
    case 5123: return 2;
    case 5125:
    case 5126: return 4;
    default: return 0;
  }
}

/* Accessor ai, of type want ("VEC3", "SCALAR"), for use (messages): every byte it reaches lies in its
 * buffer view, which lies in its buffer. */
static ss_status get_accessor(gl *g, long ai, const char *use, const char *want, acc *a) {
  char ctx[48], vctx[48];
  snprintf(ctx, sizeof ctx, "accessors[%ld]", ai);
  const jv *o = NULL, *vo = NULL;
  ss_status st;
  if ((st = entry(g, g->accessors, "accessors", ai, &o))) return st;
  if (jget(&g->d, o, "sparse"))
    return ss_fail(g->err, SS_ERR_UNSUPPORTED, "%s: %s (%s) is sparse: sparse accessors are not supported", g->name,
                   ctx, use);
  const char *type = jstr(&g->d, jget(&g->d, o, "type"));
  if (!type) return ss_fail(g->err, SS_ERR_PARSE, "%s: %s: 'type' is missing or not a string", g->name, ctx);
  if (strcmp(type, want))
    return ss_fail(g->err, SS_ERR_PARSE, "%s: %s (%s) has type '%s', %s expected", g->name, ctx, use, type, want);
  double ct = 0, count = 0, off = 0, voff = 0, vlen = 0, stride = 0, buf;
  long vi = 0, bi = 0;
  if ((st = get_int(g, o, ctx, "componentType", 1, 0, 0, 1e9, &ct)) ||
      (st = get_bool(g, o, ctx, "normalized", &a->norm)) ||
      (st = get_int(g, o, ctx, "count", 1, 0, 1, MAX_EXACT, &count)) ||
      (st = get_int(g, o, ctx, "byteOffset", 0, 0, 0, MAX_EXACT, &off)))
    return st;
  a->ctype = (int)ct, a->csize = comp_size(a->ctype), a->ncomp = !strcmp(want, "VEC3") ? 3 : 1;
  if (!a->csize)
    return ss_fail(g->err, SS_ERR_PARSE,
                   "%s: %s.componentType %d is not a glTF component type (5120, 5121, 5122, 5123, "
                   "5125, 5126)",
                   g->name, ctx, a->ctype);
  if (!jget(&g->d, o, "bufferView"))
    return ss_fail(g->err, SS_ERR_UNSUPPORTED, "%s: %s (%s) has no bufferView (all zeros): not supported", g->name, ctx,
                   use);
  if ((st = get_ref(g, o, ctx, "bufferView", 1, g->views, "bufferViews", &vi))) return st;
  snprintf(vctx, sizeof vctx, "bufferViews[%ld]", vi);
  if ((st = entry(g, g->views, "bufferViews", vi, &vo)) ||
      (st = get_ref(g, vo, vctx, "buffer", 1, g->buffers, "buffers", &bi)) ||
      (st = get_int(g, vo, vctx, "byteOffset", 0, 0, 0, MAX_EXACT, &voff)) ||
      (st = get_int(g, vo, vctx, "byteLength", 1, 0, 1, MAX_EXACT, &vlen)) ||
      (st = get_int(g, vo, vctx, "byteStride", 0, 0, 4, 252, &stride)))
    return st;
  const unsigned char *bp = NULL;
  size_t bn = 0;
  if ((st = get_buffer(g, bi, &bp, &bn))) return st;
  buf = (double)bn;
  /* all the numbers are integers below 2^53: their sums below 2^54 are exact in uint64 */
  if ((uint64_t)voff + (uint64_t)vlen > (uint64_t)bn)
    return ss_fail(g->err, SS_ERR_PARSE,
                   "%s: %s: byteOffset %.17g + byteLength %.17g is past the end of buffers[%ld] (%.17g "
                   "bytes)",
                   g->name, vctx, voff, vlen, bi, buf);
  const uint64_t esize = (uint64_t)a->csize * (uint64_t)a->ncomp;
  if (jget(&g->d, vo, "byteStride")) {
    if ((uint64_t)stride % 4)
      return ss_fail(g->err, SS_ERR_PARSE, "%s: %s.byteStride %.17g is not a multiple of 4", g->name, vctx, stride);
    if ((uint64_t)stride < esize)
      return ss_fail(g->err, SS_ERR_PARSE, "%s: %s.byteStride %.17g is smaller than the %llu-byte elements of %s",
                     g->name, vctx, stride, (unsigned long long)esize, ctx);
  } else
    stride = (double)esize;
  /* needed = byteOffset + (count - 1) stride + element size, with stride <= 252: below 2^62 */
  const uint64_t need = (uint64_t)off + ((uint64_t)count - 1) * (uint64_t)stride + esize;
  if (need > (uint64_t)vlen) {
    if (off > 0)
      return ss_fail(g->err, SS_ERR_PARSE,
                     "%s: %s: count %.17g with stride %.17g from byteOffset %.17g needs %llu bytes; %s "
                     "has %.17g",
                     g->name, ctx, count, stride, off, (unsigned long long)need, vctx, vlen);
    return ss_fail(g->err, SS_ERR_PARSE, "%s: %s: count %.17g with stride %.17g needs %llu bytes; %s has %.17g",
                   g->name, ctx, count, stride, (unsigned long long)need, vctx, vlen);
  }
  a->p = bp + (size_t)voff + (size_t)off;
  a->count = (size_t)count, a->stride = (size_t)stride;
  return SS_OK;
}

static double comp_value(const unsigned char *q, int ct, int norm) {
  switch (ct) {
    case 5120: {
      int v = q[0] >= 128 ? (int)q[0] - 256 : (int)q[0];
      return norm ? fmax(v / 127.0, -1.0) : v;
    }
    case 5121: return norm ? q[0] / 255.0 : q[0];
    case 5122: {
      unsigned u = (unsigned)q[0] | (unsigned)q[1] << 8;
      int v = u >= 32768 ? (int)u - 65536 : (int)u;
      return norm ? fmax(v / 32767.0, -1.0) : v;
    }
    case 5123: {
      unsigned u = (unsigned)q[0] | (unsigned)q[1] << 8;
      return norm ? u / 65535.0 : u;
    }
    case 5125: return u32le(q);
    default: {
      uint32_t b = u32le(q);
      float f;
      memcpy(&f, &b, sizeof f);
      return f;
    }
  }
}

static size_t index_at(const acc *a, size_t k) {
  const unsigned char *q = a->p + k * a->stride;
  return a->ctype == 5121 ? q[0] : a->ctype == 5123 ? (size_t)q[0] | (size_t)q[1] << 8 : (size_t)u32le(q);
}

/* ---- meshes and nodes ---- */

/* The triangles of meshes[mi].primitives[pi] placed by T (4x4, column-major). */
static ss_status add_primitive(gl *g, long mi, long pi, const jv *prim, const double *T) {
  char ctx[64], use[80];
  snprintf(ctx, sizeof ctx, "meshes[%ld].primitives[%ld]", mi, pi);
  if (prim->t != J_OBJ) return ss_fail(g->err, SS_ERR_PARSE, "%s: %s is not an object", g->name, ctx);
  double mode = 4;
  ss_status st;
  if ((st = get_int(g, prim, ctx, "mode", 0, 4, 0, 6, &mode))) return st;
  g->prims++;
  if (mode < 4) { /* points and lines: no surface */
    g->dropped++;
    return SS_OK;
  }
  const jv *attr = jget(&g->d, prim, "attributes");
  if (!attr || attr->t != J_OBJ)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: %s: 'attributes' is missing or not an object", g->name, ctx);
  char actx[80];
  snprintf(actx, sizeof actx, "%s.attributes", ctx);
  long pa_i = -1, ia_i = -1;
  acc pa, ia;
  memset(&pa, 0, sizeof pa), memset(&ia, 0, sizeof ia);
  if ((st = get_ref(g, attr, actx, "POSITION", 1, g->accessors, "accessors", &pa_i)) ||
      (st = get_ref(g, prim, ctx, "indices", 0, g->accessors, "accessors", &ia_i)))
    return st;
  snprintf(use, sizeof use, "%s POSITION", ctx);
  if ((st = get_accessor(g, pa_i, use, "VEC3", &pa))) return st;
  if (pa.ctype == 5125 || (pa.ctype != 5126 && !g->quant))
    return ss_fail(g->err, SS_ERR_PARSE, "%s: accessors[%ld] (%s) has componentType %d: positions are float (5126)%s",
                   g->name, pa_i, use, pa.ctype, pa.ctype == 5125 ? "" : ", or integers with KHR_mesh_quantization");
  if (pa.ctype == 5126 && pa.norm)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: accessors[%ld] (%s): float components cannot be normalized", g->name,
                   pa_i, use);
  if (ia_i >= 0) {
    snprintf(use, sizeof use, "%s indices", ctx);
    if ((st = get_accessor(g, ia_i, use, "SCALAR", &ia))) return st;
    if ((ia.ctype != 5121 && ia.ctype != 5123 && ia.ctype != 5125) || ia.norm)
      return ss_fail(g->err, SS_ERR_PARSE,
                     "%s: accessors[%ld] (%s) has componentType %d%s: indices are unsigned byte, short "
                     "or int (5121, 5123, 5125), not normalized",
                     g->name, ia_i, use, ia.ctype, ia.norm ? ", normalized" : "");
  }
  const size_t nidx = ia_i >= 0 ? ia.count : pa.count;
  if (mode == 4 && nidx % 3)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: %s: %zu %s do not make triangles (TRIANGLES needs a multiple of 3)",
                   g->name, ctx, nidx, ia_i >= 0 ? "indices" : "vertices");
  const size_t ntri = mode == 4 ? nidx / 3 : nidx >= 3 ? nidx - 2 : 0;
  if (g->V.n / 3 + pa.count > (size_t)IO_MAX_ELEMENTS)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: more than %d vertices", g->name, IO_MAX_ELEMENTS);
  if (!g->placed[pa_i]) g->placed[pa_i] = 1, g->stored += pa.count;
  if (g->V.n / 3 + pa.count > GLTF_FLOOR && g->V.n / 3 + pa.count > GLTF_MAX_COPIES * g->stored)
    return ss_fail(g->err, SS_ERR_PARSE,
                   "%s: %s: the scene places its %zu stored vertices more than %d times over (%zu vertices "
                   "so far): instancing out of proportion to the file is refused; export the shape alone",
                   g->name, ctx, g->stored, GLTF_MAX_COPIES, g->V.n / 3 + pa.count);
  if (g->F.n / 3 + ntri > (size_t)IO_MAX_ELEMENTS)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: more than %d triangles", g->name, IO_MAX_ELEMENTS);
  /* the indices first: an index out of range fails before any vertex is placed */
  for (size_t k = 0; ia_i >= 0 && k < nidx; k++) {
    size_t v = index_at(&ia, k);
    if (v >= pa.count)
      return ss_fail(g->err, SS_ERR_PARSE,
                     "%s: %s: index %zu (indices element %zu) is out of range: POSITION has %zu "
                     "vertices",
                     g->name, ctx, v, k, pa.count);
  }
  const int base = (int)(g->V.n / 3);
  for (size_t k = 0; k < pa.count; k++) {
    const unsigned char *q = pa.p + k * pa.stride;
    double x[3], y[3];
    for (int c = 0; c < 3; c++) x[c] = comp_value(q + c * pa.csize, pa.ctype, pa.norm);
    if (!isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2]))
      return ss_fail(g->err, SS_ERR_PARSE, "%s: accessors[%ld] (%s POSITION): vertex %zu is not finite", g->name, pa_i,
                     ctx, k);
    for (int r = 0; r < 3; r++) y[r] = T[r] * x[0] + T[4 + r] * x[1] + T[8 + r] * x[2] + T[12 + r];
    if (!isfinite(y[0]) || !isfinite(y[1]) || !isfinite(y[2]))
      return ss_fail(g->err, SS_ERR_PARSE, "%s: %s: vertex %zu is not finite after its node's transform", g->name, ctx,
                     k);
    if (io_dvec_push(&g->V, y[0]) || io_dvec_push(&g->V, y[1]) || io_dvec_push(&g->V, y[2]))
      return ss_fail(g->err, SS_ERR_NOMEM, "%s: out of memory", g->name);
  }
  for (size_t t = 0; t < ntri; t++) {
    size_t k[3];
    if (mode == 4)
      k[0] = 3 * t, k[1] = 3 * t + 1, k[2] = 3 * t + 2;
    else if (mode == 5)
      k[0] = t, k[1] = t + 1 + t % 2, k[2] = t + 2 - t % 2; /* every other one reversed: one orientation */
    else
      k[0] = t + 1, k[1] = t + 2, k[2] = 0;
    size_t v[3];
    for (int c = 0; c < 3; c++) v[c] = ia_i >= 0 ? index_at(&ia, k[c]) : k[c];
    /* a strip's or fan's repeated index joins pieces (a restart), it is no triangle */
    if (mode != 4 && (v[0] == v[1] || v[1] == v[2] || v[0] == v[2])) continue;
    for (int c = 0; c < 3; c++)
      if (io_ivec_push(&g->F, base + (int)v[c])) return ss_fail(g->err, SS_ERR_NOMEM, "%s: out of memory", g->name);
  }
  return SS_OK;
}

static ss_status add_mesh(gl *g, long mi, const double *T) {
  const jv *me = NULL, *prims;
  ss_status st;
  if ((st = entry(g, g->meshes, "meshes", mi, &me))) return st;
  prims = jget(&g->d, me, "primitives");
  if (!prims || prims->t != J_ARR)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: meshes[%ld]: 'primitives' is missing or not an array", g->name, mi);
  for (size_t p = 0; p < prims->n; p++)
    if ((st = add_primitive(g, mi, (long)p, jat(&g->d, prims, p), T))) return st;
  return SS_OK;
}

/* r = a b, 4x4 column-major */
static void mat_mul(const double *a, const double *b, double *r) {
  for (int c = 0; c < 4; c++)
    for (int i = 0; i < 4; i++) {
      double s = 0;
      for (int k = 0; k < 4; k++) s += a[4 * k + i] * b[4 * c + k];
      r[4 * c + i] = s;
    }
}

static ss_status local_transform(gl *g, const jv *nd, const char *ctx, double *M) {
  double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
  int hm, ht, hr, hs;
  ss_status st;
  if ((st = get_numbers(g, nd, ctx, "matrix", 16, M, &hm)) ||
      (st = get_numbers(g, nd, ctx, "translation", 3, t, &ht)) ||
      (st = get_numbers(g, nd, ctx, "rotation", 4, q, &hr)) || (st = get_numbers(g, nd, ctx, "scale", 3, s, &hs)))
    return st;
  if (hm) {
    if (ht || hr || hs)
      return ss_fail(g->err, SS_ERR_PARSE, "%s: %s has both a matrix and translation / rotation / scale", g->name, ctx);
    if (M[3] != 0 || M[7] != 0 || M[11] != 0 || M[15] != 1)
      return ss_fail(g->err, SS_ERR_PARSE, "%s: %s.matrix: the last row is not 0 0 0 1 (not an affine transform)",
                     g->name, ctx);
    return SS_OK;
  }
  const double qn = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(qn > 0) || !isfinite(qn))
    return ss_fail(g->err, SS_ERR_PARSE, "%s: %s.rotation is not a rotation quaternion (norm %g)", g->name, ctx, qn);
  const double x = q[0] / qn, y = q[1] / qn, z = q[2] / qn, w = q[3] / qn;
  const double R[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w), /* column 0 */
                       2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w), /* column 1 */
                       2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
  for (int c = 0; c < 3; c++) {
    for (int r = 0; r < 3; r++) M[4 * c + r] = R[3 * c + r] * s[c];
    M[4 * c + 3] = 0;
  }
  M[12] = t[0], M[13] = t[1], M[14] = t[2], M[15] = 1;
  return SS_OK;
}

static ss_status add_node(gl *g, long ni, const double *parent, int depth);

/* The nodes listed in obj's member key (a node's "children", a scene's "nodes"), each placed under T;
 * absent: none */
static ss_status add_nodes(gl *g, const jv *obj, const char *ctx, const char *key, const double *T, int depth) {
  const jv *list = jget(&g->d, obj, key);
  if (!list) return SS_OK;
  if (list->t != J_ARR) return ss_fail(g->err, SS_ERR_PARSE, "%s: %s.%s is not an array", g->name, ctx, key);
  for (size_t i = 0; i < list->n; i++) {
    const jv *e = jat(&g->d, list, i);
    if (e->t != J_NUM || e->num != floor(e->num) || e->num < 0 || e->num >= (double)alen(g->nodes))
      return ss_fail(g->err, SS_ERR_PARSE, "%s: %s.%s[%zu] is not an index into 'nodes' (%zu entries)", g->name, ctx,
                     key, i, alen(g->nodes));
    ss_status st = add_node(g, (long)e->num, T, depth);
    if (st) return st;
  }
  return SS_OK;
}

static ss_status add_node(gl *g, long ni, const double *parent, int depth) {
  if (depth > 1000) return ss_fail(g->err, SS_ERR_PARSE, "%s: scene graph deeper than 1000 nodes", g->name);
  if (g->state[ni] == 1)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: nodes[%ld] is its own ancestor (a cycle through 'children')", g->name,
                   ni);
  if (g->state[ni] == 2)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: nodes[%ld] is reached twice in the scene (a node has one parent at most)",
                   g->name, ni);
  g->state[ni] = 1;
  char ctx[40];
  snprintf(ctx, sizeof ctx, "nodes[%ld]", ni);
  const jv *nd = NULL;
  double L[16], W[16];
  long mi = -1;
  ss_status st;
  if ((st = entry(g, g->nodes, "nodes", ni, &nd)) || (st = local_transform(g, nd, ctx, L)) ||
      (st = get_ref(g, nd, ctx, "mesh", 0, g->meshes, "meshes", &mi)))
    return st;
  mat_mul(parent, L, W);
  if (mi >= 0 && (st = add_mesh(g, mi, W))) return st;
  if ((st = add_nodes(g, nd, ctx, "children", W, depth + 1))) return st;
  g->state[ni] = 2;
  return SS_OK;
}

static const double IDENTITY[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

static ss_status read_document(gl *g) {
  ss_status st;
  const jv *asset = jget(&g->d, g->root, "asset");
  if (!asset || asset->t != J_OBJ)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: no 'asset' object: not a glTF 2.0 file", g->name);
  const char *ver = jstr(&g->d, jget(&g->d, asset, "version"));
  if (!ver) return ss_fail(g->err, SS_ERR_PARSE, "%s: asset.version is missing or not a string", g->name);
  if (strncmp(ver, "2.", 2)) {
    char show[24];
    return ss_fail(g->err, SS_ERR_UNSUPPORTED, "%s: glTF version '%s': only glTF 2.0 is read", g->name,
                   io_tok_show(ver, strlen(ver), show, sizeof show));
  }
  const char *ext_lists[2] = {"extensionsRequired", "extensionsUsed"};
  for (int l = 0; l < 2; l++) {
    const jv *a = jget(&g->d, g->root, ext_lists[l]);
    if (!a) continue;
    if (a->t != J_ARR) return ss_fail(g->err, SS_ERR_PARSE, "%s: '%s' is not an array", g->name, ext_lists[l]);
    for (size_t i = 0; i < a->n; i++) {
      const char *e = jstr(&g->d, jat(&g->d, a, i));
      if (!e) return ss_fail(g->err, SS_ERR_PARSE, "%s: %s[%zu] is not a string", g->name, ext_lists[l], i);
      if (!strcmp(e, "KHR_mesh_quantization"))
        g->quant = 1;
      else if (l == 0) {
        char show[64];
        return ss_fail(g->err, SS_ERR_UNSUPPORTED,
                       "%s: the file requires the extension %s, which this reader does not "
                       "support (only KHR_mesh_quantization)",
                       g->name, io_tok_show(e, strlen(e), show, sizeof show));
      }
    }
  }
  const jv *scenes;
  if ((st = top_array(g, "buffers", &g->buffers)) || (st = top_array(g, "bufferViews", &g->views)) ||
      (st = top_array(g, "accessors", &g->accessors)) || (st = top_array(g, "meshes", &g->meshes)) ||
      (st = top_array(g, "nodes", &g->nodes)) || (st = top_array(g, "scenes", &scenes)))
    return st;
  /* both sized by entries of the JSON text, which lie in memory */
  g->bufs = calloc(alen(g->buffers) + 1, sizeof *g->bufs);
  g->state = calloc(alen(g->nodes) + 1, 1);
  g->placed = calloc(alen(g->accessors) + 1, 1);
  if (!g->bufs || !g->state || !g->placed) return ss_fail(g->err, SS_ERR_NOMEM, "%s: out of memory", g->name);
  long si = -1;
  if ((st = get_ref(g, g->root, "(top level)", "scene", 0, scenes, "scenes", &si))) return st;
  if (si < 0 && alen(scenes)) si = 0;
  if (si < 0) { /* no scene: every mesh once, as stored */
    for (size_t mi = 0; mi < alen(g->meshes); mi++)
      if ((st = add_mesh(g, (long)mi, IDENTITY))) return st;
  } else {
    char ctx[40];
    snprintf(ctx, sizeof ctx, "scenes[%ld]", si);
    const jv *sc = NULL;
    if ((st = entry(g, scenes, "scenes", si, &sc)) || (st = add_nodes(g, sc, ctx, "nodes", IDENTITY, 0))) return st;
  }
  if (g->F.n == 0)
    return ss_fail(g->err, SS_ERR_PARSE,
                   "%s: no triangles in the scene (%zu meshes, %ld primitives of points or lines "
                   "dropped)",
                   g->name, alen(g->meshes), g->dropped);
  return SS_OK;
}

/* "NAME:LINE:COLUMN: JSON: what" (in a GLB "NAME: JSON chunk, line L, column C: what") */
static ss_status json_error(gl *g, const jparse *p, const unsigned char *s) {
  long line = 1, col = 1;
  for (size_t i = 0; i < p->epos; i++) {
    if (s[i] == '\n')
      line++, col = 1;
    else
      col++;
  }
  if (g->glb)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: JSON chunk, line %ld, column %ld: %s", g->name, line, col, p->emsg);
  return ss_fail(g->err, SS_ERR_PARSE, "%s:%ld:%ld: %s", g->name, line, col, p->emsg);
}

/* A GLB's chunks: the JSON text in [*js, *js + *jn), the BIN chunk in g. */
static ss_status read_glb(gl *g, const unsigned char *u, size_t len, const unsigned char **js, size_t *jn) {
  if (len < 12)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: %zu bytes, shorter than a GLB's 12-byte header", g->name, len);
  const uint32_t ver = u32le(u + 4), total = u32le(u + 8);
  if (ver != 2)
    return ss_fail(g->err, SS_ERR_UNSUPPORTED, "%s: GLB version %u: only glTF 2.0 (GLB version 2) is read", g->name,
                   ver);
  if (total != len)
    return ss_fail(g->err, SS_ERR_PARSE, "%s: the GLB header declares %u bytes; the data has %zu", g->name, total, len);
  size_t off = 12;
  int k = 0;
  for (; off < len; k++) {
    if (len - off < 8)
      return ss_fail(g->err, SS_ERR_PARSE, "%s: byte %zu: GLB chunk %d: its 8-byte header is cut off", g->name, off, k);
    const uint32_t cl = u32le(u + off), ct = u32le(u + off + 4);
    if (cl > len - off - 8)
      return ss_fail(g->err, SS_ERR_PARSE, "%s: byte %zu: GLB chunk %d declares %u bytes; %zu remain", g->name, off, k,
                     cl, len - off - 8);
    if (cl % 4)
      return ss_fail(g->err, SS_ERR_PARSE, "%s: byte %zu: GLB chunk %d: length %u is not a multiple of 4", g->name, off,
                     k, cl);
    if (k == 0) {
      if (ct != GLB_JSON)
        return ss_fail(g->err, SS_ERR_PARSE, "%s: byte %zu: the first GLB chunk is not JSON (type 0x%08x)", g->name,
                       off, ct);
      *js = u + off + 8, *jn = cl;
    } else if (k == 1 && ct == GLB_BIN)
      g->bin = u + off + 8, g->binlen = cl, g->has_bin = 1;
    else if (ct == GLB_JSON || ct == GLB_BIN)
      return ss_fail(g->err, SS_ERR_PARSE, "%s: byte %zu: GLB chunk %d: a second %s chunk", g->name, off, k,
                     ct == GLB_JSON ? "JSON" : "BIN (or a BIN chunk not second)");
    off += 8 + (size_t)cl; /* other chunk types are skipped, as the specification asks */
  }
  if (k == 0) return ss_fail(g->err, SS_ERR_PARSE, "%s: a GLB without chunks", g->name);
  return SS_OK;
}

int io_gltf_sniff(const char *buf, size_t len) {
  if (!buf) return 0;
  if (len >= 4 && !memcmp(buf, "glTF", 4)) return 1;
  size_t i = 0;
  while (i < len && (buf[i] == ' ' || buf[i] == '\t' || buf[i] == '\r' || buf[i] == '\n')) i++;
  if (i < len && buf[i] == '{') {
    size_t lim = len - i > 65536 ? i + 65536 : len;
    for (size_t j = i; j + 7 <= lim; j++)
      if (!memcmp(buf + j, "\"asset\"", 7)) return 1;
  }
  return 0;
}

ss_status io_parse_gltf(const char *path, const char *name, const char *buf, size_t len, ss_mesh *m, ss_error *err) {
  if (!m) return ss_fail(err, SS_ERR_INVALID, "read glTF: NULL output");
  memset(m, 0, sizeof *m);
  if (!name) name = path ? path : "<memory>";
  if (!buf && len) return ss_fail(err, SS_ERR_INVALID, "%s: NULL buffer", name);
  gl g;
  memset(&g, 0, sizeof g);
  g.name = name, g.path = path, g.err = err;
  const unsigned char *u = (const unsigned char *)buf, *js = u;
  size_t jn = len;
  ss_status st = SS_OK;
  if (len >= 4 && !memcmp(buf, "glTF", 4)) {
    g.glb = 1;
    st = read_glb(&g, u, len, &js, &jn);
  }
  if (!st && len == 0) st = ss_fail(err, SS_ERR_PARSE, "%s:1: empty file", name);
  if (!st) {
    jparse p;
    if (json_parse(&p, js, jn, &g.d)) st = json_error(&g, &p, js);
  }
  if (!st) {
    g.root = g.d.v; /* the first value made is the outermost */
    if (g.root->t != J_OBJ)
      st = ss_fail(err, SS_ERR_PARSE, "%s: the JSON text is not an object: not a glTF file", name);
  }
  if (!st) st = read_document(&g);
  if (!st) st = io_finish_mesh(&g.V, &g.F, m, name, err);
  if (!st) st = ssi_mesh_weld(m, NULL, err);
  for (size_t i = 0; g.bufs && i < alen(g.buffers); i++) free(g.bufs[i].own);
  free(g.bufs), free(g.state), free(g.placed), free(g.V.a), free(g.F.a);
  jdoc_free(&g.d);
  if (st) ss_mesh_free(m);
  return st;
}

ss_status ss_read_gltf(const char *path, ss_mesh *m, ss_error *err) {
  if (!m) return ss_fail(err, SS_ERR_INVALID, "read glTF: NULL output");
  memset(m, 0, sizeof *m);
  if (!path) return ss_fail(err, SS_ERR_INVALID, "read glTF: NULL path");
  char *buf;
  size_t len;
  ss_status st = io_slurp(path, &buf, &len, err);
  if (st) return st;
  st = io_parse_gltf(path, path, buf, len, m, err);
  free(buf);
  return st;
}
