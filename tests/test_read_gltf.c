/* Our glTF 2.0 reader (no assimp needed): a tetrahedron and a cube written here read back with the exact
 * coordinates and faces; node translation, matrix and translation / rotation / scale (a known quaternion)
 * applied, parent before child; a mesh instanced twice; triangle strips and fans with their triangles and
 * orientation; 8-, 16- and 32-bit indices; an interleaved buffer (byteStride); the GLB twin from a file
 * and from memory equal to the .gltf; an external .bin beside the .gltf read by path and refused from
 * memory; KHR_mesh_quantization int16 normalized positions; JSON escapes; and malformed inputs each
 * refused with a message naming the file and the cause. */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <unistd.h>

#include "mesh/io_internal.h"
#include "specseg/io.h"
#include "specseg/mesh.h"
#include "testlib.h"

/* printf into a malloc'd string */
static char *fmt(const char *f, ...) {
  va_list ap;
  va_start(ap, f);
  int n = vsnprintf(NULL, 0, f, ap);
  va_end(ap);
  char *s = malloc((size_t)n + 1);
  va_start(ap, f);
  vsnprintf(s, (size_t)n + 1, f, ap);
  va_end(ap);
  return s;
}

/* s with the first occurrence of a replaced by b (a must occur) */
static char *replace(const char *s, const char *a, const char *b) {
  const char *p = strstr(s, a);
  if (!p) {
    fprintf(stderr, "replace: '%s' not found\n", a);
    exit(2);
  }
  return fmt("%.*s%s%s", (int)(p - s), s, b, p + strlen(a));
}

/* A .gltf: one buffer holding bin as a data URI, then `rest` (the members after "buffers") */
static char *gltf_text(const char *rest, const void *bin, size_t n) {
  char *b = tl_base64(bin, n);
  char *s =
      fmt("{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;"
          "base64,%s\"}],%s}",
          n, b, rest);
  free(b);
  return s;
}

/* The GLB of the same: buffer 0 without uri is the BIN chunk */
static unsigned char *glb_bytes(const char *rest, const void *bin, size_t n, size_t *len) {
  char *json = fmt("{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu}],%s}", n, rest);
  size_t jn = strlen(json), jp = (jn + 3) / 4 * 4, bp = (n + 3) / 4 * 4;
  *len = 12 + 8 + jp + 8 + bp;
  unsigned char *g = calloc(*len, 1);
  uint32_t h[5] = {0x46546C67u, 2, (uint32_t)*len, (uint32_t)jp, 0x4E4F534Au};
  memcpy(g, h, 20);
  memset(g + 20, ' ', jp);
  memcpy(g + 20, json, jn);
  uint32_t c[2] = {(uint32_t)bp, 0x004E4942u};
  memcpy(g + 20 + jp, c, 8);
  memcpy(g + 28 + jp, bin, n);
  free(json);
  return g;
}

static ss_status read_text(const char *name, const char *text, ss_mesh *r, ss_error *e) {
  tl_write_file(tl_tmp(name), text, strlen(text));
  return ss_read_mesh(tl_tmp(name), r, e);
}

/* r has exactly these vertices and faces */
static int same(const ss_mesh *r, const double *V, int nv, const int *F, int nf) {
  if (r->nv != nv || r->nf != nf) return 0;
  for (int i = 0; i < 3 * nv; i++)
    if (r->V[i] != V[i]) return 0;
  for (int i = 0; i < 3 * nf; i++)
    if (r->F[i] != F[i]) return 0;
  return 1;
}

static int near(const ss_mesh *r, const double *V, int nv, double tol) {
  if (r->nv != nv) return 0;
  for (int i = 0; i < 3 * nv; i++)
    if (fabs(r->V[i] - V[i]) > tol) return 0;
  return 1;
}

