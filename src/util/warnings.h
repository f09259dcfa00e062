/* Internal: the warning strings the library hands back to its callers ("what; what; ..."). */
#ifndef SS_UTIL_WARNINGS_H
#define SS_UTIL_WARNINGS_H

#include <stddef.h>

/* Appends `what` to the NUL-terminated string w (capacity size), "; "-separated; truncates, never
 * overflows; does nothing when w is NULL or size is 0. */
void ssi_warn_append(char *w, size_t size, const char *what);

#endif
