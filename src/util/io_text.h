/* Internal helpers for text and binary file readers: whole-file loading, line and token scanning
 * with line numbers, strict number parsing, growable arrays. Not public API. */
#ifndef SS_IO_TEXT_H
#define SS_IO_TEXT_H

#include <stddef.h>

#include "specseg/core.h"

/* Loads a whole regular file into a malloc'd buffer with a trailing NUL (not counted in *len).
 * Directories, missing files and read errors fail with SS_ERR_IO and "PATH: what". */
ss_status io_slurp(const char *path, char **buf, size_t *len, ss_error *err);

/* "PATH:LINE: what" */
ss_status io_fail_line(ss_error *err, ss_status code, const char *path, long line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;
/* "PATH: byte OFFSET: what" */
ss_status io_fail_byte(ss_error *err, ss_status code, const char *path, size_t byte, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* Line scanner over a loaded buffer. `line` is the 1-based number of the line last returned. */
typedef struct io_text {
  const char *buf;
  size_t len, pos;
  long line;
} io_text;

void io_text_init(io_text *t, const char *buf, size_t len);
/* Next line as [*b, *e) without the '\n' (a trailing '\r' is kept; it counts as blank space).
 * Returns 0 at end of input. */
int io_text_line(io_text *t, const char **b, const char **e);

/* Token scanning within a line [*p, e): blank space is ' ', '\t', '\r', '\v', '\f'.
 * When `comment` is nonzero a '#' starts a comment that runs to the end of the line.
 * Returns 0 when no token is left, else sets [*tb, *tb + *tl) and advances *p. */
int io_token(const char **p, const char *e, int comment, const char **tb, size_t *tl);
/* Is the rest of the line blank (or a comment when `comment`)? */
int io_line_blank(const char *p, const char *e, int comment);

/* Strict parsing of a whole token. Return 0 on success, -1 when the token is not a number of the kind
 * (or out of range). Doubles accept "nan", "inf" and friends (strtod syntax). */
int io_parse_double(const char *tb, size_t tl, double *out);
int io_parse_ll(const char *tb, size_t tl, long long *out);

/* Token compare (exact, case-sensitive) and a printable, truncated copy for messages. */
int io_tok_eq(const char *tb, size_t tl, const char *s);
const char *io_tok_show(const char *tb, size_t tl, char *out, size_t outsz);

/* Growable arrays: grown geometrically as elements arrive, never sized from a declared count. */
typedef struct io_dvec {
  double *a;
  size_t n, cap;
} io_dvec;
typedef struct io_ivec {
  int *a;
  size_t n, cap;
} io_ivec;
int io_dvec_push(io_dvec *v, double x); /* 0 ok, -1 out of memory */
int io_ivec_push(io_ivec *v, int x);
typedef struct io_bvec {
  unsigned char *a;
  size_t n, cap;
} io_bvec;
int io_bvec_push(io_bvec *v, unsigned char x);

#endif
