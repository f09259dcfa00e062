/* Number text under a host program's locale whose decimal point is ',' (de_DE): our files are still
 * written and read with '.', and the host's locale is left as it was (util/c_locale.h). The locale is
 * built for the test with localedef into a scratch folder (LOCPATH); without localedef or Debian's
 * `locales` data the test SKIPs with the reason. */
#define _POSIX_C_SOURCE 200809L /* setenv, mkdtemp */
#include <locale.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "specseg/eval.h"
#include "specseg/io.h"
#include "specseg/mesh.h"
#include "testlib.h"
#include "util/c_locale.h"

/* the host's locale still in force: printf writes a comma */
static int comma_locale(void) {
  char b[16];
  snprintf(b, sizeof b, "%g", 0.5);
  return strcmp(b, "0,5") == 0;
}

/* a comma-decimal locale made for this test and set as the program's, as a host program would */
static int set_comma_locale(void) {
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "localedef -i de_DE -f UTF-8 '%s/de_DE.UTF-8' > /dev/null 2>&1", tl_tmpdir);
  if (system(cmd) != 0) return 0;
  setenv("LOCPATH", tl_tmpdir, 1);
  return setlocale(LC_ALL, "de_DE.UTF-8") != NULL && comma_locale();
}

static const double V[] = {0, 0, 0, 1.5, 0, 0, 0, 0.25, 0, 0, 0, -1.953125e-3};
static const int F[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};

static int same_tet(const ss_mesh *m) {
  if (m->nv != 4 || m->nf != 4) return 0;
  for (int i = 0; i < 12; i++)
    if (m->V[i] != V[i]) return 0;
  return 1;
}

/* the file's text holds the number with '.' and no ',' anywhere */
static int written_with_points(const char *path, const char *number) {
  size_t n;
  char *t = tl_read_file(path, &n);
  int ok = t && strstr(t, number) && !strchr(t, ',');
  free(t);
  return ok;
}

