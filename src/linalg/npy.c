/* NumPy .npy files (https://numpy.org/doc/stable/reference/generated/numpy.lib.format.html).
 * Writers: format 1.0, '<f8' or '<i4', C order, header padded with spaces so the data starts at a
 * multiple of 64 bytes. Readers: format 1.0/2.0/3.0, '<f8' or '>f8' (doubles), '<i4' / '<i8' / '>i4' /
 * '>i8' (ints), C or Fortran order, 1-D or 2-D; the
 * header dictionary is parsed strictly and the data size is checked against the file size before
 * anything of that size is allocated. */
#include "specseg/io.h"
#include "util/out_file.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


/* Writes format 1.0, C order: descr '<f8' (d) or '<i4' (iv), rows x cols given column-major. */
static ss_status npy_write(const char *path, const double *d, const int *iv, int rows, int cols, ss_error *err) {
  if (rows < 0 || cols < 0) return ss_fail(err, SS_ERR_INVALID, "%s: negative array shape (%d, %d)", path, rows, cols);
  if ((size_t)rows * (size_t)cols > 0 && !d && !iv) return ss_fail(err, SS_ERR_INVALID, "%s: NULL array", path);
  char dict[128];
  int dl = snprintf(dict, sizeof dict, "{'descr': '%s', 'fortran_order': False, 'shape': (%d, %d), }",
                    iv ? "<i4" : "<f8", rows, cols);
  /* magic(6) + version(2) + length(2) + dict + padding + '\n' ≡ 0 (mod 64) */
  size_t total = 10 + (size_t)dl + 1;
  size_t pad = (64 - total % 64) % 64;
  size_t hlen = (size_t)dl + pad + 1;
  unsigned char head[256];
  memcpy(head, "\x93NUMPY\x01\x00", 8);
  head[8] = (unsigned char)(hlen & 0xff);
  head[9] = (unsigned char)(hlen >> 8);
  memcpy(head + 10, dict, (size_t)dl);
  memset(head + 10 + dl, ' ', pad);
  head[10 + hlen - 1] = '\n';

  ssi_out o; /* whole or not at all (util/out_file.h) */
  ss_status st = ssi_out_open(&o, path, err);
  if (st) return st;
  FILE *f = o.f;
  int ok = fwrite(head, 1, 10 + hlen, f) == 10 + hlen;
  /* C order: row by row from the column-major input, little-endian bytes through a small buffer */
  unsigned char buf[4096];
  int isz = iv ? 4 : 8, per = (int)sizeof buf / isz;
  for (int i = 0; ok && i < rows; i++) {
    for (int j0 = 0; ok && j0 < cols; j0 += per) {
      int nb = cols - j0 < per ? cols - j0 : per;
      for (int j = 0; j < nb; j++) {
        size_t at = (size_t)i + (size_t)rows * (size_t)(j0 + j);
        uint64_t u;
        if (iv) {
          u = (uint32_t)iv[at];
        } else {
          memcpy(&u, &d[at], 8);
        }
        for (int t = 0; t < isz; t++) buf[(size_t)j * isz + t] = (unsigned char)(u >> (8 * t));
      }
      ok = fwrite(buf, (size_t)isz, (size_t)nb, f) == (size_t)nb;
    }
  }
  if (!ok) {
    int e = errno;
    ssi_out_abort(&o);
    return ss_fail(err, SS_ERR_IO, "%s: write error: %s", path, strerror(e ? e : EIO));
  }
  return ssi_out_commit(&o, path, err);
}

ss_status ss_write_npy(const char *path, const double *a, int rows, int cols, ss_error *err) {
  return npy_write(path, a, NULL, rows, cols, err);
}

ss_status ss_write_npy_ints(const char *path, const int *a, int rows, int cols, ss_error *err) {
  return npy_write(path, NULL, a, rows, cols, err);
}

/* --- header dictionary parsing ------------------------------------------------------------- */

typedef struct {
  const char *s, *end;
} cursor;

