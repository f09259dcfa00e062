#include "util/io_text.h"
#include "util/c_locale.h"

#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

ss_status io_slurp(const char *path, char **buf, size_t *len, ss_error *err) {
  *buf = NULL;
  *len = 0;
  struct stat st;
  if (stat(path, &st) != 0) return ss_fail(err, SS_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
  if (S_ISDIR(st.st_mode)) return ss_fail(err, SS_ERR_IO, "%s: is a directory", path);
  /* devices such as /dev/zero never end: only regular files and pipes are read */
  if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode)) return ss_fail(err, SS_ERR_IO, "%s: not a regular file", path);
  FILE *f = fopen(path, "rb");
  if (!f) return ss_fail(err, SS_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
  /* Grow as bytes arrive rather than trusting st_size (pipes and /proc files report 0). */
  size_t cap = 65536, n = 0;
  char *b = malloc(cap);
  if (!b) {
    fclose(f);
    return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", path);
  }
  for (;;) {
    if (cap - n < 2) {
      if (cap > SIZE_MAX / 2) {
        free(b);
        fclose(f);
        return ss_fail(err, SS_ERR_NOMEM, "%s: file too large", path);
      }
      char *nb = realloc(b, cap * 2);
      if (!nb) {
        free(b);
        fclose(f);
        return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory reading the file", path);
      }
      b = nb;
      cap *= 2;
    }
    size_t got = fread(b + n, 1, cap - n - 1, f);
    n += got;
    if (got == 0) break;
  }
  int bad = ferror(f);
  int e = errno;
  fclose(f);
  if (bad) {
    free(b);
    return ss_fail(err, SS_ERR_IO, "%s: read error: %s", path, strerror(e));
  }
  b[n] = '\0';
  *buf = b;
  *len = n;
  return SS_OK;
}

ss_status io_fail_line(ss_error *err, ss_status code, const char *path, long line, const char *fmt, ...) {
  char what[768];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  return ss_fail(err, code, "%s:%ld: %s", path, line, what);
}

ss_status io_fail_byte(ss_error *err, ss_status code, const char *path, size_t byte, const char *fmt, ...) {
  char what[768];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  return ss_fail(err, code, "%s: byte %zu: %s", path, byte, what);
}

void io_text_init(io_text *t, const char *buf, size_t len) {
  t->buf = buf;
  t->len = len;
  t->pos = 0;
  t->line = 0;
}

int io_text_line(io_text *t, const char **b, const char **e) {
  if (t->pos >= t->len) return 0;
  const char *s = t->buf + t->pos;
  const char *nl = memchr(s, '\n', t->len - t->pos);
  const char *end = nl ? nl : t->buf + t->len;
  *b = s;
  *e = end;
  t->pos = (size_t)(end - t->buf) + (nl ? 1 : 0);
  t->line++;
  return 1;
}

static int is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

int io_token(const char **p, const char *e, int comment, const char **tb, size_t *tl) {
  const char *s = *p;
  while (s < e && is_blank(*s)) s++;
  if (s >= e || (comment && *s == '#')) {
    *p = e;
    return 0;
  }
  const char *t = s;
  while (t < e && !is_blank(*t) && !(comment && *t == '#')) t++;
  *tb = s;
  *tl = (size_t)(t - s);
  *p = t;
  return 1;
}

int io_line_blank(const char *p, const char *e, int comment) {
  const char *tb;
  size_t tl;
  return !io_token(&p, e, comment, &tb, &tl);
}

/* Copies a token into a NUL-terminated scratch buffer; embedded NULs make the parse fail later,
 * and tokens longer than any number we accept are rejected outright. */
static int tok_copy(const char *tb, size_t tl, char *out, size_t outsz) {
  if (tl == 0 || tl >= outsz) return -1;
  memcpy(out, tb, tl);
  out[tl] = '\0';
  return 0;
}

int io_parse_double(const char *tb, size_t tl, double *out) {
  char s[128];
  if (tok_copy(tb, tl, s, sizeof s)) return -1;
  char *end;
  errno = 0;
  double v = ssi_strtod_c(s, &end);
  if (end != s + tl) return -1;
  /* ERANGE on underflow gives a usable denormal/zero; on overflow strtod returns ±HUGE_VAL, which is
   * what an "inf" literal gives too — keep it and let the mesh checks report non-finite values. */
  *out = v;
  return 0;
}

int io_parse_ll(const char *tb, size_t tl, long long *out) {
  char s[64];
  if (tok_copy(tb, tl, s, sizeof s)) return -1;
  char *end;
  errno = 0;
  long long v = strtoll(s, &end, 10);
  if (end != s + tl || errno == ERANGE) return -1;
  *out = v;
  return 0;
}

int io_tok_eq(const char *tb, size_t tl, const char *s) { return strlen(s) == tl && memcmp(tb, s, tl) == 0; }

const char *io_tok_show(const char *tb, size_t tl, char *out, size_t outsz) {
  size_t k = 0;
  for (size_t i = 0; i < tl && k + 4 < outsz; i++) {
    unsigned char c = (unsigned char)tb[i];
    out[k++] = (c >= 32 && c < 127) ? (char)c : '?';
  }
  if (tl > 0 && k < tl && k + 4 <= outsz) {
    out[k++] = '.';
    out[k++] = '.';
    out[k++] = '.';
  }
  out[k] = '\0';
  return out;
}

int io_dvec_push(io_dvec *v, double x) {
  if (v->n == v->cap) {
    size_t nc = v->cap ? v->cap * 2 : 1024;
    if (nc > SIZE_MAX / sizeof(double)) return -1;
    double *na = realloc(v->a, nc * sizeof(double));
    if (!na) return -1;
    v->a = na;
    v->cap = nc;
  }
  v->a[v->n++] = x;
  return 0;
}

int io_bvec_push(io_bvec *v, unsigned char x) {
  if (v->n == v->cap) {
    size_t nc = v->cap ? v->cap * 2 : 1024;
    if (nc < v->cap) return -1;
    unsigned char *na = realloc(v->a, nc);
    if (!na) return -1;
    v->a = na;
    v->cap = nc;
  }
  v->a[v->n++] = x;
  return 0;
}

int io_ivec_push(io_ivec *v, int x) {
  if (v->n == v->cap) {
    size_t nc = v->cap ? v->cap * 2 : 1024;
    if (nc > SIZE_MAX / sizeof(int)) return -1;
    int *na = realloc(v->a, nc * sizeof(int));
    if (!na) return -1;
    v->a = na;
    v->cap = nc;
  }
  v->a[v->n++] = x;
  return 0;
}