static void test_meshes(void) {
  const ss_mesh m = {4, 4, (double *)V, (int *)F};
  const char *names[] = {"t.off", "t.obj", "t.ply"};
  for (int k = 0; k < 3; k++) {
    ss_error e = {{0}};
    const char *p = tl_tmp(names[k]);
    ss_status st = k == 2 ? ss_write_ply(p, &m, NULL, SS_PLY_ASCII, &e) : ss_write_mesh(p, &m, NULL, &e);
    CHECK_MSG(st == SS_OK, "%s: %s", names[k], e.msg);
    CHECK_MSG(written_with_points(p, "1.5"), "%s written with a decimal comma", names[k]);
    ss_mesh r = {0};
    CHECK_MSG(ss_read_mesh(p, &r, &e) == SS_OK && same_tet(&r), "%s read back: %s", names[k], e.msg);
    ss_mesh_free(&r);
  }
  /* text as another program wrote it, from memory: OFF, OBJ and a glTF with a real-valued matrix */
  const char off[] = "OFF\n4 4 0\n0 0 0\n1.5 0 0\n0 0.25 0\n0 0 -1.953125e-3\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const char obj[] = "v 0 0 0\nv 1.5 0 0\nv 0 0.25 0\nv 0 0 -1.953125e-3\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  ss_error e = {{0}};
  ss_mesh r = {0};
  CHECK_MSG(ss_read_mesh_memory(off, sizeof off - 1, "m.off", &r, &e) == SS_OK && same_tet(&r), "OFF: %s", e.msg);
  ss_mesh_free(&r);
  CHECK_MSG(ss_read_mesh_memory(obj, sizeof obj - 1, "m.obj", &r, &e) == SS_OK && same_tet(&r), "OBJ: %s", e.msg);
  ss_mesh_free(&r);
  /* glTF: positions as a data URI of 4 floats x 3 (the tetrahedron scaled by 2 in a node matrix) */
  const float P[12] = {0, 0, 0, 0.75f, 0, 0, 0, 0.125f, 0, 0, 0, -9.765625e-4f};
  const unsigned short I[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  unsigned char bin[72];
  memcpy(bin, P, 48), memcpy(bin + 48, I, 24);
  char *uri = tl_base64(bin, sizeof bin);
  char gltf[1400];
  snprintf(gltf, sizeof gltf,
           "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
           "\"nodes\":[{\"mesh\":0,\"matrix\":[2.0,0,0,0, 0,2.0,0,0, 0,0,2.0,0, 0,0,0,1.0]}],"
           "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
           "\"buffers\":[{\"byteLength\":72,\"uri\":\"data:application/octet-stream;base64,%s\"}],"
           "\"bufferViews\":[{\"buffer\":0,\"byteLength\":48},{\"buffer\":0,\"byteOffset\":48,\"byteLength\":24}],"
           "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
           "\"min\":[0,0,-9.765625e-4],\"max\":[0.75,0.125,0]},"
           "{\"bufferView\":1,\"componentType\":5123,\"count\":12,\"type\":\"SCALAR\"}]}",
           uri ? uri : "");
  free(uri);
  CHECK_MSG(ss_read_mesh_memory(gltf, strlen(gltf), "m.gltf", &r, &e) == SS_OK && same_tet(&r), "glTF: %s", e.msg);
  ss_mesh_free(&r);
}

static void test_vectors_and_rows(void) {
  const double v[3] = {0.5, -1.25e-7, 3};
  ss_error e = {{0}};
  const char *p = tl_tmp("v.txt");
  CHECK_MSG(ss_write_doubles(p, v, 3, &e) == SS_OK, "%s", e.msg);
  CHECK(written_with_points(p, "0.5"));
  double *r = NULL;
  int n = 0;
  CHECK_MSG(ss_read_doubles(p, &r, &n, &e) == SS_OK && n == 3 && r[0] == v[0] && r[1] == v[1] && r[2] == v[2], "%s",
            e.msg);
  free(r);
  /* the benchmark's pairs.csv row: its reals with '.' (the row's commas are its separators) */
  ss_benchmark_row row;
  memset(&row, 0, sizeof row);
  snprintf(row.method, sizeof row.method, "m");
  snprintf(row.x, sizeof row.x, "a"), snprintf(row.y, sizeof row.y, "b");
  row.ok = 1, row.points = 3, row.mean = 0.5, row.median = 0.25, row.sym_mean = 0.125, row.seconds = 1.5;
  char line[4096];
  ss_benchmark_csv_format_row(&row, line, sizeof line);
  CHECK_MSG(strstr(line, "m,a,b,0.5,0.25,0.125,1.500000,") == line, "%s", line);
}

int main(void) {
  if (!tl_tmpdir_make("/tmp/ss_test_c_locale_XXXXXX")) {
    fprintf(stderr, "no scratch folder\n");
    return 1;
  }
  /* the helpers in the C locale give C's text */
  char b[32];
  ssi_snprintf_c(b, sizeof b, "%.3g", 0.125);
  CHECK(strcmp(b, "0.125") == 0);
  if (!set_comma_locale()) {
    SKIP("no comma-decimal locale here (localedef with Debian's `locales` data builds de_DE.UTF-8)");
  } else {
    ssi_snprintf_c(b, sizeof b, "%.3g", 0.125);
    CHECK_MSG(strcmp(b, "0.125") == 0, "%s", b);
    char *end;
    CHECK(ssi_strtod_c("2.5x", &end) == 2.5 && *end == 'x');
    double d = 0;
    CHECK(ssi_sscanf_c("7.25", "%lf", &d) == 1 && d == 7.25);
    test_meshes();
    test_vectors_and_rows();
    /* the host's locale is as it set it, after every call */
    CHECK(comma_locale());
    setlocale(LC_ALL, "C");
  }
  tl_tmpdir_remove();
  TEST_MAIN_END();
}
