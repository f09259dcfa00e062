/* The version the library was built as (include/specseg/version.h). */
#include "specseg/version.h"

#define SS_STR2(x) #x
#define SS_STR(x) SS_STR2(x)

const char *ss_version(void) {
  return SS_STR(SPECSEG_VERSION_MAJOR) "." SS_STR(SPECSEG_VERSION_MINOR) "." SS_STR(SPECSEG_VERSION_PATCH);
}

int ss_version_number(void) { return SPECSEG_VERSION; }
