/* One prepared FAUST shape for the Table 1 runner: segmentation + eigenpairs (ss_shape_prep), its
 * own FPS landmarks and the landmark distance fields at its critical points for the three landmark
 * sets — all of it depends on the shape only, so it is computed once and optionally cached on disk. */
#include "eval_internal.h"
#include "specseg/io.h"
#include "specseg/spectrum.h"
#include "specseg/streamline.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

void ev_shape_free(ev_shape *s) {
  if (!s) return;
  free(s->rprep.evals), free(s->rprep.evecs); /* the rest of rprep is prep's */
  ss_shape_prep_free(&s->prep);
  ss_mesh_free(&s->mesh);
  for (int i = 0; i < 3; i++) free(s->lmd[i]), ss_fmap_probes_free(&s->base[i]);
  memset(s, 0, sizeof *s);
}

ss_status ev_fps_landmarks(const ss_mesh *m, const ss_segmentation *seg, const ss_segment_options *so, int seed_vertex,
                           int *lm, ss_error *err) {
  if (!seg->psi || seg->work.nv <= 0) return ss_fail(err, SS_ERR_INVALID, "fps landmarks: segmentation has no work mesh");
  if (seed_vertex < 0 || seed_vertex >= m->nv) return ss_fail(err, SS_ERR_INVALID, "fps landmarks: bad seed vertex");
  ss_geodesic_mesh *gm = NULL;
  ss_mesh smooth = {0};
  int pts[EV_NL];
  double P[3 * EV_NL];
  ss_status st = ss_geodesic_mesh_build(&seg->work, &gm, err);
  if (!st) st = ss_fps(gm, seg->psi[seed_vertex], EV_NL, pts, NULL, err);
  ss_geodesic_mesh_free(gm);
  if (st) return st;
  /* back to the input: the input vertex whose smoothed position is nearest (the smoothed mesh has
   * the input's connectivity; the CMCF settings are the segmentation's) */
  ss_cmcf_options co;
  ss_cmcf_default_options(&co);
  if (so && so->cmcf_steps > 0) co.steps = so->cmcf_steps;
  if (so && so->cmcf_dt > 0) co.dt = so->cmcf_dt;
  if ((st = ss_cmcf_smooth(m, &co, &smooth, err))) return st;
  for (int i = 0; i < EV_NL; i++) memcpy(P + 3 * i, seg->work.V + 3 * (size_t)pts[i], sizeof(double) * 3);
  st = ss_closest_vertices(P, EV_NL, &smooth, lm, err);
  ss_mesh_free(&smooth);
  if (st) return st;
  lm[0] = seed_vertex; /* the seed is the given input vertex itself (the only landmark known to match) */
  return SS_OK;
}

/* scaled exact distances from the landmarks of each set (Ψ-mapped to the work mesh) to the
 * critical points, as ss_pair_segments computes them */
static ss_status landmark_fields(ev_shape *s, const ev_context *ctx, ss_error *err) {
  const ss_segmentation *seg = &s->prep.seg;
  const ss_mesh *w = &seg->work;
  int src[3 * EV_NL];
  for (int set = 0; set < 3; set++)
    for (int i = 0; i < EV_NL; i++) src[set * EV_NL + i] = seg->psi[ev_landmarks(ctx, s, set)[i]];
  double *F = malloc(sizeof(double) * (size_t)w->nv * 3 * EV_NL);
  ss_geodesic_mesh *gm = NULL;
  ss_status st = F ? SS_OK : ss_fail(err, SS_ERR_NOMEM, "eval: out of memory");
  if (!st) st = ss_geodesic_mesh_build(w, &gm, err);
  if (!st) st = ss_geodesic_fields(gm, src, 3 * EV_NL, 0, F, err);
  if (!st) {
    double scale = 1.0 / sqrt(ss_mesh_area(w));
    for (int set = 0; set < 3 && !st; set++) {
      s->lmd[set] = malloc(sizeof(double) * (size_t)seg->m * EV_NL);
      if (!s->lmd[set]) { st = ss_fail(err, SS_ERR_NOMEM, "eval: out of memory"); break; }
      for (int i = 0; i < EV_NL; i++)
        for (int c = 0; c < seg->m; c++)
          s->lmd[set][c + (size_t)seg->m * i] = F[seg->crit[c] + (size_t)w->nv * (set * EV_NL + i)] * scale;
    }
  }
  ss_geodesic_mesh_free(gm);
  free(F);
  return st;
}

