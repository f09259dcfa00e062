/* specseg — library version. The macros give the version of the headers a program was compiled
 * with; ss_version() / ss_version_number() that of the library it runs with. Semantic versioning:
 * the shared library's SOVERSION is the major version (0.x: the minor version too). */
#ifndef SPECSEG_VERSION_H
#define SPECSEG_VERSION_H

#define SPECSEG_VERSION_MAJOR 0
#define SPECSEG_VERSION_MINOR 2
#define SPECSEG_VERSION_PATCH 0
/* e.g. 0.2.0 -> 200 (MAJOR * 10000 + MINOR * 100 + PATCH) */
#define SPECSEG_VERSION (SPECSEG_VERSION_MAJOR * 10000 + SPECSEG_VERSION_MINOR * 100 + SPECSEG_VERSION_PATCH)

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__) || defined(__clang__)
__attribute__((visibility("default")))
#endif
/* The version of the library a program runs with (the macros above give the headers').
 *
 * Returns: "MAJOR.MINOR.PATCH", a static string (do not free).
 */
const char *ss_version(void);
#if defined(__GNUC__) || defined(__clang__)
__attribute__((visibility("default")))
#endif
/* The version number of the library a program runs with, to compare with SPECSEG_VERSION.
 *
 * Returns: MAJOR * 10000 + MINOR * 100 + PATCH of the library at run time.
 */
int ss_version_number(void);

#ifdef __cplusplus
}
#endif
#endif
