/* libFuzzer harness: read -> check -> geodesics / eigenpairs on small meshes, each input under a time
 * bound (libFuzzer's -timeout, set by scripts/fuzz.sh; a slower input is a finding, saved as
 * timeout-*). The bytes are read as a mesh (content sniffing); meshes of at most 400 faces and 300
 * vertices go on to ss_mesh_check, exact and graph geodesics from vertex 0 and ss_mesh_eigs (k = 3),
 * which must return a result or an error — finite, non-negative distances with d(source) = 0. Every
 * stage's cost is bounded by the mesh's size (issue 13, item 5), so any input finishing late is a bug. */
#include <math.h>

#include "fuzz_common.h"
#include "specseg/geodesic.h"
#include "specseg/io.h"
#include "specseg/mesh.h"
#include "specseg/spectrum.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  ss_mesh m;
  ss_error e = {{0}};
  ss_status st = ss_read_mesh_memory(data, size, "<fuzz>", &m, &e);
  fuzz_check_mesh(st, &m, &e, "<fuzz>");
  if (st) return 0;
  if (m.nf > 400 || m.nv > 300) {
    ss_mesh_free(&m);
    return 0;
  }
  ss_mesh_report r;
  if (ss_mesh_check(&m, &r, &e) == SS_OK) {
    FUZZ_ASSERT(r.vertices == m.nv && r.faces == m.nf);
    FUZZ_ASSERT(r.components >= 0 && r.components <= m.nv);
    FUZZ_ASSERT(!(r.area < 0) && !(r.bbox_diagonal < 0));
  }
  double *d = malloc(sizeof(double) * (size_t)m.nv);
  int src = 0;
  for (int method = 0; d && method < 2; method++) {
    ss_geodesic_method gmeth = method ? SS_GEODESIC_GRAPH : SS_GEODESIC_EXACT;
    if (ss_geodesic_distances(&m, gmeth, &src, 1, INFINITY, d, &e) == SS_OK) {
      FUZZ_ASSERT(d[0] == 0);
      for (int i = 0; i < m.nv; i++) FUZZ_ASSERT(d[i] >= 0); /* inf where unreached; never NaN */
    } else {
      FUZZ_ASSERT(e.msg[0] != '\0');
    }
  }
  free(d);
  if (m.nv >= 5) {
    double ev[3];
    if (ss_mesh_eigs(&m, 3, ev, NULL, &e) == SS_OK)
      for (int i = 0; i < 3; i++) FUZZ_ASSERT(isfinite(ev[i]));
    else
      FUZZ_ASSERT(e.msg[0] != '\0');
  }
  ss_mesh_free(&m);
  return 0;
}
