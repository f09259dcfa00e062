/* Internal: how every writer of the library opens and finishes its output file, so that a file is
 * either written whole or left as it was (issue 32).
 *
 * ssi_out_open(path) follows symlinks to their final target (a dangling link: the file it names is
 * created; the link itself stays), then
 *   - a regular file or a name not there yet: a temporary file in the target's folder (".NAME.tmp-*",
 *     the existing file's permission bits, else 0666 less the umask), which ssi_out_commit flushes,
 *     fsyncs and renames over the target: a reader, a write error (disk full, a file size limit) or a
 *     crash half-way never leaves a partial file under the final name;
 *   - a FIFO or a character device (a pipe, /dev/null, /dev/stdout): written directly, never replaced;
 *   - a directory, a block device or a socket: refused.
 * Messages: "PATH: cannot open for writing: ..." and "PATH: write error: ..." (PATH as given). */
#ifndef SS_UTIL_OUT_FILE_H
#define SS_UTIL_OUT_FILE_H

#include "specseg/core.h"

#include <stdio.h>

typedef struct ssi_out {
  FILE *f;      /* write here */
  char *target; /* the file finally written (symlinks resolved) */
  char *tmp;    /* the temporary renamed over target on commit; NULL when written directly */
} ssi_out;

ss_status ssi_out_open(ssi_out *o, const char *path, ss_error *err);
/* Flushes, fsyncs, closes and renames into place; on any failure (a write error seen earlier
 * included) the temporary is removed and the target left as it was. Frees o. */
ss_status ssi_out_commit(ssi_out *o, const char *path, ss_error *err);
/* Gives up: closes and removes the temporary (the target left as it was). Frees o. */
void ssi_out_abort(ssi_out *o);

#endif
