/* The manifest of a data set for the Table 1 runner: meshes in groups, each group's ground truth
 * (identity or per-pair map files), landmarks (files or the paper's FPS procedure), optional
 * symmetry maps and the pairs to run. Line-based text, parsed and checked here; the files it names
 * are read by the runner (manifest_data.c). The format is documented in docs/evaluation.md ("Any data set"). */
#include "specseg/eval.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_LINE 8192
#define MAX_TOK 16
#define MAX_MESHES 100000

typedef struct pending { /* a `pair` / `map` / `landmarks fps REF` line, resolved at the end */
  int line, group;
  char *a, *b, *path;
} pending;

typedef struct parser {
  const char *name, *base;
  ss_manifest *m;
  int cap_meshes, cap_groups, cap_gline, cap_gpairs;
  pending *pairs, *maps, *refs;
  int npairs, nmaps, nrefs, cap_pairs, cap_maps, cap_refs;
  int *group_line;  /* per group: the line that opened it */
  int *group_pairs; /* per group: 1 when a `pairs` line chose the mode */
  ss_error *err;
} parser;

static char *dup_str(const char *s) {
  size_t n = strlen(s) + 1;
  char *d = malloc(n);
  if (d) memcpy(d, s, n);
  return d;
}

/* a path relative to the manifest's folder (absolute paths kept) */
static char *resolve(const parser *P, const char *p) {
  if (p[0] == '/' || !P->base || !P->base[0]) return dup_str(p);
  size_t n = strlen(P->base) + strlen(p) + 2;
  char *d = malloc(n);
  if (d) snprintf(d, n, "%s/%s", P->base, p);
  return d;
}

static ss_status perr(parser *P, int line, const char *fmt, const char *a, const char *b) {
  char what[600];
  snprintf(what, sizeof what, fmt, a ? a : "", b ? b : "");
  return ss_fail(P->err, SS_ERR_PARSE, "%s:%d: %s", P->name, line, what);
}
static ss_status nomem(parser *P) { return ss_fail(P->err, SS_ERR_NOMEM, "%s: out of memory", P->name); }

static int grow(void **p, int *cap, int n, size_t size) {
  if (n < *cap) return 1;
  int c = *cap ? 2 * *cap : 16;
  void *q = realloc(*p, size * (size_t)c);
  if (!q) return 0;
  *p = q, *cap = c;
  return 1;
}

static int parse_int(const char *s, long lo, long hi, long *v) {
  char *end;
  errno = 0;
  long x = strtol(s, &end, 10);
  if (end == s || *end || errno || x < lo || x > hi) return 1;
  *v = x;
  return 0;
}

static ss_status open_group(parser *P, const char *name, int line) {
  ss_manifest *m = P->m;
  for (int g = 0; g < m->ngroups; g++)
    if (!strcmp(m->groups[g].name, name)) return perr(P, line, "group '%s' declared twice", name, NULL);
  if (m->ngroups > 0 && m->groups[m->ngroups - 1].count == 0)
    return perr(P, P->group_line[m->ngroups - 1], "group '%s' has no meshes", m->groups[m->ngroups - 1].name, NULL);
  if (!grow((void **)&m->groups, &P->cap_groups, m->ngroups, sizeof *m->groups) ||
      !grow((void **)&P->group_line, &P->cap_gline, m->ngroups, sizeof(int)) ||
      !grow((void **)&P->group_pairs, &P->cap_gpairs, m->ngroups, sizeof(int)))
    return nomem(P);
  ss_manifest_group *g = &m->groups[m->ngroups];
  memset(g, 0, sizeof *g);
  g->name = dup_str(name);
  if (!g->name) return nomem(P);
  g->first = m->nmeshes, g->reference = -1;
  P->group_line[m->ngroups] = line, P->group_pairs[m->ngroups] = 0;
  m->ngroups++;
  return SS_OK;
}

/* the current group, opening the implicit "default" group before any `group` line */
static ss_status current(parser *P, int line, ss_manifest_group **g) {
  if (P->m->ngroups == 0) {
    ss_status st = open_group(P, "default", line);
    if (st) return st;
  }
  *g = &P->m->groups[P->m->ngroups - 1];
  return SS_OK;
}

