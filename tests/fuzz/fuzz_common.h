/* Shared by the libFuzzer harnesses (tests/fuzz/fuzz_*.c, built by scripts/fuzz.sh with clang):
 * checks every harness makes on a reader's result. A violated property aborts, which libFuzzer
 * reports as a finding with the input saved. */
#ifndef SS_FUZZ_COMMON_H
#define SS_FUZZ_COMMON_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "specseg/core.h"

#define FUZZ_ASSERT(c)                                                           \
  do {                                                                           \
    if (!(c)) {                                                                  \
      fprintf(stderr, "fuzz property violated at %s:%d: %s\n", __FILE__, __LINE__, #c); \
      abort();                                                                   \
    }                                                                            \
  } while (0)

/* A reader's outcome: a mesh whose indices are all in range with at least one face, or an error with
 * a message that starts with the input's name and leaves the mesh zeroed. */
static inline void fuzz_check_mesh(ss_status st, const ss_mesh *m, const ss_error *e, const char *name) {
  if (st) {
    FUZZ_ASSERT(m->nv == 0 && m->nf == 0 && m->V == NULL && m->F == NULL);
    FUZZ_ASSERT(e->msg[0] != '\0');
    FUZZ_ASSERT(!strncmp(e->msg, name, strlen(name)));
    return;
  }
  FUZZ_ASSERT(m->nv > 0 && m->nf > 0 && m->V && m->F);
  for (size_t i = 0; i < 3 * (size_t)m->nf; i++) FUZZ_ASSERT(m->F[i] >= 0 && m->F[i] < m->nv);
}

#endif
