/* Internal: the checksummed binary files of the library and the eval cache (one code path).
 *
 * A file is
 *   line 1: a key, one text line ending in '\n' (what the contents depend on: a format tag and version,
 *           the byte order and type sizes of the machine that wrote it, the input, the options);
 *   line 2: "payload BYTES fnv1a64x4 HASH\n": the payload's length and the checksum of the key line
 *           followed by the payload (ssi_fnv1a_x4; files of earlier versions say "fnv1a64", the
 *           byte-wise FNV-1a, and are read as well);
 *   then BYTES bytes of payload (raw native arrays), and nothing after them.
 * ssi_blob_read refuses (with the reason) a file whose key is not the expected one, whose length is
 * not exact or whose checksum does not match; the caller range-checks the contents. */
#ifndef SS_UTIL_BLOB_H
#define SS_UTIL_BLOB_H

#include "specseg/core.h"

#include <stddef.h>
#include <stdint.h>

/* The starting value of the eval cache since its first version: FNV-1a's published 64-bit offset
 * basis 14695981039346656037 with its last digit missing. Kept, so existing cache entries (their key
 * checksums and file names) stay valid; the multiplier is FNV's 64-bit prime. */
#define SSI_FNV_INIT 1469598103934665603ull
#define SSI_BLOB_MAX_KEY 4096 /* longest key line, '\n' included */

/* FNV-1a 64 of n bytes, continuing from h (SSI_FNV_INIT to start). */
uint64_t ssi_fnv1a(uint64_t h, const void *data, size_t n);
/* The payload checksum: FNV-1a's step over 8-byte words (native order, as the payload) in four
 * interleaved lanes, each step followed by a xorshift so high bits reach low ones, the lanes and
 * the tail bytes then folded by byte-wise FNV-1a; ~25x the byte-wise speed (20 MB: ~1 ms). */
uint64_t ssi_fnv1a_x4(uint64_t h, const void *data, size_t n);
/* FNV-1a 64 of a mesh: nv, nf, V (3 nv doubles), F (3 nf ints). */
uint64_t ssi_mesh_hash(const ss_mesh *m);
/* "le" or "be": this machine's byte order. */
const char *ssi_byte_order(void);

/* A growing byte buffer (writing: put) or a cursor over one (reading: get from pos to n). Any failure
 * (allocation, reading past the end) sets bad and makes the later calls no-ops returning 0. */
typedef struct ssi_blob {
  unsigned char *p;
  size_t n, cap, pos;
  int bad;
} ssi_blob;

void ssi_blob_put(ssi_blob *b, const void *data, size_t n);
int ssi_blob_get(ssi_blob *b, void *data, size_t n); /* 1: read */
int ssi_blob_skip(ssi_blob *b, size_t n);            /* 1: skipped */
void ssi_blob_free(ssi_blob *b);

/* put / get cnt elements of *ptr's type */
#define SSI_PUT(b, ptr, cnt) ssi_blob_put((b), (ptr), sizeof *(ptr) * (size_t)(cnt))
#define SSI_GET(b, ptr, cnt) ssi_blob_get((b), (ptr), sizeof *(ptr) * (size_t)(cnt))

/* Writes key (one line ending in '\n'), the payload line and b's n bytes to path, through a temporary
 * file beside it renamed into place (atomic: a concurrent reader never sees a half-written file).
 * 0, or -1 with errno set (nothing left behind). */
int ssi_blob_write(const char *path, const char *key, const ssi_blob *b);

/* Reads a file written by ssi_blob_write. expect_key: the key line it must have ('\n' included), or
 * NULL to accept any (then check it yourself). key (may be NULL): its key line, keysize bytes.
 * On success *b is a cursor over the payload (b->pos at its start, b->n its end; ssi_blob_free).
 * Returns 1: read; 0: no such file (nothing said); -1: the file is there but not usable, why in note. */
int ssi_blob_read(const char *path, const char *expect_key, char *key, size_t keysize, ssi_blob *b, char *note,
                  size_t nnote);
/* The same from n bytes in memory (copied). */
int ssi_blob_read_memory(const void *data, size_t n, const char *expect_key, char *key, size_t keysize, ssi_blob *b,
                         char *note, size_t nnote);

#endif