static ss_status add_pending(parser *P, pending **list, int *n, int *cap, int line, const char *a, const char *b,
                             const char *path) {
  if (!grow((void **)list, cap, *n, sizeof **list)) return nomem(P);
  pending *q = &(*list)[(*n)++];
  memset(q, 0, sizeof *q);
  q->line = line, q->group = P->m->ngroups - 1;
  q->a = dup_str(a), q->b = b ? dup_str(b) : NULL, q->path = path ? resolve(P, path) : NULL;
  if (!q->a || (b && !q->b) || (path && !q->path)) return nomem(P);
  return SS_OK;
}

static ss_status directive(parser *P, int line, char **t, int nt) {
  ss_manifest *m = P->m;
  ss_manifest_group *g = NULL;
  ss_status st;
  const char *d = t[0];
  if (!strcmp(d, "group")) {
    if (nt != 2) return perr(P, line, "'group' takes one name", NULL, NULL);
    return open_group(P, t[1], line);
  }
  if ((st = current(P, line, &g))) return st;
  if (!strcmp(d, "mesh")) {
    if (nt < 2 || nt % 2) return perr(P, line, "'mesh PATH [name N] [landmarks FILE] [symmetry FILE]': odd options", NULL, NULL);
    if (m->nmeshes >= MAX_MESHES) return perr(P, line, "more than 100000 meshes", NULL, NULL);
    if (!grow((void **)&m->meshes, &P->cap_meshes, m->nmeshes, sizeof *m->meshes)) return nomem(P);
    ss_manifest_mesh *s = &m->meshes[m->nmeshes];
    memset(s, 0, sizeof *s);
    s->group = m->ngroups - 1;
    m->nmeshes++; /* counted now, so ss_manifest_free releases what is set */
    g->count++;
    if (!(s->path = resolve(P, t[1]))) return nomem(P);
    const char *name = NULL;
    for (int i = 2; i < nt; i += 2) {
      char **slot = !strcmp(t[i], "landmarks") ? &s->landmarks : !strcmp(t[i], "symmetry") ? &s->symmetry : NULL;
      if (!strcmp(t[i], "name")) {
        if (name) return perr(P, line, "'name' given twice", NULL, NULL);
        name = t[i + 1];
        continue;
      }
      if (!slot) return perr(P, line, "unknown mesh option '%s' (name, landmarks, symmetry)", t[i], NULL);
      if (*slot) return perr(P, line, "'%s' given twice", t[i], NULL);
      if (!(*slot = resolve(P, t[i + 1]))) return nomem(P);
    }
    if (name) s->name = dup_str(name);
    else { /* the file name without folder and extension */
      const char *b = strrchr(t[1], '/');
      b = b ? b + 1 : t[1];
      s->name = dup_str(b);
      char *dot = s->name ? strrchr(s->name, '.') : NULL;
      if (dot && dot != s->name) *dot = 0;
    }
    if (!s->name) return nomem(P);
    if (!s->name[0]) return perr(P, line, "mesh '%s' has an empty name", t[1], NULL);
    for (int i = 0; i < m->nmeshes - 1; i++)
      if (!strcmp(m->meshes[i].name, s->name))
        return perr(P, line, "mesh name '%s' used twice (give 'name N')", s->name, NULL);
    return SS_OK;
  }
  if (!strcmp(d, "gt")) {
    if (nt != 2 || (strcmp(t[1], "identity") && strcmp(t[1], "maps")))
      return perr(P, line, "'gt identity' or 'gt maps'", NULL, NULL);
    g->gt_maps = !strcmp(t[1], "maps");
    return SS_OK;
  }
  if (!strcmp(d, "landmarks")) {
    if (nt >= 2 && !strcmp(t[1], "file")) {
      if (nt != 3) return perr(P, line, "'landmarks file FILE'", NULL, NULL);
      if (g->landmarks) return perr(P, line, "group '%s': landmark file given twice", g->name, NULL);
      return (g->landmarks = resolve(P, t[2])) ? SS_OK : nomem(P);
    }
    if (nt >= 2 && !strcmp(t[1], "fps")) {
      if (nt > 4) return perr(P, line, "'landmarks fps [REFERENCE [SEED_VERTEX]]'", NULL, NULL);
      if (nt == 4) {
        long v;
        if (parse_int(t[3], 0, 2147483647L, &v)) return perr(P, line, "bad seed vertex '%s'", t[3], NULL);
        g->fps_seed = (int)v;
      }
      if (nt >= 3) return add_pending(P, &P->refs, &P->nrefs, &P->cap_refs, line, t[2], NULL, NULL);
      return SS_OK;
    }
    return perr(P, line, "'landmarks file FILE' or 'landmarks fps [REFERENCE [SEED_VERTEX]]'", NULL, NULL);
  }
  if (!strcmp(d, "symmetry")) {
    if (nt != 2) return perr(P, line, "'symmetry FILE'", NULL, NULL);
    if (g->symmetry) return perr(P, line, "group '%s': symmetry map given twice", g->name, NULL);
    return (g->symmetry = resolve(P, t[1])) ? SS_OK : nomem(P);
  }
  if (!strcmp(d, "pairs")) {
    if (P->group_pairs[m->ngroups - 1]) return perr(P, line, "group '%s': 'pairs' given twice", g->name, NULL);
    P->group_pairs[m->ngroups - 1] = 1;
    if (nt == 2 && !strcmp(t[1], "all")) g->pairs = SS_MANIFEST_PAIRS_ALL;
    else if (nt == 2 && !strcmp(t[1], "first")) g->pairs = SS_MANIFEST_PAIRS_FIRST;
    else if (nt == 2 && !strcmp(t[1], "listed")) g->pairs = SS_MANIFEST_PAIRS_LISTED;
    else if (nt == 4 && !strcmp(t[1], "random")) {
      long n, s;
      if (parse_int(t[2], 1, 10000000L, &n)) return perr(P, line, "bad pair count '%s' (1..10000000)", t[2], NULL);
      if (t[3][0] == '-' || parse_int(t[3], 0, 2147483647L, &s))
        return perr(P, line, "bad seed '%s' (0..2147483647)", t[3], NULL);
      g->pairs = SS_MANIFEST_PAIRS_RANDOM, g->random_n = (int)n, g->random_seed = (uint64_t)s;
    } else
      return perr(P, line, "'pairs all', 'pairs first', 'pairs listed' or 'pairs random N SEED'", NULL, NULL);
    return SS_OK;
  }
  if (!strcmp(d, "pair")) {
    if (nt != 3) return perr(P, line, "'pair SOURCE TARGET' (mesh names)", NULL, NULL);
    return add_pending(P, &P->pairs, &P->npairs, &P->cap_pairs, line, t[1], t[2], NULL);
  }
  if (!strcmp(d, "map")) {
    if (nt != 4) return perr(P, line, "'map SOURCE TARGET FILE' (mesh names, then the map file)", NULL, NULL);
    return add_pending(P, &P->maps, &P->nmaps, &P->cap_maps, line, t[1], t[2], t[3]);
  }
  return perr(P, line, "unknown directive '%s' (group, mesh, gt, landmarks, symmetry, pairs, pair, map)", d, NULL);
}

