/* Command-line parsing for every subcommand: a command describes its arguments in one table (names,
 * kind, destination, range, the usage error for a bad value) and cli_parse does the rest.
 *
 *   int k = 50; const char *out = NULL; int timings = 0;
 *   const cli_opt opts[] = {
 *       CLI_OPT_POS("MESH", &mesh, NULL),
 *       CLI_OPT_STR("-o|--output", &out),
 *       CLI_OPT_INT("--k", &k, 3, 10000, NULL),       NULL: "--k needs an integer between 3 and 10000, not 'V'"
 *       CLI_OPT_FLAG("--timings", &timings, 1),
 *       CLI_OPT_END};
 *   cli_args A;
 *   cli_args_init(&A, argc, argv, USAGE, opts);
 *   int rc = cli_parse(&A);
 *   if (rc >= 0) return rc;                             help printed (0), usage error (2), or a callback's code
 *
 * Conventions, the same for every command: a value is the next argument, whatever it looks like
 * ("--k 3", "-o -"), or follows the first '=' of the same argument ("--k=3"); -h / --help anywhere
 * prints the usage text on stdout (exit 0); unknown options, "--name needs a value", "--name takes no
 * value" (a flag given "=value") and every bad value are usage errors (exit 2): "specseg: usage: CMD:
 * MESSAGE", the usage text's synopsis and a pointer to --help on stderr, and under --json (when the
 * command has it) one JSON object on stdout saying why nothing ran. Arguments that do not start with
 * '-', and "-" itself (standard input / output), are positional. An option given twice keeps its last
 * value (CLI_INTS collects them all). Arguments are taken in order and parsing stops at the first
 * error.
 *
 * The usage text starts with its synopsis ("usage: specseg CMD ..." up to the first blank line), which
 * usage errors repeat; --help prints all of it. */
#ifndef SPECSEG_CLI_OPTIONS_H
#define SPECSEG_CLI_OPTIONS_H

#include <stdint.h>
#include <stdio.h>

typedef enum cli_kind {
  CLI_END = 0, /* ends a table */
  CLI_POS,     /* positional: the table's CLI_POS entries take them in order (*(const char **)dest); one
                  with fn takes all that remain (fn(A, o, arg)). msg: the error for one too many
                  (default "unexpected argument '%s'") */
  CLI_FLAG,    /* no value: *(int *)dest = lo; with msg: refused when *dest holds another non-zero value
                  (flags that exclude each other) */
  CLI_STR,     /* *(const char **)dest = the value */
  CLI_STR2,    /* two values: *(const char **)dest and *(const char **)dest2 */
  CLI_INT,     /* an integer in [lo, hi]: *(int *)dest (msg NULL: "NAME needs an integer between LO and HI,
                  not 'V'", NAME the option's first name) */
  CLI_INTS,    /* repeatable CLI_INT: ((int *)dest)[(*(int *)dest2)++]; dest has room for argc values */
  CLI_DOUBLE,  /* a number (not NaN) from dlo to dhi, each end included unless `open` says CLI_OPEN_LO /
                  CLI_OPEN_HI: *(double *)dest */
  CLI_UINT64,  /* a non-negative integer: *(uint64_t *)dest */
  CLI_CHOICE,  /* one of the '|'-separated words of `choices`: *(int *)dest = values[i] (values NULL: i) */
  CLI_WXH,     /* "WxH", each an integer in [lo, hi]: *(int *)dest = W, *(int *)dest2 = H */
  CLI_CALL,    /* fn(A, o, value), with o->dest and o->dest2 as it wants them */
} cli_kind;

enum { CLI_OPEN_LO = 1, CLI_OPEN_HI = 2 };

struct cli_args;
typedef struct cli_opt cli_opt;
/* A value (or positional argument) taken: -1; else the exit code, after reporting (cli_bad, cli_error). */
typedef int (*cli_opt_fn)(struct cli_args *A, const cli_opt *o, const char *value);

struct cli_opt {
  const char *names; /* "--k", "-o|--output"; CLI_POS: the argument's name in the usage ("MESH") */
  cli_kind kind;
  void *dest;
  const char *msg; /* the usage error for a bad value; "%s" in it stands for the value (no other
                      conversions) */
  long lo, hi;
  double dlo, dhi;
  int open;
  const char *choices;
  const int *values;
  void *dest2;
  cli_opt_fn fn;
};

/* The entries, with their destinations' types checked (an enum destination: CLI_ENUM(&e), an int of
 * the same size). CLI_OPT_FLAG1: a flag with msg (see CLI_FLAG). */
#define CLI_INTP(p) _Generic((p), int *: (p))
#define CLI_ENUM(p) ((void)sizeof(char[sizeof *(p) == sizeof(int) ? 1 : -1]), (int *)(p))
#define CLI_STRP(p) _Generic((p), const char **: (p))
#define CLI_OPT_POS(name, dest_, msg_) {.names = (name), .kind = CLI_POS, .dest = CLI_STRP(dest_), .msg = (msg_)}
#define CLI_OPT_POS_FN(name, fn_, dest_) {.names = (name), .kind = CLI_POS, .dest = (dest_), .fn = (fn_)}
#define CLI_OPT_FLAG(names_, dest_, value) {.names = (names_), .kind = CLI_FLAG, .dest = CLI_INTP(dest_), .lo = (value)}
#define CLI_OPT_FLAG1(names_, dest_, value, msg_) \
  {.names = (names_), .kind = CLI_FLAG, .dest = CLI_INTP(dest_), .lo = (value), .msg = (msg_)}
