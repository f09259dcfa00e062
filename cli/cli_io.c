/* "-" as a file name: standard input for the readers, standard output for the writers (see cli.h). */
#include <errno.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "cli_shape.h"
#include "specseg/render.h"
#include "util/out_file.h"

#define STDIN_NAME "<stdin>"
#define STDOUT_NAME "<stdout>"

int cli_is_std(const char *path) { return path && path[0] == '-' && path[1] == '\0'; }
const char *cli_in_name(const char *path) { return cli_is_std(path) ? STDIN_NAME : path; }
const char *cli_out_name(const char *path) { return cli_is_std(path) ? STDOUT_NAME : path; }

int cli_count_std(const char *const *paths, int n) {
  int c = 0;
  for (int i = 0; i < n; i++) c += cli_is_std(paths[i]);
  return c;
}

/* ---- inputs that cannot be read twice ------------------------------------------------------------
 * Standard input and named pipes (process substitution, `<(...)`) are read whole once, growing the
 * buffer as bytes arrive (a pipe has no size), and kept: a later read of the same name (render reads
 * a file given once for every mesh, and a landmark file twice) parses the same bytes. Regular files
 * are read by path by the library, as before. */

typedef struct stream {
  char *path, *buf;
  size_t len;
} stream;

static stream *streams;
static int nstreams;

static ss_status slurp_stream(FILE *f, const char *name, char **buf, size_t *len, ss_error *err) {
  size_t cap = 65536, n = 0;
  char *b = malloc(cap);
  if (!b) return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", name);
  for (;;) {
    if (n == cap) {
      char *nb = cap <= SIZE_MAX / 2 ? realloc(b, cap * 2) : NULL;
      if (!nb) {
        free(b);
        return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory reading the input", name);
      }
      b = nb;
      cap *= 2;
    }
    size_t got = fread(b + n, 1, cap - n, f);
    n += got;
    if (got == 0) break;
  }
  if (ferror(f)) {
    int e = errno;
    free(b);
    return ss_fail(err, SS_ERR_IO, "%s: read error: %s", name, strerror(e));
  }
  *buf = b;
  *len = n;
  return SS_OK;
}

static ss_status stream_input_locked(const char *path, int *is_stream, const char **buf, size_t *len, ss_error *err);

/* *is_stream 1: the bytes of a stream input in *buf, *len; 0: a regular (or missing) file, for the
 * library's path readers. Serialised: a batch reads its meshes on several threads. */
static ss_status stream_input(const char *path, int *is_stream, const char **buf, size_t *len, ss_error *err) {
  static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
  pthread_mutex_lock(&lock);
  ss_status st = stream_input_locked(path, is_stream, buf, len, err);
  pthread_mutex_unlock(&lock);
  return st;
}

static ss_status stream_input_locked(const char *path, int *is_stream, const char **buf, size_t *len, ss_error *err) {
  *is_stream = 0;
  int std = cli_is_std(path);
  struct stat st;
  if (std) {
    /* a terminal is read until end of input; other devices (/dev/zero) may never end */
    if (fstat(STDIN_FILENO, &st) == 0 && S_ISCHR(st.st_mode) && !isatty(STDIN_FILENO)) {
      return ss_fail(err, SS_ERR_IO, STDIN_NAME ": not a file, pipe or terminal");
    }
  } else if (stat(path, &st) != 0 || !(S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode))) {
    return SS_OK;
  }
  *is_stream = 1;
  for (int i = 0; i < nstreams; i++)
    if (!strcmp(streams[i].path, path)) {
      *buf = streams[i].buf;
      *len = streams[i].len;
      return SS_OK;
    }
  stream *g = realloc(streams, sizeof *streams * (size_t)(nstreams + 1));
  if (!g) return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", cli_in_name(path));
  streams = g;
  stream *s = &streams[nstreams];
  FILE *f = std ? stdin : fopen(path, "rb");
  if (!f) return ss_fail(err, SS_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
  ss_status rc = slurp_stream(f, cli_in_name(path), &s->buf, &s->len, err);
  if (!std) fclose(f);
  if (rc) return rc;
  if (!(s->path = strdup(path))) {
    free(s->buf);
    return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", cli_in_name(path));
  }
  nstreams++;
  *buf = s->buf;
  *len = s->len;
  return SS_OK;
}