/* a tetrahedron with outward faces: float positions (48 bytes), uint16 indices (24 bytes) */
static const float TP[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
static const uint16_t TI[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
static unsigned char TBIN[72];
/* everything after "buffers"; NODE is the node object */
#define TET_REST(NODE)                                                                                                 \
  "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[" NODE                                                          \
  "],"                                                                                                                 \
  "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"                                   \
  "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},{\"buffer\":0,\"byteOffset\":48,\"byteLength\":" \
  "24}],"                                                                                                              \
  "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"                            \
  "{\"bufferView\":1,\"componentType\":5123,\"count\":12,\"type\":\"SCALAR\"}]"

static void tet_expect(const double *T, double *V) { /* V = T applied to TP (T: x' = A x + t, row-major 3x4) */
  for (int i = 0; i < 4; i++)
    for (int r = 0; r < 3; r++)
      V[3 * i + r] = T[4 * r] * TP[3 * i] + T[4 * r + 1] * TP[3 * i + 1] + T[4 * r + 2] * TP[3 * i + 2] + T[4 * r + 3];
}

static void test_tetrahedron(void) {
  ss_error e;
  ss_mesh r = {0};
  char *t = gltf_text(TET_REST("{\"mesh\":0}"), TBIN, sizeof TBIN);
  ss_status st = read_text("tet.gltf", t, &r, &e);
  CHECK_MSG(st == SS_OK, "tet.gltf: %s", e.msg);
  double V[12];
  int F[12];
  for (int i = 0; i < 12; i++) V[i] = TP[i], F[i] = TI[i];
  CHECK_MSG(!st && same(&r, V, 4, F, 4), "tetrahedron: the file's vertices and faces");
  if (!st) tl_check_closed(&r, "tet.gltf");
  ss_mesh_free(&r);
  /* by content from memory, and through ss_read_gltf whatever the name */
  st = ss_read_mesh_memory(t, strlen(t), "<json>", &r, &e);
  CHECK_MSG(st == SS_OK && same(&r, V, 4, F, 4), "from memory: %s", st ? e.msg : "mesh differs");
  ss_mesh_free(&r);
  tl_write_file(tl_tmp("tet.json.txt"), t, strlen(t));
  st = ss_read_gltf(tl_tmp("tet.json.txt"), &r, &e);
  CHECK_MSG(st == SS_OK && same(&r, V, 4, F, 4), "ss_read_gltf: %s", st ? e.msg : "mesh differs");
  ss_mesh_free(&r);
  /* the GLB twin: from a file and from memory, equal to the .gltf */
  size_t gn;
  unsigned char *g = glb_bytes(TET_REST("{\"mesh\":0}"), TBIN, sizeof TBIN, &gn);
  tl_write_file(tl_tmp("tet.glb"), g, gn);
  st = ss_read_mesh(tl_tmp("tet.glb"), &r, &e);
  CHECK_MSG(st == SS_OK && same(&r, V, 4, F, 4), "tet.glb: %s", st ? e.msg : "mesh differs");
  ss_mesh_free(&r);
  st = ss_read_mesh_memory(g, gn, "<glb>", &r, &e);
  CHECK_MSG(st == SS_OK && same(&r, V, 4, F, 4), "glb from memory: %s", st ? e.msg : "mesh differs");
  ss_mesh_free(&r);
  st = ss_read_gltf(tl_tmp("tet.glb"), &r, &e);
  CHECK_MSG(st == SS_OK && same(&r, V, 4, F, 4), "ss_read_gltf glb: %s", st ? e.msg : "mesh differs");
  ss_mesh_free(&r);
  free(g), free(t);
}

static void check_tet_transform(const char *node, const double *T, const char *what) {
  ss_error e;
  ss_mesh r = {0};
  char *rest = fmt(TET_REST("%s"), node);
  char *t = gltf_text(rest, TBIN, sizeof TBIN);
  ss_status st = read_text("tr.gltf", t, &r, &e);
  double V[12];
  tet_expect(T, V);
  CHECK_MSG(st == SS_OK && near(&r, V, 4, 1e-12), "%s: %s", what, st ? e.msg : "vertices differ");
  static const int F[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  if (!st) CHECK_MSG(r.nf == 4 && !memcmp(r.F, F, sizeof F), "%s: faces", what);
  ss_mesh_free(&r);
  free(rest), free(t);
}

static void test_transforms(void) {
  /* translation */
  const double Tt[12] = {1, 0, 0, 10, 0, 1, 0, -2, 0, 0, 1, 0.5};
  check_tet_transform("{\"mesh\":0,\"translation\":[10,-2,0.5]}", Tt, "translation");
  /* matrix (column-major): scale 2 in x, 3 in y, 4 in z, then translate (1, 2, 3) */
  const double Tm[12] = {2, 0, 0, 1, 0, 3, 0, 2, 0, 0, 4, 3};
  check_tet_transform("{\"mesh\":0,\"matrix\":[2,0,0,0, 0,3,0,0, 0,0,4,0, 1,2,3,1]}", Tm, "matrix");
  /* TRS: 90 degrees about z (quaternion (0, 0, sin 45, cos 45), given unnormalised x2), scale 2, then
   * translation: (x, y, z) -> (1 - 2y, 2x, 2z) */
  const double Ttrs[12] = {0, -2, 0, 1, 2, 0, 0, 0, 0, 0, 2, 0};
  check_tet_transform(
      "{\"mesh\":0,\"translation\":[1,0,0],\"rotation\":[0,0,1.4142135623730951,1.4142135623730951],"
      "\"scale\":[2,2,2]}",
      Ttrs, "translation / rotation / scale");
  /* parent * child: the parent rotates 90 degrees about x ((x, y, z) -> (x, -z, y)), the child translates
   * by (0, 1, 0) first: (x, y, z) -> (x, -z, y + 1) */
  const double Tpc[12] = {1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 1};
  ss_error e;
  ss_mesh r = {0};
  char *rest =
      fmt(TET_REST("{\"children\":[1],\"rotation\":[0.7071067811865476,0,0,0.7071067811865476]},"
                   "{\"mesh\":0,\"translation\":[0,1,0]}"));
  char *t = gltf_text(rest, TBIN, sizeof TBIN);
  ss_status st = read_text("pc.gltf", t, &r, &e);
  double V[12];
  tet_expect(Tpc, V);
  CHECK_MSG(st == SS_OK && near(&r, V, 4, 1e-15), "parent and child: %s", st ? e.msg : "vertices differ");
  ss_mesh_free(&r);
  free(rest), free(t);
  /* a mesh instanced twice: once per instance, in node order (the second shifted by 5 in z) */
  rest = fmt(TET_REST("{\"mesh\":0},{\"mesh\":0,\"translation\":[0,0,5]}"));
  char *r2 = replace(rest, "\"nodes\":[0]", "\"nodes\":[0,1]");
  t = gltf_text(r2, TBIN, sizeof TBIN);
  st = read_text("twice.gltf", t, &r, &e);
  CHECK_MSG(st == SS_OK && r.nv == 8 && r.nf == 8, "instanced twice: %s", st ? e.msg : "counts");
  if (!st && r.nv == 8) {
    int ok = 1;
    for (int i = 0; i < 4; i++)
      for (int d = 0; d < 3; d++)
        ok &= r.V[3 * i + d] == TP[3 * i + d] && r.V[12 + 3 * i + d] == TP[3 * i + d] + (d == 2 ? 5 : 0);
    for (int k = 0; k < 12; k++) ok &= r.F[k] == TI[k] && r.F[12 + k] == TI[k] + 4;
    CHECK_MSG(ok, "instanced twice: the second copy after the first, shifted");
  }
  ss_mesh_free(&r);
  free(rest), free(r2), free(t);
}

/* the cube of test_read_stl, with 8-, 16- and 32-bit indices, and interleaved with normals (stride 24) */
static const double CV[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
static const int CF[] = {0, 3, 2, 0, 2, 1, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                         1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};

static void test_cube(void) {
  static const int ctypes[3] = {5121, 5123, 5125}, sizes[3] = {1, 2, 4};
  for (int k = 0; k < 3; k++) {
    unsigned char bin[96 + 144];
    float P[24];
    for (int i = 0; i < 24; i++) P[i] = (float)CV[i];
    memcpy(bin, P, 96);
    for (int i = 0; i < 36; i++) {
      uint32_t v = (uint32_t)CF[i];
      memcpy(bin + 96 + sizes[k] * i, &v, (size_t)sizes[k]); /* little-endian host */
    }
    char *rest =
        fmt("\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],"
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":4}]}],"
            "\"bufferViews\":[{\"buffer\":0,\"byteLength\":96},{\"buffer\":0,\"byteOffset\":96,\"byteLength\":%d}],"
            "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":8,\"type\":\"VEC3\"},"
            "{\"bufferView\":1,\"componentType\":%d,\"count\":36,\"type\":\"SCALAR\"}]",
            36 * sizes[k], ctypes[k]);
    char *t = gltf_text(rest, bin, 96 + 36 * (size_t)sizes[k]);
    ss_mesh r = {0};
    ss_error e;
    ss_status st = read_text("cube.gltf", t, &r, &e);
    CHECK_MSG(st == SS_OK && same(&r, CV, 8, CF, 12), "cube, %d-bit indices: %s", 8 * sizes[k], st ? e.msg : "differs");
    if (!st) tl_check_closed(&r, "cube.gltf");
    ss_mesh_free(&r);
    free(rest), free(t);
  }
  /* interleaved: position then normal, 24 bytes a vertex; the positions accessor at offset 0, the
   * normals' at 12 (not read); the indices in a second view */
  unsigned char bin[8 * 24 + 72];
  for (int i = 0; i < 8; i++) {
    float pn[6] = {(float)CV[3 * i], (float)CV[3 * i + 1], (float)CV[3 * i + 2], 9, 9, 9};
    memcpy(bin + 24 * i, pn, 24);
  }
  for (int i = 0; i < 36; i++) {
    uint16_t v = (uint16_t)CF[i];
    memcpy(bin + 192 + 2 * i, &v, 2);
  }
  const char *rest =
      "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],"
      "\"meshes\":[{\"primitives\":[{\"attributes\":{\"NORMAL\":1,\"POSITION\":0},\"indices\":2}]}],"
      "\"bufferViews\":[{\"buffer\":0,\"byteLength\":192,\"byteStride\":24},"
      "{\"buffer\":0,\"byteOffset\":192,\"byteLength\":72}],"
      "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":8,\"type\":\"VEC3\"},"
      "{\"bufferView\":0,\"byteOffset\":12,\"componentType\":5126,\"count\":8,\"type\":\"VEC3\"},"
      "{\"bufferView\":1,\"componentType\":5123,\"count\":36,\"type\":\"SCALAR\"}]";
  char *t = gltf_text(rest, bin, sizeof bin);
  ss_mesh r = {0};
  ss_error e;
  ss_status st = read_text("inter.gltf", t, &r, &e);
  CHECK_MSG(st == SS_OK && same(&r, CV, 8, CF, 12), "interleaved (byteStride 24): %s", st ? e.msg : "differs");
  ss_mesh_free(&r);
  /* the stride's last element ends exactly at the view's end: one byte less is refused */
  char *bad = replace(t, "\"byteLength\":192,\"byteStride\":24", "\"byteLength\":180,\"byteStride\":24");
  st = read_text("inter2.gltf", bad, &r, &e);
  CHECK_MSG(st == SS_OK, "180 bytes hold 8 vertices of stride 24: %s", e.msg);
  ss_mesh_free(&r);
  free(bad);
  bad = replace(t, "\"byteLength\":192,\"byteStride\":24", "\"byteLength\":179,\"byteStride\":24");
  st = read_text("inter3.gltf", bad, &r, &e);
  CHECK_MSG(st == SS_ERR_PARSE && strstr(e.msg,
                                         "inter3.gltf: accessors[0]: count 8 with stride 24 needs 180 bytes; "
                                         "bufferViews[0] has 179"),
            "%s", e.msg);
  free(bad), free(t);
}

/* a unit square as a strip and as a fan, and points / lines primitives dropped beside them */
static void test_strip_fan(void) {
  /* strip order: (0,0) (1,0) (0,1) (1,1); fan order: (0,0) (1,0) (1,1) (0,1) */
  float P[24] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, /* */ 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const char *modes[2] = {"5", "6"};
  for (int k = 0; k < 2; k++) {
    char *rest =
        fmt("\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"mode\":%s},"
            "{\"attributes\":{\"POSITION\":0},\"mode\":1},{\"attributes\":{\"POSITION\":0},\"mode\":0}]}],"
            "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":%d,\"byteLength\":48}],"
            "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"}]",
            modes[k], 48 * k);
    char *t = gltf_text(rest, P, sizeof P); /* no scenes: every mesh once, untransformed */
    ss_mesh r = {0};
    ss_error e;
    ss_status st = read_text("sf.gltf", t, &r, &e);
    /* strip: (0 1 2), then (1 3 2) (every other triangle reversed); fan: (1 2 0), (2 3 0) */
    static const int FS[6] = {0, 1, 2, 1, 3, 2}, FF[6] = {1, 2, 0, 2, 3, 0};
    CHECK_MSG(st == SS_OK && r.nf == 2 && !memcmp(r.F, k ? FF : FS, sizeof FS), "%s: %s", k ? "fan" : "strip",
              st ? e.msg : "faces");
    for (int f = 0; !st && f < r.nf; f++) { /* all counter-clockwise seen from +z */
      const double *a = r.V + 3 * r.F[3 * f], *b = r.V + 3 * r.F[3 * f + 1], *c = r.V + 3 * r.F[3 * f + 2];
      CHECK((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0);
    }
    ss_mesh_free(&r);
    /* only the points and lines: nothing to read */
    char *pl = replace(rest, modes[k] == modes[0] ? "\"mode\":5}" : "\"mode\":6}", "\"mode\":3}");
    char *t2 = gltf_text(pl, P, sizeof P);
    st = read_text("lines.gltf", t2, &r, &e);
    CHECK_MSG(st == SS_ERR_PARSE && strstr(e.msg,
                                           "lines.gltf: no triangles in the scene (1 meshes, 3 primitives of points "
                                           "or lines dropped)"),
              "%s", e.msg);
    free(rest), free(t), free(pl), free(t2);
  }
  /* a strip with a restart (a repeated index): the degenerate triangles are dropped */
  const uint8_t I[8] = {0, 1, 2, 3, 3, 0, 0, 1};
  unsigned char bin[56];
  memcpy(bin, P, 48), memcpy(bin + 48, I, 8);
  const char *rest =
      "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":5}]}],"
      "\"bufferViews\":[{\"buffer\":0,\"byteLength\":48},{\"buffer\":0,\"byteOffset\":48,\"byteLength\":8}],"
      "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
      "{\"bufferView\":1,\"componentType\":5121,\"count\":8,\"type\":\"SCALAR\"}]";
  char *t = gltf_text(rest, bin, sizeof bin);
  ss_mesh r = {0};
  ss_error e;
  ss_status st = read_text("restart.gltf", t, &r, &e);
  /* triangles (0 1 2) (1 3 2) (2 3 3)x (3 3 0)x (3 0 0)x (0 0 1)x */
  static const int FR[6] = {0, 1, 2, 1, 3, 2};
  CHECK_MSG(st == SS_OK && r.nf == 2 && !memcmp(r.F, FR, sizeof FR), "strip with a restart: %s", st ? e.msg : "faces");
  ss_mesh_free(&r);
  free(t);
}