static void skip_ws(cursor *c) {
  while (c->s < c->end && (*c->s == ' ' || *c->s == '\t' || *c->s == '\n' || *c->s == '\r')) c->s++;
}

static int accept(cursor *c, char ch) {
  skip_ws(c);
  if (c->s < c->end && *c->s == ch) {
    c->s++;
    return 1;
  }
  return 0;
}

/* Python string literal with ' or " quotes, no escapes (none occur in valid headers). */
static int parse_string(cursor *c, char *out, size_t cap) {
  skip_ws(c);
  if (c->s >= c->end || (*c->s != '\'' && *c->s != '"')) return 0;
  char q = *c->s++;
  size_t n = 0;
  while (c->s < c->end && *c->s != q) {
    if (*c->s == '\\' || n + 1 >= cap) return 0;
    out[n++] = *c->s++;
  }
  if (c->s >= c->end) return 0;
  c->s++;
  out[n] = 0;
  return 1;
}

static int parse_word(cursor *c, const char *w) {
  skip_ws(c);
  size_t n = strlen(w);
  if ((size_t)(c->end - c->s) >= n && !memcmp(c->s, w, n)) {
    c->s += n;
    return 1;
  }
  return 0;
}

static int parse_dim(cursor *c, long long *v) {
  skip_ws(c);
  if (c->s >= c->end || *c->s < '0' || *c->s > '9') return 0;
  long long x = 0;
  while (c->s < c->end && *c->s >= '0' && *c->s <= '9') {
    x = x * 10 + (*c->s - '0');
    if (x > INT32_MAX) return 0;
    c->s++;
  }
  if (c->s < c->end && *c->s == 'L') c->s++; /* Python 2 longs */
  *v = x;
  return 1;
}

/* Returns NULL on success, else a description of what is wrong. */
static const char *parse_header(const char *h, size_t len, int *big_endian, char dtype[3], int *fortran, int *ndim,
                                long long shape[2]) {
  cursor c = {h, h + len};
  int have_descr = 0, have_order = 0, have_shape = 0;
  if (!accept(&c, '{')) return "header is not a dictionary";
  for (;;) {
    if (accept(&c, '}')) break;
    char key[32], val[32];
    if (!parse_string(&c, key, sizeof key)) return "malformed dictionary key";
    if (!accept(&c, ':')) return "missing ':' in header dictionary";
    if (!strcmp(key, "descr")) {
      if (have_descr++) return "duplicate 'descr'";
      if (!parse_string(&c, val, sizeof val)) return "'descr' is not a string";
      if ((val[0] != '<' && val[0] != '>' && val[0] != '|') || !val[1] || val[2] < '1' || val[2] > '8' || val[3])
        return "unsupported dtype";
      *big_endian = val[0] == '>';
      dtype[0] = val[1], dtype[1] = val[2], dtype[2] = 0;
      if (strcmp(dtype, "f8") && strcmp(dtype, "i4") && strcmp(dtype, "i8"))
        return "unsupported dtype (float64 '<f8' / '>f8', or for integers '<i4', '<i8' and big-endian)";
    } else if (!strcmp(key, "fortran_order")) {
      if (have_order++) return "duplicate 'fortran_order'";
      if (parse_word(&c, "True")) *fortran = 1;
      else if (parse_word(&c, "False")) *fortran = 0;
      else return "'fortran_order' is not True or False";
    } else if (!strcmp(key, "shape")) {
      if (have_shape++) return "duplicate 'shape'";
      if (!accept(&c, '(')) return "'shape' is not a tuple";
      *ndim = 0;
      for (;;) {
        if (accept(&c, ')')) break;
        long long d;
        if (*ndim >= 2) return "only 1-D and 2-D arrays are supported";
        if (!parse_dim(&c, &d)) return "'shape' entry is not a non-negative integer in range";
        shape[(*ndim)++] = d;
        if (accept(&c, ',')) continue;
        if (accept(&c, ')')) break;
        return "malformed 'shape' tuple";
      }
      if (*ndim == 0) return "0-D arrays are not supported";
    } else {
      return "unknown key in header dictionary";
    }
    if (accept(&c, ',')) continue;
    if (accept(&c, '}')) break;
    return "malformed header dictionary";
  }
  skip_ws(&c);
  if (c.s != c.end) return "trailing characters after the header dictionary";
  if (!have_descr || !have_order || !have_shape) return "header lacks 'descr', 'fortran_order' or 'shape'";
  return NULL;
}

