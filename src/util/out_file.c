/* Outputs written whole or not at all: a temporary file beside the target, renamed over it once
 * complete and on disk; see out_file.h. */
#define _POSIX_C_SOURCE 200809L /* readlink, lstat, fsync, fdopen */
#include "out_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* the folder part of p ("." when none), malloc'd */
static char *dir_of(const char *p) {
  const char *s = strrchr(p, '/');
  if (!s) return strdup(".");
  if (s == p) return strdup("/");
  char *d = malloc((size_t)(s - p) + 1);
  if (d) memcpy(d, p, (size_t)(s - p)), d[s - p] = 0;
  return d;
}

/* The file a chain of symlinks ends at (not resolved further when a link dangles: its target is
 * the file to create). malloc'd, NULL with errno set (ELOOP beyond 40 links). */
static char *follow_links(const char *path) {
  char *cur = strdup(path);
  for (int hops = 0; cur; hops++) {
    struct stat st;
    if (lstat(cur, &st) != 0 || !S_ISLNK(st.st_mode)) return cur;
    if (hops == 40) return free(cur), errno = ELOOP, NULL;
    size_t cap = st.st_size > 0 ? (size_t)st.st_size + 1 : 4096;
    char *t = malloc(cap);
    ssize_t k = t ? readlink(cur, t, cap) : -1;
    if (k < 0 || (size_t)k >= cap) {
      int e = k < 0 && t ? errno : ENAMETOOLONG;
      free(t), free(cur);
      return errno = t ? e : ENOMEM, NULL;
    }
    t[k] = 0;
    char *next = t;
    if (t[0] != '/') { /* relative to the link's folder */
      char *d = dir_of(cur);
      size_t n = d ? strlen(d) + strlen(t) + 2 : 0;
      next = d ? malloc(n) : NULL;
      if (next) snprintf(next, n, "%s/%s", d, t);
      free(d), free(t);
      if (!next) return free(cur), errno = ENOMEM, NULL;
    }
    free(cur);
    cur = next;
  }
  return errno = ENOMEM, NULL;
}

ss_status ssi_out_open(ssi_out *o, const char *path, ss_error *err) {
  memset(o, 0, sizeof *o);
  if (!path || !*path) return ss_fail(err, SS_ERR_INVALID, "write: no file name");
  char *target = follow_links(path);
  if (!target) return ss_fail(err, SS_ERR_IO, "%s: cannot open for writing: %s", path, strerror(errno));
  struct stat st;
  int exists = stat(target, &st) == 0;
  if (exists && (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode))) { /* a stream: written as it is */
    o->f = fopen(target, "wb");
    if (!o->f) {
      int e = errno;
      free(target);
      return ss_fail(err, SS_ERR_IO, "%s: cannot open for writing: %s", path, strerror(e));
    }
    o->target = target;
    return SS_OK;
  }
  if (exists && !S_ISREG(st.st_mode)) { /* a folder, a block device, a socket: never replaced */
    free(target);
    const int dir = S_ISDIR(st.st_mode);
    ss_status r = ss_fail(err, SS_ERR_IO, "%s: cannot open for writing: %s", path,
                          dir ? "is a folder" : "not a regular file, pipe or character device (not replaced)");
    errno = dir ? EISDIR : EINVAL;
    return r;
  }
  /* a temporary in the same folder: rename(2) is atomic within one file system */
  static atomic_uint counter;
  char *dir = dir_of(target);
  const char *base = strrchr(target, '/') ? strrchr(target, '/') + 1 : target;
  size_t n = dir ? strlen(dir) + strlen(base) + 64 : 0;
  char *tmp = dir ? malloc(n) : NULL;
  if (!tmp) {
    free(dir), free(target);
    return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", path);
  }
  int fd = -1, e = 0;
  for (int attempt = 0; attempt < 100 && fd < 0; attempt++) {
    snprintf(tmp, n, "%s/.%s.tmp-%ld-%u", dir, base, (long)getpid(), atomic_fetch_add(&counter, 1u));
    fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    e = errno;
    if (fd < 0 && e != EEXIST) break;
  }
  free(dir);
  if (fd < 0) {
    free(tmp), free(target);
    return ss_fail(err, SS_ERR_IO, "%s: cannot open for writing: %s", path, strerror(e));
  }
  if (exists) (void)fchmod(fd, st.st_mode & 07777); /* the replaced file's permissions */
  o->f = fdopen(fd, "wb");
  if (!o->f) {
    e = errno;
    close(fd), remove(tmp), free(tmp), free(target);
    return ss_fail(err, SS_ERR_IO, "%s: cannot open for writing: %s", path, strerror(e));
  }
  o->target = target, o->tmp = tmp;
  return SS_OK;
}

static void out_free(ssi_out *o) {
  free(o->target), free(o->tmp);
  memset(o, 0, sizeof *o);
}

void ssi_out_abort(ssi_out *o) {
  if (!o) return;
  if (o->f) fclose(o->f);
  if (o->tmp) remove(o->tmp);
  out_free(o);
}

ss_status ssi_out_commit(ssi_out *o, const char *path, ss_error *err) {
  if (!o || !o->f) return ss_fail(err, SS_ERR_INVALID, "%s: write: not open", path);
  errno = 0;
  int bad = ferror(o->f), e = bad ? (errno ? errno : EIO) : 0;
  if (!bad && fflush(o->f)) bad = 1, e = errno;
  /* on disk before it replaces the old file: after a crash, the old file or the whole new one */
  if (!bad && o->tmp && fsync(fileno(o->f))) bad = 1, e = errno;
  if (fclose(o->f) && !bad) bad = 1, e = errno;
  o->f = NULL;
  if (!bad && o->tmp && rename(o->tmp, o->target)) bad = 1, e = errno;
  if (bad) {
    if (o->tmp) remove(o->tmp);
    out_free(o);
    ss_status st = ss_fail(err, SS_ERR_IO, "%s: write error: %s", path, strerror(e ? e : EIO));
    errno = e ? e : EIO; /* for callers that report strerror(errno) */
    return st;
  }
  if (o->tmp) { /* the rename itself on disk (best effort: not every file system syncs folders) */
    char *d = dir_of(o->target);
    int dfd = d ? open(d, O_RDONLY | O_DIRECTORY | O_CLOEXEC) : -1;
    if (dfd >= 0) (void)fsync(dfd), close(dfd);
    free(d);
  }
  out_free(o);
  return SS_OK;
}