/* positions as int16, normalized (KHR_mesh_quantization), scaled back by the node */
static void test_quantized(void) {
  const uint16_t I[3] = {0, 1, 2};
  unsigned char bin[32];
  memcpy(bin + 24, I, 6), memset(bin + 30, 0, 2);
  const char *rest =
      "\"extensionsUsed\":[\"KHR_mesh_quantization\"],\"extensionsRequired\":[\"KHR_mesh_quantization\"],"
      "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"scale\":[2,2,2]}],"
      "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
      "\"bufferViews\":[{\"buffer\":0,\"byteLength\":24,\"byteStride\":8},"
      "{\"buffer\":0,\"byteOffset\":24,\"byteLength\":6}],"
      "\"accessors\":[{\"bufferView\":0,\"componentType\":5122,\"normalized\":true,\"count\":3,"
      "\"type\":\"VEC3\"},{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}]";
  /* stride 8 (6 bytes of data, 2 of padding): elements 0, 1, 2 start at bytes 0, 8, 16 */
  int16_t S[12] = {0, 0, 0, 0, 32767, 0, 0, 0, 0, 16384, 0, 0};
  memcpy(bin, S, 24);
  char *t = gltf_text(rest, bin, sizeof bin);
  ss_mesh r = {0};
  ss_error e;
  ss_status st = read_text("quant.gltf", t, &r, &e);
  const double V[9] = {0, 0, 0, 2, 0, 0, 0, 2 * (16384 / 32767.0), 0};
  CHECK_MSG(st == SS_OK && near(&r, V, 3, 1e-15), "int16 normalized positions: %s", st ? e.msg : "differ");
  ss_mesh_free(&r);
  free(t);
  /* -32768 clamps to -1 (max(c / 32767, -1)); int8 not normalized reads the integers */
  int16_t S2[12] = {-32768, -32767, 0, 0, 32767, 0, 0, 0, 0, 16384, 0, 0};
  memcpy(bin, S2, 24);
  t = gltf_text(rest, bin, sizeof bin);
  st = read_text("quant2.gltf", t, &r, &e);
  CHECK_MSG(st == SS_OK && r.nv == 3 && r.V[0] == -2 && r.V[1] == -2, "int16 -32768 clamped: %s",
            st ? e.msg : "values");
  ss_mesh_free(&r);
  /* without the extension declared: refused */
  char *nq = replace(
      rest, "\"extensionsUsed\":[\"KHR_mesh_quantization\"],\"extensionsRequired\":[\"KHR_mesh_quantization\"],", "");
  char *t2 = gltf_text(nq, bin, sizeof bin);
  st = read_text("noquant.gltf", t2, &r, &e);
  CHECK_MSG(st == SS_ERR_PARSE && strstr(e.msg, "noquant.gltf: accessors[0]") &&
                strstr(e.msg, "componentType 5122: positions are float (5126), or integers with KHR_mesh_quantization"),
            "%s", e.msg);
  free(t), free(nq), free(t2);
}

