/* The option tables every subcommand declares, parsed in one place (see cli_options.h): OPTION VALUE
 * and OPTION=VALUE, flags, positional arguments, -h / --help, the values' checks and the usage errors. */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
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
        "Meshes: OFF, OBJ, PLY, STL (ascii / binary), glTF 2.0 (.gltf / .glb) (our readers); FBX, COLLADA, 3DS and\n"
        "the other formats of assimp when built with libassimp-dev (all meshes of a scene merged, node transforms\n"
        "applied); an STL's and a scene's vertices welded by exact coordinates.\n",
        f);
}

void cli_args_init(cli_args *a, int argc, char **argv, const char *usage, const cli_opt *opts) {
  memset(a, 0, sizeof *a);
  a->argc = argc;
  a->argv = argv;
  a->next = 1;
  a->cmd = argc > 0 && argv[0] ? argv[0] : "specseg";
  a->usage = usage;
  a->opts = opts;
  a->rc = -1;
}

/* Is `name` (length n) one of the '|'-separated names of o? */
static int has_name(const cli_opt *o, const char *name, size_t n) {
  for (const char *s = o->names; s;) {
    const char *bar = strchr(s, '|');
    size_t L = bar ? (size_t)(bar - s) : strlen(s);
    if (L == n && !strncmp(s, name, n)) return 1;
    s = bar ? bar + 1 : NULL;
  }
  return 0;
}

/* The option `name` (length n, without '='), or NULL. */
static const cli_opt *lookup(const cli_args *a, const char *name, size_t n) {
  for (const cli_opt *o = a->opts; o && o->kind != CLI_END; o++)
    if (o->kind != CLI_POS && has_name(o, name, n)) return o;
  return NULL;
}

/* Arguments an option takes after its name: 0 (a flag), 1 or 2. */
static int values_of(const cli_opt *o) { return o->kind == CLI_FLAG ? 0 : o->kind == CLI_STR2 ? 2 : 1; }

static int is_option(const char *s) { return s[0] == '-' && s[1] != '\0'; }
static int is_help(const char *s) { return !strcmp(s, "-h") || !strcmp(s, "--help"); }

