/* NumPy .npy files (https://numpy.org/doc/stable/reference/generated/numpy.lib.format.html).
 * Writer: format 1.0, '<f8', C order, header padded with spaces so the data starts at a multiple
 * of 64 bytes. Reader: format 1.0/2.0/3.0, '<f8' or '>f8', C or Fortran order, 1-D or 2-D; the
 * header dictionary is parsed strictly and the data size is checked against the file size before
 * anything of that size is allocated. */
#include "specseg/io.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int host_is_little_endian(void) {
  const uint16_t one = 1;
  unsigned char c;
  memcpy(&c, &one, 1);
  return c == 1;
}

static void swap8(unsigned char *p) {
  for (int i = 0; i < 4; i++) {
    unsigned char t = p[i];
    p[i] = p[7 - i];
    p[7 - i] = t;
  }
}

ss_status ss_write_npy(const char *path, const double *a, int rows, int cols, ss_error *err) {
  if (rows < 0 || cols < 0) return ss_fail(err, SS_ERR_INVALID, "%s: negative array shape (%d, %d)", path, rows, cols);
  char dict[128];
  int dl = snprintf(dict, sizeof dict, "{'descr': '<f8', 'fortran_order': False, 'shape': (%d, %d), }", rows, cols);
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

  FILE *f = fopen(path, "wb");
  if (!f) return ss_fail(err, SS_ERR_IO, "%s: cannot open for writing: %s", path, strerror(errno));
  int ok = fwrite(head, 1, 10 + hlen, f) == 10 + hlen;
  /* C order: row by row from the column-major input, written through a small buffer */
  double buf[512];
  int le = host_is_little_endian();
  for (int i = 0; ok && i < rows; i++) {
    for (int j0 = 0; ok && j0 < cols; j0 += 512) {
      int nb = cols - j0 < 512 ? cols - j0 : 512;
      for (int j = 0; j < nb; j++) {
        buf[j] = a[(size_t)i + (size_t)rows * (size_t)(j0 + j)];
        if (!le) swap8((unsigned char *)&buf[j]);
      }
      ok = fwrite(buf, sizeof(double), (size_t)nb, f) == (size_t)nb;
    }
  }
  int e = ok ? 0 : errno;
  if (fclose(f) != 0 && ok) ok = 0, e = errno;
  if (!ok) return ss_fail(err, SS_ERR_IO, "%s: write error: %s", path, strerror(e));
  return SS_OK;
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
static const char *parse_header(const char *h, size_t len, int *big_endian, int *fortran, int *ndim,
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
      if (!strcmp(val, "<f8")) *big_endian = 0;
      else if (!strcmp(val, ">f8")) *big_endian = 1;
      else return "unsupported dtype (only float64, '<f8' or '>f8')";
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

ss_status ss_read_npy(const char *path, double **a, int *rows, int *cols, ss_error *err) {
  *a = NULL;
  *rows = *cols = 0;
  FILE *f = fopen(path, "rb");
  if (!f) return ss_fail(err, SS_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
  ss_status st = SS_OK;
  char *hdr = NULL;
  double *data = NULL;
  unsigned char pre[12];
  if (fread(pre, 1, 8, f) != 8 || memcmp(pre, "\x93NUMPY", 6)) {
    st = ss_fail(err, SS_ERR_PARSE, "%s: byte 0: not a NumPy .npy file (bad magic)", path);
    goto out;
  }
  int major = pre[6];
  size_t hlen, hstart;
  if (major == 1) {
    if (fread(pre + 8, 1, 2, f) != 2) {
      st = ss_fail(err, SS_ERR_PARSE, "%s: byte 8: truncated header", path);
      goto out;
    }
    hlen = (size_t)pre[8] | ((size_t)pre[9] << 8);
    hstart = 10;
  } else if (major == 2 || major == 3) {
    if (fread(pre + 8, 1, 4, f) != 4) {
      st = ss_fail(err, SS_ERR_PARSE, "%s: byte 8: truncated header", path);
      goto out;
    }
    hlen = (size_t)pre[8] | ((size_t)pre[9] << 8) | ((size_t)pre[10] << 16) | ((size_t)pre[11] << 24);
    hstart = 12;
  } else {
    st = ss_fail(err, SS_ERR_PARSE, "%s: byte 6: unsupported .npy format version %d.%d", path, major, pre[7]);
    goto out;
  }
  /* the header must really be in the file before we allocate for it */
  if (fseek(f, 0, SEEK_END) != 0) {
    st = ss_fail(err, SS_ERR_IO, "%s: cannot seek", path);
    goto out;
  }
  long fsize = ftell(f);
  if (fsize < 0 || hlen > (size_t)fsize - hstart || (size_t)fsize < hstart) {
    st = ss_fail(err, SS_ERR_PARSE, "%s: byte 8: header length %zu exceeds the file size", path, hlen);
    goto out;
  }
  if (hlen == 0) {
    st = ss_fail(err, SS_ERR_PARSE, "%s: byte %zu: empty header", path, hstart);
    goto out;
  }
  if (fseek(f, (long)hstart, SEEK_SET) != 0 || !(hdr = malloc(hlen))) {
    st = ss_fail(err, SS_ERR_NOMEM, "%s: cannot read header", path);
    goto out;
  }
  if (fread(hdr, 1, hlen, f) != hlen) {
    st = ss_fail(err, SS_ERR_PARSE, "%s: byte %zu: truncated header", path, hstart);
    goto out;
  }
  for (size_t i = 0; i < hlen; i++)
    if ((unsigned char)hdr[i] >= 0x80 || hdr[i] == 0) {
      st = ss_fail(err, SS_ERR_PARSE, "%s: byte %zu: non-ASCII character in header", path, hstart + i);
      goto out;
    }
  int big = 0, fortran = 0, ndim = 0;
  long long shape[2] = {0, 1};
  const char *why = parse_header(hdr, hlen, &big, &fortran, &ndim, shape);
  if (why) {
    st = ss_fail(err, SS_ERR_PARSE, "%s: byte %zu: %s", path, hstart, why);
    goto out;
  }
  long long r = shape[0], c = ndim == 2 ? shape[1] : 1;
  if (r > INT32_MAX || c > INT32_MAX) {
    st = ss_fail(err, SS_ERR_PARSE, "%s: shape too large", path);
    goto out;
  }
  unsigned long long count = (unsigned long long)r * (unsigned long long)c;
  size_t dstart = hstart + hlen;
  unsigned long long avail = (unsigned long long)fsize - dstart;
  if (count > avail / 8) {
    st = ss_fail(err, SS_ERR_PARSE, "%s: byte %zu: truncated data: shape needs %llu values, file holds %llu", path,
                 dstart, count, avail / 8);
    goto out;
  }
  if (avail != count * 8) {
    st = ss_fail(err, SS_ERR_PARSE, "%s: byte %llu: %llu trailing bytes after the data", path,
                 (unsigned long long)dstart + count * 8, avail - count * 8);
    goto out;
  }
  data = malloc(sizeof(double) * (size_t)(count > 0 ? count : 1));
  if (!data) {
    st = ss_fail(err, SS_ERR_NOMEM, "%s: out of memory for %llu values", path, count);
    goto out;
  }
  if (count && fread(data, 8, (size_t)count, f) != (size_t)count) {
    st = ss_fail(err, SS_ERR_IO, "%s: read error", path);
    goto out;
  }
  if (big == host_is_little_endian())
    for (size_t i = 0; i < count; i++) swap8((unsigned char *)&data[i]);
  if (!fortran && ndim == 2 && r > 1 && c > 1) {
    /* C order -> column-major */
    double *t = malloc(sizeof(double) * (size_t)count);
    if (!t) {
      st = ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", path);
      goto out;
    }
    for (long long i = 0; i < r; i++)
      for (long long j = 0; j < c; j++) t[i + r * j] = data[i * c + j];
    free(data);
    data = t;
  }
  *a = data;
  data = NULL;
  *rows = (int)r;
  *cols = (int)c;
out:
  free(hdr);
  free(data);
  fclose(f);
  return st;
}
