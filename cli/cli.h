/* The specseg program: one file per subcommand, each a thin shell over library calls. */
#ifndef SPECSEG_CLI_H
#define SPECSEG_CLI_H

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

/* ---- Argument scanning (cli_args.c): the one option scanner every subcommand uses. ----------------
 * A subcommand declares its options in a NULL-terminated list of names; a name ending in '=' takes a
 * value ("-o=", "--steps="), one ending in "==" two ("--descriptors==": A.val and A.val2, the next two
 * arguments, or "=V1" and the next one), the others are flags ("--bbox"). A value is the next argument,
 * whatever it looks like ("--steps 3", "-o -"), or follows the first '=' of the same argument ("--steps=3").
 * Handled here once for all: -h / --help anywhere (the usage text on stdout, exit 0), unknown options,
 * "--name needs a value", "--name takes no value" (a flag given "=value"), all usage errors (exit 2).
 * Arguments that do not start with '-', and "-" itself (standard input / output), are positional.
 *
 *   static const char *const OPTS[] = {"-o=", "--steps=", "--bbox", NULL};
 *   cli_args A;
 *   cli_args_init(&A, argc, argv, USAGE, OPTS);
 *   while (cli_next(&A)) {
 *     if (A.pos) ...                            positional argument A.pos
 *     else if (cli_is(&A, "-o")) out = A.val;   option with its value
 *     else if (cli_is(&A, "--bbox")) ...        flag (A.val is NULL)
 *   }
 *   if (A.rc >= 0) return A.rc;                 help printed (0) or usage error (2)
 *
 * The usage text starts with its synopsis ("usage: specseg CMD ..." up to the first blank line), which
 * usage errors repeat; --help prints all of it. */
typedef struct cli_args {
  int argc;
  char **argv;
  int next;                 /* index of the next argument */
  const char *cmd;          /* for messages: argv[0] ("eigs"); may be reset (e.g. "eval merge") */
  const char *usage;        /* the subcommand's usage text */
  const char *const *opts;  /* declared options */
  const char *pos;          /* current positional argument, or NULL */
  const char *opt;          /* current option, as declared without its '=' (NULL for a positional) */
  const char *val;          /* its value (NULL for a flag) */
  const char *val2;         /* the second value of a two-valued option ("name==") */
  char name[64];            /* storage for opt */
  int rc;                   /* -1 while scanning / at the end; SS_EXIT_OK after --help; SS_EXIT_USAGE */
} cli_args;

void cli_args_init(cli_args *a, int argc, char **argv, const char *usage, const char *const *opts);
/* Next argument: 1 with pos or opt/val set; 0 at the end (rc -1), after --help (rc 0) or after a usage
 * error it reported (rc 2). */
int cli_next(cli_args *a);
/* Is the current argument the option `name` (as declared, without '=')? */
int cli_is(const cli_args *a, const char *name);
/* "specseg: usage: CMD: MESSAGE", the synopsis and a pointer to --help on stderr; sets and returns
 * a->rc = SS_EXIT_USAGE. */
int cli_bad(cli_args *a, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* The full usage text (and the conventions shared by every subcommand) on f. */
void cli_print_usage(const char *usage, FILE *f);

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
/* Frees the buffered standard input (main, before exiting). */
void cli_io_cleanup(void);

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
int cmd_render(int argc, char **argv);

#endif
