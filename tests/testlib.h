/* Minimal test harness: CHECK records failures and goes on; TEST_MAIN prints "N passed, N failed". */
#ifndef SS_TESTLIB_H
#define SS_TESTLIB_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "specseg/mesh.h"

static int tl_pass = 0, tl_fail = 0, tl_skip = 0;

#define CHECK(cond)                                                                   \
  do {                                                                                \
    if (cond) tl_pass++;                                                              \
    else { tl_fail++; fprintf(stderr, "FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond); } \
  } while (0)

#define CHECK_MSG(cond, ...)                                                          \
  do {                                                                                \
    if (cond) tl_pass++;                                                              \
    else {                                                                            \
      tl_fail++;                                                                      \
      fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                 \
      fprintf(stderr, __VA_ARGS__);                                                   \
      fputc('\n', stderr);                                                            \
    }                                                                                 \
  } while (0)

#define CHECK_NEAR(a, b, tol) CHECK_MSG(fabs((double)(a) - (double)(b)) <= (tol), "%.17g vs %.17g (tol %g)", (double)(a), (double)(b), (double)(tol))

#define SKIP(...) do { tl_skip++; printf("SKIP: "); printf(__VA_ARGS__); printf("\n"); } while (0)

/* Data folder (../shared/data) or NULL when absent. */
static inline const char *tl_data_dir(void) {
  const char *d = getenv("SS_DATA_DIR");
  if (!d) return NULL;
  char probe[4096];
  snprintf(probe, sizeof probe, "%s/faust/tr_reg_000.off", d);
  FILE *f = fopen(probe, "rb");
  if (!f) return NULL;
  fclose(f);
  return d;
}

/* A test's scratch folder: tl_tmpdir_make("/tmp/ss_test_NAME_XXXXXX") once (0 when it cannot be
 * made), tl_tmp(name) a path in it (four rotating buffers: up to four in use at once),
 * tl_tmpdir_remove() at the end. */
static char tl_tmpdir[512];

static inline int tl_tmpdir_make(const char *tmpl) {
  snprintf(tl_tmpdir, sizeof tl_tmpdir, "%s", tmpl);
  return mkdtemp(tl_tmpdir) != NULL;
}

static inline const char *tl_tmp(const char *name) {
  static char buf[4][1024];
  static int k = 0;
  k = (k + 1) % 4;
  snprintf(buf[k], sizeof buf[k], "%s/%s", tl_tmpdir, name);
  return buf[k];
}

static inline void tl_tmpdir_remove(void) {
  char cmd[600];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tl_tmpdir);
  if (system(cmd)) fprintf(stderr, "could not remove %s\n", tl_tmpdir);
}

/* n bytes as standard base64 with padding, in a malloc'd NUL-terminated string (NULL when out of
 * memory): glTF data URIs */
static inline char *tl_base64(const void *data, size_t n) {
  static const char B64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const unsigned char *in = (const unsigned char *)data;
  char *out = (char *)malloc(4 * (n / 3 + 1) + 1);
  if (!out) return NULL;
  size_t o = 0;
  for (size_t i = 0; i < n; i += 3) {
    unsigned long v = (unsigned long)in[i] << 16 | (i + 1 < n ? (unsigned long)in[i + 1] << 8 : 0) |
                      (i + 2 < n ? in[i + 2] : 0);
    out[o++] = B64[v >> 18 & 63], out[o++] = B64[v >> 12 & 63];
    out[o++] = i + 1 < n ? B64[v >> 6 & 63] : '=';
    out[o++] = i + 2 < n ? B64[v & 63] : '=';
  }
  out[o] = '\0';
  return out;
}

/* The whole file at path in a malloc'd buffer with a NUL after its *n bytes; NULL (and *n 0) when it
 * cannot be read */
static inline char *tl_read_file(const char *path, size_t *n) {
  *n = 0;
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  long sz = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *b = sz >= 0 ? malloc((size_t)sz + 1) : NULL;
  if (b) b[*n = fread(b, 1, (size_t)sz, f)] = 0;
  fclose(f);
  return b;
}

/* n bytes of data as the whole file at path (exits the test on failure to open it) */
static inline void tl_write_file(const char *path, const void *data, size_t n) {
  FILE *f = fopen(path, "wb");
  if (!f) { perror(path); exit(2); }
  fwrite(data, 1, n, f);
  fclose(f);
}

/* r is one closed, manifold, consistently oriented surface of genus 0 (a sphere's topology) */
static inline void tl_check_closed(const ss_mesh *r, const char *what) {
  ss_mesh_report rep;
  ss_error e;
  CHECK(ss_mesh_check(r, &rep, &e) == SS_OK);
  CHECK_MSG(rep.components == 1 && rep.boundary_edges == 0 && rep.manifold && rep.oriented && rep.euler_characteristic == 2,
            "%s: components %d, boundary edges %d, manifold %d, oriented %d, chi %d", what, rep.components,
            rep.boundary_edges, rep.manifold, rep.oriented, rep.euler_characteristic);
}

/* For each of nv vertices V (nv x 3), the vertex nearest to its mirror image in the plane x = 0 (brute
 * force: small test meshes); returns the largest of those distances. */
static inline double tl_mirror_map(const double *V, int nv, int *sym) {
  double maxd = 0;
  for (int i = 0; i < nv; i++) {
    const double *p = V + 3 * (size_t)i;
    double best = INFINITY;
    for (int j = 0; j < nv; j++) {
      const double *q = V + 3 * (size_t)j;
      const double d = (p[0] + q[0]) * (p[0] + q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
      if (d < best) best = d, sym[i] = j;
    }
    if (sqrt(best) > maxd) maxd = sqrt(best);
  }
  return maxd;
}

#define TEST_MAIN_END()                                                                  \
  do {                                                                                   \
    printf("%d passed, %d failed", tl_pass, tl_fail);                                    \
    if (tl_skip) printf(", %d skipped", tl_skip);                                        \
    printf("\n");                                                                        \
    /* 77: CTest's SKIP_RETURN_CODE, so a test that skipped checks shows as skipped */   \
    return tl_fail ? 1 : tl_skip ? 77 : 0;                                               \
  } while (0)

/* The identity map of a mesh (nv vertices, nf triangles F) with every vertex moved to a neighbour of
 * a neighbour (a random walk of two steps along the edges, seeded): a map off by about two edge
 * lengths everywhere. */
static inline void tl_scrambled_identity(int nv, int nf, const int *F, unsigned seed, int *map) {
  int *deg = calloc((size_t)nv + 1, sizeof(int)), *adj = malloc(sizeof(int) * 6 * (size_t)nf),
      *fill = calloc((size_t)nv, sizeof(int));
  for (int f = 0; f < nf; f++)
    for (int c = 0; c < 3; c++) deg[F[3 * f + c] + 1] += 2;
  for (int i = 0; i < nv; i++) deg[i + 1] += deg[i];
  for (int f = 0; f < nf; f++)
    for (int c = 0; c < 3; c++) {
      const int a = F[3 * f + c], b = F[3 * f + (c + 1) % 3], d = F[3 * f + (c + 2) % 3];
      adj[deg[a] + fill[a]++] = b, adj[deg[a] + fill[a]++] = d;
    }
  unsigned s = seed;
  for (int i = 0; i < nv; i++) {
    int v = i;
    for (int step = 0; step < 2; step++) {
      s = s * 1103515245u + 12345u;
      const int k = deg[v + 1] - deg[v];
      if (k > 0) v = adj[deg[v] + (int)((s >> 8) % (unsigned)k)];
    }
    map[i] = v;
  }
  free(deg), free(adj), free(fill);
}

#endif