#define CLI_OPT_STR(names_, dest_) {.names = (names_), .kind = CLI_STR, .dest = CLI_STRP(dest_)}
#define CLI_OPT_STR2(names_, dest_, dest_2) \
  {.names = (names_), .kind = CLI_STR2, .dest = CLI_STRP(dest_), .dest2 = CLI_STRP(dest_2)}
#define CLI_OPT_INT(names_, dest_, lo_, hi_, msg_) \
  {.names = (names_), .kind = CLI_INT, .dest = CLI_INTP(dest_), .msg = (msg_), .lo = (lo_), .hi = (hi_)}
#define CLI_OPT_INTS(names_, dest_, count, lo_, hi_, msg_)                                                      \
  {.names = (names_), .kind = CLI_INTS, .dest = CLI_INTP(dest_), .msg = (msg_), .lo = (lo_), .hi = (hi_),     \
   .dest2 = CLI_INTP(count)}
#define CLI_OPT_DOUBLE(names_, dest_, lo_, hi_, open_, msg_)                                                    \
  {.names = (names_), .kind = CLI_DOUBLE, .dest = _Generic((dest_), double *: (dest_)), .msg = (msg_),        \
   .dlo = (lo_), .dhi = (hi_), .open = (open_)}
#define CLI_OPT_UINT64(names_, dest_, msg_) \
  {.names = (names_), .kind = CLI_UINT64, .dest = _Generic((dest_), uint64_t *: (dest_)), .msg = (msg_)}
#define CLI_OPT_CHOICE(names_, dest_, choices_, values_, msg_)                                               \
  {.names = (names_), .kind = CLI_CHOICE, .dest = CLI_INTP(dest_), .msg = (msg_), .choices = (choices_),   \
   .values = (values_)}
#define CLI_OPT_WXH(names_, w, h, lo_, hi_, msg_)                                                             \
  {.names = (names_), .kind = CLI_WXH, .dest = CLI_INTP(w), .msg = (msg_), .lo = (lo_), .hi = (hi_),        \
   .dest2 = CLI_INTP(h)}
#define CLI_OPT_CALL(names_, fn_, dest_, dest_2) \
  {.names = (names_), .kind = CLI_CALL, .dest = (dest_), .dest2 = (dest_2), .fn = (fn_)}
#define CLI_OPT_END {.names = NULL, .kind = CLI_END}
/* a macro's number as text, for a msg ("[4, " CLI_STRINGIFY(SS_REMESH_MAX_FACES) "]") */
#define CLI_STRINGIFY(x) CLI_STRINGIFY_(x)
#define CLI_STRINGIFY_(x) #x

/* --shard I/N, 1 <= I <= N: *i = I - 1, *n = N (eval, eval --benchmark). */
int cli_opt_shard(struct cli_args *A, const cli_opt *o, const char *value);
#define CLI_OPT_SHARD(i, n)                                                                               \
  {.names = "--shard", .kind = CLI_CALL, .fn = cli_opt_shard, .dest = CLI_INTP(i), .dest2 = CLI_INTP(n), \
   .msg = "--shard: I/N with 1 <= I <= N (e.g. 3/8)"}

/* The scanner's state; cli_parse runs it over the whole table. */
typedef struct cli_args {
  int argc;
  char **argv;
  int next;             /* index of the next argument */
  const char *cmd;      /* for messages: argv[0] ("eigs"); may be reset (e.g. "eval merge") */
  const char *usage;    /* the subcommand's usage text */
  const cli_opt *opts;  /* the table */
  const char *pos;      /* current positional argument, or NULL */
  const cli_opt *opt;   /* current option's entry (NULL for a positional) */
  const char *val;      /* its value (NULL for a flag) */
  const char *val2;     /* the second value of a CLI_STR2 option */
  char name[64];        /* the option as given, without "=value" */
  int npos;             /* positional arguments taken by CLI_POS entries so far */
  int rc;               /* -1 while scanning / at the end; SS_EXIT_OK after --help; SS_EXIT_USAGE */
} cli_args;

void cli_args_init(cli_args *a, int argc, char **argv, const char *usage, const cli_opt *opts);
/* Every argument into its destination: -1 when all were taken; else the exit code (0 after --help,
 * 2 after a usage error, or what a callback returned). */
int cli_parse(cli_args *a);
/* "specseg: usage: CMD: MESSAGE", the synopsis and a pointer to --help on stderr (and under --json the
 * JSON object on stdout); sets and returns a->rc = SS_EXIT_USAGE. */
int cli_bad(cli_args *a, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* The full usage text (and the conventions shared by every subcommand) on f. */
void cli_print_usage(const char *usage, FILE *f);

#endif
