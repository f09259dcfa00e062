/* The files a manifest names beyond its meshes, read for the Table 1 runner: landmark files, the GT
 * landmarks of the paper's FPS procedure (on each group's reference, carried to the group's meshes
 * by the ground truth), symmetry maps and ground-truth maps — each checked before use. */
#include "eval_internal.h"
#include "specseg/io.h"

#include <stdlib.h>
#include <string.h>

void ev_manifest_data_free(ev_manifest_data *d) {
  if (!d) return;
  for (int i = 0; i < d->n && d->sym; i++)
    if (d->owned[i]) free(d->sym[i]);
  free(d->best), free(d->gt), free(d->sym), free(d->owned), free(d->symn);
  memset(d, 0, sizeof *d);
}

static ss_status read_landmarks(const char *path, int *lm, ss_error *err) {
  int *v = NULL, n = 0;
  ss_status st = ss_read_ints(path, &v, &n, err);
  if (st) return st;
  if (n != EV_NL) st = ss_fail(err, SS_ERR_PARSE, "%s: %d landmarks, %d expected (the paper's count)", path, n, EV_NL);
  else memcpy(lm, v, sizeof(int) * EV_NL);
  free(v);
  return st;
}

ss_status ev_manifest_gt_map(const ss_manifest *m, int x, int y, int nvx, int nvy, int **map, ss_error *err) {
  *map = NULL;
  const char *path = ss_manifest_map_path(m, x, y);
  if (!path)
    return ss_fail(err, SS_ERR_INVALID, "manifest: no ground-truth map '%s' -> '%s'", m->meshes[x].name, m->meshes[y].name);
  int *v = NULL, n = 0;
  ss_status st = ss_read_ints(path, &v, &n, err);
  if (st) return st;
  if (n != nvx) st = ss_fail(err, SS_ERR_PARSE, "%s: %d lines, the source '%s' has %d vertices", path, n, m->meshes[x].name, nvx);
  for (int i = 0; i < n && !st; i++)
    if (v[i] < 0 || v[i] >= nvy)
      st = ss_fail(err, SS_ERR_PARSE, "%s:%d: vertex %d, the target '%s' has %d vertices (0-based)", path, i + 1, v[i],
                   m->meshes[y].name, nvy);
  if (st) free(v);
  else *map = v;
  return st;
}

