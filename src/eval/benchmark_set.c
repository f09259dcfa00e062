/* A benchmark folder (the remeshed FAUST_r / TOSCA_r layout): its meshes, ground-truth point files,
 * pairs (a pairs file, test_pairs.txt or every ordered pair, optionally sampled) and the classes of
 * shape names. */
#include "benchmark_internal.h"
#include "specseg/io.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

char *bm_strdup(const char *s) {
  if (!s) return NULL;
  size_t n = strlen(s) + 1;
  char *d = malloc(n);
  if (d) memcpy(d, s, n);
  return d;
}

char *bm_join(const char *dir, const char *name) {
  size_t a = strlen(dir), b = strlen(name);
  char *p = malloc(a + b + 2);
  if (!p) return NULL;
  memcpy(p, dir, a);
  size_t k = a;
  if (a && dir[a - 1] != '/') p[k++] = '/';
  memcpy(p + k, name, b + 1);
  return p;
}

int bm_is_dir(const char *path) {
  struct stat st;
  return path && !stat(path, &st) && S_ISDIR(st.st_mode);
}

static int is_file(const char *path) {
  struct stat st;
  return path && !stat(path, &st) && S_ISREG(st.st_mode);
}

/* names with numbers compared by value (cat2 < cat10, tr_reg_009 < tr_reg_010), then as strings */
int bm_name_cmp(const char *a, const char *b) {
  const char *p = a, *q = b;
  while (*p && *q) {
    if (isdigit((unsigned char)*p) && isdigit((unsigned char)*q)) {
      const char *p0 = p, *q0 = q;
      while (*p0 == '0' && isdigit((unsigned char)p0[1])) p0++;
      while (*q0 == '0' && isdigit((unsigned char)q0[1])) q0++;
      const char *p1 = p0, *q1 = q0;
      while (isdigit((unsigned char)*p1)) p1++;
      while (isdigit((unsigned char)*q1)) q1++;
      if (p1 - p0 != q1 - q0) return p1 - p0 < q1 - q0 ? -1 : 1;
      int c = strncmp(p0, q0, (size_t)(p1 - p0));
      if (c) return c < 0 ? -1 : 1;
      while (isdigit((unsigned char)*p)) p++;
      while (isdigit((unsigned char)*q)) q++;
      continue;
    }
    if (*p != *q) return (unsigned char)*p < (unsigned char)*q ? -1 : 1;
    p++, q++;
  }
  if (*p || *q) return *p ? 1 : -1;
  int c = strcmp(a, b);
  return (c > 0) - (c < 0);
}

void ss_benchmark_class(const char *name, char *cls, size_t n) {
  if (!cls || n == 0) return;
  size_t len = name ? strlen(name) : 0, k = len;
  while (k > 0 && isdigit((unsigned char)name[k - 1])) k--;
  if (k == 0) k = len; /* digits only: its own class */
  if (k >= n) k = n - 1;
  if (k) memcpy(cls, name, k);
  cls[k] = 0;
}

void ss_benchmark_pair_class(const char *x, const char *y, char *cls, size_t n) {
  char a[SS_BENCH_NAME], b[SS_BENCH_NAME];
  ss_benchmark_class(x, a, sizeof a);
  ss_benchmark_class(y, b, sizeof b);
  if (!strcmp(a, b)) snprintf(cls, n, "%s", a);
  else snprintf(cls, n, "%.46s/%.46s", a, b);
}

void ss_benchmark_set_free(ss_benchmark_set *b) {
  if (!b) return;
  for (int i = 0; i < b->nshapes; i++) {
    free(b->shapes[i].name), free(b->shapes[i].mesh);
    free(b->shapes[i].vts), free(b->shapes[i].sym);
  }
  free(b->shapes), free(b->px), free(b->py);
  free(b->dir), free(b->mesh_dir), free(b->corres_dir), free(b->pairs_file);
  memset(b, 0, sizeof *b);
}

static int shape_cmp(const void *a, const void *b) {
  return bm_name_cmp(((const ss_benchmark_shape *)a)->name, ((const ss_benchmark_shape *)b)->name);
}

/* the mesh files of a folder (regular files with an extension ss_read_mesh reads, hidden ones
 * skipped) as shapes; -1 when it cannot be listed */