/* an external buffer beside the .gltf: read by path (percent-decoded name), refused from memory */
static void test_external(void) {
  tl_write_file(tl_tmp("tet data.bin"), TBIN, sizeof TBIN);
  char *t = fmt("{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":72,\"uri\":\"tet%%20data.bin\"}],%s}",
                TET_REST("{\"mesh\":0}"));
  ss_mesh r = {0};
  ss_error e;
  ss_status st = read_text("ext.gltf", t, &r, &e);
  CHECK_MSG(st == SS_OK && r.nv == 4 && r.nf == 4, "external buffer: %s", st ? e.msg : "counts");
  ss_mesh_free(&r);
  st = ss_read_gltf(tl_tmp("ext.gltf"), &r, &e);
  CHECK_MSG(st == SS_OK && r.nv == 4, "external buffer, ss_read_gltf: %s", st ? e.msg : "counts");
  ss_mesh_free(&r);
  st = ss_read_mesh_memory(t, strlen(t), "<stdin>", &r, &e);
  CHECK_MSG(st == SS_ERR_UNSUPPORTED &&
                strstr(e.msg,
                       "<stdin>: buffers[0]: the external file 'tet%20data.bin' cannot be "
                       "read from memory") &&
                !r.V,
            "%s", e.msg);
  /* missing file */
  char *t2 = replace(t, "tet%20data.bin", "nothere.bin");
  st = read_text("ext2.gltf", t2, &r, &e);
  CHECK_MSG(st == SS_ERR_IO && strstr(e.msg, "ext2.gltf: buffers[0]: ") && strstr(e.msg, "nothere.bin: cannot open"),
            "%s", e.msg);
  free(t), free(t2);
}

