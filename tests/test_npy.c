/* NumPy .npy: exact round trips, byte layout of the header, and clean rejection of malformed files. */
#define _POSIX_C_SOURCE 200809L
#include "specseg/io.h"
#include "testlib.h"

#include <stdint.h>
#include <unistd.h>

static char dir[512];

static const char *tmp_path(const char *name) {
  static char p[1024];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  return p;
}

static void write_bytes(const char *path, const void *data, size_t n) {
  FILE *f = fopen(path, "wb");
  if (!f) return;
  fwrite(data, 1, n, f);
  fclose(f);
}

/* A v1.0 file with the given dictionary (padded to 64 bytes) followed by `nval` doubles 0,1,2,... */
static void write_npy_raw(const char *path, const char *dict, int nval, int extra_bytes) {
  unsigned char buf[4096];
  size_t dl = strlen(dict), total = 10 + dl + 1, pad = (64 - total % 64) % 64, hlen = dl + pad + 1;
  memcpy(buf, "\x93NUMPY\x01\x00", 8);
  buf[8] = (unsigned char)(hlen & 0xff);
  buf[9] = (unsigned char)(hlen >> 8);
  memcpy(buf + 10, dict, dl);
  memset(buf + 10 + dl, ' ', pad);
  buf[10 + hlen - 1] = '\n';
  size_t off = 10 + hlen;
  for (int i = 0; i < nval; i++) {
    double v = i;
    memcpy(buf + off, &v, 8);
    off += 8;
  }
  for (int i = 0; i < extra_bytes; i++) buf[off++] = 0;
  write_bytes(path, buf, off);
}

/* A header `dict` and n integers of isz bytes (little- or big-endian). */
static void write_npy_ints_raw(const char *path, const char *dict, const long long *v, int n, int isz, int big) {
  unsigned char buf[4096];
  size_t dl = strlen(dict), total = 10 + dl + 1, pad = (64 - total % 64) % 64, hlen = dl + pad + 1;
  memcpy(buf, "\x93NUMPY\x01\x00", 8);
  buf[8] = (unsigned char)(hlen & 0xff);
  buf[9] = (unsigned char)(hlen >> 8);
  memcpy(buf + 10, dict, dl);
  memset(buf + 10 + dl, ' ', pad);
  buf[10 + hlen - 1] = '\n';
  size_t off = 10 + hlen;
  for (int i = 0; i < n; i++)
    for (int t = 0; t < isz; t++) buf[off++] = (unsigned char)((unsigned long long)v[i] >> (8 * (big ? isz - 1 - t : t)));
  write_bytes(path, buf, off);
}

/* ss_write_npy_ints / ss_read_npy_ints: '<i4' round trip, '<i8' / '>i4' / Fortran order read, int64 out
 * of range and float files refused, the memory reader. */