static int list_meshes(const char *dir, ss_benchmark_shape **out, int *n, ss_error *err, ss_status *st) {
  *out = NULL, *n = 0, *st = SS_OK;
  DIR *d = opendir(dir);
  if (!d) return -1;
  int cap = 0;
  struct dirent *e;
  while ((e = readdir(d))) {
    if (e->d_name[0] == '.') continue;
    const char *dot = strrchr(e->d_name, '.');
    if (!dot || dot == e->d_name || !ss_mesh_extension_supported(e->d_name)) continue;
    char *path = bm_join(dir, e->d_name);
    if (!path) { *st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); break; }
    if (!is_file(path)) { free(path); continue; }
    if (*n == cap) {
      cap = cap ? 2 * cap : 64;
      ss_benchmark_shape *g = realloc(*out, sizeof **out * (size_t)cap);
      if (!g) { free(path); *st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); break; }
      *out = g;
    }
    ss_benchmark_shape *s = &(*out)[(*n)++];
    memset(s, 0, sizeof *s);
    s->mesh = path;
    s->name = malloc((size_t)(dot - e->d_name) + 1);
    if (!s->name) { *st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); break; }
    memcpy(s->name, e->d_name, (size_t)(dot - e->d_name));
    s->name[dot - e->d_name] = 0;
  }
  closedir(d);
  return 0;
}

/* a pairs file: two names a line */
typedef struct name_pair {
  char *x, *y;
} name_pair;

static ss_status read_pairs(const char *path, name_pair **out, int *n, ss_error *err) {
  *out = NULL, *n = 0;
  FILE *f = fopen(path, "rb");
  if (!f) return ss_fail(err, SS_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
  char line[4096];
  int cap = 0, ln = 0;
  ss_status st = SS_OK;
  while (fgets(line, sizeof line, f)) {
    ln++;
    size_t len = strlen(line);
    if (len == sizeof line - 1 && line[len - 1] != '\n') { st = ss_fail(err, SS_ERR_PARSE, "%s:%d: line too long", path, ln); break; }
    char *h = strchr(line, '#');
    if (h) *h = 0;
    char *tok[3];
    int nt = 0;
    for (char *t = strtok(line, " \t\r\n"); t && nt < 3; t = strtok(NULL, " \t\r\n")) tok[nt++] = t;
    if (nt == 0) continue;
    if (nt != 2) {
      st = ss_fail(err, SS_ERR_PARSE, "%s:%d: %s; a pair is two shape names, tab or blank separated", path, ln,
                   nt == 1 ? "one name only" : "more than two names");
      break;
    }
    if (strlen(tok[0]) >= SS_BENCH_NAME || strlen(tok[1]) >= SS_BENCH_NAME) {
      st = ss_fail(err, SS_ERR_PARSE, "%s:%d: a name longer than %d characters", path, ln, SS_BENCH_NAME - 1);
      break;
    }
    if (!strcmp(tok[0], tok[1])) { st = ss_fail(err, SS_ERR_PARSE, "%s:%d: a pair of '%s' with itself", path, ln, tok[0]); break; }
    if (*n == cap) {
      cap = cap ? 2 * cap : 256;
      name_pair *g = realloc(*out, sizeof **out * (size_t)cap);
      if (!g) { st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); break; }
      *out = g;
    }
    (*out)[*n].x = bm_strdup(tok[0]), (*out)[*n].y = bm_strdup(tok[1]);
    if (!(*out)[*n].x || !(*out)[*n].y) {
      free((*out)[*n].x), free((*out)[*n].y);
      st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory");
      break;
    }
    (*n)++;
  }
  if (!st && ferror(f)) st = ss_fail(err, SS_ERR_IO, "%s: read error", path);
  fclose(f);
  if (st) {
    for (int i = 0; i < *n; i++) free((*out)[i].x), free((*out)[i].y);
    free(*out);
    *out = NULL, *n = 0;
  }
  return st;
}

int bm_find_shape(const ss_benchmark_set *b, const char *name) {
  int lo = 0, hi = b->nshapes - 1;
  while (lo <= hi) {
    int mid = (lo + hi) / 2, c = bm_name_cmp(name, b->shapes[mid].name);
    if (!c) return mid;
    if (c < 0) hi = mid - 1;
    else lo = mid + 1;
  }
  return -1;
}