void cli_io_cleanup(void) {
  for (int i = 0; i < nstreams; i++) free(streams[i].path), free(streams[i].buf);
  free(streams);
  streams = NULL;
  nstreams = 0;
}

/* A prepared shape (.sss) where a mesh is meant: the mesh it holds (the input's vertices and faces,
 * in their order), so every command that reads a mesh takes it (issue 32). */
static ss_status read_prepared_mesh(const char *path, ss_mesh *m, ss_error *err) {
  cli_shape s;
  ss_status st = cli_read_shape(path, &s, err);
  if (st) return st;
  *m = s.ps.mesh;
  memset(&s.ps.mesh, 0, sizeof s.ps.mesh);
  cli_shape_free(&s);
  return SS_OK;
}

ss_status cli_read_mesh(const char *path, ss_mesh *m, ss_error *err) {
  const char *b;
  size_t n;
  memset(m, 0, sizeof *m);
  if (cli_is_prepared_shape(path)) return read_prepared_mesh(path, m, err);
  int is;
  ss_status st = stream_input(path, &is, &b, &n, err);
  if (st || !is) return st ? st : ss_read_mesh(path, m, err);
  return ss_read_mesh_memory(b, n, cli_in_name(path), m, err);
}

ss_status cli_read_mesh_colors(const char *path, ss_mesh *m, unsigned char **rgb, ss_error *err) {
  const char *b;
  size_t n;
  memset(m, 0, sizeof *m);
  *rgb = NULL;
  if (cli_is_prepared_shape(path)) return read_prepared_mesh(path, m, err); /* no colours */
  int is;
  ss_status st = stream_input(path, &is, &b, &n, err);
  if (st || !is) return st ? st : ss_read_mesh_colors(path, m, rgb, err);
  return ss_read_mesh_colors_memory(b, n, cli_in_name(path), m, rgb, err);
}

ss_status cli_read_stream(const char *path, int *is_stream, const char **buf, size_t *len, ss_error *err) {
  return stream_input(path, is_stream, buf, len, err);
}

/* ---- .npy vectors ---------------------------------------------------------------------------------
 * A file whose name ends in .npy (or whose bytes start with the NumPy magic, e.g. on standard input) is
 * read as NumPy: shape (n,), (n, 1) or (1, n) for a vector. For doubles, "F.npy:J" takes column J
 * (0-based) of an (n, k) array, e.g. one eigenvector of `eigs --evecs`. */

int cli_is_npy(const char *path) {
  size_t n = path ? strlen(path) : 0;
  return n > 4 && !strcmp(path + n - 4, ".npy");
}

static int is_npy_bytes(const char *b, size_t len) { return len >= 6 && !memcmp(b, "\x93NUMPY", 6); }

/* "F.npy:J" naming no existing file: *col = J and the path without ":J" in buf; else 0. */
static int npy_column(const char *path, char *buf, size_t cap, int *col) {
  const char *c = path ? strrchr(path, ':') : NULL;
  if (!c || c - path < 5 || strncmp(c - 4, ".npy", 4) || !c[1] || (size_t)(c - path) >= cap) return 0;
  struct stat st;
  if (stat(path, &st) == 0) return 0;
  long v = 0;
  for (const char *q = c + 1; *q; q++) {
    if (*q < '0' || *q > '9' || v > 100000000) return 0;
    v = v * 10 + (*q - '0');
  }
  memcpy(buf, path, (size_t)(c - path));
  buf[c - path] = '\0';
  *col = (int)v;
  return 1;
}

/* An (r, c) array as a vector of n values: a column `col` (>= 0) or the whole of a (n,), (n, 1), (1, n)
 * array; *a is replaced by the vector. */
static ss_status npy_vector(const char *name, void **a, size_t esz, int r, int c, int col, int *n, ss_error *err) {
  if (col >= 0) {
    if (col >= c) return ss_fail(err, SS_ERR_INVALID, "%s: column %d asked, the array has %d (shape (%d, %d))", name, col, c, r, c);
    memmove(*a, (char *)*a + esz * (size_t)r * (size_t)col, esz * (size_t)r);
    *n = r;
    return SS_OK;
  }
  if (r > 1 && c > 1)
    return ss_fail(err, SS_ERR_PARSE, "%s: shape (%d, %d) is not a vector (give one column as %s:J)", name, r, c, name);
  *n = r * c;
  return SS_OK;
}

