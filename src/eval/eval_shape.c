/* One prepared FAUST shape for the Table 1 runner: segmentation + eigenpairs (ss_shape_prep), its
 * own FPS landmarks and the landmark distance fields at its critical points for the three landmark
 * sets — all of it depends on the shape only, so it is computed once and optionally cached on disk. */
#include "eval_internal.h"
#include "util/c_locale.h"
#include "util/blob.h"
#include "specseg/io.h"
#include "specseg/spectrum.h"
#include "specseg/streamline.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* rprep's own parts (the rest of rprep is prep's): its eigenpairs and probe cache */
static void rprep_free(ev_shape *s) {
  free(s->rprep.evals), free(s->rprep.evecs);
  for (int i = 0; i < s->rprep.nprobe_cache && s->rprep.probe_cache; i++) ss_fmap_probe_cache_free(&s->rprep.probe_cache[i]);
  free(s->rprep.probe_cache);
  memset(&s->rprep, 0, sizeof s->rprep);
}

/* rprep as a prepared shape of the refined method's matches: its probe cache, once per shape rather
 * than in every match (rprep starts as a shallow copy of prep, which has none) */
static ss_status rprep_cache(ev_shape *s, const ev_context *ctx, ss_error *err) {
  s->rprep.probe_cache = NULL, s->rprep.nprobe_cache = 0;
  return ss_shape_prep_probe_cache(&s->rprep, &ctx->ropt, err);
}

void ev_shape_free(ev_shape *s) {
  if (!s) return;
  rprep_free(s);
  ss_shape_prep_free(&s->prep);
  ss_mesh_free(&s->mesh);
  for (int i = 0; i < 3; i++) free(s->lmd[i]), ss_fmap_probes_free(&s->base[i]);
  ss_centre_signature_free(&s->sig);
  memset(s, 0, sizeof *s);
}

