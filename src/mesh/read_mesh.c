/* Format dispatch for mesh reading (extension first, then content sniffing) and the shared
 * hand-over of grown arrays into an ss_mesh. */
#include <ctype.h>
#include <stdint.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "mesh/io_internal.h"
#include "specseg/io.h"

ss_status io_finish_mesh(io_dvec *V, io_ivec *F, ss_mesh *m, const char *path, ss_error *err) {
  memset(m, 0, sizeof *m);
  if (F->n == 0) return ss_fail(err, SS_ERR_PARSE, "%s: mesh has no faces", path);
  if (V->n == 0) return ss_fail(err, SS_ERR_PARSE, "%s: mesh has no vertices", path);
  /* shrink to fit: the geometric growth may have over-allocated up to 2x */
  double *Va = realloc(V->a, V->n * sizeof(double));
  if (Va) V->a = Va;
  int *Fa = realloc(F->a, F->n * sizeof(int));
  if (Fa) F->a = Fa;
  m->nv = (int)(V->n / 3);
  m->nf = (int)(F->n / 3);
  m->V = V->a;
  m->F = F->a;
  V->a = NULL;
  F->a = NULL;
  V->n = V->cap = F->n = F->cap = 0;
  return SS_OK;
}

static int ext_is(const char *path, const char *ext) {
  const char *dot = strrchr(path, '.');
  const char *slash = strrchr(path, '/');
  if (!dot || (slash && dot < slash)) return 0;
  dot++;
  size_t n = strlen(ext);
  if (strlen(dot) != n) return 0;
  for (size_t i = 0; i < n; i++)
    if (tolower((unsigned char)dot[i]) != ext[i]) return 0;
  return 1;
}

/* The formats our own readers parse, by extension: the one list that the dispatch below,
 * ss_mesh_extension_supported and the assimp routing (which never takes these) all read. */
static const struct {
  const char *ext;
  char kind; /* parse_any's switch */
} OWN_FORMATS[] = {{"off", 'o'}, {"obj", 'j'}, {"ply", 'p'}, {"stl", 's'}, {"gltf", 'g'}, {"glb", 'g'}};

int ssi_mesh_own_format(const char *path) {
  for (size_t i = 0; path && i < sizeof OWN_FORMATS / sizeof *OWN_FORMATS; i++)
    if (ext_is(path, OWN_FORMATS[i].ext)) return OWN_FORMATS[i].kind;
  return 0;
}

/* Content sniffing for files without a known extension. */
static int sniff(const char *buf, size_t len) {
  if (len >= 4 && !memcmp(buf, "ply", 3) && (buf[3] == '\n' || buf[3] == '\r')) return 'p';
  io_text t;
  io_text_init(&t, buf, len);
  const char *b, *e, *p, *tb;
  size_t tl;
  for (int lines = 0; lines < 1000 && io_text_line(&t, &b, &e); lines++) {
    p = b;
    if (!io_token(&p, e, 1, &tb, &tl)) continue;
    if (tl >= 3 && !memcmp(tb + tl - 3, "OFF", 3)) return 'o';
    if (io_tok_eq(tb, tl, "v") || io_tok_eq(tb, tl, "f") || io_tok_eq(tb, tl, "vn") || io_tok_eq(tb, tl, "vt") ||
        io_tok_eq(tb, tl, "g") || io_tok_eq(tb, tl, "o") || io_tok_eq(tb, tl, "mtllib"))
      return 'j';
    long long x;
    if (!io_parse_ll(tb, tl, &x)) return 'o'; /* OFF without its header starts with the counts */
    return 0;
  }
  return 0;
}

/* The parser for a loaded buffer: by the extension of `path` when given (the path also locates a .gltf's
 * external buffers), else by content, our formats only: nothing read from memory goes to assimp. */
