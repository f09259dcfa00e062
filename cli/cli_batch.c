/* Batch runs of the per-mesh commands (several meshes or folders, -o OUTDIR, --jobs N, a progress bar on
 * a terminal) and the machine-readable summaries (--json) of every command that has one; see cli.h.
 * Also where the diagnostics of cli_error / cli_warn / cli_usage go: stderr (serialised, clearing the
 * progress bar first) and the JSON record of the job running on the calling thread. */
#include <dirent.h>
#include <errno.h>
#include <omp.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"

/* ---- diagnostics ------------------------------------------------------------------------------------ */

static pthread_mutex_t err_lock = PTHREAD_MUTEX_INITIALIZER;
static _Thread_local cli_job *current_job;
static int bar_shown;     /* the progress bar is on the last line of stderr */
static char bar_text[256];

static char *dup_str(const char *s) {
  size_t n = strlen(s) + 1;
  char *d = malloc(n);
  if (d) memcpy(d, s, n);
  return d;
}

static void note(cli_job *j, const char *kind, const char *msg) {
  if (!j) return;
  if (!strcmp(kind, "warning")) {
    char **w = realloc(j->warnings, sizeof *w * (size_t)(j->nwarnings + 1));
    if (!w) return;
    j->warnings = w;
    if ((w[j->nwarnings] = dup_str(msg))) j->nwarnings++;
  } else if (!j->error) {
    j->error = dup_str(msg); /* the first error is the cause */
  }
}

void cli_diag(const char *kind, const char *fmt, va_list ap) {
  char msg[2048];
  vsnprintf(msg, sizeof msg, fmt, ap);
  pthread_mutex_lock(&err_lock);
  if (bar_shown) fputs("\r\033[K", stderr);
  fprintf(stderr, "specseg: %s: %s\n", kind, msg);
  if (bar_shown) fputs(bar_text, stderr);
  fflush(stderr);
  note(current_job, kind, msg);
  pthread_mutex_unlock(&err_lock);
}

/* ---- JSON ------------------------------------------------------------------------------------------- */

/* The length of the valid UTF-8 sequence at p (1..4), or 0 when it is not one (RFC 3629: no
 * overlong forms, no surrogates, nothing above U+10FFFF). */
static int utf8_len(const unsigned char *p) {
  const unsigned char c = p[0];
  if (c < 0x80) return 1;
  int n = c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3 : c >= 0xF0 && c <= 0xF4 ? 4 : 0;
  if (!n) return 0;
  unsigned char lo = 0x80, hi = 0xBF; /* the second byte's range */
  if (c == 0xE0) lo = 0xA0;
  else if (c == 0xED) hi = 0x9F;
  else if (c == 0xF0) lo = 0x90;
  else if (c == 0xF4) hi = 0x8F;
  if (p[1] < lo || p[1] > hi) return 0;
  for (int i = 2; i < n; i++)
    if ((p[i] & 0xC0) != 0x80) return 0;
  return n;
}

/* A JSON string: file names are bytes, JSON text is UTF-8; a byte that is not part of valid UTF-8 is
 * written as \udcXX (XX the byte), Python's surrogateescape: json.loads then os.fsencode gives the
 * name's bytes back, and the output stays valid UTF-8 JSON. */
static void json_str(FILE *f, const char *s) {
  fputc('"', f);
  for (const unsigned char *p = (const unsigned char *)s; p && *p; p++) {
    int n = utf8_len(p);
    if (n == 0) {
      fprintf(f, "\\udc%02x", *p);
      continue;
    }
    if (n > 1) {
      fwrite(p, 1, (size_t)n, f);
      p += n - 1;
      continue;
    }
    if (*p == '"' || *p == '\\') fprintf(f, "\\%c", *p);
    else if (*p == '\n') fputs("\\n", f);
    else if (*p == '\t') fputs("\\t", f);
    else if (*p < 0x20) fprintf(f, "\\u%04x", *p);
    else fputc(*p, f);
  }
  fputc('"', f);
}

static void json_num(FILE *f, double v) {
  if (v != v || v - v != 0) fputs("null", f); /* NaN, inf */
  else fprintf(f, "%.17g", v);
}

static cli_field *field(cli_job *j, const char *key) {
  if (!j) return NULL;
  cli_field *g = realloc(j->fields, sizeof *g * (size_t)(j->nfields + 1));
  if (!g) return NULL;
  j->fields = g;
  cli_field *f = &g[j->nfields++];
  memset(f, 0, sizeof *f);
  snprintf(f->key, sizeof f->key, "%s", key);
  return f;
}