/* JSON: escapes in keys and strings (a surrogate pair), a BOM, other members ignored, last duplicate wins */
static void test_json(void) {
  char *rest = fmt(
      "\"extras\":{\"s\":\"\\ud83d\\ude00 \\\" \\\\ \\/ \\b\\f\\n\\r\\t \\u00e9 é\",\"n\":[-0.5e-3,1E+2,0,true,false,"
      "null,{}]},\"scenes\":[{\"nodes\":[0]}],\"n\\u006Fdes\":[{\"mesh\":7}],\"nodes\" : [ {\"mesh\" : 0} ] ,%s",
      TET_REST("{\"mesh\":0}") + strlen("\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"));
  char *t0 = gltf_text(rest, TBIN, sizeof TBIN);
  char *t = replace(t0, "{\"asset\"", "\xEF\xBB\xBF{\"\\u0061sset\"");
  ss_mesh r = {0};
  ss_error e;
  ss_status st = read_text("json.gltf", t, &r, &e);
  CHECK_MSG(st == SS_OK && r.nv == 4 && r.nf == 4, "escapes, BOM, duplicate keys: %s", st ? e.msg : "counts");
  ss_mesh_free(&r);
  free(rest), free(t0), free(t);
}

typedef struct bad_case {
  const char *what, *from, *to, *want; /* the valid tetrahedron with `from` replaced by `to` */
} bad_case;

