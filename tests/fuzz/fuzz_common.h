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

/* A parser over loaded bytes (mesh/io_internal.h's io_parse_*) on the fuzzer's data as the readers
 * hand it over (a private copy with a trailing NUL), its result checked as above under the name. */
static inline void fuzz_parser(ss_status (*parse)(const char *, const char *, size_t, ss_mesh *, ss_error *),
                               const char *name, const uint8_t *data, size_t size) {
  char *buf = malloc(size + 1);
  if (!buf) return;
  memcpy(buf, data, size);
  buf[size] = '\0';
  ss_mesh m = {0};
  ss_error e = {{0}};
  ss_status st = parse(name, buf, size, &m, &e);
  fuzz_check_mesh(st, &m, &e, name);
  ss_mesh_free(&m);
  free(buf);
}

#endif