void cli_job_int(cli_job *j, const char *key, long v) {
  cli_field *f = field(j, key);
  if (f) f->kind = 'i', f->i = v;
}
void cli_job_num(cli_job *j, const char *key, double v) {
  cli_field *f = field(j, key);
  if (f) f->kind = 'd', f->d = v;
}
void cli_job_str(cli_job *j, const char *key, const char *v) {
  cli_field *f = field(j, key);
  if (f && v && (f->s = dup_str(v))) f->kind = 's';
  else if (f) f->kind = 'n';
}

void cli_job_json(cli_job *j, const char *key, const char *json) {
  cli_field *f = field(j, key);
  if (f && json && (f->s = dup_str(json))) f->kind = 'j';
  else if (f) f->kind = 'n';
}

void cli_json_str(FILE *f, const char *s) { json_str(f, s); }
void cli_json_num(FILE *f, double v) { json_num(f, v); }

static void json_job(FILE *f, const cli_job *j, const char *indent) {
  fprintf(f, "{");
  int first = 1;
#define KEY(k) fprintf(f, "%s\n%s  \"%s\": ", first ? "" : ",", indent, k), first = 0
  if (j->input) KEY("input"), json_str(f, j->input);
  KEY("ok"), fputs(j->rc == 0 ? "true" : "false", f);
  KEY("seconds"), json_num(f, j->seconds);
  KEY("outputs"), fputc('[', f);
  for (int i = 0; i < j->noutputs; i++) fputs(i ? ", " : "", f), json_str(f, j->outputs[i]);
  fputc(']', f);
  KEY("warnings"), fputc('[', f);
  for (int i = 0; i < j->nwarnings; i++) fputs(i ? ", " : "", f), json_str(f, j->warnings[i]);
  fputc(']', f);
  if (j->rc) KEY("error"), json_str(f, j->error ? j->error : "failed");
  for (int i = 0; i < j->nfields; i++) {
    const cli_field *x = &j->fields[i];
    KEY(x->key);
    if (x->kind == 'i') fprintf(f, "%ld", x->i);
    else if (x->kind == 'd') json_num(f, x->d);
    else if (x->kind == 's') json_str(f, x->s);
    else if (x->kind == 'j') fputs(x->s, f);
    else fputs("null", f);
  }
#undef KEY
  fprintf(f, "\n%s}", indent);
}

/* ---- jobs ------------------------------------------------------------------------------------------- */

void cli_job_begin(cli_job *j, const char *input) {
  memset(j, 0, sizeof *j);
  j->input = input;
  j->t0 = ss_time();
  current_job = j;
}

static void job_free(cli_job *j) {
  for (int i = 0; i < j->noutputs; i++) free(j->outputs[i]);
  for (int i = 0; i < j->nwarnings; i++) free(j->warnings[i]);
  for (int i = 0; i < j->nfields; i++) free(j->fields[i].s);
  free(j->outputs), free(j->warnings), free(j->fields), free(j->error);
  if (j->rep) fclose(j->rep);
  free(j->rep_buf);
  if (current_job == j) current_job = NULL;
  memset(j, 0, sizeof *j);
}

/* {"command": ..., "ok": N, "failed": N, "seconds": S, "jobs": J, "results": [job, ...]} on stdout */
static int print_json_skipped(const char *cmd, const cli_job *jobs, int n, int failed, double seconds, int nthreads,
                              char *const *skipped, int nskipped) {
  printf("{\n  \"command\": ");
  json_str(stdout, cmd);
  printf(",\n  \"ok\": %d,\n  \"failed\": %d,\n  \"seconds\": ", n - failed, failed);
  json_num(stdout, seconds);
  printf(",\n  \"jobs\": %d,", nthreads);
  if (nskipped) { /* folder entries that are not meshes: listed, as they were warned about */
    printf("\n  \"skipped\": [");
    for (int i = 0; i < nskipped; i++) printf("%s", i ? ", " : ""), json_str(stdout, skipped[i]);
    printf("],");
  }
  printf("\n  \"results\": [");
  for (int i = 0; i < n; i++) {
    printf("%s", i ? ", " : "");
    json_job(stdout, &jobs[i], "    ");
  }
  printf("]\n}\n");
  return fflush(stdout) ? -1 : 0;
}

