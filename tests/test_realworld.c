/* Real-world inputs (issue 13): failing factorisations, inconsistent orientation, extreme scales,
 * several components, far / sliver vertices, huge polygons and duplicate faces. Each test names the
 * defect it covers (D1..D11). */
#include "specseg/specseg.h"
#include "specseg/synth.h"
#include "testlib.h"

/* icosphere(3) plus one needle triangle whose cotangent weights (~1e19) swamp the lumped masses:
 * the CMCF system loses positive definiteness in floating point and CHOLMOD's factorisation fails. */
static void test_cmcf_factorisation_failure(void) {
  ss_mesh s = {0}, m = {0}, out = {0};
  ss_error e = {{0}};
  CHECK(ss_synth_icosphere(3, &s, &e) == SS_OK);
  CHECK(ss_mesh_alloc(&m, s.nv + 3, s.nf + 1, &e) == SS_OK);
  memcpy(m.V, s.V, sizeof(double) * 3 * (size_t)s.nv);
  memcpy(m.F, s.F, sizeof(int) * 3 * (size_t)s.nf);
  double needle[9] = {3, 0, 0, 4, 0, 0, 3.5, 1e-20, 0};
  memcpy(m.V + 3 * (size_t)s.nv, needle, sizeof needle);
  int t[3] = {s.nv, s.nv + 1, s.nv + 2};
  memcpy(m.F + 3 * (size_t)s.nf, t, sizeof t);
  ss_status st = ss_cmcf_smooth(&m, NULL, &out, &e);
  printf("D1 needle: %s\n", st ? e.msg : "ok");
  CHECK(st == SS_ERR_NUMERIC); /* a clear error, not an abort */
  CHECK(out.V == NULL && out.nv == 0);
  ss_mesh_free(&out);
  ss_mesh_free(&m);
  ss_mesh_free(&s);
}

/* A sphere with every vertex duplicated, alternate faces using the second copies: a crumbled soup of
 * pieces on which the flow degenerates (the factorisation fails at a later step). CMCF and the
 * whole segmentation must return an error or a result, never crash. */
static void test_duplicated_vertices_sphere(void) {
  ss_mesh s = {0}, m = {0}, out = {0};
  ss_error e = {{0}};
  CHECK(ss_synth_icosphere(3, &s, &e) == SS_OK);
  CHECK(ss_mesh_alloc(&m, 2 * s.nv, s.nf, &e) == SS_OK);
  memcpy(m.V, s.V, sizeof(double) * 3 * (size_t)s.nv);
  memcpy(m.V + 3 * (size_t)s.nv, s.V, sizeof(double) * 3 * (size_t)s.nv);
  for (int f = 0; f < s.nf; f++)
    for (int j = 0; j < 3; j++) m.F[3 * f + j] = s.F[3 * f + j] + (f % 2 ? 0 : s.nv);
  ss_status st = ss_cmcf_smooth(&m, NULL, &out, &e);
  printf("D1 duplicated vertices, cmcf: %s\n", st ? e.msg : "ok");
  if (st) CHECK(out.V == NULL);
  ss_mesh_free(&out);
  ss_segmentation seg = {0};
  st = ss_segment(&m, NULL, &seg, &e);
  printf("D1 duplicated vertices, segment: %s\n", st ? e.msg : "ok");
  if (st) CHECK(seg.labels == NULL);
  else CHECK(seg.m > 0);
  ss_segmentation_free(&seg);
  ss_mesh_free(&m);
  ss_mesh_free(&s);
}

int main(void) {
  test_cmcf_factorisation_failure();
  test_duplicated_vertices_sphere();
  TEST_MAIN_END();
}