/* Parses a whole .npy image; want_int 0: '<f8' / '>f8' into doubles; 1: '<i4', '<i8' (and '>') into
 * ints (int64 values outside the int range are an error). *out column-major, malloc'd. */
static ss_status npy_parse(const char *path, const unsigned char *b, size_t fsize, int want_int, void **out, int *rows,
                           int *cols, ss_error *err) {
  *out = NULL;
  *rows = *cols = 0;
  if (fsize < 8 || memcmp(b, "\x93NUMPY", 6)) return ss_fail(err, SS_ERR_PARSE, "%s: byte 0: not a NumPy .npy file (bad magic)", path);
  int major = b[6];
  size_t hlen, hstart;
  if (major == 1) {
    if (fsize < 10) return ss_fail(err, SS_ERR_PARSE, "%s: byte 8: truncated header", path);
    hlen = (size_t)b[8] | ((size_t)b[9] << 8);
    hstart = 10;
  } else if (major == 2 || major == 3) {
    if (fsize < 12) return ss_fail(err, SS_ERR_PARSE, "%s: byte 8: truncated header", path);
    hlen = (size_t)b[8] | ((size_t)b[9] << 8) | ((size_t)b[10] << 16) | ((size_t)b[11] << 24);
    hstart = 12;
  } else {
    return ss_fail(err, SS_ERR_PARSE, "%s: byte 6: unsupported .npy format version %d.%d", path, major, b[7]);
  }
  if (hlen > fsize - hstart) return ss_fail(err, SS_ERR_PARSE, "%s: byte 8: header length %zu exceeds the file size", path, hlen);
  if (hlen == 0) return ss_fail(err, SS_ERR_PARSE, "%s: byte %zu: empty header", path, hstart);
  const char *hdr = (const char *)b + hstart;
  for (size_t i = 0; i < hlen; i++)
    if ((unsigned char)hdr[i] >= 0x80 || hdr[i] == 0)
      return ss_fail(err, SS_ERR_PARSE, "%s: byte %zu: non-ASCII character in header", path, hstart + i);
  int big = 0, fortran = 0, ndim = 0;
  char dtype[3] = "";
  long long shape[2] = {0, 1};
  const char *why = parse_header(hdr, hlen, &big, dtype, &fortran, &ndim, shape);
  if (!why && !want_int && strcmp(dtype, "f8")) why = "unsupported dtype (only float64, '<f8' or '>f8')";
  if (!why && want_int && dtype[0] != 'i') why = "unsupported dtype for integers (only '<i4', '<i8', '>i4', '>i8')";
  if (why) return ss_fail(err, SS_ERR_PARSE, "%s: byte %zu: %s", path, hstart, why);
  long long r = shape[0], c = ndim == 2 ? shape[1] : 1;
  if (r > INT32_MAX || c > INT32_MAX) return ss_fail(err, SS_ERR_PARSE, "%s: shape too large", path);
  int isz = dtype[1] - '0';
  unsigned long long count = (unsigned long long)r * (unsigned long long)c;
  size_t dstart = hstart + hlen;
  unsigned long long avail = (unsigned long long)fsize - dstart;
  if (count > avail / (unsigned)isz)
    return ss_fail(err, SS_ERR_PARSE, "%s: byte %zu: truncated data: shape needs %llu values, file holds %llu", path,
                   dstart, count, avail / (unsigned)isz);
  if (avail != count * (unsigned)isz)
    return ss_fail(err, SS_ERR_PARSE, "%s: byte %llu: %llu trailing bytes after the data", path,
                   (unsigned long long)dstart + count * (unsigned)isz, avail - count * (unsigned)isz);
  if (count > SIZE_MAX / 8) return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory for %llu values", path, count);
  size_t esz = want_int ? sizeof(int) : sizeof(double);
  unsigned char *data = malloc(esz * (size_t)(count > 0 ? count : 1));
  if (!data) return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory for %llu values", path, count);
  const unsigned char *q = b + dstart;
  for (size_t k = 0; k < count; k++, q += isz) {
    /* element k in file order goes to (i, j) of the column-major result */
    size_t dst = k;
    if (!fortran && ndim == 2) dst = (k / (size_t)c) + (size_t)r * (k % (size_t)c);
    uint64_t u = 0;
    for (int t = 0; t < isz; t++) u = (u << 8) | q[big ? t : isz - 1 - t];
    if (!want_int) {
      double d;
      memcpy(&d, &u, 8);
      ((double *)data)[dst] = d;
    } else {
      long long v = isz == 4 ? (long long)(int32_t)(uint32_t)u : (long long)(int64_t)u;
      if (v < INT32_MIN || v > INT32_MAX) {
        free(data);
        return ss_fail(err, SS_ERR_PARSE, "%s: value %zu (%lld) outside the int range", path, k, v);
      }
      ((int *)data)[dst] = (int)v;
    }
  }
  *out = data;
  *rows = (int)r;
  *cols = (int)c;
  return SS_OK;
}