static int print_json(const char *cmd, const cli_job *jobs, int n, int failed, double seconds, int nthreads) {
  return print_json_skipped(cmd, jobs, n, failed, seconds, nthreads, NULL, 0);
}

int cli_job_end(cli_job *j, const char *cmd, int rc, int json) {
  j->rc = rc;
  j->seconds = ss_time() - j->t0;
  current_job = NULL;
  if (json && print_json(cmd, j, 1, rc != 0, j->seconds, 1) && !rc) rc = cli_error("cannot write to standard output");
  job_free(j);
  return rc;
}

static void add_output(cli_job *j, const char *path) {
  if (!path || cli_is_std(path)) return;
  char **o = realloc(j->outputs, sizeof *o * (size_t)(j->noutputs + 1));
  if (!o) return;
  j->outputs = o;
  if ((o[j->noutputs] = dup_str(path))) j->noutputs++;
}

/* OUTDIR/STEM + suffix for input `in` */
static char *batch_path(const cli_batch *b, const char *in, const char *suffix) {
  const char *base = strrchr(in, '/');
  base = base ? base + 1 : in;
  const char *dot = strrchr(base, '.');
  size_t stem = dot && dot > base ? (size_t)(dot - base) : strlen(base);
  size_t od = strlen(b->outdir);
  while (od > 1 && b->outdir[od - 1] == '/') od--;
  size_t n = od + 1 + stem + strlen(suffix) + 1;
  char *p = malloc(n);
  if (p) snprintf(p, n, "%.*s/%.*s%s", (int)od, b->outdir, (int)stem, base, suffix);
  return p;
}

const char *cli_job_output(cli_job *j, const char *given, const char *suffix) {
  const char *p = given;
  char *made = NULL;
  if (j->b && j->b->batch) {
    if (!j->b->outdir || !suffix) return NULL; /* a batch without -o: reports only */
    p = made = batch_path(j->b, j->input, j->b->suffix ? j->b->suffix : suffix);
  }
  add_output(j, p);
  if (made) {
    free(made);
    return j->noutputs ? j->outputs[j->noutputs - 1] : NULL;
  }
  return p;
}

const char *cli_job_extra(cli_job *j, const char *given) {
  if (!given) return NULL;
  if (j->b && j->b->batch) {
    if (!j->b->outdir) return NULL;
    char *made = batch_path(j->b, j->input, given);
    add_output(j, made);
    free(made);
    return j->noutputs ? j->outputs[j->noutputs - 1] : NULL;
  }
  add_output(j, given);
  return given;
}

FILE *cli_job_report(cli_job *j, int data_on_stdout) {
  if (j->rep) return j->rep;
  if ((j->b && j->b->batch) || (j->b && j->b->json)) {
    if ((j->rep = open_memstream(&j->rep_buf, &j->rep_len))) return j->rep;
  }
  return data_on_stdout || (j->b && j->b->json) ? stderr : stdout;
}

/* ---- batch setup ------------------------------------------------------------------------------------ */

void cli_batch_init(cli_batch *b, const char *cmd) {
  memset(b, 0, sizeof *b);
  b->cmd = cmd;
}

void cli_batch_free(cli_batch *b) {
  for (int i = 0; i < b->nin; i++) free(b->in[i]);
  free(b->in);
  b->in = NULL;
  b->nin = b->cap = 0;
  for (int i = 0; i < b->nskipped; i++) free(b->skipped[i]);
  free(b->skipped);
  b->skipped = NULL;
  b->nskipped = 0;
}

int cli_batch_suffix(cli_args *A, const cli_opt *o, const char *suffix) {
  cli_batch *b = o->dest;
  b->suffix = suffix;
  if (suffix[0] != '.' || strchr(suffix, '/'))
    return cli_bad(A, "--suffix takes a suffix such as .npy or .labels.txt, not '%s'", suffix);
  return -1;
}

static int push_input(cli_batch *b, const char *path) {
  if (b->nin == b->cap) {
    int cap = b->cap ? 2 * b->cap : 16;
    char **g = realloc(b->in, sizeof *g * (size_t)cap);
    if (!g) return -1;
    b->in = g, b->cap = cap;
  }
  if (!(b->in[b->nin] = dup_str(path))) return -1;
  b->nin++;
  return 0;
}