ss_status ev_shape_refined(ev_shape *s, const ev_context *ctx, ss_error *err) {
  if (ctx->kref <= 0 || s->rprep.evecs) return SS_OK;
  const int nv = s->mesh.nv, kr = ctx->kref;
  if (kr < 3 || kr >= nv) return ss_fail(err, SS_ERR_INVALID, "eval: %d eigenpairs on %d vertices", kr, nv);
  double t0 = ss_time(), *ev = malloc(sizeof(double) * (size_t)kr), *ph = malloc(sizeof(double) * (size_t)nv * kr);
  ss_status st = ev && ph ? ss_mesh_eigs(&s->mesh, kr, ev, ph, err) : ss_fail(err, SS_ERR_NOMEM, "eval: out of memory");
  if (st) {
    free(ev), free(ph);
    return st;
  }
  /* at unit area, as the prep's own eigenpairs (and with its masses) */
  ss_shape_prep_unit_area(s->prep.area, nv, kr, ev, ph, NULL);
  s->rprep = s->prep;
  s->rprep.mesh = &s->mesh;
  s->rprep.kev = kr, s->rprep.evals = ev, s->rprep.evecs = ph;
  s->rprep.t_segment = 0, s->rprep.t_eigs = ss_time() - t0;
  return SS_OK;
}

/* ---- disk cache ---------------------------------------------------------------------------------
 * One file per shape and key, DIR/faust_NNN_<FNV-1a of the key>.bin:
 *   line 1: the key, everything the content depends on: the format tag, the library version, the
 *           byte order and type sizes of the machine that wrote it, the input mesh (vertex / face
 *           counts and a 64-bit FNV-1a hash of its V and F arrays), the segmentation options, the
 *           basis size and the BEST / GT landmarks;
 *   line 2: "payload BYTES fnv1a64 HASH": the payload's length and the FNV-1a checksum of the key
 *           line followed by the payload;
 *   then the payload: raw native arrays (sizes, eigenpairs and masses at unit area as the prep holds
 *           them, labels, centres, Ψ, distances to the centres, FPS landmarks, landmark fields,
 *           the shape's area, timings).
 * An entry is used only when its key equals the current one, its length is exact and its checksum
 * matches (then its contents are range-checked once more); anything else — bytes flipped, a file
 * cut short, columns swapped, written by another version or for another mesh — is reported and
 * recomputed, and the file rewritten. A change to what the preparation computes must bump the tag.
 * The payload ends with the refined method's eigenpairs (their count, 0 when absent; the eigenvalues,
 * the eigenvectors and their seconds): an entry written without them is completed (rewritten) by a
 * run that needs them, and a run that does not skips them. */

#define CACHE_TAG "specseg-eval-v5"

static uint64_t fnv1a(uint64_t h, const void *data, size_t n) {
  const unsigned char *p = data;
  for (size_t i = 0; i < n; i++) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}
#define FNV_INIT 1469598103934665603ull

static uint64_t mesh_hash(const ss_mesh *m) {
  uint64_t h = fnv1a(FNV_INIT, &m->nv, sizeof m->nv);
  h = fnv1a(h, &m->nf, sizeof m->nf);
  h = fnv1a(h, m->V, sizeof(double) * 3 * (size_t)m->nv);
  return fnv1a(h, m->F, sizeof(int) * 3 * (size_t)m->nf);
}

static void cache_key(const ev_context *c, int id, const ss_mesh *mesh, char *key, size_t n) {
  const ss_segment_options *o = &c->mopt.seg;
  const uint16_t probe = 1;
  snprintf(key, n,
           CACHE_TAG " lib %d.%d.%d %s int%d double%d faust %03d mesh %d %d %016llx kev %d faces %d nostream %d "
           "cleanup %d neigs %d cmcf %d %.17g best %d %d %d %d %d gt %d %d %d %d %d\n",
           SPECSEG_VERSION_MAJOR, SPECSEG_VERSION_MINOR, SPECSEG_VERSION_PATCH, *(const unsigned char *)&probe ? "le" : "be",
           (int)sizeof(int), (int)sizeof(double), id, mesh->nv, mesh->nf, (unsigned long long)mesh_hash(mesh), c->kev,
           o->target_faces, o->no_streamline, o->cleanup_rings, o->n_eigs, o->cmcf_steps, o->cmcf_dt, c->best[0],
           c->best[1], c->best[2], c->best[3], c->best[4], c->gt[0], c->gt[1], c->gt[2], c->gt[3], c->gt[4]);
}

