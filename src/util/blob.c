/* The checksummed binary files (key line, payload line, raw payload) shared by the prepared-shape
 * files (match/shape_file.c) and the eval cache (eval/eval_shape.c); see blob.h. */
#include "blob.h"
#include "out_file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

uint64_t ssi_fnv1a(uint64_t h, const void *data, size_t n) {
  const unsigned char *p = data;
  for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}

uint64_t ssi_fnv1a_x4(uint64_t h, const void *data, size_t n) {
  const unsigned char *p = data;
  uint64_t lane[4] = {h, h ^ 1, h ^ 2, h ^ 3};
  size_t i = 0;
  for (; i + 32 <= n; i += 32)
    for (int l = 0; l < 4; l++) {
      uint64_t w;
      memcpy(&w, p + i + 8 * l, 8);
      uint64_t x = (lane[l] ^ w) * 1099511628211ull;
      lane[l] = x ^ (x >> 29);
    }
  h = ssi_fnv1a(h, lane, sizeof lane);
  return ssi_fnv1a(h, p + i, n - i);
}

uint64_t ssi_mesh_hash(const ss_mesh *m) {
  uint64_t h = ssi_fnv1a(SSI_FNV_INIT, &m->nv, sizeof m->nv);
  h = ssi_fnv1a(h, &m->nf, sizeof m->nf);
  h = ssi_fnv1a(h, m->V, sizeof(double) * 3 * (size_t)m->nv);
  return ssi_fnv1a(h, m->F, sizeof(int) * 3 * (size_t)m->nf);
}

const char *ssi_byte_order(void) {
  const uint16_t probe = 1;
  return *(const unsigned char *)&probe ? "le" : "be";
}

void ssi_blob_put(ssi_blob *b, const void *data, size_t n) {
  if (b->bad || !n) return;
  if (n > SIZE_MAX / 2 - b->n) { b->bad = 1; return; }
  if (b->n + n > b->cap) {
    size_t cap = b->cap ? b->cap : 1 << 16;
    while (cap < b->n + n) cap *= 2;
    unsigned char *q = realloc(b->p, cap);
    if (!q) { b->bad = 1; return; }
    b->p = q, b->cap = cap;
  }
  memcpy(b->p + b->n, data, n);
  b->n += n;
}

int ssi_blob_get(ssi_blob *b, void *data, size_t n) {
  if (b->bad || n > b->n - b->pos) return b->bad = 1, 0;
  if (n) memcpy(data, b->p + b->pos, n);
  b->pos += n;
  return 1;
}

int ssi_blob_skip(ssi_blob *b, size_t n) {
  if (b->bad || n > b->n - b->pos) return b->bad = 1, 0;
  b->pos += n;
  return 1;
}

void ssi_blob_free(ssi_blob *b) {
  if (!b) return;
  free(b->p);
  memset(b, 0, sizeof *b);
}

int ssi_blob_write(const char *path, const char *key, const ssi_blob *b) {
  if (b->bad) return errno = ENOMEM, -1;
  ssi_out o; /* a temporary beside the target, renamed into place (util/out_file.h) */
  ss_error err;
  if (ssi_out_open(&o, path, &err)) return errno = errno ? errno : EIO, -1;
  uint64_t h = ssi_fnv1a_x4(ssi_fnv1a(SSI_FNV_INIT, key, strlen(key)), b->p, b->n);
  int ok = fputs(key, o.f) >= 0 && fprintf(o.f, "payload %zu fnv1a64x4 %016llx\n", b->n, (unsigned long long)h) > 0 &&
           (b->n == 0 || fwrite(b->p, 1, b->n, o.f) == b->n);
  int e = errno;
  if (!ok) {
    ssi_out_abort(&o);
    return errno = e ? e : EIO, -1;
  }
  errno = 0;
  if (ssi_out_commit(&o, path, &err)) return errno = errno ? errno : EIO, -1;
  return 0;
}

