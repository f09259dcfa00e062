/* The specseg program: one file per subcommand, each a thin shell over library calls. */
#ifndef SPECSEG_CLI_H
#define SPECSEG_CLI_H

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

/* Each subcommand: argv[0] is the subcommand name. */
int cmd_info(int argc, char **argv);
int cmd_eigs(int argc, char **argv);
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