ss_status ev_shape_signature(ev_shape *s, const ev_context *ctx, ss_error *err) {
  if (s->sig.m > 0) return SS_OK;
  return ss_centre_signature_compute(&s->prep, &ctx->mopt.autopair, &s->sig, err);
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
  if (!st) st = ss_geodesic_fields_targets(gm, src, 3 * EV_NL, seg->crit, seg->m, F, err); /* needed there only */
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
  if ((st = rprep_cache(s, ctx, err))) rprep_free(s);
  return st;
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

/* The shape's identity in the key: "faust NNN" for FAUST (the key of earlier versions, so their
 * entries stay valid), "file" for any other mesh, which the mesh hash and the landmarks identify
 * (the same mesh under two names or manifests shares its entry). */
static void cache_key(const ev_context *c, const ev_shape *s, int faust, const ss_mesh *mesh, char *key, size_t n) {
  const ss_segment_options *o = &c->mopt.seg;
  const int *b = ev_landmarks(c, s, SS_LM_BEST), *g = ev_landmarks(c, s, SS_LM_GT);
  char who[32];
  if (faust) snprintf(who, sizeof who, "faust %03d", s->id);
  else snprintf(who, sizeof who, "file");
  ssi_snprintf_c(key, n,
           CACHE_TAG " lib %d.%d.%d %s int%d double%d %s mesh %d %d %016llx kev %d faces %d nostream %d "
           "cleanup %d neigs %d cmcf %d %.17g best %d %d %d %d %d gt %d %d %d %d %d\n",
           SPECSEG_VERSION_MAJOR, SPECSEG_VERSION_MINOR, SPECSEG_VERSION_PATCH, ssi_byte_order(),
           (int)sizeof(int), (int)sizeof(double), who, mesh->nv, mesh->nf, (unsigned long long)ssi_mesh_hash(mesh), c->kev,
           o->target_faces, o->no_streamline, o->cleanup_rings, o->n_eigs, o->cmcf_steps, o->cmcf_dt, b[0], b[1], b[2],
           b[3], b[4], g[0], g[1], g[2], g[3], g[4]);
}

/* DIR/faust_NNN_<key hash>.bin, or DIR/<label>_<key hash>.bin (label's characters outside
 * [A-Za-z0-9._-] as '_', at most 64) */
static void cache_path(const char *dir, const char *key, const char *label, char *path, size_t n) {
  char name[72];
  size_t j = 0;
  for (const char *c = label; *c && j < 64; c++)
    name[j++] = (*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || *c == '.' ||
                        *c == '-' || *c == '_'
                    ? *c
                    : '_';
  name[j] = 0;
  snprintf(path, n, "%s/%s_%016llx.bin", dir, name, (unsigned long long)ssi_fnv1a(SSI_FNV_INIT, key, strlen(key)));
}

#define PUT(ptr, cnt) SSI_PUT(&b, (ptr), (cnt))
#define GET(ptr, cnt) SSI_GET(&b, (ptr), (cnt))

/* 1: loaded; 0: no file (nothing said); -1: the file is there but not usable (why: in note) */
static int cache_load(const char *path, const char *key, const ev_context *ctx, ev_shape *s, char *note,
                      size_t nnote) {
  ssi_blob b;
  int r = ssi_blob_read(path, key, NULL, 0, &b, note, nnote);
  if (r <= 0) return r;

  int ok, nv = 0, kev = 0, m = 0, wn = 0;
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
    ok = ssi_blob_skip(&b, skip);
  }
  ok = ok && b.pos == b.n;
  ssi_blob_free(&b);
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
  ssi_blob b = {0};
  PUT(&nv, 1), PUT(&p->kev, 1), PUT(&m, 1), PUT(&wn, 1);
  PUT(p->evals, p->kev), PUT(p->evecs, (size_t)nv * p->kev), PUT(p->M, nv), PUT(p->seg.labels, nv);
  PUT(p->seg.centers, m), PUT(p->seg.psi, nv), PUT(p->seg.work_dist, wn), PUT(s->fps, EV_NL);
  PUT(s->lmd[0], m * EV_NL), PUT(s->lmd[1], m * EV_NL), PUT(s->lmd[2], m * EV_NL);
  PUT(&p->area, 1), PUT(&s->t_prep, 1), PUT(&p->t_segment, 1), PUT(&p->t_eigs, 1);
  const ss_shape_prep *r = &s->rprep;
  int kr = r->evecs ? r->kev : 0;
  PUT(&kr, 1);
  if (kr > 0) PUT(r->evals, kr), PUT(r->evecs, (size_t)nv * kr), PUT(&r->t_eigs, 1);
  /* the cache is an optimisation: a read-only folder only costs time */
  (void)ssi_blob_write(path, key, &b);
  ssi_blob_free(&b);
}

static ss_status shape_load(const char *path, const char *label, const char *shown, int faust, const char *cache_dir, int id,
                            const int *best, const int *gt, const ev_context *ctx, ev_shape *s, char *note, size_t nnote,
                            ss_error *err) {
  memset(s, 0, sizeof *s);
  if (note && nnote) note[0] = 0;
  s->id = id;
  if (best || gt) {
    s->own_lm = 1;
    memcpy(s->best, best ? best : ctx->best, sizeof s->best);
    memcpy(s->gt, gt ? gt : ctx->gt, sizeof s->gt);
  }
  char key[1024], cpath[4200], why[512] = "";
  ss_status st = ss_read_mesh(path, &s->mesh, err);
  if (st) return st;
  for (int set = 0; set < 2 && s->own_lm; set++)
    for (int i = 0; i < EV_NL; i++) {
      int v = set ? s->gt[i] : s->best[i];
      if (v < 0 || v >= s->mesh.nv) {
        st = ss_fail(err, SS_ERR_INVALID, "%s: %s landmark %d is vertex %d, the mesh has %d vertices", path,
                     set ? "gt" : "best", i + 1, v, s->mesh.nv);
        goto fail;
      }
    }
  if (cache_dir) {
    cache_key(ctx, s, faust, &s->mesh, key, sizeof key);
    cache_path(cache_dir, key, label, cpath, sizeof cpath);
    int r = cache_load(cpath, key, ctx, s, why, sizeof why);
    if (r > 0) {
      if (ctx->kref <= 0) return SS_OK;
      if (s->rprep.evecs) {
        if ((st = rprep_cache(s, ctx, err))) goto fail;
        return SS_OK;
      }
      /* an entry without this run's refined eigenpairs: add them */
      if ((st = ev_shape_refined(s, ctx, err))) goto fail;
      cache_store(cpath, key, s);
      return SS_OK;
    }
    if (r < 0 && note && nnote)
      snprintf(note, nnote, "eval cache: %s: %s; not used, recomputing %s and rewriting the entry", cpath, why, shown);
  }
  if ((st = ev_shape_prepare(s, ctx, err))) goto fail;
  if (cache_dir) cache_store(cpath, key, s);
  return SS_OK;
fail:
  ev_shape_free(s);
  return st;
}

ss_status ev_shape_load(const char *data_dir, const char *cache_dir, int id, const ev_context *ctx, ev_shape *s,
                        char *note, size_t nnote, ss_error *err) {
  char path[4096], label[32], shown[32];
  snprintf(path, sizeof path, "%s/faust/tr_reg_%03d.off", data_dir, id);
  snprintf(label, sizeof label, "faust_%03d", id);
  snprintf(shown, sizeof shown, "tr_reg_%03d", id);
  return shape_load(path, label, shown, 1, cache_dir, id, NULL, NULL, ctx, s, note, nnote, err);
}

ss_status ev_shape_load_file(const char *path, const char *label, const char *cache_dir, int id, const int *best,
                             const int *gt, const ev_context *ctx, ev_shape *s, char *note, size_t nnote, ss_error *err) {
  return shape_load(path, label, label, 0, cache_dir, id, best, gt, ctx, s, note, nnote, err);
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
  rprep_free(s);
  ss_shape_prep_free(&s->prep);
  for (int i = 0; i < 3; i++) free(s->lmd[i]), s->lmd[i] = NULL;
  return st;
}