static int pair_cmp(const void *a, const void *b) {
  const int *p = a, *q = b;
  return p[0] != q[0] ? (p[0] > q[0]) - (p[0] < q[0]) : (p[1] > q[1]) - (p[1] < q[1]);
}
static int map_cmp(const void *a, const void *b) {
  const ss_manifest_map *p = a, *q = b;
  return p->x != q->x ? (p->x > q->x) - (p->x < q->x) : (p->y > q->y) - (p->y < q->y);
}

/* the named mesh of group g (line for messages) */
static ss_status lookup(parser *P, const pending *q, const char *name, int *idx) {
  *idx = ss_manifest_find(P->m, name);
  if (*idx < 0) return perr(P, q->line, "no mesh named '%s'", name, NULL);
  if (P->m->meshes[*idx].group != q->group)
    return perr(P, q->line, "mesh '%s' is not in group '%s'", name, P->m->groups[q->group].name);
  return SS_OK;
}

/* everything that needs the whole file: names, the pair lists, the map lines */
static ss_status finish(parser *P, int last_line) {
  ss_manifest *m = P->m;
  ss_status st;
  if (m->nmeshes == 0) return perr(P, last_line, "no meshes", NULL, NULL);
  if (m->groups[m->ngroups - 1].count == 0)
    return perr(P, P->group_line[m->ngroups - 1], "group '%s' has no meshes", m->groups[m->ngroups - 1].name, NULL);
  for (int r = 0; r < P->nrefs; r++) {
    int idx;
    if ((st = lookup(P, &P->refs[r], P->refs[r].a, &idx))) return st;
    m->groups[P->refs[r].group].reference = idx;
  }
  /* maps */
  if (P->nmaps) {
    m->maps = calloc((size_t)P->nmaps, sizeof *m->maps);
    if (!m->maps) return nomem(P);
  }
  for (int r = 0; r < P->nmaps; r++) {
    pending *q = &P->maps[r];
    ss_manifest_map *mp = &m->maps[m->nmaps];
    if ((st = lookup(P, q, q->a, &mp->x)) || (st = lookup(P, q, q->b, &mp->y))) return st;
    if (!m->groups[q->group].gt_maps)
      return perr(P, q->line, "group '%s' has identity ground truth: 'map' needs 'gt maps'", m->groups[q->group].name, NULL);
    if (mp->x == mp->y) return perr(P, q->line, "map of mesh '%s' onto itself", q->a, NULL);
    if (ss_manifest_map_path(m, mp->x, mp->y)) return perr(P, q->line, "second map of '%s' -> '%s'", q->a, q->b);
    mp->path = q->path, q->path = NULL;
    m->nmaps++;
    qsort(m->maps, (size_t)m->nmaps, sizeof *m->maps, map_cmp); /* kept sorted for the look-ups above */
  }
  /* pairs, group by group */
  long total = 0;
  for (int g = 0; g < m->ngroups; g++) total += (long)m->groups[g].count * (m->groups[g].count - 1);
  total += P->npairs;
  if (total > 50000000L) return perr(P, last_line, "more than 50,000,000 pairs", NULL, NULL);
  int *pp = malloc(sizeof(int) * 2 * (size_t)(total > 0 ? total : 1));
  int *all = malloc(sizeof(int) * 2 * (size_t)(total > 0 ? total : 1));
  m->px = malloc(sizeof(int) * (size_t)(total > 0 ? total : 1));
  m->py = malloc(sizeof(int) * (size_t)(total > 0 ? total : 1));
  if (!pp || !all || !m->px || !m->py) { free(pp), free(all); return nomem(P); }
  st = SS_OK;
  for (int gi = 0; gi < m->ngroups && !st; gi++) {
    ss_manifest_group *g = &m->groups[gi];
    int np = 0, nlisted = 0;
    for (int r = 0; r < P->npairs; r++) nlisted += P->pairs[r].group == gi;
    if (nlisted && !P->group_pairs[gi]) g->pairs = SS_MANIFEST_PAIRS_LISTED;
    if (g->reference < 0) g->reference = g->first;
    const int a0 = g->first, n = g->count;
    if (g->pairs == SS_MANIFEST_PAIRS_ALL) {
      for (int a = a0; a < a0 + n; a++)
        for (int b = a0; b < a0 + n; b++)
          if (a != b) pp[2 * np] = a, pp[2 * np + 1] = b, np++;
    } else if (g->pairs == SS_MANIFEST_PAIRS_FIRST) {
      for (int b = a0; b < a0 + n; b++)
        if (b != g->reference) pp[2 * np] = g->reference, pp[2 * np + 1] = b, np++;
    } else if (g->pairs == SS_MANIFEST_PAIRS_RANDOM) {
      long avail = (long)n * (n - 1);
      if (g->random_n > avail) {
        char what[64];
        snprintf(what, sizeof what, "%d", g->random_n);
        st = perr(P, P->group_line[gi], "group '%s': %s random pairs requested, fewer ordered pairs exist", g->name, what);
        break;
      }
      int na = 0;
      for (int a = a0; a < a0 + n; a++)
        for (int b = a0; b < a0 + n; b++)
          if (a != b) all[2 * na] = a, all[2 * na + 1] = b, na++;
      ss_rng r;
      ss_rng_seed(&r, g->random_seed ^ 0x510E527FADE682D1ull);
      for (int i = 0; i < g->random_n; i++) { /* partial Fisher–Yates: without replacement */
        int j = i + ss_rng_below(&r, na - i), ta = all[2 * i], tb = all[2 * i + 1];
        all[2 * i] = all[2 * j], all[2 * i + 1] = all[2 * j + 1], all[2 * j] = ta, all[2 * j + 1] = tb;
        pp[2 * np] = all[2 * i], pp[2 * np + 1] = all[2 * i + 1], np++;
      }
    }
    for (int r = 0; r < P->npairs && !st; r++) {
      pending *q = &P->pairs[r];
      if (q->group != gi) continue;
      int a, b;
      if ((st = lookup(P, q, q->a, &a)) || (st = lookup(P, q, q->b, &b))) break;
      if (a == b) { st = perr(P, q->line, "pair of mesh '%s' with itself", q->a, NULL); break; }
      int dup = 0;
      for (int i = 0; i < np && !dup; i++) dup = pp[2 * i] == a && pp[2 * i + 1] == b;
      if (!dup) pp[2 * np] = a, pp[2 * np + 1] = b, np++;
    }
    if (st) break;
    if (np == 0) {
      st = perr(P, P->group_line[gi], "group '%s' has no pairs (one mesh, or 'pairs listed' without 'pair' lines)", g->name,
                NULL);
      break;
    }
    if (g->pairs == SS_MANIFEST_PAIRS_ALL || g->pairs == SS_MANIFEST_PAIRS_FIRST)
      qsort(pp, (size_t)np, 2 * sizeof(int), pair_cmp);
    for (int i = 0; i < np && !st; i++) {
      if (g->gt_maps && !ss_manifest_map_path(m, pp[2 * i], pp[2 * i + 1]))
        st = perr(P, P->group_line[gi], "gt maps: no 'map' line for the pair '%s' -> '%s'", m->meshes[pp[2 * i]].name,
                  m->meshes[pp[2 * i + 1]].name);
      m->px[m->npairs] = pp[2 * i], m->py[m->npairs] = pp[2 * i + 1], m->npairs++;
    }
    if (!st && g->gt_maps && (g->landmarks || g->symmetry))
      st = perr(P, P->group_line[gi], "group '%s' (gt maps): a group-wide %s file needs identity ground truth (give one per mesh)",
                g->name, g->landmarks ? "landmark" : "symmetry");
  }
  free(pp), free(all);
  return st;
}