static void test_ints(void) {
  ss_error e;
  int A[6] = {0, -1, 2147483647, -2147483647 - 1, 5, 42}, *a = NULL, r, c;
  CHECK(ss_write_npy_ints(tmp_path("i.npy"), A, 3, 2, &e) == SS_OK);
  CHECK(ss_read_npy_ints(tmp_path("i.npy"), &a, &r, &c, &e) == SS_OK && r == 3 && c == 2 && a && !memcmp(a, A, sizeof A));
  free(a);
  a = NULL;
  /* the bytes: '<i4', C order (row 0 = A[0], A[3]) */
  FILE *f = fopen(tmp_path("i.npy"), "rb");
  unsigned char b[256];
  size_t got = f ? fread(b, 1, sizeof b, f) : 0;
  if (f) fclose(f);
  size_t d0 = 10 + (size_t)b[8]; /* data start, a multiple of 64 */
  CHECK(d0 % 64 == 0 && got == d0 + 24 && !memcmp(b + 10, "{'descr': '<i4'", 15) && b[d0 + 4] == 0x00 && b[d0 + 7] == 0x80);
  CHECK(ss_read_npy_ints_memory(b, got, "mem", &a, &r, &c, &e) == SS_OK && r == 3 && c == 2 && a && a[3] == A[3]);
  free(a);
  a = NULL;
  double *d = NULL;
  CHECK(ss_read_npy(tmp_path("i.npy"), &d, &r, &c, &e) == SS_ERR_PARSE && !d); /* ints are not doubles */
  const long long v[4] = {7, -3, 1000000, 0};
  write_npy_ints_raw(tmp_path("i8.npy"), "{'descr': '<i8', 'fortran_order': False, 'shape': (4,), }", v, 4, 8, 0);
  CHECK(ss_read_npy_ints(tmp_path("i8.npy"), &a, &r, &c, &e) == SS_OK && r == 4 && c == 1 && a && a[0] == 7 && a[1] == -3 &&
        a[2] == 1000000);
  free(a);
  a = NULL;
  write_npy_ints_raw(tmp_path("be.npy"), "{'descr': '>i4', 'fortran_order': True, 'shape': (2, 2), }", v, 4, 4, 1);
  CHECK(ss_read_npy_ints(tmp_path("be.npy"), &a, &r, &c, &e) == SS_OK && r == 2 && c == 2 && a && a[0] == 7 && a[1] == -3 &&
        a[2] == 1000000);
  free(a);
  a = NULL;
  const long long big[1] = {1LL << 40};
  write_npy_ints_raw(tmp_path("big.npy"), "{'descr': '<i8', 'fortran_order': False, 'shape': (1,), }", big, 1, 8, 0);
  CHECK(ss_read_npy_ints(tmp_path("big.npy"), &a, &r, &c, &e) == SS_ERR_PARSE && !a && strstr(e.msg, "big.npy"));
  double D[2] = {1, 2};
  CHECK(ss_write_npy(tmp_path("d.npy"), D, 2, 1, &e) == SS_OK);
  CHECK(ss_read_npy_ints(tmp_path("d.npy"), &a, &r, &c, &e) == SS_ERR_PARSE && !a);
  write_npy_ints_raw(tmp_path("u4.npy"), "{'descr': '<u4', 'fortran_order': False, 'shape': (1,), }", v, 1, 4, 0);
  CHECK(ss_read_npy_ints(tmp_path("u4.npy"), &a, &r, &c, &e) == SS_ERR_PARSE && !a);
  const char *names[] = {"i.npy", "i8.npy", "be.npy", "big.npy", "d.npy", "u4.npy"};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) remove(tmp_path(names[i]));
}

static ss_status read_it(const char *path, double **a, int *r, int *c, ss_error *e) {
  ss_status st = ss_read_npy(path, a, r, c, e);
  if (st) CHECK_MSG(*a == NULL && strlen(e->msg) > 0 && strstr(e->msg, path) != NULL, "error message: %s", e->msg);
  return st;
}

