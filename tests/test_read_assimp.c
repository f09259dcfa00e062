/* Formats read through assimp: ascii and binary STL of an icosphere and a cube written here, read back
 * welded into a closed mesh (vertex and face counts, vertices in order of first occurrence, the exact
 * faces), the same bytes from memory (format by content), a minimal glTF 2.0 with an embedded base64
 * buffer (a tetrahedron under a node translation) and its .glb twin, the exact weld itself, and clean
 * errors. A build without assimp must refuse STL naming libassimp-dev; the other checks then SKIP. */
#include <stdint.h>
#include <unistd.h>

#include "mesh/io_internal.h"
#include "specseg/io.h"
#include "specseg/mesh.h"
#include "specseg/synth.h"
#include "testlib.h"

static char tmpdir[512];

static const char *tmp(const char *name) {
  static char buf[4][1024];
  static int k = 0;
  k = (k + 1) % 4;
  snprintf(buf[k], sizeof buf[k], "%s/%s", tmpdir, name);
  return buf[k];
}

static void write_file(const char *path, const void *data, size_t n) {
  FILE *f = fopen(path, "wb");
  if (!f) { perror(path); exit(2); }
  fwrite(data, 1, n, f);
  fclose(f);
}

static char *read_all(const char *path, size_t *n) {
  *n = 0;
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  long sz = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *b = malloc((size_t)sz + 1);
  *n = fread(b, 1, (size_t)sz, f);
  fclose(f);
  return b;
}

/* STL of m: every face's three corners as float32 (ascii with %.9g of the same floats, so both
 * encodings hold identical coordinates). */
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
        fprintf(f, "      vertex %.9g %.9g %.9g\n", (double)(float)p[0], (double)(float)p[1], (double)(float)p[2]);
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

static void check_closed(const ss_mesh *r, const char *what) {
  ss_mesh_report rep;
  ss_error e;
  CHECK(ss_mesh_check(r, &rep, &e) == SS_OK);
  CHECK_MSG(rep.components == 1 && rep.boundary_edges == 0 && rep.manifold && rep.oriented && rep.euler_characteristic == 2,
            "%s: components %d, boundary edges %d, manifold %d, oriented %d, chi %d", what, rep.components,
            rep.boundary_edges, rep.manifold, rep.oriented, rep.euler_characteristic);
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
      const char *p = tmp(bin ? "m_bin.STL" : "m_ascii.stl"); /* extension case-insensitive */
      write_stl(p, ms[s], bin);
      ss_status st = ss_read_mesh(p, &r, &e);
      CHECK_MSG(st == SS_OK, "%s: %s", p, e.msg);
      if (st) continue;
      CHECK_MSG(r.nv == ms[s]->nv && r.nf == ms[s]->nf, "%s %s: %d v %d f, want %d %d", s ? "cube" : "icosphere",
                bin ? "binary" : "ascii", r.nv, r.nf, ms[s]->nv, ms[s]->nf);
      CHECK(same_as_welded(ms[s], &r));
      check_closed(&r, p);
      /* the same bytes from memory: the format comes from the content */
      size_t n;
      char *b = read_all(p, &n);
      ss_mesh r2 = {0};
      st = ss_read_mesh_memory(b, n, "<bytes>", &r2, &e);
      CHECK_MSG(st == SS_OK, "memory: %s", e.msg);
      if (!st) CHECK(r2.nv == r.nv && r2.nf == r.nf && !memcmp(r2.V, r.V, sizeof(double) * 3 * r.nv) &&
                     !memcmp(r2.F, r.F, sizeof(int) * 3 * r.nf));
      free(b);
      ss_mesh_free(&r2);
      ss_mesh_free(&r);
    }
  /* malformed: a truncated binary STL, an ascii STL without facets */
  write_file(tmp("bad.stl"), "solid x\nendsolid x\n", 19);
  CHECK(ss_read_mesh(tmp("bad.stl"), &r, &e) != SS_OK && strstr(e.msg, "bad.stl") && r.nv == 0 && !r.V);
  char junk[100] = {0};
  junk[80] = 9; /* 9 facets declared, none there */
  write_file(tmp("short.stl"), junk, sizeof junk);
  CHECK(ss_read_mesh(tmp("short.stl"), &r, &e) != SS_OK && strstr(e.msg, "short.stl"));
  CHECK(ss_read_mesh(tmp("missing.stl"), &r, &e) == SS_ERR_IO && strstr(e.msg, "cannot open"));
  ss_mesh_free(&ico), ss_mesh_free(&cube);
}

static const char B64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

static void base64(const unsigned char *in, size_t n, char *out) {
  size_t o = 0;
  for (size_t i = 0; i < n; i += 3) {
    uint32_t v = (uint32_t)in[i] << 16 | (i + 1 < n ? (uint32_t)in[i + 1] << 8 : 0) | (i + 2 < n ? in[i + 2] : 0);
    out[o++] = B64[v >> 18 & 63], out[o++] = B64[v >> 12 & 63];
    out[o++] = i + 1 < n ? B64[v >> 6 & 63] : '=';
    out[o++] = i + 2 < n ? B64[v & 63] : '=';
  }
  out[o] = '\0';
}

