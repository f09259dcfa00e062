/* Formats read through assimp, by extension only: a tetrahedron as a minimal COLLADA (.dae) file under a
 * node translation reads back welded and closed; a malformed one fails naming the file. A build without
 * assimp must refuse it naming libassimp-dev (the other checks then SKIP). glTF and GLB never go to
 * assimp (our reader, test_read_gltf.c), nor does anything read from memory. */
#include <stdint.h>
#include <unistd.h>

#include "mesh/io_internal.h"
#include "specseg/io.h"
#include "specseg/mesh.h"
#include "testlib.h"

/* positions (0 0 0) (1 0 0) (0 1 0) (0 0 1), outward faces, the node translated by (10, 0, 0) */
static const char DAE[] =
    "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
    "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
    " <asset><unit name=\"meter\" meter=\"1\"/><up_axis>Z_UP</up_axis></asset>\n"
    " <library_geometries><geometry id=\"tet\"><mesh>\n"
    "  <source id=\"p\"><float_array id=\"pa\" count=\"12\">0 0 0 1 0 0 0 1 0 0 0 1</float_array>\n"
    "   <technique_common><accessor source=\"#pa\" count=\"4\" stride=\"3\"><param name=\"X\" type=\"float\"/>"
    "<param name=\"Y\" type=\"float\"/><param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
    "  <vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n"
    "  <triangles count=\"4\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/>"
    "<p>0 2 1 0 1 3 0 3 2 1 2 3</p></triangles>\n"
    " </mesh></geometry></library_geometries>\n"
    " <library_visual_scenes><visual_scene id=\"s\"><node id=\"n\"><translate>10 0 0</translate>"
    "<instance_geometry url=\"#tet\"/></node></visual_scene></library_visual_scenes>\n"
    " <scene><instance_visual_scene url=\"#s\"/></scene>\n"
    "</COLLADA>\n";

static void test_dae(void) {
  ss_mesh r = {0};
  ss_error e;
  ss_status st = ss_read_mesh(tl_tmp("tet.dae"), &r, &e);
  CHECK_MSG(st == SS_OK && r.nv == 4 && r.nf == 4, "tet.dae: %s", st ? e.msg : "counts");
  if (!st && r.nv == 4) {
    double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
    for (int i = 0; i < 4; i++)
      for (int d = 0; d < 3; d++) {
        double x = r.V[3 * i + d];
        lo[d] = x < lo[d] ? x : lo[d], hi[d] = x > hi[d] ? x : hi[d];
      }
    /* the node's translation applied (assimp may turn the axes to Y up: compare the extents only) */
    CHECK_MSG((lo[0] == 10 && hi[0] == 11) && hi[1] - lo[1] == 1 && hi[2] - lo[2] == 1, "x from %g to %g", lo[0],
              hi[0]);
    tl_check_closed(&r, "tet.dae");
  }
  ss_mesh_free(&r);
  tl_write_file(tl_tmp("bad.dae"), "<COLLADA><library_geometries><geometry", 39);
  CHECK_MSG(ss_read_mesh(tl_tmp("bad.dae"), &r, &e) != SS_OK && strstr(e.msg, "bad.dae") && !r.V, "%s", e.msg);
  /* the same bytes from memory are not sniffed for assimp */
  CHECK_MSG(ss_read_mesh_memory(DAE, sizeof DAE - 1, "<dae>", &r, &e) == SS_ERR_UNSUPPORTED &&
                strstr(e.msg, "<dae>:1: unknown mesh format (expected OFF, OBJ, PLY, STL or glTF)"),
            "%s", e.msg);
}

int main(void) {
  if (!tl_tmpdir_make("/tmp/ss_test_assimp_XXXXXX")) {
    perror("mkdtemp");
    return 2;
  }
  tl_write_file(tl_tmp("tet.dae"), DAE, sizeof DAE - 1);
  /* which build is this? */
  ss_mesh r = {0};
  ss_error e;
  ss_status st = ss_read_mesh(tl_tmp("tet.dae"), &r, &e);
  ss_mesh_free(&r);
  const int have = st != SS_ERR_UNSUPPORTED;
  CHECK(ss_mesh_extension_supported("a/b.OFF") == 1 && ss_mesh_extension_supported("x.ply") == 1 &&
        ss_mesh_extension_supported("x.obj") == 1 && ss_mesh_extension_supported("x.stl") == 1 &&
        ss_mesh_extension_supported("x.gltf") == 1 && ss_mesh_extension_supported("x.GLB") == 1 &&
        ss_mesh_extension_supported("x.txt") == 0 && ss_mesh_extension_supported("dae") == 0);
  CHECK(ss_mesh_extension_supported("m.dae") == (have ? 2 : 0) &&
        ss_mesh_extension_supported("m.FBX") == (have ? 2 : 0));
  /* glTF is ours in every build: a .gltf never reaches assimp */
  char hint[16];
  CHECK(!ssi_mesh_assimp_ext("m.gltf", hint, sizeof hint) && !ssi_mesh_assimp_ext("m.glb", hint, sizeof hint) &&
        ssi_mesh_assimp_ext("m.fbx", hint, sizeof hint) && !strcmp(hint, "fbx"));
  if (!have) {
    CHECK_MSG(strstr(e.msg, "libassimp-dev") && strstr(e.msg, "DAE") && strstr(e.msg, "tet.dae"), "%s", e.msg);
    SKIP("this build has no assimp: COLLADA reading not checked (%s)", e.msg);
  } else {
    test_dae();
  }
  tl_tmpdir_remove();
  TEST_MAIN_END();
}