static void cache_path(const char *dir, const char *key, int id, char *path, size_t n) {
  snprintf(path, n, "%s/faust_%03d_%016llx.bin", dir, id, (unsigned long long)fnv1a(FNV_INIT, key, strlen(key)));
}

/* a growing byte buffer (writing) / a cursor over one (reading) */
typedef struct cbuf {
  unsigned char *p;
  size_t n, cap, pos;
  int bad;
} cbuf;

static void put(cbuf *b, const void *data, size_t n) {
  if (b->bad) return;
  if (b->n + n > b->cap) {
    size_t cap = b->cap ? b->cap : 1 << 16;
    while (cap < b->n + n) cap *= 2;
    unsigned char *q = realloc(b->p, cap);
    if (!q) { b->bad = 1; return; }
    b->p = q, b->cap = cap;
  }
  memcpy(b->p + b->n, data, n);
  b->n += n;
}

static int get(cbuf *b, void *data, size_t n) {
  if (b->bad || n > b->n - b->pos) return b->bad = 1, 0;
  memcpy(data, b->p + b->pos, n);
  b->pos += n;
  return 1;
}

#define PUT(ptr, cnt) put(&b, (ptr), sizeof *(ptr) * (size_t)(cnt))
#define GET(ptr, cnt) get(&b, (ptr), sizeof *(ptr) * (size_t)(cnt))