static int cmp_name(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

static int has_sss(const char *p) {
  size_t n = strlen(p);
  return n > 4 && !strcmp(p + n - 4, ".sss");
}

/* the mesh files of a folder (extensions the library reads, no hidden files), sorted by name */
static int add_folder(cli_batch *b, cli_args *A, const char *dir) {
  DIR *d = opendir(dir);
  if (!d) return cli_bad(A, "%s: cannot open the folder: %s", dir, strerror(errno));
  int first = b->nin, skipped = 0;
  size_t dl = strlen(dir);
  while (dl > 1 && dir[dl - 1] == '/') dl--;
  struct dirent *e;
  while ((e = readdir(d))) {
    if (e->d_name[0] == '.') continue;
    size_t n = dl + 1 + strlen(e->d_name) + 1;
    char *p = malloc(n);
    if (!p) { closedir(d); return cli_error("out of memory"); }
    snprintf(p, n, "%.*s/%s", (int)dl, dir, e->d_name);
    struct stat st;
    /* meshes and prepared shapes (every per-mesh command reads a .sss as its mesh) */
    int take = stat(p, &st) == 0 && S_ISREG(st.st_mode) && (ss_mesh_extension_supported(p) || has_sss(p));
    if (take && push_input(b, p)) { free(p); closedir(d); return cli_error("out of memory"); }
    if (!take) { /* said, not dropped silently: a subfolder, a file of another kind */
      char **g = realloc(b->skipped, sizeof *g * (size_t)(b->nskipped + 1));
      if (g) b->skipped = g, g[b->nskipped++] = dup_str(p);
      skipped++;
    }
    free(p);
  }
  closedir(d);
  if (b->nin == first) return cli_bad(A, "%s: no mesh files (OFF, OBJ, PLY, STL, glTF%s, prepared shapes .sss) in the folder",
                                      dir, ss_mesh_extension_supported("x.fbx") ? ", FBX, ..." : "");
  qsort(b->in + first, (size_t)(b->nin - first), sizeof *b->in, cmp_name);
  if (skipped)
    cli_warn("%s: %d entr%s skipped (subfolders, files that are neither meshes nor prepared shapes)", dir, skipped,
             skipped == 1 ? "y" : "ies");
  return -1;
}

int cli_batch_add(cli_batch *b, cli_args *A, const char *mesh) {
  struct stat st;
  if (!cli_is_std(mesh) && stat(mesh, &st) == 0 && S_ISDIR(st.st_mode)) {
    b->batch = 1;
    return add_folder(b, A, mesh);
  }
  if (push_input(b, mesh)) return cli_error("out of memory");
  return -1;
}

int cli_batch_pos(cli_args *A, const cli_opt *o, const char *mesh) { return cli_batch_add(o->dest, A, mesh); }

static int same_file(const char *a, const char *b) {
  struct stat x, y;
  return stat(a, &x) == 0 && stat(b, &y) == 0 && x.st_dev == y.st_dev && x.st_ino == y.st_ino;
}

static int mkdir_p(const char *dir) {
  char p[4096];
  if (snprintf(p, sizeof p, "%s", dir) >= (int)sizeof p) return -1;
  for (char *s = p + 1; *s; s++)
    if (*s == '/') {
      *s = '\0';
      if (mkdir(p, 0777) && errno != EEXIST) return -1;
      *s = '/';
    }
  if (mkdir(p, 0777) && errno != EEXIST) return -1;
  struct stat st;
  return stat(p, &st) == 0 && S_ISDIR(st.st_mode) ? 0 : -1;
}

int cli_batch_setup(cli_batch *b, cli_args *A, const char *outdir, int need_out, const char *main_suffix,
                    const char *const *extras, int nextras) {
  if (b->nin == 0) return cli_bad(A, "no mesh given");
  struct stat st;
  size_t ol = outdir ? strlen(outdir) : 0;
  if (b->nin > 1 || (outdir && !cli_is_std(outdir) && ((ol && outdir[ol - 1] == '/') || (stat(outdir, &st) == 0 && S_ISDIR(st.st_mode)))))
    b->batch = 1;
  if (!b->batch) {
    if (b->suffix) return cli_bad(A, "--suffix is for batches (several meshes, a folder, or -o a folder)");
    const char *outs[16] = {outdir}; /* one mesh: its outputs are file names; none may be the input */
    int no = 1;
    for (int e = 0; e < nextras && no < 16; e++) outs[no++] = extras[e];
    return cli_check_outputs(A, outs, no, (const char *const *)b->in, 1);
  }
  for (int i = 0; i < b->nin; i++)
    if (cli_is_std(b->in[i])) return cli_bad(A, "a batch reads mesh files, not standard input ('-')");
  if (!outdir && need_out) return cli_bad(A, "a batch needs -o OUTDIR (a folder for the outputs)");
  if (outdir && cli_is_std(outdir)) return cli_bad(A, "a batch writes into a folder: -o OUTDIR, not '-'");
  for (int e = 0; e < nextras; e++)
    if (extras[e] && (extras[e][0] != '.' || strchr(extras[e], '/')))
      return cli_bad(A, "in a batch the other outputs take a suffix after the mesh's name (such as .ply), not '%s'", extras[e]);
  b->outdir = outdir;
  if (!outdir) return -1;
  /* every output: distinct, and none of them an input */
  int nsuf = 1 + nextras, nout = b->nin * nsuf, rc = -1;
  char **all = calloc((size_t)nout, sizeof *all);
  if (!all) return cli_error("out of memory");
  for (int i = 0; i < b->nin && rc < 0; i++)
    for (int s = 0; s < nsuf && rc < 0; s++) {
      const char *suf = s == 0 ? (b->suffix ? b->suffix : main_suffix) : extras[s - 1];
      if (!suf) continue;
      char *p = all[i * nsuf + s] = batch_path(b, b->in[i], suf);
      if (!p) rc = cli_error("out of memory");
      for (int k = 0; rc < 0 && p && k < b->nin; k++)
        if (same_file(p, b->in[k])) rc = cli_bad(A, "%s would overwrite the input %s (choose another -o or --suffix)", p, b->in[k]);
    }
  if (rc < 0) {
    char **sorted = malloc(sizeof *sorted * (size_t)nout);
    int m = 0;
    for (int i = 0; sorted && i < nout; i++)
      if (all[i]) sorted[m++] = all[i];
    if (sorted) qsort(sorted, (size_t)m, sizeof *sorted, cmp_name);
    for (int i = 1; sorted && rc < 0 && i < m; i++)
      if (!strcmp(sorted[i], sorted[i - 1]))
        rc = cli_bad(A, "two outputs would be %s (meshes of the same name, in two folders or with two extensions?)",
                     sorted[i]);
    free(sorted);
  }
  for (int i = 0; i < nout; i++) free(all[i]);
  free(all);
  if (rc < 0 && mkdir_p(outdir)) rc = cli_error("%s: cannot create the folder: %s", outdir, strerror(errno));
  return rc;
}

/* ---- running ---------------------------------------------------------------------------------------- */

typedef struct runner {
  cli_batch *b;
  cli_job_fn fn;
  void *cfg;
  cli_job *jobs;
  int next, done, failed, omp_threads;
  double t0;
  int bar;
  pthread_mutex_t lock;
} runner;

static void draw_bar(runner *r) { /* under err_lock */
  const int w = 30, n = r->b->nin;
  int fill = n ? w * r->done / n : w;
  char bar[64];
  for (int i = 0; i < w; i++) bar[i] = i < fill ? '#' : '.';
  bar[w] = '\0';
  double el = ss_time() - r->t0;
  char eta[32] = "";
  if (r->done > 0 && r->done < n) snprintf(eta, sizeof eta, ", ETA %.0f s", el / r->done * (n - r->done));
  char failed[32] = "";
  if (r->failed) snprintf(failed, sizeof failed, ", %d failed", r->failed);
  snprintf(bar_text, sizeof bar_text, "  %s [%s] %d/%d meshes%s, %.1f s%s", r->b->cmd, bar, r->done, n, failed, el, eta);
  fprintf(stderr, "\r\033[K%s", bar_text);
  fflush(stderr);
  bar_shown = 1;
}

static void *worker(void *arg) {
  runner *r = arg;
  omp_set_num_threads(r->omp_threads);
  for (;;) {
    pthread_mutex_lock(&r->lock);
    int i = r->next < r->b->nin ? r->next++ : -1;
    pthread_mutex_unlock(&r->lock);
    if (i < 0) break;
    cli_job *j = &r->jobs[i];
    const char *in = j->input;
    cli_job_begin(j, in);
    j->b = r->b;
    j->index = i;
    int rc = r->fn(j, r->cfg);
    j->rc = rc;
    j->seconds = ss_time() - j->t0;
    current_job = NULL;
    if (j->rep) fflush(j->rep);
    pthread_mutex_lock(&r->lock);
    r->done++;
    r->failed += rc != 0;
    pthread_mutex_unlock(&r->lock);
    if (r->bar) {
      pthread_mutex_lock(&err_lock);
      draw_bar(r);
      pthread_mutex_unlock(&err_lock);
    }
  }
  return NULL;
}

static int ncpu(void) {
  long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? (int)n : 1;
}

int cli_batch_finish(cli_batch *b, int rc, cli_job_fn fn, void *cfg) {
  if (rc < 0) return cli_batch_run(b, fn, cfg);
  cli_batch_free(b);
  return rc;
}

int cli_batch_run(cli_batch *b, cli_job_fn fn, void *cfg) {
  if (!b->batch) { /* one mesh: the command as it always was, plus --json */
    cli_job j;
    cli_job_begin(&j, b->in[0]);
    j.b = b;
    int rc = fn(&j, cfg);
    j.rc = rc;
    j.seconds = ss_time() - j.t0;
    current_job = NULL;
    if (b->json && print_json(b->cmd, &j, 1, rc != 0, j.seconds, 1) && !rc) rc = cli_error("cannot write to standard output");
    job_free(&j);
    cli_batch_free(b);
    return rc;
  }
  runner r;
  memset(&r, 0, sizeof r);
  r.b = b, r.fn = fn, r.cfg = cfg, r.t0 = ss_time();
  r.bar = isatty(STDERR_FILENO);
  pthread_mutex_init(&r.lock, NULL);
  int jobs = b->jobs ? b->jobs : ncpu();
  if (jobs > b->nin) jobs = b->nin;
  int omp = omp_get_max_threads() / jobs;
  r.omp_threads = omp > 0 ? omp : 1;
  r.jobs = calloc((size_t)b->nin, sizeof *r.jobs);
  pthread_t *th = calloc((size_t)jobs, sizeof *th);
  if (!r.jobs || !th) {
    free(r.jobs), free(th);
    cli_batch_free(b);
    return cli_error("out of memory");
  }
  for (int i = 0; i < b->nin; i++) r.jobs[i].input = b->in[i];
  if (r.bar) {
    pthread_mutex_lock(&err_lock);
    draw_bar(&r);
    pthread_mutex_unlock(&err_lock);
  }
  int started = 0;
  for (int t = 0; t < jobs; t++)
    if (pthread_create(&th[t], NULL, worker, &r) == 0) started++;
  if (started == 0) worker(&r); /* no threads to be had: run them here */
  for (int t = 0; t < started; t++) pthread_join(th[t], NULL);
  double total = ss_time() - r.t0;
  pthread_mutex_lock(&err_lock);
  if (bar_shown) fputs("\r\033[K", stderr), fflush(stderr);
  bar_shown = 0;
  pthread_mutex_unlock(&err_lock);
  int rc = r.failed ? SS_EXIT_FAIL : SS_EXIT_OK;
  if (b->json) {
    if (print_json_skipped(b->cmd, r.jobs, b->nin, r.failed, total, jobs, b->skipped, b->nskipped) && !rc) rc = cli_error("cannot write to standard output");
  } else { /* each mesh's report, in the order given, its lines prefixed by the mesh */
    for (int i = 0; i < b->nin; i++) {
      const cli_job *j = &r.jobs[i];
      const char *s = j->rep_buf;
      while (s && *s) {
        const char *e = strchr(s, '\n');
        size_t n = e ? (size_t)(e - s) : strlen(s);
        printf("%s: %.*s\n", j->input, (int)n, s);
        s += n + (e != NULL);
      }
    }
  }
  if (fflush(stdout) && !rc) rc = cli_error("cannot write to standard output");
  fprintf(stderr, "specseg %s: %d meshes, %d done, %d failed, %.2f s (%d at a time)%s%s\n", b->cmd, b->nin, b->nin - r.failed,
          r.failed, total, jobs, b->outdir ? " -> " : "", b->outdir ? b->outdir : "");
  for (int i = 0; i < b->nin; i++) job_free(&r.jobs[i]);
  free(r.jobs), free(th);
  pthread_mutex_destroy(&r.lock);
  cli_batch_free(b);
  return rc;
}