ss_status ev_manifest_data_load(const ss_manifest *m, const ev_context *ctx, int lm_mask, ev_manifest_data *d,
                                ss_error *err) {
  memset(d, 0, sizeof *d);
  const int n = m->nmeshes;
  d->n = n;
  d->best = calloc((size_t)n, sizeof *d->best);
  d->gt = calloc((size_t)n, sizeof *d->gt);
  d->sym = calloc((size_t)n, sizeof *d->sym);
  d->owned = calloc((size_t)n, sizeof *d->owned);
  d->symn = calloc((size_t)n, sizeof *d->symn);
  if (!d->best || !d->gt || !d->sym || !d->owned || !d->symn) {
    ev_manifest_data_free(d);
    return ss_fail(err, SS_ERR_NOMEM, "manifest: out of memory");
  }
  /* meshes in no pair are never prepared: they need no carried landmarks */
  char *used = calloc((size_t)n, 1);
  if (!used) {
    ev_manifest_data_free(d);
    return ss_fail(err, SS_ERR_NOMEM, "manifest: out of memory");
  }
  for (int p = 0; p < m->npairs; p++) used[m->px[p]] = used[m->py[p]] = 1;
  ss_status st = SS_OK;
  for (int g = 0; g < m->ngroups && !st; g++) {
    const ss_manifest_group *G = &m->groups[g];
    /* BEST: the mesh's own file, else the group's (identity ground truth) */
    if (lm_mask >> SS_LM_BEST & 1) {
      int glm[EV_NL], have = 0;
      for (int i = G->first; i < G->first + G->count && !st; i++) {
        const char *f = m->meshes[i].landmarks;
        if (f) st = read_landmarks(f, d->best[i], err);
        else if (G->landmarks) {
          if (!have && !(st = read_landmarks(G->landmarks, glm, err))) have = 1;
          if (!st) memcpy(d->best[i], glm, sizeof glm);
        } else
          st = ss_fail(err, SS_ERR_INVALID,
                       "manifest: group '%s': mesh '%s' has no landmarks for the set 'best' (give 'landmarks file FILE' "
                       "or 'mesh ... landmarks FILE', or leave 'best' out of --landmarks)",
                       G->name, m->meshes[i].name);
      }
    }
    /* GT: the paper's FPS procedure on the reference, carried by the ground truth */
    if (!st && (lm_mask >> SS_LM_GT & 1)) {
      int ref[EV_NL];
      const int r = G->reference;
      if ((st = ev_fps_file(m->meshes[r].path, G->fps_seed, ctx, ref, err))) break;
      for (int i = G->first; i < G->first + G->count && !st; i++) {
        if (i == r || !G->gt_maps || !used[i]) { memcpy(d->gt[i], ref, sizeof ref); continue; }
        /* the map's length is checked against the reference's vertex count by reading the mesh's header */
        ss_mesh mr = {0}, mi = {0};
        int *map = NULL;
        st = ss_read_mesh(m->meshes[r].path, &mr, err);
        if (!st) st = ss_read_mesh(m->meshes[i].path, &mi, err);
        if (!st && !ss_manifest_map_path(m, r, i))
          st = ss_fail(err, SS_ERR_INVALID,
                       "manifest: group '%s' (gt maps): the GT landmarks need a map from the reference '%s' to '%s'", G->name,
                       m->meshes[r].name, m->meshes[i].name);
        if (!st) st = ev_manifest_gt_map(m, r, i, mr.nv, mi.nv, &map, err);
        for (int l = 0; l < EV_NL && !st; l++) d->gt[i][l] = map[ref[l]];
        free(map), ss_mesh_free(&mr), ss_mesh_free(&mi);
      }
    }
    /* symmetry maps: read here, checked (and identities made) by ev_manifest_symmetry */
    int *gsym = NULL, ngsym = 0;
    for (int i = G->first; i < G->first + G->count && !st; i++) {
      const char *f = m->meshes[i].symmetry;
      int k = 0;
      if (f) {
        if (!(st = ss_read_ints(f, &d->sym[i], &k, err))) d->owned[i] = 1, d->symn[i] = k;
      } else if (G->symmetry) {
        if (!gsym && !(st = ss_read_ints(G->symmetry, &gsym, &ngsym, err))) d->owned[i] = 1; /* the first user owns it */
        d->sym[i] = gsym, d->symn[i] = ngsym;
      }
    }
  }
  free(used);
  if (st) ev_manifest_data_free(d);
  return st;
}

ss_status ev_manifest_symmetry(const ss_manifest *m, const int *nv, ev_manifest_data *d, ss_error *err) {
  for (int i = 0; i < m->nmeshes; i++) {
    if (nv[i] <= 0) continue; /* not needed by this run */
    if (!d->sym[i]) {
      if (!(d->sym[i] = malloc(sizeof(int) * (size_t)nv[i]))) return ss_fail(err, SS_ERR_NOMEM, "manifest: out of memory");
      d->owned[i] = 1;
      for (int v = 0; v < nv[i]; v++) d->sym[i][v] = v;
      continue;
    }
    const ss_manifest_mesh *s = &m->meshes[i];
    const char *f = s->symmetry ? s->symmetry : m->groups[s->group].symmetry;
    const int n = d->symn[i];
    if (n != nv[i]) return ss_fail(err, SS_ERR_PARSE, "%s: %d lines, mesh '%s' has %d vertices", f, n, s->name, nv[i]);
    for (int x = 0; x < n; x++)
      if (d->sym[i][x] < 0 || d->sym[i][x] >= nv[i])
        return ss_fail(err, SS_ERR_PARSE, "%s:%d: vertex %d, mesh '%s' has %d vertices (0-based)", f, x + 1, d->sym[i][x],
                       s->name, nv[i]);
  }
  return SS_OK;
}