static ss_status read_npy_vec(const char *path, int as_int, void **out, int *n, ss_error *err) {
  char plain[4096];
  int col = -1, r = 0, c = 0;
  const char *p = npy_column(path, plain, sizeof plain, &col) ? plain : path;
  if (col >= 0 && as_int) return ss_fail(err, SS_ERR_INVALID, "%s: a column (:J) is only for value fields", path);
  const char *b;
  size_t len;
  int is;
  ss_status st = stream_input(p, &is, &b, &len, err);
  if (st) return st;
  const char *name = cli_in_name(p);
  if (as_int)
    st = is ? ss_read_npy_ints_memory(b, len, name, (int **)out, &r, &c, err) : ss_read_npy_ints(p, (int **)out, &r, &c, err);
  else
    st = is ? ss_read_npy_memory(b, len, name, (double **)out, &r, &c, err) : ss_read_npy(p, (double **)out, &r, &c, err);
  if (!st) st = npy_vector(name, out, as_int ? sizeof(int) : sizeof(double), r, c, col, n, err);
  if (st) {
    free(*out);
    *out = NULL;
    *n = 0;
  }
  return st;
}

/* A stream (stdin, pipe) holding .npy bytes: 1. */
static int stream_is_npy(const char *path) {
  const char *b;
  size_t len;
  int is;
  ss_error e;
  if (!cli_is_std(path)) {
    struct stat st;
    if (stat(path, &st) != 0 || !(S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode))) return 0;
  }
  return stream_input(path, &is, &b, &len, &e) == SS_OK && is && is_npy_bytes(b, len);
}

static int wants_npy(const char *path) {
  char plain[4096];
  int col;
  return cli_is_npy(path) || npy_column(path, plain, sizeof plain, &col) || stream_is_npy(path);
}

ss_status cli_read_ints(const char *path, int **out, int *n, ss_error *err) {
  const char *b;
  size_t len;
  *out = NULL;
  *n = 0;
  if (wants_npy(path)) return read_npy_vec(path, 1, (void **)out, n, err);
  int is;
  ss_status st = stream_input(path, &is, &b, &len, err);
  if (st || !is) return st ? st : ss_read_ints(path, out, n, err);
  return ss_read_ints_memory(b, len, cli_in_name(path), out, n, err);
}

ss_status cli_read_ints_lines(const char *path, int **out, int **lines, int *n, ss_error *err) {
  const char *b;
  size_t len;
  *out = NULL;
  *lines = NULL;
  *n = 0;
  if (wants_npy(path)) { /* "line" i + 1 = entry i, so messages still point at the entry */
    ss_status st = read_npy_vec(path, 1, (void **)out, n, err);
    if (st) return st;
    if (!(*lines = malloc(sizeof(int) * (size_t)(*n > 0 ? *n : 1)))) {
      free(*out);
      *out = NULL;
      return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", cli_in_name(path));
    }
    for (int i = 0; i < *n; i++) (*lines)[i] = i + 1;
    return SS_OK;
  }
  int is;
  ss_status st = stream_input(path, &is, &b, &len, err);
  if (st || !is) return st ? st : ss_read_ints_lines(path, out, lines, n, err);
  return ss_read_ints_lines_memory(b, len, cli_in_name(path), out, lines, n, err);
}

ss_status cli_read_doubles(const char *path, double **out, int *n, ss_error *err) {
  const char *b;
  size_t len;
  *out = NULL;
  *n = 0;
  if (wants_npy(path)) return read_npy_vec(path, 0, (void **)out, n, err);
  int is;
  ss_status st = stream_input(path, &is, &b, &len, err);
  if (st || !is) return st ? st : ss_read_doubles(path, out, n, err);
  return ss_read_doubles_memory(b, len, cli_in_name(path), out, n, err);
}