/* -h / --help anywhere, values of valued options excepted ("-o --help" writes a file "--help"). */
static int help_requested(const cli_args *a) {
  for (int i = 1; i < a->argc; i++) {
    const char *s = a->argv[i];
    if (!is_option(s)) continue;
    if (is_help(s)) return 1;
    const char *eq = strchr(s, '=');
    const cli_opt *o = lookup(a, s, eq ? (size_t)(eq - s) : strlen(s));
    if (o && values_of(o)) i += values_of(o) - (eq != NULL); /* skip the values that follow */
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
  if (!lookup(a, "--json", 6)) return 0;
  for (int i = 1; i < a->argc; i++)
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

/* The usage error for a value o refuses: its msg with each "%s" replaced by the value; for an integer
 * without msg, "NAME needs an integer between LO and HI, not 'VALUE'". */
static int bad_value(cli_args *a, const cli_opt *o, const char *v) {
  if (!o->msg) {
    const char *bar = strchr(o->names, '|');
    int n = bar ? (int)(bar - o->names) : (int)strlen(o->names);
    return cli_bad(a, "%.*s needs an integer between %ld and %ld, not '%s'", n, o->names, o->lo, o->hi, v);
  }
  char msg[2048];
  size_t n = 0;
  for (const char *p = o->msg; *p && n + 1 < sizeof msg; p++) {
    if (p[0] == '%' && p[1] == 's') {
      for (const char *q = v; *q && n + 1 < sizeof msg; q++) msg[n++] = *q;
      p++;
    } else {
      msg[n++] = *p;
    }
  }
  msg[n] = '\0';
  return cli_bad(a, "%s", msg);
}

int cli_opt_shard(cli_args *A, const cli_opt *o, const char *v) {
  int si, sn;
  char tail;
  if (sscanf(v, "%d/%d%c", &si, &sn, &tail) != 2 || sn < 1 || si < 1 || si > sn) return bad_value(A, o, v);
  *(int *)o->dest = si - 1, *(int *)o->dest2 = sn;
  return -1;
}

/* "WxH", both in [lo, hi] (the value cut to 63 characters, as it always was) */
static int parse_wxh(const char *v, long lo, long hi, int *w, int *h) {
  char buf[64];
  snprintf(buf, sizeof buf, "%s", v);
  char *x = strchr(buf, 'x');
  if (!x) return -1;
  *x = 0;
  return cli_parse_int(buf, lo, hi, w) || cli_parse_int(x + 1, lo, hi, h) ? -1 : 0;
}

/* the index of v among the '|'-separated words, or -1 */
static int choice_index(const char *words, const char *v) {
  size_t n = strlen(v);
  int i = 0;
  for (const char *s = words; s; i++) {
    const char *bar = strchr(s, '|');
    size_t L = bar ? (size_t)(bar - s) : strlen(s);
    if (L == n && !strncmp(s, v, n)) return i;
    s = bar ? bar + 1 : NULL;
  }
  return -1;
}

/* The current option's value into its destination: -1, or the exit code. */
static int take_option(cli_args *a) {
  const cli_opt *o = a->opt;
  const char *v = a->val;
  switch (o->kind) {
  case CLI_FLAG:
    if (o->msg && *(int *)o->dest && *(int *)o->dest != o->lo) return bad_value(a, o, "");
    *(int *)o->dest = (int)o->lo;
    return -1;
  case CLI_STR:
    *(const char **)o->dest = v;
    return -1;
  case CLI_STR2:
    *(const char **)o->dest = v, *(const char **)o->dest2 = a->val2;
    return -1;
  case CLI_INT:
    return cli_parse_int(v, o->lo, o->hi, (int *)o->dest) ? bad_value(a, o, v) : -1;
  case CLI_INTS: {
    int *n = o->dest2;
    if (cli_parse_int(v, o->lo, o->hi, (int *)o->dest + *n)) return bad_value(a, o, v);
    ++*n;
    return -1;
  }
  case CLI_DOUBLE: {
    double *d = o->dest;
    if (cli_parse_double(v, d) || !(o->open & CLI_OPEN_LO ? *d > o->dlo : *d >= o->dlo) ||
        !(o->open & CLI_OPEN_HI ? *d < o->dhi : *d <= o->dhi))
      return bad_value(a, o, v);
    return -1;
  }
  case CLI_UINT64: {
    char *end;
    errno = 0;
    unsigned long long s = strtoull(v, &end, 10);
    if (errno || *end || !*v || v[0] == '-') return bad_value(a, o, v);
    *(uint64_t *)o->dest = s;
    return -1;
  }
  case CLI_CHOICE: {
    int i = choice_index(o->choices, v);
    if (i < 0) return bad_value(a, o, v);
    *(int *)o->dest = o->values ? o->values[i] : i;
    return -1;
  }
  case CLI_WXH:
    return parse_wxh(v, o->lo, o->hi, (int *)o->dest, (int *)o->dest2) ? bad_value(a, o, v) : -1;
  case CLI_CALL:
    return o->fn(a, o, v);
  default:
    return -1;
  }
}

/* A positional argument to the next CLI_POS entry, or to the one with fn: -1, or the exit code. */
static int take_positional(cli_args *a) {
  const cli_opt *last = NULL;
  int k = 0;
  for (const cli_opt *o = a->opts; o && o->kind != CLI_END; o++) {
    if (o->kind != CLI_POS) continue;
    if (o->fn) return o->fn(a, o, a->pos);
    if (k++ == a->npos) {
      a->npos++;
      *(const char **)o->dest = a->pos;
      return -1;
    }
    last = o;
  }
  if (last && last->msg) return bad_value(a, last, a->pos);
  return cli_bad(a, "unexpected argument '%s'", a->pos);
}

/* The next argument into a->pos or a->opt / a->val: 1; 0 at the end (rc -1), after --help (rc 0) or
 * after a usage error it reported (rc 2). */
static int next_argument(cli_args *a) {
  a->pos = a->val = a->val2 = NULL;
  a->opt = NULL;
  if (a->rc >= 0) return 0;
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
  const cli_opt *o = lookup(a, s, n);
  if (!o) {
    cli_bad(a, "unknown option '%.*s'", (int)n, s);
    return 0;
  }
  if (n >= sizeof a->name) { /* cannot happen for a declared name; keeps the copy bounded */
    cli_bad(a, "option '%.40s...' too long", s);
    return 0;
  }
  memcpy(a->name, s, n);
  a->name[n] = '\0';
  a->opt = o;
  int nval = values_of(o);
  if (nval == 0) {
    if (eq) {
      cli_bad(a, "%s takes no value (got '%s')", a->name, s);
      return 0;
    }
    return 1;
  }
  if (eq) a->val = eq + 1;
  else if (a->next < a->argc) a->val = a->argv[a->next++];
  if (nval == 2 && a->next < a->argc) a->val2 = a->argv[a->next++];
  if (!a->val || !*a->val || (nval == 2 && (!a->val2 || !*a->val2))) {
    cli_bad(a, nval == 2 ? "%s needs two values" : "%s needs a value", a->name);
    return 0;
  }
  return 1;
}

int cli_parse(cli_args *a) {
  while (next_argument(a)) {
    int rc = a->pos ? take_positional(a) : take_option(a);
    if (rc >= 0) return rc;
  }
  return a->rc;
}
