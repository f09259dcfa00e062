/* libFuzzer harness: the prepared-shape reader (ss_prepared_shape_read_memory) on payloads whose
 * checksum is right (issue 32, item 2). The checksum only catches accidental damage, so mutating a
 * whole file would only exercise its refusal: here the input is a prepared-shape file without its
 * payload line (the key line, then the raw payload), and the harness writes the mesh counts and hash
 * of the key line from the payload's mesh and the payload line (length, checksum) itself, so every
 * mutation reaches the value checks. Properties: a file read has finite values in range (what a
 * match trusts), and the landmark-free pairing of its signature with itself returns (it crashed on a
 * NaN descriptor); a refused one says why ("<fuzz>: ...") and leaves nothing allocated.
 * Seeds: tests/fuzz/corpus/shape/ (small prepared shapes, `specseg prepare`, payload line removed). */
#include "fuzz_common.h"
#include "specseg/match.h"
#include "util/blob.h"

#include <math.h>

/* the payload's first record, the mesh: nv, nf, int64 count, 3 nv doubles, int64 count, 3 nf ints;
 * its hash (ssi_mesh_hash) when the sizes are consistent. 1: found */
static int payload_mesh(const uint8_t *p, size_t n, int *nv, int *nf, uint64_t *hash) {
  int64_t c;
  if (n < 8 + 8) return 0;
  memcpy(nv, p, 4), memcpy(nf, p + 4, 4), memcpy(&c, p + 8, 8);
  if (*nv < 1 || *nf < 1 || *nv > 1 << 20 || *nf > 1 << 21 || c != 3 * (int64_t)*nv) return 0;
  size_t vo = 16, vb = 24 * (size_t)*nv;
  if (n < vo + vb + 8) return 0;
  memcpy(&c, p + vo + vb, 8);
  size_t fo = vo + vb + 8, fb = 12 * (size_t)*nf;
  if (c != 3 * (int64_t)*nf || n < fo + fb) return 0;
  ss_mesh m = {*nv, *nf, malloc(vb), malloc(fb)};
  if (!m.V || !m.F) return free(m.V), free(m.F), 0;
  memcpy(m.V, p + vo, vb), memcpy(m.F, p + fo, fb);
  *hash = ssi_mesh_hash(&m);
  free(m.V), free(m.F);
  return 1;
}

static void check_read(const ss_prepared_shape *s) {
  const ss_shape_prep *mp = ss_prepared_shape_matched(s);
  const size_t nv = (size_t)mp->seg.nv, k = (size_t)mp->kev;
  FUZZ_ASSERT(mp->evals && mp->evecs && mp->M && k >= 3);
  for (size_t i = 0; i < k; i++) FUZZ_ASSERT(isfinite(mp->evals[i]));
  for (size_t i = 0; i < nv * k; i++) FUZZ_ASSERT(isfinite(mp->evecs[i]));
  for (size_t i = 0; i < nv; i++) FUZZ_ASSERT(mp->M[i] > 0 && isfinite(mp->M[i]));
  for (size_t i = 0; i < 3 * (size_t)s->mesh.nv; i++) FUZZ_ASSERT(isfinite(s->mesh.V[i]));
  if (!s->has_signature) return;
  const ss_centre_signature *g = &s->sig;
  for (size_t i = 0; i < (size_t)g->m * g->nd; i++) FUZZ_ASSERT(isfinite(g->descr[i]));
  for (size_t i = 0; i < (size_t)g->m * g->m; i++) FUZZ_ASSERT(isfinite(g->D[i]) && g->D[i] >= 0);
  if (g->m > 8) return; /* the pairing's search: small signatures only (time per input) */
  ss_segment_pairs out = {0};
  ss_error e = {{0}};
  ss_autopair_options o = s->autopair;
  o.recheck_margin = 0, o.alt_max = 0; /* one orientation test: the search and its mirror candidate */
  if (ss_pair_centres_auto(g, g, &o, &out, NULL, &e) == SS_OK) FUZZ_ASSERT(out.n == g->m);
  ss_segment_pairs_free(&out);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const uint8_t *nl = memchr(data, '\n', size < SSI_BLOB_MAX_KEY ? size : SSI_BLOB_MAX_KEY);
  if (!nl) return 0;
  size_t klen = (size_t)(nl - data) + 1, plen = size - klen;
  const uint8_t *pay = data + klen;
  char key[SSI_BLOB_MAX_KEY + 64];
  memcpy(key, data, klen), key[klen] = 0;
  if (memchr(key, 0, klen)) return 0;
  /* the key's "mesh NV NF HASH" from the payload's mesh (its hash is part of what a reader checks) */
  int nv, nf;
  uint64_t h;
  char *at = strstr(key, " mesh ");
  if (at && payload_mesh(pay, plen, &nv, &nf, &h)) {
    int end = 0, a, b;
    unsigned long long old;
    if (sscanf(at, " mesh %d %d %16llx%n", &a, &b, &old, &end) == 3) {
      char tail[SSI_BLOB_MAX_KEY];
      snprintf(tail, sizeof tail, "%s", at + end);
      snprintf(at, sizeof key - (size_t)(at - key), " mesh %d %d %016llx%s", nv, nf, (unsigned long long)h, tail);
      klen = strlen(key);
      if (klen >= SSI_BLOB_MAX_KEY) return 0;
    }
  }
  char head[96];
  uint64_t sum = ssi_fnv1a_x4(ssi_fnv1a(SSI_FNV_INIT, key, klen), pay, plen);
  int hl = snprintf(head, sizeof head, "payload %zu fnv1a64x4 %016llx\n", plen, (unsigned long long)sum);
  uint8_t *file = malloc(klen + (size_t)hl + plen + 1);
  if (!file) return 0;
  memcpy(file, key, klen), memcpy(file + klen, head, (size_t)hl);
  if (plen) memcpy(file + klen + hl, pay, plen);
  ss_prepared_shape s;
  ss_error e = {{0}};
  ss_status st = ss_prepared_shape_read_memory(file, klen + (size_t)hl + plen, "<fuzz>", &s, &e);
  free(file);
  if (st) {
    FUZZ_ASSERT(!strncmp(e.msg, "<fuzz>", 6));
    FUZZ_ASSERT(s.mesh.V == NULL && s.prep.evecs == NULL && s.sig.descr == NULL);
    return 0;
  }
  check_read(&s);
  ss_prepared_shape_free(&s);
  return 0;
}
