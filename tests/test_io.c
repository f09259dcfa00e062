/* Mesh and text-vector I/O: exact write -> read round trips for every writer, hand-written OBJ / OFF /
 * PLY (ascii, binary LE and BE) variants with known content, and clean failures (message naming the
 * file and line / byte) on every file of the malformed corpus. */
#include <dirent.h>
#include <limits.h>
#include <stdint.h>
#include <sys/stat.h>
#include <unistd.h>

#include "specseg/io.h"
#include "specseg/mesh.h"
#include "specseg/synth.h"
#include "testlib.h"

static void write_text(const char *path, const char *s) { tl_write_file(path, s, strlen(s)); }

static int same_mesh(const ss_mesh *a, const ss_mesh *b) {
  if (a->nv != b->nv || a->nf != b->nf) return 0;
  if (memcmp(a->F, b->F, sizeof(int) * 3 * (size_t)a->nf)) return 0;
  for (size_t i = 0; i < 3 * (size_t)a->nv; i++)
    if (memcmp(&a->V[i], &b->V[i], sizeof(double))) return 0; /* bit-exact */
  return 1;
}

/* A small mesh with awkward coordinates (non-representable decimals, tiny and huge magnitudes). */
static void test_mesh(ss_mesh *m) {
  CHECK(ss_synth_icosphere(1, m, NULL) == SS_OK);
  m->V[0] = 1.0 / 3.0;
  m->V[1] = -1e-300;
  m->V[2] = 4.9e-324;
  m->V[3] = 1.7976931348623157e308;
  m->V[4] = -0.1;
}

static void test_round_trips(void) {
  ss_mesh m;
  test_mesh(&m);
  unsigned char *rgb = malloc(3 * (size_t)m.nv);
  for (int i = 0; i < 3 * m.nv; i++) rgb[i] = (unsigned char)(i * 37 + 11);
  struct { const char *name; int kind; } cases[] = {
      {"rt.off", -1}, {"rt_ascii.ply", SS_PLY_ASCII}, {"rt_le.ply", SS_PLY_BINARY_LE}, {"rt_be.ply", SS_PLY_BINARY_BE}, {"RT.PLY", -2}};
  for (int c = 0; c < 5; c++)
    for (int col = 0; col < 2; col++) {
      char name[64];
      snprintf(name, sizeof name, "%s%s", col ? "c_" : "", cases[c].name);
      const char *p = tl_tmp(name);
      ss_error err = {{0}};
      ss_status st = cases[c].kind == -1 ? ss_write_off(p, &m, col ? rgb : NULL, &err)
                     : cases[c].kind == -2 ? ss_write_mesh(p, &m, col ? rgb : NULL, &err)
                                           : ss_write_ply(p, &m, col ? rgb : NULL, (ss_ply_format)cases[c].kind, &err);
      CHECK_MSG(st == SS_OK, "%s: %s", name, err.msg);
      ss_mesh r;
      st = ss_read_mesh(p, &r, &err);
      CHECK_MSG(st == SS_OK, "%s: %s", name, err.msg);
      CHECK_MSG(st == SS_OK && same_mesh(&m, &r), "%s differs after the round trip", name);
      ss_mesh_free(&r);
      /* the format-specific reader gives the same */
      st = cases[c].kind == -1 ? ss_read_off(p, &r, &err) : ss_read_ply(p, &r, &err);
      CHECK_MSG(st == SS_OK && same_mesh(&m, &r), "%s (direct reader): %s", name, err.msg);
      ss_mesh_free(&r);
      /* colours are where the header says */
      size_t n;
      char *txt = tl_read_file(p, &n);
      if (!txt) { CHECK(0); continue; }
      if (col) {
        int ok = 1;
        char *body = strstr(txt, "end_header\n");
        if (cases[c].kind == -1) {
          CHECK(!strncmp(txt, "COFF\n", 5));
          char *line = strchr(strchr(txt, '\n') + 1, '\n') + 1; /* first vertex line */
          for (int i = 0; i < 3 && ok; i++) {
            double x, y, z;
            unsigned r_, g_, b_, a_;
            if (sscanf(line, "%lf %lf %lf %u %u %u %u", &x, &y, &z, &r_, &g_, &b_, &a_) != 7) ok = 0;
            else ok = r_ == rgb[3 * i] && g_ == rgb[3 * i + 1] && b_ == rgb[3 * i + 2] && a_ == 255;
            line = strchr(line, '\n') + 1;
          }
        } else if (cases[c].kind == SS_PLY_ASCII) {
          char *line = body + 11;
          for (int i = 0; i < 3 && ok; i++) {
            double x, y, z;
            unsigned r_, g_, b_;
            if (sscanf(line, "%lf %lf %lf %u %u %u", &x, &y, &z, &r_, &g_, &b_) != 6) ok = 0;
            else ok = r_ == rgb[3 * i] && g_ == rgb[3 * i + 1] && b_ == rgb[3 * i + 2];
            line = strchr(line, '\n') + 1;
          }
        } else {
          const unsigned char *b = (const unsigned char *)body + 11;
          CHECK(n == (size_t)(b - (const unsigned char *)txt) + 27 * (size_t)m.nv + 13 * (size_t)m.nf);
          for (int i = 0; i < m.nv && ok; i++) ok = !memcmp(b + 27 * (size_t)i + 24, rgb + 3 * i, 3);
        }
        CHECK_MSG(ok, "%s: colours not written as expected", name);
      } else if (cases[c].kind == -1) {
        CHECK(!strncmp(txt, "OFF\n", 4));
      }
      free(txt);
    }
  /* writer rejects an invalid mesh and an unknown extension */
  ss_error err;
  m.F[4] = m.nv;
  CHECK(ss_write_off(tl_tmp("bad.off"), &m, NULL, &err) == SS_ERR_INVALID);
  m.F[4] = 0;
  CHECK(ss_write_mesh(tl_tmp("x.stl"), &m, NULL, &err) == SS_ERR_UNSUPPORTED);
  CHECK(ss_write_off("/nonexistent-dir/x.off", &m, NULL, &err) == SS_ERR_IO);
  free(rgb);
  ss_mesh_free(&m);
}