ss_status cli_read_landmarks(const char *path, int **lx, int **ly, int **lines, int *n, int *columns, ss_error *err) {
  const char *b;
  size_t len;
  *lx = *ly = NULL;
  if (lines) *lines = NULL;
  *n = 0;
  if (columns) *columns = 0;
  if (wants_npy(path)) { /* (n,) or (n, 1): one column; (n, 2): "i j" pairs */
    int *a = NULL, r = 0, c = 0, is;
    const char *name = cli_in_name(path);
    ss_status st = stream_input(path, &is, &b, &len, err);
    if (!st) st = is ? ss_read_npy_ints_memory(b, len, name, &a, &r, &c, err) : ss_read_npy_ints(path, &a, &r, &c, err);
    if (st) return st;
    if (c > 2 || r == 0) {
      free(a);
      return ss_fail(err, SS_ERR_PARSE, "%s: landmarks need shape (n,), (n, 1) or (n, 2), not (%d, %d)", name, r, c);
    }
    int *x = malloc(sizeof(int) * (size_t)r), *y = malloc(sizeof(int) * (size_t)r);
    int *ln = lines ? malloc(sizeof(int) * (size_t)r) : NULL;
    if (!x || !y || (lines && !ln)) {
      free(a), free(x), free(y), free(ln);
      return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", name);
    }
    for (int i = 0; i < r; i++) {
      x[i] = a[i];
      y[i] = c == 2 ? a[r + i] : a[i];
      if (ln) ln[i] = i + 1;
      if (x[i] < 0 || y[i] < 0) {
        free(a), free(x), free(y), free(ln);
        return ss_fail(err, SS_ERR_PARSE, "%s: row %d: negative vertex index", name, i);
      }
    }
    free(a);
    *lx = x, *ly = y, *n = r;
    if (lines) *lines = ln;
    if (columns) *columns = c == 2 ? 2 : 1;
    return SS_OK;
  }
  int is;
  ss_status st = stream_input(path, &is, &b, &len, err);
  if (st || !is) return st ? st : ss_read_landmarks_lines(path, lx, ly, lines, n, columns, err);
  return ss_read_landmarks_memory(b, len, cli_in_name(path), lx, ly, lines, n, columns, err);
}

ss_status cli_read_matrix(const char *path, double **a, int *rows, int *cols, ss_error *err) {
  const char *b;
  size_t len;
  int is;
  *a = NULL;
  *rows = *cols = 0;
  ss_status st = stream_input(path, &is, &b, &len, err);
  if (st) return st;
  return is ? ss_read_npy_memory(b, len, cli_in_name(path), a, rows, cols, err) : ss_read_npy(path, a, rows, cols, err);
}

/* ---- standard output ------------------------------------------------------------------------------ */

/* The CLI's own text outputs go through util/out_file.h as the library's writers do (a temporary
 * renamed into place, symlinks followed, pipes and devices written directly): the open ones in a
 * table, as cli_close_out is given the FILE only (batch jobs open theirs on several threads). */
static pthread_mutex_t outs_lock = PTHREAD_MUTEX_INITIALIZER;
static ssi_out *outs;
static int nouts, couts;

FILE *cli_open_out(const char *path) {
  if (cli_is_std(path)) return stdout;
  ssi_out o;
  ss_error e;
  if (ssi_out_open(&o, path, &e)) return NULL; /* errno: the reason */
  pthread_mutex_lock(&outs_lock);
  if (nouts == couts) {
    ssi_out *g = realloc(outs, sizeof *outs * (size_t)(couts ? 2 * couts : 8));
    if (g) outs = g, couts = couts ? 2 * couts : 8;
  }
  int room = nouts < couts;
  if (room) outs[nouts++] = o;
  pthread_mutex_unlock(&outs_lock);
  if (!room) {
    ssi_out_abort(&o);
    errno = ENOMEM;
    return NULL;
  }
  return o.f;
}

int cli_close_out(FILE *f) {
  if (f == stdout || f == stderr) return ferror(f) | fflush(f) ? -1 : 0;
  ssi_out o = {0};
  pthread_mutex_lock(&outs_lock);
  for (int i = 0; i < nouts; i++)
    if (outs[i].f == f) {
      o = outs[i];
      outs[i] = outs[--nouts];
      break;
    }
  pthread_mutex_unlock(&outs_lock);
  if (!o.f) return fclose(f) ? -1 : 0; /* not opened by cli_open_out */
  ss_error e;
  return ssi_out_commit(&o, o.target, &e) ? -1 : 0;
}