int main(void) {
  const char *t = getenv("TMPDIR");
  snprintf(dir, sizeof dir, "%s/ss_test_npy_XXXXXX", t ? t : "/tmp");
  if (!mkdtemp(dir)) {
    CHECK_MSG(0, "cannot create a temporary folder");
    TEST_MAIN_END();
  }
  ss_error e;
  double *a = NULL;
  int r = -1, c = -1;

  /* round trip of a 5 x 3 column-major matrix with awkward values */
  double A[15];
  for (int i = 0; i < 15; i++) A[i] = (i - 7) * 0.1 + (i == 3 ? 1e-300 : 0) + (i == 4 ? -1.5e300 : 0);
  A[5] = -0.0;
  CHECK(ss_write_npy(tmp_path("a.npy"), A, 5, 3, &e) == SS_OK);
  CHECK(ss_read_npy(tmp_path("a.npy"), &a, &r, &c, &e) == SS_OK);
  CHECK(r == 5 && c == 3);
  CHECK(a && memcmp(a, A, sizeof A) == 0);
  free(a);
  a = NULL;
  /* layout: magic, version 1.0, data at a multiple of 64, C order */
  {
    FILE *f = fopen(tmp_path("a.npy"), "rb");
    unsigned char buf[512];
    size_t got = f ? fread(buf, 1, sizeof buf, f) : 0;
    if (f) fclose(f);
    CHECK(got > 10 && memcmp(buf, "\x93NUMPY\x01\x00", 8) == 0);
    size_t hlen = buf[8] | (buf[9] << 8);
    CHECK((10 + hlen) % 64 == 0);
    CHECK(got == 10 + hlen + sizeof A);
    CHECK(buf[10 + hlen - 1] == '\n');
    CHECK(strstr((char *)buf + 10, "'descr': '<f8'") != NULL);
    CHECK(strstr((char *)buf + 10, "'fortran_order': False") != NULL);
    CHECK(strstr((char *)buf + 10, "'shape': (5, 3)") != NULL);
    double first_row_second;
    memcpy(&first_row_second, buf + 10 + hlen + 8, 8); /* C order: element (0,1) comes second */
    CHECK(first_row_second == A[5]);
  }
  /* empty and single-column matrices */
  CHECK(ss_write_npy(tmp_path("e.npy"), A, 0, 4, &e) == SS_OK);
  CHECK(ss_read_npy(tmp_path("e.npy"), &a, &r, &c, &e) == SS_OK && r == 0 && c == 4);
  free(a);
  a = NULL;
  CHECK(ss_write_npy(tmp_path("v.npy"), A, 15, 1, &e) == SS_OK);
  CHECK(ss_read_npy(tmp_path("v.npy"), &a, &r, &c, &e) == SS_OK && r == 15 && c == 1 && a && !memcmp(a, A, sizeof A));
  free(a);
  a = NULL;

  /* variants NumPy itself writes: 1-D, Fortran order, big-endian, double quotes, no trailing comma */
  write_npy_raw(tmp_path("1d.npy"), "{'descr': '<f8', 'fortran_order': False, 'shape': (6,), }", 6, 0);
  CHECK(ss_read_npy(tmp_path("1d.npy"), &a, &r, &c, &e) == SS_OK && r == 6 && c == 1 && a && a[5] == 5.0);
  free(a);
  a = NULL;
  write_npy_raw(tmp_path("f.npy"), "{'descr': '<f8', 'fortran_order': True, 'shape': (2, 3), }", 6, 0);
  CHECK(ss_read_npy(tmp_path("f.npy"), &a, &r, &c, &e) == SS_OK && r == 2 && c == 3 && a && a[1] == 1.0 && a[2] == 2.0);
  free(a);
  a = NULL;
  write_npy_raw(tmp_path("c.npy"), "{\"descr\": \"<f8\", \"shape\": (2, 3), \"fortran_order\": False}", 6, 0);
  CHECK(ss_read_npy(tmp_path("c.npy"), &a, &r, &c, &e) == SS_OK && r == 2 && c == 3 && a && a[1] == 3.0 &&
        a[2] == 1.0); /* (1,0) = 3 in C order */
  free(a);
  a = NULL;
  {
    /* big-endian: bytes of 1.0 and 2.0 reversed */
    unsigned char buf[256];
    const char *dict = "{'descr': '>f8', 'fortran_order': False, 'shape': (2,), }";
    size_t dl = strlen(dict), hlen = 128 - 10;
    memcpy(buf, "\x93NUMPY\x01\x00", 8);
    buf[8] = (unsigned char)hlen;
    buf[9] = 0;
    memset(buf + 10, ' ', hlen);
    memcpy(buf + 10, dict, dl);
    buf[127] = '\n';
    double v[2] = {1.0, 2.0};
    for (int i = 0; i < 2; i++) {
      unsigned char b[8];
      memcpy(b, &v[i], 8);
      for (int j = 0; j < 8; j++) buf[128 + 8 * i + j] = b[7 - j];
    }
    write_bytes(tmp_path("be.npy"), buf, 144);
    CHECK(ss_read_npy(tmp_path("be.npy"), &a, &r, &c, &e) == SS_OK && r == 2 && a && a[0] == 1.0 && a[1] == 2.0);
    free(a);
    a = NULL;
  }

  /* malformed files: each must fail cleanly with a message naming the file */
  struct { const char *name, *dict; int nval, extra; } bad[] = {
      {"dtype.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (2,), }", 2, 0},
      {"int.npy", "{'descr': '<i8', 'fortran_order': False, 'shape': (2,), }", 2, 0},
      {"short.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 4), }", 11, 0},
      {"trailing.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (2,), }", 2, 3},
      {"huge.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (2000000000, 2000000000), }", 2, 0},
      {"overflow.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (99999999999999999999,), }", 2, 0},
      {"neg.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (-2,), }", 2, 0},
      {"3d.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (1, 1, 2), }", 2, 0},
      {"nokey.npy", "{'descr': '<f8', 'shape': (2,), }", 2, 0},
      {"dupkey.npy", "{'descr': '<f8', 'descr': '<f8', 'fortran_order': False, 'shape': (2,), }", 2, 0},
      {"unknown.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (2,), 'x': 1}", 2, 0},
      {"notdict.npy", "['descr', '<f8']", 2, 0},
      {"unclosed.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (2,", 2, 0},
      {"badbool.npy", "{'descr': '<f8', 'fortran_order': 0, 'shape': (2,), }", 2, 0},
      {"quote.npy", "{'descr: '<f8', 'fortran_order': False, 'shape': (2,), }", 2, 0},
      {"junk.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (2,), } xyz", 2, 0},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    write_npy_raw(tmp_path(bad[i].name), bad[i].dict, bad[i].nval, bad[i].extra);
    ss_status st = read_it(tmp_path(bad[i].name), &a, &r, &c, &e);
    CHECK_MSG(st == SS_ERR_PARSE, "%s: status %d", bad[i].name, st);
  }
  /* byte-level damage */
  write_bytes(tmp_path("empty.npy"), "", 0);
  CHECK(read_it(tmp_path("empty.npy"), &a, &r, &c, &e) == SS_ERR_PARSE);
  write_bytes(tmp_path("magic.npy"), "\x93NUMPX\x01\x00\x10\x00{}", 12);
  CHECK(read_it(tmp_path("magic.npy"), &a, &r, &c, &e) == SS_ERR_PARSE);
  write_bytes(tmp_path("version.npy"), "\x93NUMPY\x07\x00\x10\x00{}", 12);
  CHECK(read_it(tmp_path("version.npy"), &a, &r, &c, &e) == SS_ERR_PARSE);
  write_bytes(tmp_path("hlen.npy"), "\x93NUMPY\x01\x00\xff\xff{'descr'", 18);
  CHECK(read_it(tmp_path("hlen.npy"), &a, &r, &c, &e) == SS_ERR_PARSE);
  write_bytes(tmp_path("hlen2.npy"), "\x93NUMPY\x02\x00\xff\xff\xff\xff{'descr'", 20);
  CHECK(read_it(tmp_path("hlen2.npy"), &a, &r, &c, &e) == SS_ERR_PARSE);
  write_bytes(tmp_path("cut.npy"), "\x93NUMPY\x01", 7);
  CHECK(read_it(tmp_path("cut.npy"), &a, &r, &c, &e) == SS_ERR_PARSE);
  write_bytes(tmp_path("nul.npy"), "\x93NUMPY\x01\x00\x04\x00{\0}\n", 14);
  CHECK(read_it(tmp_path("nul.npy"), &a, &r, &c, &e) == SS_ERR_PARSE);
  /* truncated copy of a valid file */
  {
    FILE *f = fopen(tmp_path("a.npy"), "rb");
    unsigned char buf[512];
    size_t got = f ? fread(buf, 1, sizeof buf, f) : 0;
    if (f) fclose(f);
    write_bytes(tmp_path("trunc.npy"), buf, got - 5);
    CHECK(read_it(tmp_path("trunc.npy"), &a, &r, &c, &e) == SS_ERR_PARSE);
  }
  CHECK(read_it(tmp_path("missing.npy"), &a, &r, &c, &e) == SS_ERR_IO);
  CHECK(read_it(dir, &a, &r, &c, &e) != SS_OK); /* a directory */
  CHECK(ss_write_npy(tmp_path("no/such/dir.npy"), A, 5, 3, &e) == SS_ERR_IO);

  test_ints();
  /* clean up */
  const char *names[] = {"a.npy", "e.npy", "v.npy", "1d.npy", "f.npy", "c.npy", "be.npy", "empty.npy", "magic.npy",
                         "version.npy", "hlen.npy", "hlen2.npy", "cut.npy", "nul.npy", "trunc.npy"};
  if (!getenv("KEEP")) for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) remove(tmp_path(names[i]));
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) remove(tmp_path(bad[i].name));
  if (!getenv("KEEP")) rmdir(dir);
  TEST_MAIN_END();
}
