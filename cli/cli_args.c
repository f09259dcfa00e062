/* The option scanner shared by every subcommand (see cli.h): OPTION VALUE and OPTION=VALUE, flags,
 * -h / --help, and the usage errors, in one place. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"

void cli_print_usage(const char *usage, FILE *f) {
  fputs(usage, f);
  size_t n = strlen(usage);
  if (n && usage[n - 1] != '\n') fputc('\n', f);
  fputs("  -h, --help          this text\n"
        "An option that takes a value accepts it as the next argument or after '=': --opt VALUE or --opt=VALUE.\n"
        "Vector files (labels, maps, fields, landmarks) are text, or NumPy when named *.npy (read: shape (n,),\n"
        "(n, 1), landmarks (n, 2), fields F.npy:J for column J; written: (n, 1) int32 / float64).\n"
        "Meshes: OFF, OBJ, PLY (our readers); STL (ascii / binary), glTF 2.0 (.gltf / .glb), FBX, COLLADA, 3DS and\n"
        "the other formats of assimp when built with libassimp-dev (all meshes of a scene merged, node transforms\n"
        "applied, vertices welded by exact coordinates).\n",
        f);
}

void cli_args_init(cli_args *a, int argc, char **argv, const char *usage, const char *const *opts) {
  memset(a, 0, sizeof *a);
  a->argc = argc;
  a->argv = argv;
  a->next = 1;
  a->cmd = argc > 0 && argv[0] ? argv[0] : "specseg";
  a->usage = usage;
  a->opts = opts;
  a->rc = -1;
}

/* The declared option `name` (length n, without '='): 0 unknown, 1 flag, 2 takes a value, 3 two. */
static int lookup(const cli_args *a, const char *name, size_t n) {
  for (const char *const *o = a->opts; o && *o; o++) {
    size_t L = strlen(*o), eqs = 0;
    while (eqs < L && eqs < 2 && (*o)[L - 1 - eqs] == '=') eqs++;
    if (L - eqs == n && !strncmp(*o, name, n)) return 1 + (int)eqs;
  }
  return 0;
}

static int is_option(const char *s) { return s[0] == '-' && s[1] != '\0'; }
static int is_help(const char *s) { return !strcmp(s, "-h") || !strcmp(s, "--help"); }

/* -h / --help anywhere, values of valued options excepted ("-o --help" writes a file "--help"). */
static int help_requested(const cli_args *a) {
  for (int i = 1; i < a->argc; i++) {
    const char *s = a->argv[i];
    if (!is_option(s)) continue;
    if (is_help(s)) return 1;
    const char *eq = strchr(s, '=');
    int kind = lookup(a, s, eq ? (size_t)(eq - s) : strlen(s));
    if (kind >= 2) i += kind - 1 - (eq != NULL); /* skip the values that follow */
  }
  return 0;
}

static void print_synopsis(const char *usage, FILE *f) {
  const char *end = strstr(usage, "\n\n");
  size_t n = end ? (size_t)(end - usage) : strlen(usage);
  fprintf(f, "%.*s\n", (int)n, usage);
}

/* --json given to a command that takes it */
static int wants_json(const cli_args *a) {
  int declared = 0;
  for (const char *const *o = a->opts; o && *o && !declared; o++) declared = !strcmp(*o, "--json");
  for (int i = 1; declared && i < a->argc; i++)
    if (a->argv[i] && !strcmp(a->argv[i], "--json")) return 1;
  return 0;
}

int cli_bad(cli_args *a, const char *fmt, ...) {
  char msg[2048];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  fprintf(stderr, "specseg: usage: %s: %s\n", a->cmd, msg);
  /* under --json, stdout still gets one object: nothing ran, and why */
  if (wants_json(a)) {
    fputs("{\"command\": ", stdout);
    cli_json_str(stdout, a->cmd);
    fputs(", \"ok\": 0, \"failed\": 0, \"usage_error\": ", stdout);
    cli_json_str(stdout, msg);
    fputs(", \"results\": []}\n", stdout);
  }
  print_synopsis(a->usage, stderr);
  fprintf(stderr, "Run 'specseg %s --help' for all options.\n", a->cmd);
  return a->rc = SS_EXIT_USAGE;
}

int cli_next(cli_args *a) {
  a->pos = a->opt = a->val = a->val2 = NULL;
  if (a->rc >= 0) return 0; /* a usage error reported by the caller between two calls */
  if (a->next == 1 && help_requested(a)) {
    cli_print_usage(a->usage, stdout);
    a->rc = fflush(stdout) ? cli_error("cannot write to standard output") : SS_EXIT_OK;
    return 0;
  }
  if (a->next >= a->argc) return 0;
  const char *s = a->argv[a->next++];
  if (!is_option(s)) {
    a->pos = s;
    return 1;
  }
  const char *eq = strchr(s, '=');
  size_t n = eq ? (size_t)(eq - s) : strlen(s);
  int kind = lookup(a, s, n);
  if (kind == 0) {
    cli_bad(a, "unknown option '%.*s'", (int)n, s);
    return 0;
  }
  if (n >= sizeof a->name) { /* cannot happen for a declared name; keeps the copy bounded */
    cli_bad(a, "option '%.40s...' too long", s);
    return 0;
  }
  memcpy(a->name, s, n);
  a->name[n] = '\0';
  a->opt = a->name;
  if (kind == 1) {
    if (eq) {
      cli_bad(a, "%s takes no value (got '%s')", a->name, s);
      return 0;
    }
    return 1;
  }
  if (eq) a->val = eq + 1;
  else if (a->next < a->argc) a->val = a->argv[a->next++];
  if (kind == 3 && a->next < a->argc) a->val2 = a->argv[a->next++];
  if (!a->val || !*a->val || (kind == 3 && (!a->val2 || !*a->val2))) {
    cli_bad(a, kind == 3 ? "%s needs two values" : "%s needs a value", a->name);
    return 0;
  }
  return 1;
}

int cli_is(const cli_args *a, const char *name) { return a->opt && !strcmp(a->opt, name); }