/* A name's file: the same device and inode (through symlinks), or the same name when absent. */
static int same_output(const char *a, const char *b) {
  struct stat x, y;
  if (stat(a, &x) == 0 && stat(b, &y) == 0) return x.st_dev == y.st_dev && x.st_ino == y.st_ino;
  return !strcmp(a, b);
}

int cli_output_clash(const char *const *outp, int nout, const char *const *inp, int nin, const char **o, const char **in) {
  for (int i = 0; i < nout; i++) {
    if (!outp[i] || cli_is_std(outp[i])) continue;
    struct stat st; /* a pipe or a device is written, not replaced: /dev/null as input and output is fine */
    if (stat(outp[i], &st) == 0 && !S_ISREG(st.st_mode)) continue;
    for (int k = 0; k < nin; k++)
      if (inp[k] && !cli_is_std(inp[k]) && same_output(outp[i], inp[k])) return *o = outp[i], *in = inp[k], 1;
    for (int k = 0; k < i; k++)
      if (outp[k] && !cli_is_std(outp[k]) && same_output(outp[i], outp[k])) return *o = outp[i], *in = NULL, 2;
  }
  return 0;
}

int cli_check_outputs(cli_args *A, const char *const *outp, int nout, const char *const *inp, int nin) {
  const char *o, *in;
  int c = cli_output_clash(outp, nout, inp, nin, &o, &in);
  if (c == 1) return cli_bad(A, "the output %s would overwrite the input %s (choose another output name)", o, in);
  if (c == 2) return cli_bad(A, "two outputs would be %s", o);
  return -1;
}

/* Text vectors on stdout, in the format of ss_write_ints / ss_write_doubles. */
static ss_status write_values_stdout(const int *iv, const double *dv, int n, ss_error *err) {
  if (n < 0 || (n > 0 && !iv && !dv)) return ss_fail(err, SS_ERR_INVALID, STDOUT_NAME ": invalid vector (n = %d)", n);
  for (int i = 0; i < n && !ferror(stdout); i++) {
    if (iv) printf("%d\n", iv[i]);
    else printf("%.17g\n", dv[i]);
  }
  if (cli_close_out(stdout)) return ss_fail(err, SS_ERR_IO, STDOUT_NAME ": write error: %s", strerror(errno));
  return SS_OK;
}

/* By extension: F.npy gets an (n, 1) array ('<i4' / '<f8', shape (n, 1)), anything else text lines. */
ss_status cli_write_ints(const char *path, const int *v, int n, ss_error *err) {
  if (cli_is_npy(path)) return ss_write_npy_ints(path, v, n, 1, err);
  return cli_is_std(path) ? write_values_stdout(v, NULL, n, err) : ss_write_ints(path, v, n, err);
}

ss_status cli_write_doubles(const char *path, const double *v, int n, ss_error *err) {
  if (cli_is_npy(path)) return ss_write_npy(path, v, n, 1, err);
  return cli_is_std(path) ? write_values_stdout(NULL, v, n, err) : ss_write_doubles(path, v, n, err);
}

/* The library's writers take a path: for "-" they write a file in a fresh temporary folder, whose
 * bytes are then copied to stdout; messages name <stdout> instead of the temporary file. */
typedef struct out_job {
  enum { JOB_MESH, JOB_NPY, JOB_PNG } what;
  const char *kind; /* "PNG", ... for messages */
  int binary;       /* refused on a terminal */
  const char *ext;  /* of the temporary file: chooses the format */
  const ss_mesh *m;
  const unsigned char *rgb;
  const double *a;
  int w, h;
  const int *labels; /* meshes: a PLY's label property (NULL: none) */
} out_job;

static ss_status run_job(const out_job *j, const char *path, ss_error *err) {
  switch (j->what) {
    case JOB_MESH: return ss_write_mesh_labels(path, j->m, j->rgb, j->labels, err);
    case JOB_NPY: return ss_write_npy(path, j->a, j->w, j->h, err);
    default: return ss_write_png(path, j->rgb, j->w, j->h, err);
  }
}