/* the file's bytes are buf[0, total) (malloc'd, taken over) */
static int parse(unsigned char *buf, size_t total, const char *expect_key, char *key, size_t keysize, ssi_blob *b,
                 char *note, size_t nnote) {
  memset(b, 0, sizeof *b);
  char dummy[1];
  if (!note || !nnote) note = dummy, nnote = sizeof dummy;
  note[0] = 0;
  const unsigned char *nl = memchr(buf, '\n', total < SSI_BLOB_MAX_KEY ? total : SSI_BLOB_MAX_KEY);
  size_t klen = nl ? (size_t)(nl - buf) + 1 : 0;
  size_t len = 0;
  unsigned long long sum = 0;
  char head[129], tail = 0;
  int ok = 0;
  if (!nl || memchr(buf, '\0', klen))
    snprintf(note, nnote, "no key line");
  else if (expect_key && (klen != strlen(expect_key) || memcmp(buf, expect_key, klen))) {
    int show = (int)(klen - 1 < 300 ? klen - 1 : 300);
    snprintf(note, nnote, "written for another version, mesh or options (key '%.*s')", show, (const char *)buf);
  } else if (key && klen >= keysize)
    snprintf(note, nnote, "key line of %zu bytes (at most %zu)", klen, keysize - 1);
  else {
    const unsigned char *pl = memchr(buf + klen, '\n', total - klen < 128 ? total - klen : 128);
    size_t hlen = pl ? (size_t)(pl - (buf + klen)) + 1 : 0;
    if (pl) memcpy(head, buf + klen, hlen), head[hlen] = 0;
    char kind[16] = "";
    if (!pl || sscanf(head, "payload %zu %15s %16llx%c", &len, kind, &sum, &tail) != 4 || tail != '\n' ||
        (strcmp(kind, "fnv1a64x4") && strcmp(kind, "fnv1a64")) || len > ((size_t)1 << 34))
      snprintf(note, nnote, "no payload line (length and checksum)");
    else {
      size_t off = klen + hlen, have = total - off;
      if (have < len)
        snprintf(note, nnote, "truncated: %zu of %zu payload bytes", have, len);
      else if (have > len)
        snprintf(note, nnote, "longer than its %zu payload bytes", len);
      else {
        const uint64_t h0 = ssi_fnv1a(SSI_FNV_INIT, buf, klen); /* (fnv1a64: the byte-wise one, earlier files) */
        const uint64_t h = strcmp(kind, "fnv1a64") ? ssi_fnv1a_x4(h0, buf + off, len) : ssi_fnv1a(h0, buf + off, len);
        if (h != sum)
          snprintf(note, nnote, "checksum mismatch (stored %016llx, contents %016llx)", sum, (unsigned long long)h);
        else {
          ok = 1;
          if (key) memcpy(key, buf, klen), key[klen] = 0;
          b->p = buf, b->n = b->cap = total, b->pos = off;
        }
      }
    }
  }
  if (!ok) free(buf);
  return ok ? 1 : -1;
}

int ssi_blob_read(const char *path, const char *expect_key, char *key, size_t keysize, ssi_blob *b, char *note,
                  size_t nnote) {
  memset(b, 0, sizeof *b);
  if (note && nnote) note[0] = 0;
  FILE *f = fopen(path, "rb");
  if (!f) return 0;
  size_t cap = 1 << 16, n = 0, got;
  unsigned char *buf = malloc(cap);
  while (buf && (got = fread(buf + n, 1, cap - n, f)) > 0) {
    n += got;
    if (n == cap) {
      unsigned char *q = cap < SIZE_MAX / 2 ? realloc(buf, cap * 2) : NULL;
      if (!q) free(buf), buf = NULL;
      else buf = q, cap *= 2;
    }
  }
  int rerr = ferror(f);
  fclose(f);
  if (!buf || rerr) {
    if (note && nnote) snprintf(note, nnote, buf ? "read error" : "out of memory reading it");
    free(buf);
    return -1;
  }
  return parse(buf, n, expect_key, key, keysize, b, note, nnote);
}

int ssi_blob_read_memory(const void *data, size_t n, const char *expect_key, char *key, size_t keysize, ssi_blob *b,
                         char *note, size_t nnote) {
  memset(b, 0, sizeof *b);
  unsigned char *buf = malloc(n ? n : 1);
  if (!buf) {
    if (note && nnote) snprintf(note, nnote, "out of memory for %zu bytes", n);
    return -1;
  }
  if (n) memcpy(buf, data, n);
  return parse(buf, n, expect_key, key, keysize, b, note, nnote);
}
