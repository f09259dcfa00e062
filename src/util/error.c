#include "specseg/core.h"

#include <stdarg.h>
#include <stdio.h>

ss_status ss_fail(ss_error *e, ss_status code, const char *fmt, ...) {
  if (e) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->msg, sizeof e->msg, fmt, ap);
    va_end(ap);
  }
  return code;
}

const char *ss_status_name(ss_status s) {
  switch (s) {
    case SS_OK: return "ok";
    case SS_ERR_IO: return "i/o error";
    case SS_ERR_PARSE: return "parse error";
    case SS_ERR_INVALID: return "invalid input";
    case SS_ERR_NOMEM: return "out of memory";
    case SS_ERR_NUMERIC: return "numerical failure";
    case SS_ERR_UNSUPPORTED: return "unsupported";
  }
  return "unknown status";
}
