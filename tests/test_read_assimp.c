/* Formats read through assimp: a minimal glTF 2.0 with an embedded base64 buffer (a tetrahedron under a
 * node translation) and its .glb twin, from files and from memory (format by content), and clean
 * errors. A build without assimp must refuse glTF naming libassimp-dev; the other checks then SKIP.
 * (STL is read by our own reader: test_read_stl.c.) */
#include <stdint.h>
#include <unistd.h>

#include "mesh/io_internal.h"
#include "specseg/io.h"
#include "specseg/mesh.h"
#include "testlib.h"

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
  tl_write_file(tl_tmp("tet.gltf"), json, (size_t)n);
  ss_error e;
  ss_mesh r = {0};
  ss_status st = ss_read_mesh(tl_tmp("tet.gltf"), &r, &e);
  CHECK_MSG(st == SS_OK, "tet.gltf: %s", e.msg);
  if (!st) {
    CHECK_MSG(r.nv == 4 && r.nf == 4, "%d v %d f", r.nv, r.nf);
    int same = r.nv == 4;
    for (int i = 0; same && i < 12; i++) same = r.V[i] == P[i] + (i % 3 == 0 ? 10 : 0) && r.F[i] == I[i];
    CHECK_MSG(same, "the node's translation applied, vertices and faces in the file's order");
    tl_check_closed(&r, "tet.gltf");
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
  tl_write_file(tl_tmp("tet.glb"), glb, o);
  st = ss_read_mesh(tl_tmp("tet.glb"), &r, &e);
  CHECK_MSG(st == SS_OK && r.nv == 4 && r.nf == 4, "tet.glb: %s", st ? e.msg : "counts");
  if (!st) CHECK(r.V[0] == 10 && r.V[11] == 1);
  ss_mesh_free(&r);
  st = ss_read_mesh_memory(glb, o, "<glb>", &r, &e);
  CHECK_MSG(st == SS_OK && r.nv == 4, "glb from memory: %s", st ? e.msg : "counts");
  ss_mesh_free(&r);
  /* a scene without meshes */
  tl_write_file(tl_tmp("empty.gltf"), "{\"asset\":{\"version\":\"2.0\"}}", 27);
  CHECK(ss_read_mesh(tl_tmp("empty.gltf"), &r, &e) != SS_OK && strstr(e.msg, "empty.gltf") && !r.V);
}

int main(void) {
  if (!tl_tmpdir_make("/tmp/ss_test_assimp_XXXXXX")) { perror("mkdtemp"); return 2; }
  /* which build is this? */
  ss_mesh r = {0};
  ss_error e;
  tl_write_file(tl_tmp("probe.gltf"), "{\"asset\":{\"version\":\"2.0\"}}", 27);
  ss_status st = ss_read_mesh(tl_tmp("probe.gltf"), &r, &e);
  ss_mesh_free(&r);
  CHECK(ss_mesh_extension_supported("a/b.OFF") == 1 && ss_mesh_extension_supported("x.ply") == 1 &&
        ss_mesh_extension_supported("x.obj") == 1 && ss_mesh_extension_supported("x.stl") == 1 &&
        ss_mesh_extension_supported("x.txt") == 0 && ss_mesh_extension_supported("gltf") == 0);
  CHECK(ss_mesh_extension_supported("m.gltf") == (st == SS_ERR_UNSUPPORTED ? 0 : 2));
  CHECK(ss_mesh_extension_supported("m.GLB") == (st == SS_ERR_UNSUPPORTED ? 0 : 2));
  if (st == SS_ERR_UNSUPPORTED) {
    CHECK_MSG(strstr(e.msg, "libassimp-dev") && strstr(e.msg, "GLTF") && strstr(e.msg, "probe.gltf"), "%s", e.msg);
    SKIP("this build has no assimp: glTF reading not checked (%s)", e.msg);
  } else {
    test_gltf();
  }
  tl_tmpdir_remove();
  TEST_MAIN_END();
}