static ss_status parse_any(const char *path, const char *name, const char *buf, size_t len, ss_mesh *m,
                           unsigned char **rgb, ss_error *err) {
  char hint[16];
  int kind = ssi_mesh_own_format(path);
  if (!kind && path && ssi_mesh_assimp_ext(path, hint, sizeof hint)) kind = 'a';
  if (!kind) kind = io_stl_sniff(buf, len) ? 's' /* first: a binary STL's header may hold any text */
                                           : sniff(buf, len);
  if (!kind && io_gltf_sniff(buf, len)) kind = 'g';
  switch (kind) {
    case 'o': return io_parse_off(name, buf, len, m, err);
    case 'j': return io_parse_obj(name, buf, len, m, err);
    case 'p': return io_parse_ply_rgb(name, buf, len, m, rgb, err);
    case 's': return io_parse_stl(name, buf, len, m, err);
    case 'g': return io_parse_gltf(path, name, buf, len, m, err);
    case 'a': return ssi_read_assimp(NULL, name, buf, len, hint, m, err);
    default:
      return len == 0 ? ss_fail(err, SS_ERR_PARSE, "%s:1: empty file", name)
                      : ss_fail(err, SS_ERR_UNSUPPORTED,
                                "%s:1: unknown mesh format (expected OFF, OBJ, PLY, STL or glTF)", name);
  }
}

ss_status ss_read_mesh_colors(const char *path, ss_mesh *m, unsigned char **rgb, ss_error *err) {
  if (!m) return ss_fail(err, SS_ERR_INVALID, "read mesh: NULL output");
  memset(m, 0, sizeof *m);
  if (rgb) *rgb = NULL;
  if (!path) return ss_fail(err, SS_ERR_INVALID, "read mesh: NULL path");
  /* a regular file in an assimp format goes to assimp by path (files the scene refers to lie beside it) */
  char hint[16];
  struct stat sb;
  if (ssi_mesh_assimp_ext(path, hint, sizeof hint) && stat(path, &sb) == 0 && S_ISREG(sb.st_mode))
    return ssi_read_assimp(path, path, NULL, 0, hint, m, err);
  char *buf;
  size_t len;
  ss_status st = io_slurp(path, &buf, &len, err);
  if (st) return st;
  st = parse_any(path, path, buf, len, m, rgb, err);
  free(buf);
  return st;
}

ss_status ss_read_mesh(const char *path, ss_mesh *m, ss_error *err) { return ss_read_mesh_colors(path, m, NULL, err); }

ss_status ss_read_mesh_colors_memory(const void *buf, size_t len, const char *name, ss_mesh *m, unsigned char **rgb,
                                     ss_error *err) {
  if (!m) return ss_fail(err, SS_ERR_INVALID, "read mesh: NULL output");
  memset(m, 0, sizeof *m);
  if (rgb) *rgb = NULL;
  if (!name) name = "<memory>";
  if (!buf && len > 0) return ss_fail(err, SS_ERR_INVALID, "%s: NULL buffer", name);
  if (len == SIZE_MAX) return ss_fail(err, SS_ERR_NOMEM, "%s: buffer too large", name);
  /* the parsers get what io_slurp gives them: a private copy with a trailing NUL */
  char *copy = malloc(len + 1);
  if (!copy) return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", name);
  if (len) memcpy(copy, buf, len);
  copy[len] = '\0';
  ss_status st = parse_any(NULL, name, copy, len, m, rgb, err);
  free(copy);
  return st;
}

ss_status ss_read_mesh_memory(const void *buf, size_t len, const char *name, ss_mesh *m, ss_error *err) {
  return ss_read_mesh_colors_memory(buf, len, name, m, NULL, err);
}

ss_status io_read_with(const char *path, io_mesh_parser parse, ss_mesh *m, ss_error *err) {
  char *buf;
  size_t len;
  memset(m, 0, sizeof *m);
  ss_status st = io_slurp(path, &buf, &len, err);
  if (st) return st;
  st = parse(path, buf, len, m, err);
  free(buf);
  return st;
}

int ss_mesh_extension_supported(const char *path) {
  if (!path) return 0;
  if (ssi_mesh_own_format(path)) return 1;
#ifdef SS_HAVE_ASSIMP
  if (ssi_mesh_assimp_ext(path, NULL, 0)) return 2;
#endif
  return 0;
}