/* Replaces every occurrence of `from` in msg by `to`. */
static void rename_in_message(char *msg, size_t cap, const char *from, const char *to) {
  char out[sizeof ((ss_error *)0)->msg];
  size_t fl = strlen(from), k = 0;
  if (!fl) return;
  for (const char *p = msg; *p && k + 1 < sizeof out;) {
    if (!strncmp(p, from, fl)) {
      k += (size_t)snprintf(out + k, sizeof out - k, "%s", to);
      if (k >= sizeof out) k = sizeof out - 1;
      p += fl;
    } else {
      out[k++] = *p++;
    }
  }
  out[k] = '\0';
  snprintf(msg, cap, "%s", out);
}

static ss_status write_via_temp(const out_job *j, ss_error *err) {
  if (j->binary && isatty(STDOUT_FILENO))
    return ss_fail(err, SS_ERR_INVALID, STDOUT_NAME ": not writing binary %s data to a terminal (redirect it)", j->kind);
  const char *tmp = getenv("TMPDIR");
  char dir[4096], file[4200];
  if (!tmp || !*tmp) tmp = "/tmp";
  if (snprintf(dir, sizeof dir, "%s/specseg-XXXXXX", tmp) >= (int)sizeof dir)
    return ss_fail(err, SS_ERR_IO, STDOUT_NAME ": temporary folder name too long");
  if (!mkdtemp(dir)) return ss_fail(err, SS_ERR_IO, STDOUT_NAME ": cannot create a temporary folder in %s: %s", tmp, strerror(errno));
  snprintf(file, sizeof file, "%s/stdout.%s", dir, j->ext);
  ss_status st = run_job(j, file, err);
  if (st) {
    if (err) rename_in_message(err->msg, sizeof err->msg, file, STDOUT_NAME);
  } else {
    FILE *f = fopen(file, "rb");
    if (!f) {
      st = ss_fail(err, SS_ERR_IO, STDOUT_NAME ": cannot read back the temporary file: %s", strerror(errno));
    } else {
      char buf[65536];
      size_t n;
      while ((n = fread(buf, 1, sizeof buf, f)) > 0)
        if (fwrite(buf, 1, n, stdout) != n) break;
      int bad_in = ferror(f);
      fclose(f);
      if (bad_in) st = ss_fail(err, SS_ERR_IO, STDOUT_NAME ": cannot read back the temporary file");
      else if (cli_close_out(stdout)) st = ss_fail(err, SS_ERR_IO, STDOUT_NAME ": write error: %s", strerror(errno));
    }
  }
  remove(file);
  rmdir(dir);
  return st;
}

ss_status cli_write_mesh_labels(const char *path, const ss_mesh *m, const unsigned char *rgb, const int *labels,
                                const char *std_ext, ss_error *err) {
  if (!cli_is_std(path)) return ss_write_mesh_labels(path, m, rgb, labels, err);
  int ply = !strcmp(std_ext, "ply");
  out_job j = {JOB_MESH, ply ? "PLY" : "OFF", ply, std_ext, m, rgb, NULL, 0, 0, labels};
  return write_via_temp(&j, err);
}

ss_status cli_write_mesh(const char *path, const ss_mesh *m, const unsigned char *rgb, const char *std_ext,
                         ss_error *err) {
  return cli_write_mesh_labels(path, m, rgb, NULL, std_ext, err);
}

ss_status cli_write_png(const char *path, const unsigned char *rgb, int w, int h, ss_error *err) {
  if (!cli_is_std(path)) return ss_write_png(path, rgb, w, h, err);
  out_job j = {JOB_PNG, "PNG", 1, "png", NULL, rgb, NULL, w, h, NULL};
  return write_via_temp(&j, err);
}

ss_status cli_write_npy(const char *path, const double *a, int rows, int cols, ss_error *err) {
  if (!cli_is_std(path)) return ss_write_npy(path, a, rows, cols, err);
  out_job j = {JOB_NPY, ".npy", 1, "npy", NULL, NULL, a, rows, cols, NULL};
  return write_via_temp(&j, err);
}
