/* Our STL reader: ascii and binary STL of an icosphere and a cube written here, read back welded into a
 * closed mesh (vertex and face counts, vertices in order of first occurrence, the exact faces), the same
 * bytes from memory (format by content), keywords in capitals and several solids, the exact weld
 * itself, and a clean error naming the file and line for each malformed input (among them the inputs
 * on which assimp's reader, which read STL before, threw and leaked). */
#include <math.h>
#include <stdint.h>
#include <unistd.h>

#include "mesh/io_internal.h"
#include "specseg/io.h"
#include "specseg/mesh.h"
#include "specseg/synth.h"
#include "testlib.h"

/* STL of m: every face's three corners as float32 (ascii with %.17g of the same floats, which reads
 * back as those values exactly, so both encodings hold identical coordinates). */
static void write_stl(const char *path, const ss_mesh *m, int binary) {
  FILE *f = fopen(path, "wb");
  if (!f) { perror(path); exit(2); }
  if (binary) {
    char head[80];
    memset(head, ' ', sizeof head);
    memcpy(head, "solid specseg test (binary despite the word)", 44);
    fwrite(head, 1, 80, f);
    uint32_t nf = (uint32_t)m->nf;
    fwrite(&nf, 4, 1, f);
    for (int t = 0; t < m->nf; t++) {
      float rec[12] = {0};
      for (int c = 0; c < 3; c++)
        for (int d = 0; d < 3; d++) rec[3 + 3 * c + d] = (float)m->V[3 * (size_t)m->F[3 * t + c] + d];
      fwrite(rec, sizeof rec, 1, f);
      fwrite("\0\0", 1, 2, f);
    }
  } else {
    fprintf(f, "solid test\n");
    for (int t = 0; t < m->nf; t++) {
      fprintf(f, "  facet normal 0 0 0\n    outer loop\n");
      for (int c = 0; c < 3; c++) {
        const double *p = m->V + 3 * (size_t)m->F[3 * t + c];
        fprintf(f, "      vertex %.17g %.17g %.17g\n", (double)(float)p[0], (double)(float)p[1], (double)(float)p[2]);
      }
      fprintf(f, "    endloop\n  endfacet\n");
    }
    fprintf(f, "endsolid test\n");
  }
  fclose(f);
}

/* r is m welded: the vertices of m in order of first occurrence in its faces (as float32), the faces
 * renumbered accordingly. */
static int same_as_welded(const ss_mesh *m, const ss_mesh *r) {
  int *id = malloc(sizeof(int) * (size_t)m->nv), n = 0, ok = 1;
  for (int i = 0; i < m->nv; i++) id[i] = -1;
  for (int k = 0; k < 3 * m->nf; k++)
    if (id[m->F[k]] < 0) id[m->F[k]] = n++;
  if (n != r->nv || m->nf != r->nf) ok = 0;
  for (int k = 0; ok && k < 3 * m->nf; k++) ok = r->F[k] == id[m->F[k]];
  for (int i = 0; ok && i < m->nv; i++)
    for (int d = 0; ok && d < 3 && id[i] >= 0; d++) ok = r->V[3 * (size_t)id[i] + d] == (double)(float)m->V[3 * (size_t)i + d];
  free(id);
  return ok;
}

static void test_weld(void) {
  /* two triangles sharing an edge, given as a soup; -0 equals 0; NaN vertices stay apart */
  double V[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, /* */ 1, 0, 0, 1, 1, 0, -0.0, 1, 0, /* */ NAN, 0, 0, NAN, 0, 0, 5, 5, 5};
  int F[] = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  ss_mesh m;
  ss_error e;
  CHECK(ss_mesh_alloc(&m, 9, 3, &e) == SS_OK);
  memcpy(m.V, V, sizeof V), memcpy(m.F, F, sizeof F);
  int merged = -1;
  CHECK(ssi_mesh_weld(&m, &merged, &e) == SS_OK);
  CHECK_MSG(merged == 2 && m.nv == 7, "merged %d, nv %d", merged, m.nv);
  static const int want[] = {0, 1, 2, 1, 3, 2, 4, 5, 6};
  int same = 1;
  for (int k = 0; k < 9; k++) same &= m.F[k] == want[k];
  CHECK(same);
  CHECK(m.V[3 * 3 + 0] == 1 && m.V[3 * 3 + 1] == 1); /* vertex 4 of the soup is the 4th distinct one */
  CHECK(m.V[3 * 4] != m.V[3 * 4] && m.V[3 * 5] != m.V[3 * 5]);
  ss_mesh_free(&m);
}

