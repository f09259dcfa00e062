/* Text numbers in the C locale (c_locale.h). */
#define _POSIX_C_SOURCE 200809L /* newlocale, uselocale, freelocale */
#include "c_locale.h"

#include <locale.h>
#include <stdarg.h>
#include <stdlib.h>

/* The thread's locale before the switch, and the C locale switched to ((locale_t)0: none could be
 * made, out of memory, and the call runs in the thread's locale as it is) */
typedef struct {
  locale_t prev, c;
} c_scope;

static c_scope enter(void) {
  c_scope s = {(locale_t)0, newlocale(LC_ALL_MASK, "C", (locale_t)0)};
  if (s.c != (locale_t)0) s.prev = uselocale(s.c);
  return s;
}

static void leave(c_scope s) {
  if (s.c == (locale_t)0) return;
  uselocale(s.prev);
  freelocale(s.c);
}

double ssi_strtod_c(const char *s, char **end) {
  const c_scope c = enter();
  const double v = strtod(s, end);
  leave(c);
  return v;
}

int ssi_vsnprintf_c(char *buf, size_t n, const char *fmt, va_list ap) {
  const c_scope c = enter();
  const int r = vsnprintf(buf, n, fmt, ap);
  leave(c);
  return r;
}

int ssi_snprintf_c(char *buf, size_t n, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  const int r = ssi_vsnprintf_c(buf, n, fmt, ap);
  va_end(ap);
  return r;
}

int ssi_fprintf_c(FILE *f, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  const c_scope c = enter();
  const int r = vfprintf(f, fmt, ap);
  leave(c);
  va_end(ap);
  return r;
}

int ssi_sscanf_c(const char *s, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  const c_scope c = enter();
  const int r = vsscanf(s, fmt, ap);
  leave(c);
  va_end(ap);
  return r;
}