static void test_gltf(void) {
  /* a tetrahedron (outward faces), float positions + uint16 indices in one buffer, translated by (10, 0, 0) */
  static const float P[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  static const uint16_t I[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  unsigned char buf[72];
  memcpy(buf, P, 48), memcpy(buf + 48, I, 24);
  char b64[200], json[2048];
  base64(buf, sizeof buf, b64);
  int n = snprintf(json, sizeof json,
                   "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
                   "\"nodes\":[{\"mesh\":0,\"translation\":[10,0,0]}],"
                   "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
                   "\"buffers\":[{\"byteLength\":72,\"uri\":\"data:application/octet-stream;base64,%s\"}],"
                   "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48,\"target\":34962},"
                   "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":24,\"target\":34963}],"
                   "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
                   "\"min\":[0,0,0],\"max\":[1,1,1]},{\"bufferView\":1,\"componentType\":5123,\"count\":12,"
                   "\"type\":\"SCALAR\"}]}\n",
                   b64);
  write_file(tmp("tet.gltf"), json, (size_t)n);
  ss_error e;
  ss_mesh r = {0};
  ss_status st = ss_read_mesh(tmp("tet.gltf"), &r, &e);
  CHECK_MSG(st == SS_OK, "tet.gltf: %s", e.msg);
  if (!st) {
    CHECK_MSG(r.nv == 4 && r.nf == 4, "%d v %d f", r.nv, r.nf);
    int same = r.nv == 4;
    for (int i = 0; same && i < 12; i++) same = r.V[i] == P[i] + (i % 3 == 0 ? 10 : 0) && r.F[i] == I[i];
    CHECK_MSG(same, "the node's translation applied, vertices and faces in the file's order");
    check_closed(&r, "tet.gltf");
    ss_mesh_free(&r);
  }
  /* the same JSON from memory */
  st = ss_read_mesh_memory(json, (size_t)n, "<json>", &r, &e);
  CHECK_MSG(st == SS_OK && r.nv == 4 && r.nf == 4, "gltf from memory: %s", st ? e.msg : "counts");
  ss_mesh_free(&r);
  /* the binary container: the JSON chunk without the uri, then the BIN chunk */
  char j2[2048];
  int jn = snprintf(j2, sizeof j2, "%s", json);
  char *u = strstr(j2, ",\"uri\"");
  char *q = u ? strchr(u + 8, '"') : NULL; /* the closing quote of the data URI */
  if (u && q) memmove(u, q + 1, strlen(q + 1) + 1), jn = (int)strlen(j2);
  while (jn % 4) j2[jn++] = ' ';
  uint32_t total = 12 + 8 + (uint32_t)jn + 8 + 72;
  unsigned char glb[4096];
  size_t o = 0;
  uint32_t h[3] = {0x46546C67u, 2, total}, cj[2] = {(uint32_t)jn, 0x4E4F534Au}, cb[2] = {72, 0x004E4942u};
  memcpy(glb + o, h, 12), o += 12;
  memcpy(glb + o, cj, 8), o += 8;
  memcpy(glb + o, j2, (size_t)jn), o += (size_t)jn;
  memcpy(glb + o, cb, 8), o += 8;
  memcpy(glb + o, buf, 72), o += 72;
  write_file(tmp("tet.glb"), glb, o);
  st = ss_read_mesh(tmp("tet.glb"), &r, &e);
  CHECK_MSG(st == SS_OK && r.nv == 4 && r.nf == 4, "tet.glb: %s", st ? e.msg : "counts");
  if (!st) CHECK(r.V[0] == 10 && r.V[11] == 1);
  ss_mesh_free(&r);
  st = ss_read_mesh_memory(glb, o, "<glb>", &r, &e);
  CHECK_MSG(st == SS_OK && r.nv == 4, "glb from memory: %s", st ? e.msg : "counts");
  ss_mesh_free(&r);
  /* a scene without meshes */
  write_file(tmp("empty.gltf"), "{\"asset\":{\"version\":\"2.0\"}}", 27);
  CHECK(ss_read_mesh(tmp("empty.gltf"), &r, &e) != SS_OK && strstr(e.msg, "empty.gltf") && !r.V);
}

int main(void) {
  snprintf(tmpdir, sizeof tmpdir, "/tmp/ss_test_assimp_XXXXXX");
  if (!mkdtemp(tmpdir)) { perror("mkdtemp"); return 2; }
  test_weld();
  /* which build is this? */
  ss_mesh ico = {0}, r = {0};
  ss_error e;
  CHECK(ss_synth_icosphere(1, &ico, &e) == SS_OK);
  write_stl(tmp("probe.stl"), &ico, 1);
  ss_status st = ss_read_mesh(tmp("probe.stl"), &r, &e);
  ss_mesh_free(&ico), ss_mesh_free(&r);
  CHECK(ss_mesh_extension_supported("a/b.OFF") == 1 && ss_mesh_extension_supported("x.ply") == 1 &&
        ss_mesh_extension_supported("x.obj") == 1 && ss_mesh_extension_supported("x.txt") == 0 &&
        ss_mesh_extension_supported("stl") == 0 && ss_mesh_extension_supported("d.stl/x") == 0);
  CHECK(ss_mesh_extension_supported("m.stl") == (st == SS_ERR_UNSUPPORTED ? 0 : 2));
  CHECK(ss_mesh_extension_supported("m.GLB") == (st == SS_ERR_UNSUPPORTED ? 0 : 2));
  if (st == SS_ERR_UNSUPPORTED) {
    CHECK_MSG(strstr(e.msg, "libassimp-dev") && strstr(e.msg, "STL") && strstr(e.msg, "probe.stl"), "%s", e.msg);
    SKIP("this build has no assimp: STL / glTF reading not checked (%s)", e.msg);
  } else {
    test_stl();
    test_gltf();
  }
  char cmd[600];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
  if (system(cmd)) fprintf(stderr, "could not remove %s\n", tmpdir);
  TEST_MAIN_END();
}