ss_status ss_benchmark_open(const char *dir, const char *pairs_file, int max_pairs, uint64_t seed, ss_benchmark_set *b,
                            ss_error *err) {
  if (!b) return ss_fail(err, SS_ERR_INVALID, "benchmark: no output");
  memset(b, 0, sizeof *b);
  if (!dir || !*dir) return ss_fail(err, SS_ERR_INVALID, "benchmark: no folder");
  if (max_pairs < 0) return ss_fail(err, SS_ERR_INVALID, "benchmark: max_pairs %d < 0", max_pairs);
  if (!bm_is_dir(dir)) return ss_fail(err, SS_ERR_IO, "%s: not a folder", dir);
  ss_status st = SS_OK;
  name_pair *np = NULL;
  int nnp = 0;
  b->dir = bm_strdup(dir);
  if (!b->dir) { st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); goto fail; }
  /* 1. the meshes: in dir, or in its vtx_5k/, off/ or shapes/ */
  {
    static const char *const sub[4] = {"", "vtx_5k", "off", "shapes"};
    for (int i = 0; i < 4 && !b->nshapes; i++) {
      char *md = i ? bm_join(dir, sub[i]) : bm_strdup(dir);
      if (!md) { st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); goto fail; }
      ss_benchmark_shape *sh = NULL;
      int n = 0;
      if (bm_is_dir(md) && list_meshes(md, &sh, &n, err, &st) == 0 && !st && n > 0) {
        b->mesh_dir = md, b->shapes = sh, b->nshapes = n;
      } else {
        for (int k = 0; k < n; k++) free(sh[k].name), free(sh[k].mesh);
        free(sh);
        free(md);
        if (st) goto fail;
      }
    }
    if (!b->nshapes) {
      st = ss_fail(err, SS_ERR_IO, "%s: no mesh files in it (nor in its vtx_5k/, off/ or shapes/)", dir);
      goto fail;
    }
    qsort(b->shapes, (size_t)b->nshapes, sizeof *b->shapes, shape_cmp);
    for (int i = 1; i < b->nshapes; i++)
      if (!strcmp(b->shapes[i].name, b->shapes[i - 1].name)) {
        st = ss_fail(err, SS_ERR_INVALID, "%s: two meshes named %s (%s, %s): keep one", b->mesh_dir, b->shapes[i].name,
                     b->shapes[i - 1].mesh, b->shapes[i].mesh);
        goto fail;
      }
    for (int i = 0; i < b->nshapes; i++)
      if (strlen(b->shapes[i].name) >= SS_BENCH_NAME) {
        st = ss_fail(err, SS_ERR_INVALID, "%s: a name longer than %d characters", b->shapes[i].mesh, SS_BENCH_NAME - 1);
        goto fail;
      }
  }
  /* 2. the ground-truth points: corres/ beside the meshes, or in dir */
  {
    char *c1 = bm_join(b->mesh_dir, "corres"), *c2 = bm_join(dir, "corres");
    if (!c1 || !c2) { free(c1), free(c2); st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); goto fail; }
    if (bm_is_dir(c1)) b->corres_dir = c1, free(c2);
    else if (bm_is_dir(c2)) b->corres_dir = c2, free(c1);
    else {
      st = ss_fail(err, SS_ERR_IO, "%s: no corres/ folder of ground-truth points (NAME.vts) beside the meshes or in %s",
                   b->mesh_dir, dir);
      free(c1), free(c2);
      goto fail;
    }
  }
  /* 3. the pairs */
  if (pairs_file) {
    b->pairs_file = bm_strdup(pairs_file);
  } else {
    char *t1 = bm_join(dir, "test_pairs.txt"), *t2 = bm_join(b->mesh_dir, "test_pairs.txt");
    if (!t1 || !t2) { free(t1), free(t2); st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); goto fail; }
    if (is_file(t1)) b->pairs_file = t1, free(t2);
    else if (is_file(t2)) b->pairs_file = t2, free(t1);
    else free(t1), free(t2);
  }
  if (b->pairs_file) {
    if ((st = read_pairs(b->pairs_file, &np, &nnp, err))) goto fail;
    /* names without a mesh file become shapes without one (their pairs are skipped when run) */
    for (int i = 0; i < nnp; i++)
      for (int s = 0; s < 2; s++) {
        const char *nm = s ? np[i].y : np[i].x;
        if (bm_find_shape(b, nm) >= 0) continue;
        ss_benchmark_shape *g = realloc(b->shapes, sizeof *g * (size_t)(b->nshapes + 1));
        if (!g) { st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); goto fail; }
        b->shapes = g;
        memset(&g[b->nshapes], 0, sizeof *g);
        if (!(g[b->nshapes].name = bm_strdup(nm))) { st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); goto fail; }
        b->nshapes++;
        qsort(b->shapes, (size_t)b->nshapes, sizeof *b->shapes, shape_cmp);
      }
    b->nall = nnp;
  } else {
    long all = (long)b->nshapes * (b->nshapes - 1);
    if (all > 50000000) {
      st = ss_fail(err, SS_ERR_INVALID, "%s: %d shapes make %ld ordered pairs; give a pairs file or --max-pairs", dir,
                   b->nshapes, all);
      goto fail;
    }
    b->nall = (int)all;
  }
  if (b->nall < 1) { st = ss_fail(err, SS_ERR_INVALID, "%s: no pairs", b->pairs_file ? b->pairs_file : dir); goto fail; }
  /* 4. ground-truth files per shape */
  for (int i = 0; i < b->nshapes; i++) {
    char fn[SS_BENCH_NAME + 16];
    snprintf(fn, sizeof fn, "%s.vts", b->shapes[i].name);
    char *v = bm_join(b->corres_dir, fn);
    snprintf(fn, sizeof fn, "%s.sym.vts", b->shapes[i].name);
    char *s = bm_join(b->corres_dir, fn);
    if (!v || !s) { free(v), free(s); st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); goto fail; }
    if (is_file(v)) b->shapes[i].vts = v;
    else free(v);
    if (is_file(s)) b->shapes[i].sym = s;
    else free(s);
  }
  /* 5. the pair list, sampled: the first max_pairs of a seeded permutation, kept in the list's order */
  {
    int n = b->nall, m = max_pairs > 0 && max_pairs < n ? max_pairs : n;
    int *pick = malloc(sizeof(int) * (size_t)n);
    b->px = malloc(sizeof(int) * (size_t)m), b->py = malloc(sizeof(int) * (size_t)m);
    if (!pick || !b->px || !b->py) { free(pick); st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); goto fail; }
    for (int i = 0; i < n; i++) pick[i] = i;
    if (m < n) {
      ss_rng r;
      ss_rng_seed(&r, seed);
      for (int i = 0; i < m; i++) {
        int j = i + ss_rng_below(&r, n - i), t = pick[i];
        pick[i] = pick[j], pick[j] = t;
      }
      /* back into list order (insertion sort of m indices would be O(m^2); counting instead) */
      unsigned char *mark = calloc((size_t)n, 1);
      if (!mark) { free(pick); st = ss_fail(err, SS_ERR_NOMEM, "benchmark: out of memory"); goto fail; }
      for (int i = 0; i < m; i++) mark[pick[i]] = 1;
      int k = 0;
      for (int i = 0; i < n; i++)
        if (mark[i]) pick[k++] = i;
      free(mark);
    }
    for (int i = 0; i < m; i++) {
      int p = pick[i];
      if (np) {
        b->px[i] = bm_find_shape(b, np[p].x), b->py[i] = bm_find_shape(b, np[p].y);
      } else { /* ordered pair p of all: x = p / (n-1), y the (p mod (n-1))-th other shape */
        int x = p / (b->nshapes - 1), y = p % (b->nshapes - 1);
        b->px[i] = x, b->py[i] = y >= x ? y + 1 : y;
      }
    }
    b->npairs = m;
    free(pick);
  }
  for (int i = 0; i < nnp; i++) free(np[i].x), free(np[i].y);
  free(np);
  return SS_OK;
fail:
  for (int i = 0; i < nnp; i++) free(np[i].x), free(np[i].y);
  free(np);
  ss_benchmark_set_free(b);
  return st;
}