static ss_status parse_text(parser *P, const char *text, size_t len) {
  char buf[MAX_LINE + 2];
  int line = 0, header = 0;
  size_t pos = 0;
  ss_status st = SS_OK;
  while (pos < len && !st) {
    size_t e = pos;
    while (e < len && text[e] != '\n') e++;
    line++;
    if (e - pos > MAX_LINE) return perr(P, line, "line longer than 8192 bytes", NULL, NULL);
    memcpy(buf, text + pos, e - pos);
    buf[e - pos] = 0;
    pos = e + 1;
    char *hash = strchr(buf, '#');
    if (hash) *hash = 0;
    char *t[MAX_TOK + 1];
    int nt = 0;
    for (char *s = strtok(buf, " \t\r\f\v"); s; s = strtok(NULL, " \t\r\f\v")) {
      if (nt == MAX_TOK) return perr(P, line, "too many words", NULL, NULL);
      t[nt++] = s;
    }
    if (nt == 0) continue;
    if (!header) {
      if (nt != 2 || strcmp(t[0], "specseg-manifest"))
        return perr(P, line, "not a specseg manifest (the first line must be 'specseg-manifest 1')", NULL, NULL);
      if (strcmp(t[1], "1")) return perr(P, line, "manifest version '%s' not supported (1)", t[1], NULL);
      header = 1;
      continue;
    }
    st = directive(P, line, t, nt);
  }
  if (st) return st;
  if (!header) return perr(P, line > 0 ? line : 1, "empty: not a specseg manifest", NULL, NULL);
  return finish(P, line);
}