static void test_errors(void) {
  char *good = gltf_text(TET_REST("{\"mesh\":0}"), TBIN, sizeof TBIN);
  /* a NaN position, and a base64 text of garbage */
  unsigned char nanbin[72];
  memcpy(nanbin, TBIN, 72);
  const float nanf = NAN;
  memcpy(nanbin + 16, &nanf, 4);
  char *nanb = tl_base64(nanbin, 72), *goodb = tl_base64(TBIN, 72);
  const bad_case cases[] = {
      {"bad escape", "\"version\":\"2.0\"", "\"version\":\"2.0\\q\"", "bad.gltf:1:25: invalid escape in a string"},
      {"accessor out of range", "\"count\":4,", "\"count\":5,",
       "bad.gltf: accessors[0]: count 5 with stride 12 needs 60 bytes; bufferViews[0] has 48"},
      {"count overflow", "\"count\":4,", "\"count\":4294967295,",
       "bad.gltf: accessors[0]: count 4294967295 with stride 12 needs 51539607540 bytes; bufferViews[0] has 48"},
      {"count too large", "\"count\":4,", "\"count\":1e300,",
       "bad.gltf: accessors[0].count: 1.0000000000000001e+300 is out "
       "of range (1 to 9007199254740992)"},
      {"wrong componentType", "\"componentType\":5123", "\"componentType\":5124",
       "bad.gltf: accessors[1].componentType 5124 is not a glTF component type"},
      {"signed indices", "\"componentType\":5123", "\"componentType\":5122",
       "bad.gltf: accessors[1] (meshes[0].primitives[0] indices) has componentType 5122: indices are unsigned"},
      {"missing asset", "\"asset\"", "\"assex\"", "bad.gltf: no 'asset' object: not a glTF 2.0 file"},
      {"version 1.0", "\"2.0\"", "\"1.0\"", "bad.gltf: glTF version '1.0': only glTF 2.0 is read"},
      {"draco", "\"scene\":0", "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],\"scene\":0",
       "bad.gltf: the file requires the extension KHR_draco_mesh_compression"},
      {"meshopt", "\"scene\":0",
       "\"extensionsRequired\":[\"KHR_mesh_quantization\",\"EXT_meshopt_compression\"],\"scene\":0",
       "requires the extension EXT_meshopt_compression"},
      {"base64 garbage", goodb + 8, "A*AA", "bad.gltf: buffers[0].uri: invalid base64 character at position 9"},
      {"base64 length", goodb + 8, "A", "bad.gltf: buffers[0].uri: base64 data of 9 characters (not a multiple of 4)"},
      {"base64 short", goodb + 8, "", "bad.gltf: buffers[0].byteLength 72, but its data has 6 bytes"},
      {"node cycle", "{\"mesh\":0}", "{\"mesh\":0,\"children\":[0]}", "bad.gltf: nodes[0] is its own ancestor"},
      {"http", "\"uri\":\"data:application/octet-stream;base64,", "\"uri\":\"http://example.com/x.bin#",
       "bad.gltf: buffers[0].uri 'http://example.com/x.bin#"},
      {"data URI type", "data:application/octet-stream;base64", "data:image/png;base64",
       "bad.gltf: buffers[0].uri 'data:image/png;base64': a data URI must be"},
      {"sparse", "\"count\":4,", "\"count\":4,\"sparse\":{\"count\":1},",
       "bad.gltf: accessors[0] (meshes[0].primitives[0] POSITION) is sparse: sparse accessors are not supported"},
      {"view past the buffer", "\"byteOffset\":48,\"byteLength\":24", "\"byteOffset\":49,\"byteLength\":24",
       "bad.gltf: bufferViews[1]: byteOffset 49 + byteLength 24 is past the end of buffers[0] (72 bytes)"},
      {"byteLength past the data", "\"byteLength\":72", "\"byteLength\":73",
       "bad.gltf: buffers[0].byteLength 73, but its data has 72 bytes"},
      {"mesh reference", "{\"mesh\":0}", "{\"mesh\":3}", "bad.gltf: nodes[0].mesh: 3, but 'meshes' has 1 entries"},
      {"reached twice", "\"nodes\":[0]}", "\"nodes\":[0,0]}", "bad.gltf: nodes[0] is reached twice"},
      {"not triangles", "\"count\":12,", "\"count\":11,",
       "bad.gltf: meshes[0].primitives[0]: 11 indices do not make "
       "triangles"},
      {"stride", "\"byteLength\":48}", "\"byteLength\":48,\"byteStride\":6}",
       "bad.gltf: bufferViews[0].byteStride 6 is not "
       "a multiple of 4"},
      {"stride small", "\"byteLength\":48}", "\"byteLength\":48,\"byteStride\":8}",
       "bad.gltf: bufferViews[0].byteStride 8 "
       "is smaller than the 12-byte elements"},
      {"no bufferView", "\"bufferView\":0,", "",
       "bad.gltf: accessors[0] (meshes[0].primitives[0] POSITION) has no "
       "bufferView (all zeros): not supported"},
      {"scalar positions", "\"VEC3\"", "\"SCALAR\"", "has type 'SCALAR', VEC3 expected"},
      {"text after", "\"SCALAR\"}]}", "\"SCALAR\"}]} x", "text after the JSON value"},
      {"lone surrogate", "\"2.0\"}", "\"2.0\",\"generator\":\"\\ud800x\"}", "high surrogate in a \\u escape without"},
      {"bad number", "\"count\":4,", "\"count\":04,", "',' or '}' expected in an object"},
      {"scene index", "\"scene\":0", "\"scene\":1", "bad.gltf: (top level).scene: 1, but 'scenes' has 1 entries"},
      {"matrix and TRS", "{\"mesh\":0}", "{\"mesh\":0,\"scale\":[1,1,1],\"matrix\":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1]}",
       "bad.gltf: nodes[0] has both a matrix and translation / rotation / scale"},
      {"zero quaternion", "{\"mesh\":0}", "{\"mesh\":0,\"rotation\":[0,0,0,0]}", "nodes[0].rotation is not a rotation"},
      {"NaN position", goodb, nanb,
       "bad.gltf: accessors[0] (meshes[0].primitives[0] POSITION): vertex 1 is not finite"},
      {"number overflow", "\"byteOffset\":0,", "\"byteOffset\":1e400,", "number out of range"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
    const bad_case *c = cases + k;
    char *t = replace(good, c->from, c->to);
    ss_mesh r = {0};
    ss_error e = {{0}};
    ss_status st = read_text("bad.gltf", t, &r, &e);
    CHECK_MSG(st != SS_OK && strstr(e.msg, "bad.gltf") && strstr(e.msg, c->want) && !r.V && r.nv == 0,
              "%s: %s (want '%s')", c->what, st ? e.msg : "read", c->want);
    ss_mesh_free(&r);
    free(t);
  }
  free(nanb), free(goodb);
  /* every prefix of the valid text (step 5) is refused, naming the file */
  for (size_t cut = 0; cut < strlen(good); cut += 5) {
    tl_write_file(tl_tmp("cut.gltf"), good, cut);
    ss_mesh r = {0};
    ss_error e = {{0}};
    ss_status st = ss_read_mesh(tl_tmp("cut.gltf"), &r, &e);
    CHECK_MSG(st == SS_ERR_PARSE && strstr(e.msg, "cut.gltf:") && !r.V, "cut at %zu: %s", cut, st ? e.msg : "read");
    ss_mesh_free(&r);
  }
  /* an index out of range: 7 in place of the last index */
  unsigned char bin[72];
  memcpy(bin, TBIN, 72);
  bin[70] = 7;
  char *t = gltf_text(TET_REST("{\"mesh\":0}"), bin, sizeof bin);
  ss_mesh r = {0};
  ss_error e;
  CHECK_MSG(read_text("idx.gltf", t, &r, &e) == SS_ERR_PARSE &&
                strstr(e.msg,
                       "idx.gltf: meshes[0].primitives[0]: index 7 (indices element 11) is out of range: POSITION "
                       "has 4 vertices") &&
                !r.V,
            "%s", e.msg);
  free(t);
  /* JSON nested too deep, and a root that is not an object */
  char deep[400];
  int n = 0;
  n += snprintf(deep + n, sizeof deep - (size_t)n, "{\"asset\":");
  for (int i = 0; i < 100; i++) deep[n++] = '[';
  for (int i = 0; i < 100; i++) deep[n++] = ']';
  deep[n++] = '}', deep[n] = '\0';
  CHECK_MSG(read_text("deep.gltf", deep, &r, &e) == SS_ERR_PARSE && strstr(e.msg, "deep.gltf:1:") &&
                strstr(e.msg, ": nested deeper than 64"),
            "%s", e.msg);
  CHECK_MSG(read_text("arr.gltf", "[1, 2]", &r, &e) == SS_ERR_PARSE && strstr(e.msg,
                                                                              "arr.gltf: the JSON text is not an "
                                                                              "object"),
            "%s", e.msg);
  CHECK_MSG(
      read_text("nl.gltf", "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"nodes\": [1,]\n}", &r, &e) == SS_ERR_PARSE &&
          strstr(e.msg, "nl.gltf:3:15: unexpected character"),
      "%s", e.msg);
  CHECK_MSG(read_text("empty.gltf", "", &r, &e) == SS_ERR_PARSE && strstr(e.msg, "empty.gltf"), "%s", e.msg);
  CHECK_MSG(read_text("nomesh.gltf", "{\"asset\":{\"version\":\"2.0\"}}", &r, &e) == SS_ERR_PARSE &&
                strstr(e.msg, "nomesh.gltf: no triangles in the scene (0 meshes"),
            "%s", e.msg);
  CHECK_MSG(read_text("ctl.gltf", "{\"asset\":{\"version\":\"2.\n0\"}}", &r, &e) == SS_ERR_PARSE &&
                strstr(e.msg, "ctl.gltf:1:") && strstr(e.msg, ": control character in a string"),
            "%s", e.msg);
  CHECK_MSG(read_text("utf.gltf", "{\"asset\":{\"version\":\"2.0\xC0\xAF\"}}", &r, &e) == SS_ERR_PARSE &&
                strstr(e.msg, "utf.gltf:1:") && strstr(e.msg, ": invalid UTF-8"),
            "%s", e.msg);
  free(good);
}

static void test_glb_errors(void) {
  size_t gn;
  unsigned char *g = glb_bytes(TET_REST("{\"mesh\":0}"), TBIN, sizeof TBIN, &gn);
  unsigned char *b = malloc(gn + 8);
  ss_mesh r = {0};
  ss_error e;
  uint32_t v;
  const char *p = tl_tmp("bad.glb");
  /* total length that is not the data's */
  memcpy(b, g, gn);
  v = (uint32_t)gn + 4;
  memcpy(b + 8, &v, 4);
  tl_write_file(p, b, gn);
  CHECK_MSG(ss_read_mesh(p, &r, &e) == SS_ERR_PARSE && strstr(e.msg, "bad.glb: the GLB header declares") &&
                strstr(e.msg, "bytes; the data has"),
            "%s", e.msg);
  /* the BIN chunk's length past the end */
  memcpy(b, g, gn);
  size_t jp;
  memcpy(&v, g + 12, 4);
  jp = v;
  v = 80;
  memcpy(b + 20 + jp, &v, 4);
  tl_write_file(p, b, gn);
  CHECK_MSG(ss_read_mesh(p, &r, &e) == SS_ERR_PARSE && strstr(e.msg, "bad.glb: byte") &&
                strstr(e.msg, "GLB chunk 1 declares 80 bytes; 72 remain"),
            "%s", e.msg);
  /* truncated: the file cut short (its declared length then differs too) */
  tl_write_file(p, g, gn - 10);
  CHECK_MSG(ss_read_mesh(p, &r, &e) == SS_ERR_PARSE && strstr(e.msg, "bad.glb: the GLB header declares"), "%s", e.msg);
  /* version 1 */
  memcpy(b, g, gn);
  v = 1;
  memcpy(b + 4, &v, 4);
  tl_write_file(p, b, gn);
  CHECK_MSG(ss_read_mesh(p, &r, &e) == SS_ERR_UNSUPPORTED && strstr(e.msg, "bad.glb: GLB version 1: only glTF 2.0"),
            "%s", e.msg);
  /* the JSON chunk's length not a multiple of 4 */
  memcpy(b, g, gn);
  v = (uint32_t)jp - 1;
  memcpy(b + 12, &v, 4);
  tl_write_file(p, b, gn);
  CHECK_MSG(ss_read_mesh(p, &r, &e) == SS_ERR_PARSE && strstr(e.msg, "bad.glb: byte 12: GLB chunk 0: length"), "%s",
            e.msg);
  /* a JSON error inside the chunk */
  memcpy(b, g, gn);
  b[20 + 1] = 'x';
  tl_write_file(p, b, gn);
  CHECK_MSG(ss_read_mesh(p, &r, &e) == SS_ERR_PARSE && strstr(e.msg, "bad.glb: JSON chunk, line 1, column 2:"), "%s",
            e.msg);
  /* without a BIN chunk */
  memcpy(b, g, 20 + jp);
  v = (uint32_t)(20 + jp);
  memcpy(b + 8, &v, 4);
  tl_write_file(p, b, 20 + jp);
  CHECK_MSG(ss_read_mesh(p, &r, &e) == SS_ERR_PARSE && strstr(e.msg,
                                                              "bad.glb: buffers[0] refers to the GLB's BIN chunk, "
                                                              "which is missing"),
            "%s", e.msg);
  /* a header only, and fewer bytes than a header (from memory: by the magic) */
  CHECK_MSG(ss_read_mesh_memory("glTF\2\0\0\0\14\0\0\0", 12, "<h>", &r, &e) == SS_ERR_PARSE &&
                strstr(e.msg, "<h>: a GLB without chunks"),
            "%s", e.msg);
  CHECK_MSG(
      ss_read_mesh_memory("glTF\2\0", 6, "<h>", &r, &e) == SS_ERR_PARSE && strstr(e.msg, "<h>: 6 bytes, shorter than"),
      "%s", e.msg);
  CHECK(!r.V && r.nv == 0);
  free(g), free(b);
}

static void test_api(void) {
  ss_mesh r = {0};
  ss_error e;
  CHECK(ss_read_gltf(NULL, &r, &e) == SS_ERR_INVALID && !r.V);
  CHECK(ss_read_gltf(tl_tmp("x.gltf"), NULL, &e) == SS_ERR_INVALID);
  CHECK(ss_read_gltf(tl_tmp("missing.gltf"), &r, &e) == SS_ERR_IO && strstr(e.msg, "missing.gltf") && !r.V);
  CHECK(io_parse_gltf(NULL, NULL, NULL, 5, &r, &e) == SS_ERR_INVALID && strstr(e.msg, "<memory>: NULL buffer"));
  CHECK(io_parse_gltf(NULL, "n", "{}", 2, NULL, &e) == SS_ERR_INVALID);
  CHECK(ss_mesh_extension_supported("m.gltf") == 1 && ss_mesh_extension_supported("a/m.GLB") == 1 &&
        ss_mesh_extension_supported("gltf") == 0 && ss_mesh_extension_supported("m.gltf/x") == 0);
  CHECK(io_gltf_sniff("glTF", 4) && io_gltf_sniff(" \n{ \"asset\": {}}", 16) && !io_gltf_sniff("{\"assets\":1}", 12) &&
        !io_gltf_sniff("solid x", 7) && !io_gltf_sniff(NULL, 0));
  CHECK(!ssi_mesh_assimp_ext("m.gltf", NULL, 0) && !ssi_mesh_assimp_ext("m.glb", NULL, 0));
}

/* The tetrahedron placed by n nodes (node i translated by 2i along x when `apart`): the scene places
 * 4n vertices from 4 stored */
static char *crowd_text(int n, int apart) {
  size_t cap = (size_t)n * 48 + 512, len = 0;
  char *nodes = malloc(cap), *list = malloc((size_t)n * 12 + 16);
  size_t ll = 0;
  for (int i = 0; i < n; i++) {
    len += (size_t)snprintf(nodes + len, cap - len, apart ? "%s{\"mesh\":0,\"translation\":[%d,0,0]}" : "%s{\"mesh\":0}",
                            i ? "," : "", 2 * i);
    ll += (size_t)snprintf(list + ll, (size_t)n * 12 + 16 - ll, "%s%d", i ? "," : "", i);
  }
  char *rest = fmt("\"scene\":0,\"scenes\":[{\"nodes\":[%s]}],\"nodes\":[%s],"
                   "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
                   "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},{\"buffer\":0,"
                   "\"byteOffset\":48,\"byteLength\":24}],"
                   "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
                   "{\"bufferView\":1,\"componentType\":5123,\"count\":12,\"type\":\"SCALAR\"}]",
                   list, nodes);
  char *t = gltf_text(rest, TBIN, sizeof TBIN);
  free(nodes), free(list), free(rest);
  return t;
}

/* Instancing in proportion: 1,000 copies of a tetrahedron are read; 262,145 copies (1,048,580 vertices
 * from 4 stored, past the 2^20 floor and 64 copies) are refused, before the vertices are made */
static void test_crowd(void) {
  ss_error e = {{0}};
  ss_mesh r = {0};
  char *t = crowd_text(1000, 1);
  CHECK_MSG(ss_read_mesh_memory(t, strlen(t), "crowd.gltf", &r, &e) == SS_OK && r.nv == 4000 && r.nf == 4000,
            "1000 copies: %s (nv %d)", e.msg, r.nv);
  ss_mesh_free(&r);
  free(t);
  t = crowd_text(262145, 0);
  ss_status st = ss_read_mesh_memory(t, strlen(t), "crowd.gltf", &r, &e);
  CHECK_MSG(st == SS_ERR_PARSE && strstr(e.msg, "crowd.gltf") && strstr(e.msg, "more than 64 times") &&
                strstr(e.msg, "1048580 vertices"),
            "262145 copies: status %d, '%s'", (int)st, e.msg);
  CHECK(r.nv == 0 && r.V == NULL);
  free(t);
}

int main(void) {
  if (!tl_tmpdir_make("/tmp/ss_test_gltf_XXXXXX")) {
    perror("mkdtemp");
    return 2;
  }
  memcpy(TBIN, TP, 48), memcpy(TBIN + 48, TI, 24);
  test_tetrahedron();
  test_transforms();
  test_cube();
  test_strip_fan();
  test_quantized();
  test_external();
  test_json();
  test_errors();
  test_glb_errors();
  test_api();
  test_crowd();
  tl_tmpdir_remove();
  TEST_MAIN_END();
}
