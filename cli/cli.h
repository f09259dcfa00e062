/* The specseg program: one file per subcommand, each a thin shell over library calls. */
#ifndef SPECSEG_CLI_H
#define SPECSEG_CLI_H

#include <stdarg.h>
#include <stdio.h>

#include "specseg/specseg.h"

/* Exit codes. */
enum { SS_EXIT_OK = 0, SS_EXIT_FAIL = 1, SS_EXIT_USAGE = 2 };

/* "specseg: error: MSG" on stderr; returns SS_EXIT_FAIL. */
int cli_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* "specseg: usage: ..." on stderr; returns SS_EXIT_USAGE. */
int cli_usage(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* "specseg: warning: MSG" on stderr. */
void cli_warn(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* Strict number parsing for options: whole string must be a number in range. 0 on success. */
int cli_parse_int(const char *s, long lo, long hi, int *out);
int cli_parse_double(const char *s, double *out);

/* ---- Options and positional arguments: cli_options.h (one table per command, cli_parse). ---------- */
#include "cli_options.h"

/* ---- Files (cli_io.c): "-" is standard input or standard output. -------------------------------
 * Standard input (named "<stdin>" in messages) and named pipes such as `<(...)` are read once, whole,
 * and given to the library's in-memory readers; a later read of the same name gets the same bytes.
 * Regular files go to the library's path readers. Text outputs to "-" go to stdout; binary ones
 * (PNG, .npy, PLY) too, unless stdout is a terminal. */
int cli_is_std(const char *path);          /* path is "-" */
const char *cli_in_name(const char *path); /* "<stdin>" for "-", else path */
const char *cli_out_name(const char *path); /* "<stdout>" for "-", else path */
/* How many of the n paths (NULLs skipped) are "-". */
int cli_count_std(const char *const *paths, int n);
ss_status cli_read_mesh(const char *path, ss_mesh *m, ss_error *err);
/* The mesh and its vertex colours (*rgb: 3 nv malloc'd bytes, or NULL when the file has none). */
ss_status cli_read_mesh_colors(const char *path, ss_mesh *m, unsigned char **rgb, ss_error *err);
/* Vectors (labels, maps, fields, landmarks): text, or NumPy when the name ends in .npy or the bytes
 * start with the NumPy magic (standard input): shape (n,), (n, 1) or (1, n); landmarks also (n, 2);
 * fields also "F.npy:J", column J of an (n, k) array. Writers: .npy by extension ((n, 1) '<i4' /
 * '<f8'), else text. */
int cli_is_npy(const char *path);
ss_status cli_read_ints(const char *path, int **out, int *n, ss_error *err);
ss_status cli_read_ints_lines(const char *path, int **out, int **lines, int *n, ss_error *err); /* + line numbers */
ss_status cli_read_doubles(const char *path, double **out, int *n, ss_error *err);
ss_status cli_read_landmarks(const char *path, int **lx, int **ly, int **lines, int *n, int *columns, ss_error *err);
/* A float64 matrix from .npy (file, standard input or pipe): *a malloc'd rows x cols column-major; a
 * 1-D array is one column. */
ss_status cli_read_matrix(const char *path, double **a, int *rows, int *cols, ss_error *err);
ss_status cli_write_ints(const char *path, const int *v, int n, ss_error *err);
ss_status cli_write_doubles(const char *path, const double *v, int n, ss_error *err);
/* A mesh by the extension of path; "-" writes format `std_ext` ("off" or "ply") to stdout. */
ss_status cli_write_mesh(const char *path, const ss_mesh *m, const unsigned char *rgb, const char *std_ext,
                         ss_error *err);
/* The same with a PLY's integer vertex property `label` (labels NULL: none; other formats drop it). */
ss_status cli_write_mesh_labels(const char *path, const ss_mesh *m, const unsigned char *rgb, const int *labels,
                                const char *std_ext, ss_error *err);
ss_status cli_write_png(const char *path, const unsigned char *rgb, int w, int h, ss_error *err);
ss_status cli_write_npy(const char *path, const double *a, int rows, int cols, ss_error *err);
/* A text file the CLI writes itself: stdout for "-" (then cli_close_out only flushes). NULL with
 * errno set when it cannot be opened. cli_close_out: 0, or -1 after a write error. */
FILE *cli_open_out(const char *path);
int cli_close_out(FILE *f);
/* Outputs that would replace an input, or each other (issue 32): cli_output_clash gives 1 (*o would
 * overwrite the input *in), 2 (*o named twice) or 0; NULL and "-" are skipped, so are pipes and
 * devices (written, not replaced). cli_check_outputs reports it as a usage error (-1: none). */
int cli_output_clash(const char *const *outp, int nout, const char *const *inp, int nin, const char **o, const char **in);
int cli_check_outputs(cli_args *A, const char *const *outp, int nout, const char *const *inp, int nin);
/* Frees the buffered standard input (main, before exiting). */
void cli_io_cleanup(void);

/* ---- Batches and JSON summaries (cli_batch.c) ------------------------------------------------------
 * Every per-mesh command (info, eigs, descriptors, smooth, remesh, segment) takes several meshes, or
 * folders (their files with a mesh extension, sorted by name), and runs them as a batch: -o names a
 * folder (created if needed) that receives OUTDIR/NAME<suffix> per mesh (NAME: the file name without its
 * extension; the command's default suffix, or --suffix), options naming other outputs take a suffix
 * (--ply .ply); --jobs N meshes at once (default: the processors), each with its share of the OpenMP
 * threads; a progress bar on stderr when it is a terminal; afterwards each mesh's report lines on
 * stdout, in the order given, prefixed "MESH: ", and a summary line on stderr. A failed mesh does not
 * stop the others (exit 1 at the end). One mesh with -o naming a folder (or ending in '/') is a batch
 * too; otherwise one mesh runs exactly as before.
 * --json (every per-mesh command, match, error, eval): instead of the report lines, one JSON object on
 * stdout: {"command", "ok": meshes done, "failed", "seconds", "jobs", "results": [{"input", "ok",
 * "seconds", "outputs": [...], "warnings": [...], "error" (when it failed), and the command's own
 * counts and timings}]}.
 *
 * A command puts CLI_BATCH_OPTIONS(&b) in its option table (the meshes, --jobs, --json, --suffix: each
 * mesh goes through cli_batch_add), checks with cli_batch_setup, then cli_batch_finish(b, rc, job, cfg)
 * calls job(j, cfg) per mesh (j->input), possibly on several threads at once: a job only reads cfg, names
 * its outputs through cli_job_output / cli_job_extra, writes its report to cli_job_report and may add
 * fields (cli_job_int / _num / _str); cli_error / cli_warn inside it are recorded in its JSON. */
#define CLI_BATCH_OPTIONS(b)                                                                                    \
  CLI_OPT_POS_FN("MESH", cli_batch_pos, (b)), CLI_OPT_INT("--jobs", &(b)->jobs, 1, 256, NULL),              \
      CLI_OPT_FLAG("--json", &(b)->json, 1), CLI_OPT_CALL("--suffix", cli_batch_suffix, (b), NULL)
#define CLI_BATCH_HELP                                                                                          \
  "Several meshes or folders run as a batch: -o OUTDIR receives NAME<suffix> per mesh; other outputs take a\n" \
  "suffix (e.g. --ply .ply); one mesh with -o DIR/ too. A failed mesh does not stop the others.\n"            \
  "  --jobs N            batch: meshes at once, 1..256 (default: the processors)\n"                           \
  "  --suffix SUF        batch: the suffix of the main output (default above)\n"                              \
  "  --json              a JSON summary on stdout (counts, timings, warnings, errors, output paths)\n"

typedef struct cli_field {
  char key[48];
  int kind; /* 'i', 'd', 's', 'j' (JSON text), 'n' (null) */
  long i;
  double d;
  char *s;
} cli_field;

typedef struct cli_batch cli_batch;

typedef struct cli_job {
  const cli_batch *b; /* NULL outside a batch run (match, error, eval) */
  const char *input;  /* the mesh (NULL: no "input" key) */
  int index, rc;
  double t0, seconds;
  char *error;
  int noutputs, nwarnings, nfields;
  char **outputs, **warnings;
  cli_field *fields;
  FILE *rep; /* the report in memory (batch, --json) */
  char *rep_buf;
  size_t rep_len;
} cli_job;

struct cli_batch {
  const char *cmd;
  int jobs, json;
  const char *suffix, *outdir;
  int batch;
  int nin, cap;
  char **in;
  int nskipped;  /* folder entries that are not mesh files (warned; "skipped" in --json) */
  char **skipped;
};

typedef int (*cli_job_fn)(cli_job *j, void *cfg);

void cli_batch_init(cli_batch *b, const char *cmd);
void cli_batch_free(cli_batch *b); /* the inputs (cli_batch_run frees them itself) */
/* CLI_BATCH_OPTIONS' callbacks (o->dest: the batch): a positional mesh (cli_batch_add); --suffix. */
int cli_batch_pos(cli_args *A, const cli_opt *o, const char *mesh);
int cli_batch_suffix(cli_args *A, const cli_opt *o, const char *suffix);
/* A positional mesh (a folder: its mesh files and prepared shapes, .sss; other entries, subfolders
 * included, are skipped with a warning and listed in --json's "skipped"). -1 ok, else the exit code
 * (a usage error was reported). */
int cli_batch_add(cli_batch *b, cli_args *A, const char *mesh);
/* After scanning: batch or single run; in a batch the checks (no '-', -o OUTDIR when need_out, the
 * extras are suffixes, no output overwrites an input or another output) and the folder created.
 * main_suffix: the main output's default suffix (NULL: none); extras: the other outputs' values.
 * -1 ok, else the exit code. */
int cli_batch_setup(cli_batch *b, cli_args *A, const char *outdir, int need_out, const char *main_suffix,
                    const char *const *extras, int nextras);
/* Runs the job on every mesh (frees the inputs); the exit code (1 when a mesh failed). */
int cli_batch_run(cli_batch *b, cli_job_fn fn, void *cfg);
/* rc >= 0 (an exit code from parsing or the checks): the inputs freed, rc; else cli_batch_run. */
int cli_batch_finish(cli_batch *b, int rc, cli_job_fn fn, void *cfg);
/* The main output's path: `given` for one mesh, OUTDIR/NAME<suffix> in a batch (recorded for --json). */
const char *cli_job_output(cli_job *j, const char *given, const char *suffix);
/* Another output: `given` (NULL: none), in a batch OUTDIR/NAME<given>. */
const char *cli_job_extra(cli_job *j, const char *given);
/* Where the job's report goes: stdout (stderr when data_on_stdout or --json) for one mesh, memory in a batch. */
FILE *cli_job_report(cli_job *j, int data_on_stdout);
void cli_job_int(cli_job *j, const char *key, long v);
void cli_job_num(cli_job *j, const char *key, double v);
void cli_job_str(cli_job *j, const char *key, const char *v);
/* A field whose value is JSON text as it is (an array or object the caller wrote, e.g. with
 * open_memstream and cli_json_str / cli_json_num). */
void cli_job_json(cli_job *j, const char *key, const char *json);
void cli_json_str(FILE *f, const char *s); /* a JSON string literal, escaped */
void cli_json_num(FILE *f, double v);      /* %.17g, or null for NaN / inf */
/* A single run outside a batch (match, error, eval): begin records warnings and errors on this thread;
 * end prints the JSON (when json) in the batch's format and returns rc. */
void cli_job_begin(cli_job *j, const char *input);
int cli_job_end(cli_job *j, const char *cmd, int rc, int json);
/* "specseg: KIND: MSG" on stderr (the progress bar cleared and redrawn), recorded in the thread's job. */
void cli_diag(const char *kind, const char *fmt, va_list ap);

/* Each subcommand: argv[0] is the subcommand name. */
int cmd_info(int argc, char **argv);
int cmd_eigs(int argc, char **argv);
int cmd_descriptors(int argc, char **argv);
int cmd_demo(int argc, char **argv);
int cmd_smooth(int argc, char **argv);
int cmd_remesh(int argc, char **argv);
int cmd_segment(int argc, char **argv);
int cmd_geodesic(int argc, char **argv);
int cmd_eval(int argc, char **argv);
int cmd_error(int argc, char **argv);
int cmd_match(int argc, char **argv);
int cmd_pair(int argc, char **argv);
int cmd_refine(int argc, char **argv);
int cmd_render(int argc, char **argv);

#endif