ss_status ss_manifest_read_memory(const char *text, size_t len, const char *name, const char *base_dir, ss_manifest *m,
                                  ss_error *err) {
  memset(m, 0, sizeof *m);
  parser P;
  memset(&P, 0, sizeof P);
  P.name = name ? name : "<memory>", P.base = base_dir, P.m = m, P.err = err;
  ss_status st = SS_OK;
  if (memchr(text, 0, len)) st = ss_fail(err, SS_ERR_PARSE, "%s: binary content (a NUL byte): not a manifest", P.name);
  if (!st) st = parse_text(&P, text, len);
  pending *lists[3] = {P.pairs, P.maps, P.refs};
  int counts[3] = {P.npairs, P.nmaps, P.nrefs};
  for (int l = 0; l < 3; l++) {
    for (int i = 0; i < counts[l]; i++) free(lists[l][i].a), free(lists[l][i].b), free(lists[l][i].path);
    free(lists[l]);
  }
  free(P.group_line), free(P.group_pairs);
  if (st) ss_manifest_free(m);
  return st;
}

ss_status ss_manifest_read(const char *path, ss_manifest *m, ss_error *err) {
  memset(m, 0, sizeof *m);
  FILE *f = fopen(path, "rb");
  if (!f) return ss_fail(err, SS_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
  size_t cap = 1 << 16, n = 0;
  char *text = malloc(cap);
  while (text) {
    size_t r = fread(text + n, 1, cap - n, f);
    n += r;
    if (n < cap) break;
    if (cap >= ((size_t)1 << 30)) { free(text), text = NULL; fclose(f); return ss_fail(err, SS_ERR_PARSE, "%s: larger than 1 GB", path); }
    char *q = realloc(text, cap *= 2);
    if (!q) free(text);
    text = q;
  }
  int bad = ferror(f);
  fclose(f);
  if (!text) return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", path);
  if (bad) { free(text); return ss_fail(err, SS_ERR_IO, "%s: read error", path); }
  /* the manifest's folder: relative paths in it are relative to that */
  char *base = dup_str(path);
  if (!base) { free(text); return ss_fail(err, SS_ERR_NOMEM, "%s: out of memory", path); }
  char *slash = strrchr(base, '/');
  if (slash) *(slash == base ? slash + 1 : slash) = 0;
  else base[0] = 0;
  ss_status st = ss_manifest_read_memory(text, n, path, base, m, err);
  free(base), free(text);
  return st;
}

void ss_manifest_free(ss_manifest *m) {
  if (!m) return;
  for (int i = 0; i < m->nmeshes; i++)
    free(m->meshes[i].name), free(m->meshes[i].path), free(m->meshes[i].landmarks), free(m->meshes[i].symmetry);
  for (int g = 0; g < m->ngroups; g++) free(m->groups[g].name), free(m->groups[g].landmarks), free(m->groups[g].symmetry);
  for (int i = 0; i < m->nmaps; i++) free(m->maps[i].path);
  free(m->meshes), free(m->groups), free(m->maps), free(m->px), free(m->py);
  memset(m, 0, sizeof *m);
}

int ss_manifest_find(const ss_manifest *m, const char *name) {
  for (int i = 0; i < m->nmeshes; i++)
    if (m->meshes[i].name && !strcmp(m->meshes[i].name, name)) return i;
  return -1;
}

const char *ss_manifest_map_path(const ss_manifest *m, int x, int y) {
  int lo = 0, hi = m->nmaps - 1;
  while (lo <= hi) {
    int mid = (lo + hi) / 2;
    const ss_manifest_map *p = &m->maps[mid];
    int c = p->x != x ? (p->x < x ? -1 : 1) : p->y != y ? (p->y < y ? -1 : 1) : 0;
    if (!c) return p->path;
    if (c < 0) lo = mid + 1;
    else hi = mid - 1;
  }
  return NULL;
}