static void test_stl(void) {
  ss_error e;
  ss_mesh ico = {0}, cube = {0}, r = {0};
  CHECK(ss_synth_icosphere(3, &ico, &e) == SS_OK);
  static const double CV[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  static const int CF[] = {0, 3, 2, 0, 2, 1, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                           1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
  CHECK(ss_mesh_alloc(&cube, 8, 12, &e) == SS_OK);
  memcpy(cube.V, CV, sizeof CV), memcpy(cube.F, CF, sizeof CF);
  const ss_mesh *ms[2] = {&ico, &cube};
  for (int s = 0; s < 2; s++)
    for (int bin = 0; bin < 2; bin++) {
      const char *p = tl_tmp(bin ? "m_bin.STL" : "m_ascii.stl"); /* extension case-insensitive */
      write_stl(p, ms[s], bin);
      ss_status st = ss_read_mesh(p, &r, &e);
      CHECK_MSG(st == SS_OK, "%s: %s", p, e.msg);
      if (st) continue;
      CHECK_MSG(r.nv == ms[s]->nv && r.nf == ms[s]->nf, "%s %s: %d v %d f, want %d %d", s ? "cube" : "icosphere",
                bin ? "binary" : "ascii", r.nv, r.nf, ms[s]->nv, ms[s]->nf);
      CHECK(same_as_welded(ms[s], &r));
      tl_check_closed(&r, p);
      /* the same bytes from memory: the format comes from the content */
      size_t n;
      char *b = tl_read_file(p, &n);
      ss_mesh r2 = {0};
      st = ss_read_mesh_memory(b, n, "<bytes>", &r2, &e);
      CHECK_MSG(st == SS_OK, "memory: %s", e.msg);
      if (!st) CHECK(r2.nv == r.nv && r2.nf == r.nf && !memcmp(r2.V, r.V, sizeof(double) * 3 * r.nv) &&
                     !memcmp(r2.F, r.F, sizeof(int) * 3 * r.nf));
      free(b);
      ss_mesh_free(&r2);
      ss_mesh_free(&r);
    }
  CHECK(ss_read_mesh(tl_tmp("missing.stl"), &r, &e) == SS_ERR_IO && strstr(e.msg, "cannot open"));
  ss_mesh_free(&ico), ss_mesh_free(&cube);
}


/* two facets of a unit square, the second solid's, keywords in capitals, odd spacing, CRLF */
static void test_stl_variants(void) {
  static const char two[] =
      "solid a b c\r\n facet normal 0 0 1\r\n outer loop\r\n vertex 0 0 0\r\n vertex 1 0 0\r\n vertex 1 1 0\r\n"
      " endloop\r\n endfacet\r\nendsolid a\r\n"
      "SOLID\nFACET NORMAL 0 0 1 OUTER LOOP VERTEX 0 0 0 VERTEX 1 1 0 VERTEX 0 1 0 ENDLOOP ENDFACET ENDSOLID\n";
  ss_mesh r = {0};
  ss_error e;
  ss_status st = ss_read_mesh_memory(two, sizeof two - 1, "<two>", &r, &e);
  CHECK_MSG(st == SS_OK, "%s", e.msg);
  if (!st) {
    static const double V[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    static const int F[] = {0, 1, 2, 0, 2, 3};
    CHECK_MSG(r.nv == 4 && r.nf == 2 && !memcmp(r.V, V, sizeof V) && !memcmp(r.F, F, sizeof F), "%d v %d f", r.nv, r.nf);
  }
  ss_mesh_free(&r);
  /* "solid" in a binary header with a length that fits it: binary (the corners are float32) */
  unsigned char bin[134] = {0};
  memcpy(bin, "solid x facet", 13);
  bin[80] = 1;
  const float P[9] = {0.1f, 0, 0, 1, 0, 0, 0, 1, 0};
  memcpy(bin + 84 + 12, P, sizeof P);
  st = ss_read_mesh_memory(bin, sizeof bin, "<bin>", &r, &e);
  CHECK_MSG(st == SS_OK && r.nv == 3 && r.nf == 1 && r.V[0] == (double)0.1f, "%s", st ? e.msg : "counts");
  ss_mesh_free(&r);
}

/* ss_read_stl reads STL whatever the extension (ss_read_mesh would take a .txt for text of another
 * format), and refuses NULL arguments */
static void test_read_stl_by_name(void) {
  static const char one[] = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                            "endloop\nendfacet\nendsolid t\n";
  tl_write_file(tl_tmp("one.txt"), one, sizeof one - 1);
  ss_mesh r = {0};
  ss_error e;
  CHECK_MSG(ss_read_stl(tl_tmp("one.txt"), &r, &e) == SS_OK && r.nv == 3 && r.nf == 1, "%s", e.msg);
  ss_mesh_free(&r);
  CHECK(ss_read_stl(NULL, &r, &e) == SS_ERR_INVALID && !r.V && ss_read_stl(tl_tmp("one.txt"), NULL, &e) == SS_ERR_INVALID);
  CHECK(ss_read_stl(tl_tmp("missing.stl"), &r, &e) == SS_ERR_IO && !r.V);
}

typedef struct bad_case {
  const char *text, *want; /* want: a part of the message */
} bad_case;

static void test_stl_errors(void) {
  static const bad_case cases[] = {
      {"solid x\nendsolid x\n", "without facets"},
      {"solid x\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0\n", ":4: the file ends inside a vertex"},
      {"solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 property\n", ":4: a vertex coordinate is not a number ('property')"},
      {"solid x\n facet normalerty 0 0 1\n", ":2: 'normalerty' where 'normal' was expected"},
      {"solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\n vertex 1 0 0\n endloop\n endfacet\nendsolid\n",
       ":3: a facet with 2 vertices"},
      {"solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\n vertex 1 0 0\n vertex 1 1 0\n vertex 0 1 0\n"
       " endloop\n endfacet\nendsolid\n",
       ":3: a facet with more than 3 vertices"},
      {"solid x\n facet outer loop\n", ":2: 'outer' where 'normal' was expected"},
      {"solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\n vertex 1 0 0\n vertex 1 1 0\n endloop\n endfacet\n",
       "the file ends before 'endsolid'"},
      {"solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\n vertex 1 0 0\n vertex 1 1 0\n endloop\n endfacet\n"
       "endsolid\ngarbage\n",
       ":10: 'garbage' where 'solid' or the end of the file was expected"},
      {"solid x\n vertex 0 0 0\n", ":2: 'vertex' where 'facet' or 'endsolid' was expected"},
      {"not an stl", "not text beginning with 'solid'"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
    const char *t = cases[k].text;
    tl_write_file(tl_tmp("bad.stl"), t, strlen(t));
    ss_mesh r = {0};
    ss_error e = {{0}};
    ss_status st = ss_read_mesh(tl_tmp("bad.stl"), &r, &e);
    const char *want = cases[k].want;
    CHECK_MSG(st == SS_ERR_PARSE && strstr(e.msg, "bad.stl") && strstr(e.msg, want) && r.nv == 0 && !r.V,
              "case %zu: %s (want '%s')", k, e.msg, want);
    ss_mesh_free(&r);
  }
  /* a NUL ends no text: it is part of the token (assimp stopped reading there) */
  static const char nul[] = "solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\0 vertex 1 0 0\n";
  tl_write_file(tl_tmp("nul.stl"), nul, sizeof nul - 1);
  ss_mesh r = {0};
  ss_error e;
  CHECK_MSG(ss_read_mesh(tl_tmp("nul.stl"), &r, &e) == SS_ERR_PARSE && strstr(e.msg, "nul.stl:4: a vertex coordinate is not a number"),
            "%s", e.msg);
  /* binary: the length must be 84 + 50 n for the declared n */
  char junk[100] = {0};
  junk[80] = 9; /* 9 facets declared, none there */
  tl_write_file(tl_tmp("short.stl"), junk, sizeof junk);
  CHECK(ss_read_mesh(tl_tmp("short.stl"), &r, &e) == SS_ERR_PARSE && strstr(e.msg, "short.stl") &&
        strstr(e.msg, "declares 9 facets, which take 534 bytes; the file has 100"));
  junk[80] = 0;
  tl_write_file(tl_tmp("zero.stl"), junk, 84);
  CHECK_MSG(ss_read_mesh(tl_tmp("zero.stl"), &r, &e) == SS_ERR_PARSE && strstr(e.msg, "binary STL without facets"), "%s", e.msg);
  tl_write_file(tl_tmp("tiny.stl"), "abc", 3);
  CHECK(ss_read_mesh(tl_tmp("tiny.stl"), &r, &e) == SS_ERR_PARSE && strstr(e.msg, "shorter than a binary STL's 84-byte"));
  tl_write_file(tl_tmp("empty.stl"), "", 0);
  CHECK(ss_read_mesh(tl_tmp("empty.stl"), &r, &e) == SS_ERR_PARSE);
}

int main(void) {
  if (!tl_tmpdir_make("/tmp/ss_test_stl_XXXXXX")) { perror("mkdtemp"); return 2; }
  test_weld();
  CHECK(ss_mesh_extension_supported("m.stl") == 1 && ss_mesh_extension_supported("M.STL") == 1 &&
        ss_mesh_extension_supported("stl") == 0 && ss_mesh_extension_supported("d.stl/x") == 0);
  test_stl();
  test_stl_variants();
  test_read_stl_by_name();
  test_stl_errors();
  tl_tmpdir_remove();
  TEST_MAIN_END();
}
