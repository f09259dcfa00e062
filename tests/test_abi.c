/* ss_struct_size / ss_render_struct_size (specseg/abi.h, render.h): every struct the Python binding
 * mirrors (python/specseg/_clib.py: CORE_MIRRORS, RENDER_MIRRORS) has the size the public headers give
 * it; unknown names, the other library's names and NULL give 0. */
#include "specseg/abi.h"
#include "specseg/specseg.h"
#include "specseg/render.h"
#include "testlib.h"

#define SIZE(T) {#T, sizeof(T)}

int main(void) {
  static const struct { const char *name; size_t size; } core[] = {
      SIZE(ss_error),          SIZE(ss_mesh),           SIZE(ss_sparse),           SIZE(ss_cmcf_options),
      SIZE(ss_remesh_options), SIZE(ss_segment_options), SIZE(ss_segmentation),    SIZE(ss_fmap_match_options),
      SIZE(ss_match_options),  SIZE(ss_segment_pairs),   SIZE(ss_match_result),    SIZE(ss_autopair_options),
      SIZE(ss_shape_prep),     SIZE(ss_centre_signature), SIZE(ss_prepared_shape)};
  static const struct { const char *name; size_t size; } render[] = {SIZE(ss_render_options), SIZE(ss_render_scene)};
  for (size_t i = 0; i < sizeof core / sizeof core[0]; i++) {
    CHECK_MSG(ss_struct_size(core[i].name) == core[i].size, "%s: %zu, sizeof %zu", core[i].name,
              ss_struct_size(core[i].name), core[i].size);
    CHECK_MSG(ss_render_struct_size(core[i].name) == 0, "%s is not the render library's", core[i].name);
  }
  for (size_t i = 0; i < sizeof render / sizeof render[0]; i++) {
    CHECK(ss_render_struct_size(render[i].name) == render[i].size);
    CHECK_MSG(ss_struct_size(render[i].name) == 0, "%s is not the core's", render[i].name);
  }
  static const char *const unknown[] = {"", "ss_", "ss_mesh ", "SS_MESH", "ss_meshx", "ss_geodesic_method", "x"};
  for (size_t i = 0; i < sizeof unknown / sizeof unknown[0]; i++) {
    CHECK_MSG(ss_struct_size(unknown[i]) == 0, "'%s'", unknown[i]);
    CHECK_MSG(ss_render_struct_size(unknown[i]) == 0, "'%s'", unknown[i]);
  }
  CHECK(ss_struct_size(NULL) == 0);
  CHECK(ss_render_struct_size(NULL) == 0);
  TEST_MAIN_END();
}