static int tri_is(const ss_mesh *m, int f, int a, int b, int c) {
  return m->F[3 * f] == a && m->F[3 * f + 1] == b && m->F[3 * f + 2] == c;
}

static void test_obj(void) {
  const char *p = tl_tmp("t.obj");
  write_text(p,
             "# comment\r\nmtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0  0.5 0.5 0.5\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
             "g group\nusemtl m\ns off\n"
             "f 1/1/1 2/1/1 3/1/1 4/1/1\n" /* quad: 2 triangles */
             "v 2 0 0\nv 2 1 0\nv 3 0 0\n"
             "f -5//1 -3//1 -2//1 -1//1 -4\n" /* pentagon of relative indices 2 5 6 7 3 (1-based) */
             "l 1 2\nf 1/2 3/3 4/4\n");
  ss_mesh m;
  ss_error err = {{0}};
  CHECK_MSG(ss_read_mesh(p, &m, &err) == SS_OK, "%s", err.msg);
  CHECK(m.nv == 7 && m.nf == 6);
  if (m.nv == 7 && m.nf == 6) {
    CHECK(tri_is(&m, 0, 0, 1, 2) && tri_is(&m, 1, 0, 2, 3));
    CHECK(tri_is(&m, 2, 2, 4, 5) && tri_is(&m, 3, 2, 5, 6) && tri_is(&m, 4, 2, 6, 3));
    CHECK(tri_is(&m, 5, 0, 2, 3));
    CHECK(m.V[3 * 2] == 1 && m.V[3 * 2 + 1] == 1 && m.V[3 * 2 + 2] == 0);
    CHECK(m.V[3 * 6] == 3);
  }
  ss_mesh_free(&m);
  /* faces before their vertices (allowed for positive indices) */
  write_text(p, "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
  CHECK(ss_read_obj(p, &m, &err) == SS_OK && m.nf == 1);
  ss_mesh_free(&m);
  /* a .txt extension is sniffed */
  const char *q = tl_tmp("obj_as.txt");
  write_text(q, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  CHECK(ss_read_mesh(q, &m, &err) == SS_OK && m.nv == 3 && m.nf == 1);
  ss_mesh_free(&m);
}

static void test_off_variants(void) {
  const char *p = tl_tmp("v.off");
  ss_mesh m;
  ss_error err = {{0}};
  /* header with counts on the same line, comments, CRLF, colours on vertex and face lines, a quad */
  write_text(p, "OFF 4 2 0 # counts\r\n# a comment\r\n\r\n0 0 0 255 0 0\r\n1 0 0 0 255 0\r\n1 1 0 0 0 255\r\n0 1 0 1 1 1\r\n"
                "4 0 1 2 3 200 100 50\r\n3 0 2 3\r\n");
  CHECK_MSG(ss_read_mesh(p, &m, &err) == SS_OK, "%s", err.msg);
  CHECK(m.nv == 4 && m.nf == 3 && tri_is(&m, 0, 0, 1, 2) && tri_is(&m, 1, 0, 2, 3) && tri_is(&m, 2, 0, 2, 3));
  ss_mesh_free(&m);
  /* no header at all, and COFF / NOFF headers */
  write_text(p, "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  CHECK(ss_read_off(p, &m, &err) == SS_OK && m.nf == 1);
  ss_mesh_free(&m);
  write_text(p, "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n");
  CHECK(ss_read_off(p, &m, &err) == SS_OK && m.nf == 1 && m.V[3] == 1);
  ss_mesh_free(&m);
  /* NaN / Inf literals are read; the check reports them */
  write_text(p, "OFF\n4 2 0\n0 0 0\n1 0 nan\n0 1 0\ninf 1 1\n3 0 1 2\n3 0 2 3\n");
  CHECK_MSG(ss_read_mesh(p, &m, &err) == SS_OK, "%s", err.msg);
  ss_mesh_report r;
  CHECK(ss_mesh_check(&m, &r, &err) == SS_OK && r.nonfinite_vertices == 2);
  ss_mesh_free(&m);
}

/* little helpers to assemble binary PLY bodies */
typedef struct { unsigned char b[4096]; size_t n; int big; } bytes;
static void put(bytes *B, uint64_t u, int sz) {
  for (int i = 0; i < sz; i++) B->b[B->n + (size_t)(B->big ? sz - 1 - i : i)] = (unsigned char)(u >> (8 * i));
  B->n += (size_t)sz;
}
static void put_f(bytes *B, float x) { uint32_t u; memcpy(&u, &x, 4); put(B, u, 4); }
static void put_d(bytes *B, double x) { uint64_t u; memcpy(&u, &x, 8); put(B, u, 8); }
static void put_s(bytes *B, const char *s) { memcpy(B->b + B->n, s, strlen(s)); B->n += strlen(s); }

static const double quad[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {0, 1, 0.25}};

static int quad_ok(const ss_mesh *m) {
  if (m->nv != 4 || m->nf != 3) return 0;
  for (int i = 0; i < 4; i++)
    for (int d = 0; d < 3; d++)
      if (m->V[3 * i + d] != quad[i][d]) return 0;
  return tri_is(m, 0, 0, 1, 2) && tri_is(m, 1, 0, 2, 3) && tri_is(m, 2, 3, 2, 1);
}

static void test_ply_variants(void) {
  const char *p = tl_tmp("v.ply");
  ss_mesh m;
  ss_error err = {{0}};
  /* ascii: float coords, extra scalar and list properties, extra elements before and after, uchar
   * flags in the face element, a quad, vertex_index name, CRLF */
  write_text(p, "ply\r\nformat ascii 1.0\r\ncomment hi\r\nobj_info x\r\nelement material 2\r\nproperty list uchar float k\r\n"
                "element vertex 4\r\nproperty float x\r\nproperty uchar q\r\nproperty float y\r\nproperty float z\r\n"
                "property list int float junk\r\nelement face 2\r\nproperty uchar flags\r\nproperty list int uint vertex_index\r\n"
                "property float w\r\nelement edge 1\r\nproperty int a\r\nproperty int b\r\nend_header\r\n"
                "2 0.5 0.5\r\n0\r\n"
                "0 7 0 0 0\r\n1 7 0 0 2 1 2\r\n1 7 1 0.5 1 9\r\n0 7 1 0.25 0\r\n"
                "1 4 0 1 2 3 0.5\r\n2 3 3 2 1 0\r\n0 1\r\n");
  CHECK_MSG(ss_read_mesh(p, &m, &err) == SS_OK && quad_ok(&m), "ascii: %s", err.msg);
  ss_mesh_free(&m);

  for (int big = 0; big < 2; big++)
    for (int dbl = 0; dbl < 2; dbl++) {
      bytes B = {{0}, 0, big};
      put_s(&B, big ? "ply\nformat binary_big_endian 1.0\n" : "ply\nformat binary_little_endian 1.0\n");
      put_s(&B, dbl ? "element vertex 4\nproperty double x\nproperty double y\nproperty double z\nproperty short s\n"
                    : "element vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty list uchar ushort s\n");
      put_s(&B, dbl ? "element face 2\nproperty list int int vertex_indices\nproperty double w\n"
                    : "element face 2\nproperty list uchar uint vertex_indices\nproperty list ushort int w\n");
      put_s(&B, "element tail 2\nproperty char c\nend_header\n");
      for (int i = 0; i < 4; i++) {
        for (int d = 0; d < 3; d++) {
          if (dbl) put_d(&B, quad[i][d]);
          else put_f(&B, (float)quad[i][d]);
        }
        if (dbl) put(&B, (uint16_t)-5, 2);
        else {
          put(&B, 2, 1);
          put(&B, 7, 2);
          put(&B, 8, 2);
        }
      }
      int faces[2][5] = {{4, 0, 1, 2, 3}, {3, 3, 2, 1, 0}};
      for (int f = 0; f < 2; f++) {
        put(&B, (uint64_t)faces[f][0], dbl ? 4 : 1);
        for (int j = 0; j < faces[f][0]; j++) put(&B, (uint64_t)faces[f][1 + j], 4);
        if (dbl) put_d(&B, 0.5);
        else {
          put(&B, 1, 2);
          put(&B, (uint32_t)-1, 4);
        }
      }
      put(&B, 1, 1);
      put(&B, 2, 1);
      tl_write_file(p, B.b, B.n);
      CHECK_MSG(ss_read_ply(p, &m, &err) == SS_OK && quad_ok(&m), "binary big=%d double=%d: %s", big, dbl, err.msg);
      ss_mesh_free(&m);
      /* every strict prefix of the body fails cleanly (no crash, no success) */
      size_t hdr = (size_t)(strstr((char *)B.b, "end_header\n") - (char *)B.b) + 11;
      int all_fail = 1;
      for (size_t cut = hdr; cut < B.n - 2; cut++) { /* the 2-byte 'tail' element is optional data */
        tl_write_file(p, B.b, cut);
        ss_status st = ss_read_ply(p, &m, &err);
        if (st == SS_OK || !strstr(err.msg, ": byte ")) all_fail = 0;
        ss_mesh_free(&m);
      }
      CHECK_MSG(all_fail, "a truncated binary PLY was accepted (big=%d double=%d)", big, dbl);
    }
}

static void test_errors(void) {
  ss_mesh m;
  ss_error err = {{0}};
  CHECK(ss_read_mesh(tl_tmpdir, &m, &err) == SS_ERR_IO && strstr(err.msg, "is a directory"));
  CHECK(ss_read_mesh(tl_tmp("missing.off"), &m, &err) == SS_ERR_IO && strstr(err.msg, "missing.off"));
  CHECK(m.nv == 0 && m.V == NULL);
  const char *p = tl_tmp("bad.off");
  write_text(p, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n");
  char want[1100];
  snprintf(want, sizeof want, "%s:6: ", p);
  CHECK_MSG(ss_read_mesh(p, &m, &err) == SS_ERR_PARSE && !strncmp(err.msg, want, strlen(want)), "%s", err.msg);
  /* the whole malformed corpus: every file fails with "PATH:LINE: " or "PATH: byte N: " */
  const char *td = getenv("SS_TEST_DIR");
  if (!td) { SKIP("SS_TEST_DIR not set: malformed corpus not checked"); return; }
  char dir[1024];
  snprintf(dir, sizeof dir, "%s/data/malformed", td);
  DIR *d = opendir(dir);
  CHECK(d != NULL);
  if (!d) return;
  int count = 0;
  struct dirent *de;
  while ((de = readdir(d))) {
    const char *n = de->d_name;
    size_t l = strlen(n);
    if (l < 4 || (strcmp(n + l - 4, ".off") && strcmp(n + l - 4, ".obj") && strcmp(n + l - 4, ".ply"))) continue;
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", dir, n);
    memset(&err, 0, sizeof err);
    ss_status st = ss_read_mesh(path, &m, &err);
    size_t pl = strlen(path);
    int located = !strncmp(err.msg, path, pl) && err.msg[pl] == ':' &&
                  ((err.msg[pl + 1] >= '0' && err.msg[pl + 1] <= '9') || !strncmp(err.msg + pl, ": byte ", 7));
    CHECK_MSG(st != SS_OK && located, "%s: status %d, message '%s'", n, (int)st, err.msg);
    CHECK(m.V == NULL && m.F == NULL);
    ss_mesh_free(&m);
    count++;
  }
  closedir(d);
  CHECK_MSG(count >= 25, "only %d corpus files", count);
  printf("malformed corpus: %d files\n", count);
}

static void test_vectors(void) {
  int iv[] = {0, -1, 42, INT_MAX, INT_MIN, 7};
  double dv[] = {0.1, -1.0 / 3.0, 1e-310, 1.7976931348623157e308, INFINITY, -INFINITY, 0.0, 6.02214076e23};
  ss_error err = {{0}};
  int *ri = NULL, ni = -1;
  double *rd = NULL;
  int nd = -1;
  CHECK(ss_write_ints(tl_tmp("i.txt"), iv, 6, &err) == SS_OK);
  CHECK(ss_read_ints(tl_tmp("i.txt"), &ri, &ni, &err) == SS_OK && ni == 6 && !memcmp(ri, iv, sizeof iv));
  free(ri);
  CHECK(ss_write_doubles(tl_tmp("d.txt"), dv, 8, &err) == SS_OK);
  CHECK(ss_read_doubles(tl_tmp("d.txt"), &rd, &nd, &err) == SS_OK && nd == 8 && !memcmp(rd, dv, sizeof dv));
  free(rd);
  /* NaN round trips as NaN */
  double nanv = NAN;
  CHECK(ss_write_doubles(tl_tmp("n.txt"), &nanv, 1, &err) == SS_OK);
  CHECK(ss_read_doubles(tl_tmp("n.txt"), &rd, &nd, &err) == SS_OK && nd == 1 && isnan(rd[0]));
  free(rd);
  /* comments, blank lines, CRLF, empty file */
  write_text(tl_tmp("c.txt"), "# header\r\n\r\n  3 # three\r\n-4\r\n\n");
  CHECK(ss_read_ints(tl_tmp("c.txt"), &ri, &ni, &err) == SS_OK && ni == 2 && ri[0] == 3 && ri[1] == -4);
  free(ri);
  write_text(tl_tmp("e.txt"), "");
  CHECK(ss_read_doubles(tl_tmp("e.txt"), &rd, &nd, &err) == SS_OK && nd == 0);
  free(rd);
  /* errors: two values a line, non-numbers, out-of-range ints, fractional ints, missing file */
  write_text(tl_tmp("b1.txt"), "1\n2 3\n");
  CHECK(ss_read_ints(tl_tmp("b1.txt"), &ri, &ni, &err) == SS_ERR_PARSE && strstr(err.msg, "b1.txt:2:") && ri == NULL);
  write_text(tl_tmp("b2.txt"), "1\nx\n");
  CHECK(ss_read_doubles(tl_tmp("b2.txt"), &rd, &nd, &err) == SS_ERR_PARSE && strstr(err.msg, "b2.txt:2:"));
  write_text(tl_tmp("b3.txt"), "2147483648\n");
  CHECK(ss_read_ints(tl_tmp("b3.txt"), &ri, &ni, &err) == SS_ERR_PARSE && strstr(err.msg, "b3.txt:1:"));
  write_text(tl_tmp("b4.txt"), "1.5\n");
  CHECK(ss_read_ints(tl_tmp("b4.txt"), &ri, &ni, &err) == SS_ERR_PARSE);
  CHECK(ss_read_ints(tl_tmp("none.txt"), &ri, &ni, &err) == SS_ERR_IO);
  CHECK(ss_read_ints(tl_tmpdir, &ri, &ni, &err) == SS_ERR_IO);
}

/* The in-memory readers give what the path readers give on the same bytes, sniff the mesh format
 * (a name without extension), name the input in messages and take no NUL terminator. */
static void test_memory(void) {
  ss_error err = {{0}};
  ss_mesh m, r, q;
  test_mesh(&m);
  const char *p[4] = {tl_tmp("mem.off"), tl_tmp("mem.ply"), tl_tmp("mema.ply"), tl_tmp("membe.ply")};
  CHECK(ss_write_off(p[0], &m, NULL, &err) == SS_OK);
  CHECK(ss_write_ply(p[1], &m, NULL, SS_PLY_BINARY_LE, &err) == SS_OK);
  CHECK(ss_write_ply(p[2], &m, NULL, SS_PLY_ASCII, &err) == SS_OK);
  CHECK(ss_write_ply(p[3], &m, NULL, SS_PLY_BINARY_BE, &err) == SS_OK);
  for (int k = 0; k < 4; k++) {
    size_t n;
    char *b = tl_read_file(p[k], &n);
    CHECK(b != NULL);
    if (!b) continue;
    char *exact = malloc(n + 1); /* exactly n bytes readable, no trailing NUL */
    memcpy(exact, b, n);
    CHECK_MSG(ss_read_mesh_memory(exact, n, "<stdin>", &r, &err) == SS_OK, "%s", err.msg);
    CHECK(ss_read_mesh(p[k], &q, &err) == SS_OK && same_mesh(&r, &q) && same_mesh(&m, &r));
    ss_mesh_free(&r);
    ss_mesh_free(&q);
    free(exact);
    free(b);
  }
  ss_mesh_free(&m);
  const char obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  CHECK(ss_read_mesh_memory(obj, sizeof obj - 1, NULL, &r, &err) == SS_OK && r.nv == 3 && r.nf == 1);
  ss_mesh_free(&r);
  const char bad[] = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n";
  CHECK_MSG(ss_read_mesh_memory(bad, sizeof bad - 1, "<stdin>", &r, &err) == SS_ERR_PARSE &&
                !strncmp(err.msg, "<stdin>:6:", 10) && r.V == NULL,
            "%s", err.msg);
  CHECK(ss_read_mesh_memory("", 0, "<stdin>", &r, &err) == SS_ERR_PARSE && strstr(err.msg, "<stdin>:1: empty"));
  CHECK(ss_read_mesh_memory("hello\n", 6, NULL, &r, &err) == SS_ERR_UNSUPPORTED && !strncmp(err.msg, "<memory>:1:", 11));
  CHECK(ss_read_mesh_memory(NULL, 5, "x", &r, &err) == SS_ERR_INVALID);
  CHECK(ss_read_mesh_memory(obj, 3, "x", NULL, &err) == SS_ERR_INVALID);

  int *ri = NULL, ni = -1;
  double *rd = NULL;
  int nd = -1;
  const char ints[] = "# c\n3\n-4 # x\n"; /* no trailing NUL given: length excludes it */
  CHECK(ss_read_ints_memory(ints, sizeof ints - 1, "<stdin>", &ri, &ni, &err) == SS_OK && ni == 2 && ri[0] == 3 &&
        ri[1] == -4);
  free(ri);
  CHECK(ss_read_ints_memory("1\n2 3\n", 6, "<stdin>", &ri, &ni, &err) == SS_ERR_PARSE &&
        !strncmp(err.msg, "<stdin>:2:", 10) && ri == NULL);
  CHECK(ss_read_doubles_memory("0.5\ninf\n", 8, NULL, &rd, &nd, &err) == SS_OK && nd == 2 && rd[0] == 0.5 &&
        isinf(rd[1]));
  free(rd);
  CHECK(ss_read_doubles_memory(NULL, 0, NULL, &rd, &nd, &err) == SS_OK && nd == 0 && rd != NULL);
  free(rd);
  CHECK(ss_read_doubles_memory("1\n", 2, NULL, NULL, &nd, &err) == SS_ERR_INVALID);
  /* "12" of "12\n" only: a value cut at the buffer's end */
  CHECK(ss_read_ints_memory("12\n", 1, NULL, &ri, &ni, &err) == SS_OK && ni == 1 && ri[0] == 1);
  free(ri);
  /* with line numbers: comments and blank lines counted */
  int *rl = NULL;
  CHECK(ss_read_ints_lines_memory(ints, sizeof ints - 1, "<stdin>", &ri, &rl, &ni, &err) == SS_OK && ni == 2 &&
        ri[1] == -4 && rl[0] == 2 && rl[1] == 3);
  free(ri), free(rl);
  CHECK(ss_read_ints_lines_memory("", 0, NULL, &ri, &rl, &ni, &err) == SS_OK && ni == 0 && ri && rl);
  free(ri), free(rl);
  CHECK(ss_read_ints_lines_memory("1\nx\n", 4, "m", &ri, &rl, &ni, &err) == SS_ERR_PARSE && !strncmp(err.msg, "m:2:", 4) &&
        ri == NULL && rl == NULL);

  int *lx, *ly, *ll, nl, cols;
  CHECK(ss_read_landmarks_memory("5\n# c\n1 2\n", 10, "<stdin>", &lx, &ly, &ll, &nl, &cols, &err) == SS_OK &&
        nl == 2 && lx[0] == 5 && ly[0] == 5 && lx[1] == 1 && ly[1] == 2 && ll[0] == 1 && ll[1] == 3 && cols == 2);
  free(lx), free(ly), free(ll);
  CHECK(ss_read_landmarks_memory("", 0, "<stdin>", &lx, &ly, NULL, &nl, NULL, &err) == SS_ERR_PARSE &&
        strstr(err.msg, "<stdin>: no landmark") && lx == NULL);
  CHECK(ss_read_landmarks_memory("1 2 3\n", 6, "<stdin>", &lx, &ly, NULL, &nl, NULL, &err) == SS_ERR_PARSE &&
        !strncmp(err.msg, "<stdin>:1:", 10));
  CHECK(ss_read_landmarks_memory("1\n", 2, NULL, NULL, &ly, NULL, &nl, NULL, &err) == SS_ERR_INVALID);
}

static void test_faust(void) {
  const char *d = tl_data_dir();
  if (!d) { SKIP("FAUST data not found (SS_DATA_DIR)"); return; }
  char path[4096];
  snprintf(path, sizeof path, "%s/faust/tr_reg_000.off", d);
  ss_mesh m, r;
  ss_error err = {{0}};
  CHECK_MSG(ss_read_mesh(path, &m, &err) == SS_OK, "%s", err.msg);
  CHECK(m.nv == 6890 && m.nf == 13776);
  /* through every writer and back */
  const char *p[3] = {tl_tmp("f.off"), tl_tmp("f.ply"), tl_tmp("fa.ply")};
  CHECK(ss_write_mesh(p[0], &m, NULL, &err) == SS_OK);
  CHECK(ss_write_mesh(p[1], &m, NULL, &err) == SS_OK);
  CHECK(ss_write_ply(p[2], &m, NULL, SS_PLY_ASCII, &err) == SS_OK);
  for (int k = 0; k < 3; k++) {
    CHECK(ss_read_mesh(p[k], &r, &err) == SS_OK && same_mesh(&m, &r));
    ss_mesh_free(&r);
  }
  ss_mesh_free(&m);
}

/* ss_read_mesh_colors: a PLY's vertex colours come back (ascii, binary LE / BE, from memory too); float
 * channels in [0, 1] are scaled; files without colours (and OFF) give NULL; ss_read_mesh is unchanged. */
static void test_colors(void) {
  ss_mesh m, r;
  CHECK(ss_synth_icosphere(1, &m, NULL) == SS_OK);
  unsigned char *rgb = malloc(3 * (size_t)m.nv), *got = NULL;
  for (int i = 0; i < 3 * m.nv; i++) rgb[i] = (unsigned char)(i * 37 + 11);
  ss_error err;
  const ss_ply_format fmts[] = {SS_PLY_ASCII, SS_PLY_BINARY_LE, SS_PLY_BINARY_BE};
  for (int k = 0; k < 3; k++) {
    const char *p = tl_tmp("c.ply");
    CHECK(ss_write_ply(p, &m, rgb, fmts[k], &err) == SS_OK);
    CHECK(ss_read_mesh_colors(p, &r, &got, &err) == SS_OK);
    CHECK(got && same_mesh(&m, &r) && !memcmp(got, rgb, 3 * (size_t)m.nv));
    free(got);
    ss_mesh_free(&r);
    size_t n = 0;
    char *b = tl_read_file(p, &n);
    CHECK(ss_read_mesh_colors_memory(b, n, "mem", &r, &got, &err) == SS_OK);
    CHECK(got && !memcmp(got, rgb, 3 * (size_t)m.nv));
    free(got);
    free(b);
    ss_mesh_free(&r);
    CHECK(ss_read_mesh(p, &r, &err) == SS_OK && same_mesh(&m, &r));
    ss_mesh_free(&r);
  }
  /* no colours: NULL; OFF (even COFF) gives NULL */
  CHECK(ss_write_ply(tl_tmp("n.ply"), &m, NULL, SS_PLY_ASCII, &err) == SS_OK);
  got = (unsigned char *)1;
  CHECK(ss_read_mesh_colors(tl_tmp("n.ply"), &r, &got, &err) == SS_OK && got == NULL);
  ss_mesh_free(&r);
  CHECK(ss_write_off(tl_tmp("c.off"), &m, rgb, &err) == SS_OK);
  CHECK(ss_read_mesh_colors(tl_tmp("c.off"), &r, &got, &err) == SS_OK && got == NULL);
  ss_mesh_free(&r);
  /* float channels and the diffuse_ names; only two channels: no colours */
  write_text(tl_tmp("f.ply"), "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                           "property float z\nproperty float diffuse_red\nproperty float diffuse_green\n"
                           "property float diffuse_blue\nelement face 1\nproperty list uchar int vertex_indices\n"
                           "end_header\n0 0 0 1 0 0.5\n1 0 0 0 1 2\n0 1 0 0.2 0.4 -1\n3 0 1 2\n");
  CHECK(ss_read_mesh_colors(tl_tmp("f.ply"), &r, &got, &err) == SS_OK && got);
  if (got) {
    const unsigned char want[9] = {255, 0, 128, 0, 255, 255, 51, 102, 0};
    CHECK_MSG(!memcmp(got, want, 9), "%d %d %d  %d %d %d  %d %d %d", got[0], got[1], got[2], got[3], got[4], got[5],
              got[6], got[7], got[8]);
  }
  free(got);
  ss_mesh_free(&r);
  write_text(tl_tmp("g.ply"), "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                           "property float z\nproperty uchar red\nproperty uchar green\n"
                           "element face 1\nproperty list uchar int vertex_indices\n"
                           "end_header\n0 0 0 1 0\n1 0 0 0 1\n0 1 0 2 4\n3 0 1 2\n");
  got = (unsigned char *)1;
  CHECK(ss_read_mesh_colors(tl_tmp("g.ply"), &r, &got, &err) == SS_OK && got == NULL && r.nv == 3);
  ss_mesh_free(&r);
  free(rgb);
  ss_mesh_free(&m);
}

/* OBJ output (ss_write_mesh by extension, exact round trip, colours as "v x y z r g b") and the PLY
 * label property (ascii and binary: the mesh reads back unchanged, the labels are in the file). */
static void test_obj_out_and_labels(void) {
  ss_mesh m, r;
  ss_error err;
  test_mesh(&m);
  unsigned char *rgb = malloc(3 * (size_t)m.nv);
  int *lab = malloc(sizeof(int) * (size_t)m.nv);
  for (int i = 0; i < m.nv; i++) {
    rgb[3 * i] = (unsigned char)i, rgb[3 * i + 1] = 255, rgb[3 * i + 2] = 0;
    lab[i] = i % 7 - 1;
  }
  CHECK(ss_write_mesh(tl_tmp("o.obj"), &m, NULL, &err) == SS_OK);
  CHECK(ss_read_mesh(tl_tmp("o.obj"), &r, &err) == SS_OK && same_mesh(&m, &r));
  ss_mesh_free(&r);
  CHECK(ss_write_mesh(tl_tmp("oc.OBJ"), &m, rgb, &err) == SS_OK);
  CHECK(ss_read_mesh(tl_tmp("oc.OBJ"), &r, &err) == SS_OK && same_mesh(&m, &r));
  ss_mesh_free(&r);
  size_t n = 0;
  char *txt = tl_read_file(tl_tmp("oc.OBJ"), &n);
  CHECK(txt && strstr(txt, " 0 1 0\n") && strstr(txt, "\nf 1 "));
  free(txt);
  const ss_ply_format fmts[] = {SS_PLY_ASCII, SS_PLY_BINARY_LE, SS_PLY_BINARY_BE};
  for (int k = 0; k < 3; k++)
    for (int with_rgb = 0; with_rgb < 2; with_rgb++) {
      CHECK(ss_write_ply_labels(tl_tmp("l.ply"), &m, with_rgb ? rgb : NULL, lab, fmts[k], &err) == SS_OK);
      unsigned char *got = NULL;
      CHECK(ss_read_mesh_colors(tl_tmp("l.ply"), &r, &got, &err) == SS_OK && same_mesh(&m, &r));
      CHECK(with_rgb ? got && !memcmp(got, rgb, 3 * (size_t)m.nv) : got == NULL);
      free(got);
      ss_mesh_free(&r);
      txt = tl_read_file(tl_tmp("l.ply"), &n);
      CHECK(txt && strstr(txt, "property int label\nelement face"));
      if (txt && k == 0) { /* ascii: the last value of vertex 2's line is its label, 1 */
        char *body = strstr(txt, "end_header\n") + 11;
        for (int line = 0; line < 2; line++) body = strchr(body, '\n') + 1;
        char *eol = strchr(body, '\n'), *sp = eol;
        while (sp > body && sp[-1] != ' ') sp--;
        CHECK(atoi(sp) == lab[2]);
      }
      free(txt);
    }
  CHECK(ss_write_mesh_labels(tl_tmp("ml.ply"), &m, rgb, lab, &err) == SS_OK);
  txt = tl_read_file(tl_tmp("ml.ply"), &n);
  CHECK(txt && strstr(txt, "binary_little_endian") && strstr(txt, "property int label"));
  free(txt);
  CHECK(ss_write_mesh_labels(tl_tmp("ml.off"), &m, rgb, lab, &err) == SS_OK); /* labels dropped */
  CHECK(ss_read_mesh(tl_tmp("ml.off"), &r, &err) == SS_OK && same_mesh(&m, &r));
  ss_mesh_free(&r);
  free(rgb);
  free(lab);
  ss_mesh_free(&m);
}

int main(void) {
  if (!tl_tmpdir_make("/tmp/ss_test_io_XXXXXX")) { perror("mkdtemp"); return 2; }
  test_round_trips();
  test_obj();
  test_off_variants();
  test_ply_variants();
  test_errors();
  test_vectors();
  test_memory();
  test_colors();
  test_obj_out_and_labels();
  test_faust();
  /* clean up the scratch folder */
  DIR *d = opendir(tl_tmpdir);
  if (d) {
    struct dirent *de;
    while ((de = readdir(d)))
      if (de->d_name[0] != '.') unlink(tl_tmp(de->d_name));
    closedir(d);
  }
  rmdir(tl_tmpdir);
  TEST_MAIN_END();
}
