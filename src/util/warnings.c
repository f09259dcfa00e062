/* Appending to a caller's warning string. */
#include "util/warnings.h"

#include <stdio.h>
#include <string.h>

void ssi_warn_append(char *w, size_t size, const char *what) {
  if (!w || !size) return;
  size_t len = strlen(w);
  if (len + 1 >= size) return;
  snprintf(w + len, size - len, "%s%s", len ? "; " : "", what);
}