/* 1: loaded; 0: no file (nothing said); -1: the file is there but not usable (why: in note) */
static int cache_load(const char *path, const char *key, const ev_context *ctx, ev_shape *s, char *note,
                      size_t nnote) {
  FILE *f = fopen(path, "rb");
  if (!f) return 0;
  char line[1024], head[128];
  size_t len = 0;
  unsigned long long sum = 0;
  char tail;
  cbuf b = {0};
  int ok = 0;
  if (!fgets(line, sizeof line, f) || !strchr(line, '\n'))
    snprintf(note, nnote, "no key line");
  else if (strcmp(line, key)) {
    line[strcspn(line, "\n")] = 0;
    snprintf(note, nnote, "written for another version, mesh or options (key '%.300s')", line);
  } else if (!fgets(head, sizeof head, f) || sscanf(head, "payload %zu fnv1a64 %16llx%c", &len, &sum, &tail) != 3 ||
             tail != '\n' || len > ((size_t)1 << 34))
    snprintf(note, nnote, "no payload line (length and checksum)");
  else if (!(b.p = malloc(len ? len : 1)))
    snprintf(note, nnote, "out of memory for %zu bytes", len);
  else if ((b.n = fread(b.p, 1, len, f)) != len)
    snprintf(note, nnote, "truncated: %zu of %zu payload bytes", b.n, len);
  else if (fgetc(f) != EOF)
    snprintf(note, nnote, "longer than its %zu payload bytes", len);
  else {
    uint64_t h = fnv1a(fnv1a(FNV_INIT, key, strlen(key)), b.p, len);
    if (h != sum)
      snprintf(note, nnote, "checksum mismatch (stored %016llx, contents %016llx)", sum, (unsigned long long)h);
    else
      ok = 1;
  }
  fclose(f);
  if (!ok) return free(b.p), -1;

  int nv = 0, kev = 0, m = 0, wn = 0;
  ss_shape_prep *p = &s->prep;
  ok = GET(&nv, 1) && GET(&kev, 1) && GET(&m, 1) && GET(&wn, 1) && nv == s->mesh.nv && kev >= 3 && kev < nv &&
       m >= 1 && m <= nv && wn >= 1 && wn <= 16 * nv + 1000000;
  if (ok) {
    p->evals = malloc(sizeof(double) * (size_t)kev);
    p->evecs = malloc(sizeof(double) * (size_t)nv * kev);
    p->M = malloc(sizeof(double) * (size_t)nv);
    p->seg.labels = malloc(sizeof(int) * (size_t)nv);
    p->seg.centers = malloc(sizeof(int) * (size_t)m);
    /* Ψ and the distance to the segment centres: the tent-profile segment probes need them */
    p->seg.psi = malloc(sizeof(int) * (size_t)nv);
    p->seg.work_dist = malloc(sizeof(double) * (size_t)wn);
    for (int i = 0; i < 3; i++) s->lmd[i] = malloc(sizeof(double) * (size_t)m * EV_NL);
    ok = p->evals && p->evecs && p->M && p->seg.labels && p->seg.centers && p->seg.psi && p->seg.work_dist &&
         s->lmd[0] && s->lmd[1] && s->lmd[2];
    ok = ok && GET(p->evals, kev) && GET(p->evecs, (size_t)nv * kev) && GET(p->M, nv) && GET(p->seg.labels, nv) &&
         GET(p->seg.centers, m) && GET(p->seg.psi, nv) && GET(p->seg.work_dist, wn) && GET(s->fps, EV_NL) &&
         GET(s->lmd[0], m * EV_NL) && GET(s->lmd[1], m * EV_NL) && GET(s->lmd[2], m * EV_NL) && GET(&p->area, 1) && p->area > 0 &&
         isfinite(p->area) && GET(&s->t_prep, 1) && GET(&p->t_segment, 1) && GET(&p->t_eigs, 1);
    for (int i = 0; ok && i < nv; i++) ok = p->seg.labels[i] >= 0 && p->seg.labels[i] < m && p->seg.psi[i] >= 0 &&
                                            p->seg.psi[i] < wn;
    for (int i = 0; ok && i < m; i++) ok = p->seg.centers[i] >= 0 && p->seg.centers[i] < nv;
    for (int i = 0; ok && i < EV_NL; i++) ok = s->fps[i] >= 0 && s->fps[i] < nv;
  }
  /* the refined method's eigenpairs, when this run needs them and the entry has them */
  int kr = 0;
  double *rev = NULL, *rph = NULL, rt = 0;
  ok = ok && GET(&kr, 1) && kr >= 0 && kr < nv;
  if (ok && kr > 0 && kr == ctx->kref) {
    rev = malloc(sizeof(double) * (size_t)kr), rph = malloc(sizeof(double) * (size_t)nv * kr);
    ok = rev && rph && GET(rev, kr) && GET(rph, (size_t)nv * kr) && GET(&rt, 1);
    if (!ok) free(rev), free(rph), rev = rph = NULL;
  } else if (ok && kr > 0) { /* another run's refined eigenpairs: skipped */
    size_t skip = sizeof(double) * ((size_t)kr + (size_t)nv * kr + 1);
    ok = skip <= b.n - b.pos;
    b.pos += ok ? skip : 0;
  }
  ok = ok && b.pos == b.n;
  free(b.p);
  if (!ok) {
    snprintf(note, nnote, "checksum right but contents out of range (%d vertices, %d eigenpairs, %d segments)", nv, kev, m);
    ss_shape_prep_free(p);
    for (int i = 0; i < 3; i++) free(s->lmd[i]), s->lmd[i] = NULL;
    return -1;
  }
  p->mesh = &s->mesh;
  p->kev = kev;
  p->seg.nv = nv;
  p->seg.m = m;
  s->from_cache = 1;
  if (rev) {
    s->rprep = s->prep;
    s->rprep.kev = kr, s->rprep.evals = rev, s->rprep.evecs = rph;
    s->rprep.t_segment = 0, s->rprep.t_eigs = rt;
  }
  return 1;
}