static ss_status npy_read_path(const char *path, int want_int, void **out, int *rows, int *cols, ss_error *err) {
  *out = NULL;
  *rows = *cols = 0;
  FILE *f = fopen(path, "rb");
  if (!f) return ss_fail(err, SS_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
  unsigned char *buf = NULL;
  size_t n = 0, cap = 0;
  for (;;) {
    if (n == cap) {
      size_t nc = cap ? cap * 2 : 65536;
      unsigned char *nb = nc > cap ? realloc(buf, nc) : NULL;
      if (!nb) {
        free(buf);
        fclose(f);
        return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", path);
      }
      buf = nb, cap = nc;
    }
    size_t got = fread(buf + n, 1, cap - n, f);
    n += got;
    if (got == 0) break;
  }
  int bad = ferror(f);
  fclose(f);
  ss_status st = bad ? ss_fail(err, SS_ERR_IO, "%s: read error", path) : npy_parse(path, buf, n, want_int, out, rows, cols, err);
  free(buf);
  return st;
}

ss_status ss_read_npy(const char *path, double **a, int *rows, int *cols, ss_error *err) {
  void *o;
  ss_status st = npy_read_path(path, 0, &o, rows, cols, err);
  *a = st ? NULL : (double *)o;
  return st;
}

ss_status ss_read_npy_ints(const char *path, int **a, int *rows, int *cols, ss_error *err) {
  void *o;
  ss_status st = npy_read_path(path, 1, &o, rows, cols, err);
  *a = st ? NULL : (int *)o;
  return st;
}

ss_status ss_read_npy_memory(const void *buf, size_t len, const char *name, double **a, int *rows, int *cols,
                             ss_error *err) {
  void *o;
  if (!name) name = "<memory>";
  if (!buf && len) return ss_fail(err, SS_ERR_INVALID, "%s: NULL buffer", name);
  ss_status st = npy_parse(name, buf ? buf : "", len, 0, &o, rows, cols, err);
  *a = st ? NULL : (double *)o;
  return st;
}

ss_status ss_read_npy_ints_memory(const void *buf, size_t len, const char *name, int **a, int *rows, int *cols,
                                  ss_error *err) {
  void *o;
  if (!name) name = "<memory>";
  if (!buf && len) return ss_fail(err, SS_ERR_INVALID, "%s: NULL buffer", name);
  ss_status st = npy_parse(name, buf ? buf : "", len, 1, &o, rows, cols, err);
  *a = st ? NULL : (int *)o;
  return st;
}