static void cache_store(const char *path, const char *key, const ev_shape *s) {
  const ss_shape_prep *p = &s->prep;
  if (!p->seg.psi || !p->seg.work_dist) return;
  int nv = s->mesh.nv, m = p->seg.m, wn = p->seg.work.nv;
  cbuf b = {0};
  PUT(&nv, 1), PUT(&p->kev, 1), PUT(&m, 1), PUT(&wn, 1);
  PUT(p->evals, p->kev), PUT(p->evecs, (size_t)nv * p->kev), PUT(p->M, nv), PUT(p->seg.labels, nv);
  PUT(p->seg.centers, m), PUT(p->seg.psi, nv), PUT(p->seg.work_dist, wn), PUT(s->fps, EV_NL);
  PUT(s->lmd[0], m * EV_NL), PUT(s->lmd[1], m * EV_NL), PUT(s->lmd[2], m * EV_NL);
  PUT(&p->area, 1), PUT(&s->t_prep, 1), PUT(&p->t_segment, 1), PUT(&p->t_eigs, 1);
  const ss_shape_prep *r = &s->rprep;
  int kr = r->evecs ? r->kev : 0;
  PUT(&kr, 1);
  if (kr > 0) PUT(r->evals, kr), PUT(r->evecs, (size_t)nv * kr), PUT(&r->t_eigs, 1);
  char tmp[4300];
  snprintf(tmp, sizeof tmp, "%.4200s.tmp%ld", path, (long)getpid());
  FILE *f = b.bad ? NULL : fopen(tmp, "wb");
  if (!f) { free(b.p); return; } /* the cache is an optimisation: a read-only folder only costs time */
  uint64_t h = fnv1a(fnv1a(FNV_INIT, key, strlen(key)), b.p, b.n);
  int ok = fputs(key, f) >= 0 && fprintf(f, "payload %zu fnv1a64 %016llx\n", b.n, (unsigned long long)h) > 0 &&
           fwrite(b.p, 1, b.n, f) == b.n;
  ok = !fclose(f) && ok;
  free(b.p);
  /* rename is atomic: concurrent shards never see a half-written file */
  if (!ok || rename(tmp, path)) remove(tmp);
}

ss_status ev_shape_load(const char *data_dir, const char *cache_dir, int id, const ev_context *ctx, ev_shape *s,
                        char *note, size_t nnote, ss_error *err) {
  memset(s, 0, sizeof *s);
  if (note && nnote) note[0] = 0;
  s->id = id;
  char path[4096], key[1024], cpath[4200], why[512] = "";
  snprintf(path, sizeof path, "%s/faust/tr_reg_%03d.off", data_dir, id);
  ss_status st = ss_read_mesh(path, &s->mesh, err);
  if (st) return st;
  if (cache_dir) {
    cache_key(ctx, id, &s->mesh, key, sizeof key);
    cache_path(cache_dir, key, id, cpath, sizeof cpath);
    int r = cache_load(cpath, key, ctx, s, why, sizeof why);
    if (r > 0) {
      if (ctx->kref <= 0 || s->rprep.evecs) return SS_OK;
      /* an entry without this run's refined eigenpairs: add them */
      if ((st = ev_shape_refined(s, ctx, err))) goto fail;
      cache_store(cpath, key, s);
      return SS_OK;
    }
    if (r < 0 && note && nnote)
      snprintf(note, nnote, "eval cache: %s: %s; not used, recomputing tr_reg_%03d and rewriting the entry", cpath, why, id);
  }
  if ((st = ev_shape_prepare(s, ctx, err))) goto fail;
  if (cache_dir) cache_store(cpath, key, s);
  return SS_OK;
fail:
  ev_shape_free(s);
  return st;
}

ss_status ev_shape_prepare(ev_shape *s, const ev_context *ctx, ss_error *err) {
  ss_status st;
  double t0 = ss_time();
  st = ss_shape_prep_compute(&s->mesh, &ctx->mopt.seg, ctx->kev, &s->prep, err);
  if (st) goto fail;
  if ((st = ev_fps_landmarks(&s->mesh, &s->prep.seg, &ctx->mopt.seg, 0, s->fps, err))) goto fail;
  if ((st = landmark_fields(s, ctx, err))) goto fail;
  s->t_prep = ss_time() - t0;
  if ((st = ev_shape_refined(s, ctx, err))) goto fail;
  return SS_OK;
fail:
  free(s->rprep.evals), free(s->rprep.evecs);
  memset(&s->rprep, 0, sizeof s->rprep);
  ss_shape_prep_free(&s->prep);
  for (int i = 0; i < 3; i++) free(s->lmd[i]), s->lmd[i] = NULL;
  return st;
}
