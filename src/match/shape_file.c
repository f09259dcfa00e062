/* Prepared shapes: what a match needs from one shape (mesh, segmentation, eigenpairs, masses,
 * centre signature), computed once, written to and read from a versioned, checksummed file
 * (util/blob.h: the eval cache's format). See match.h. */
#include "specseg/match.h"
#include "util/c_locale.h"
#include "specseg/streamline.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_topology.h"
#include "match/match_submesh.h"
#include "util/blob.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TAG "specseg-shape"

void ss_prepared_shape_free(ss_prepared_shape *s) {
  if (!s) return;
  ss_centre_signature_free(&s->sig);
  ss_shape_prep_free(&s->prep);
  ss_shape_prep_free(&s->proxy_prep);
  ss_mesh_free(&s->proxy);
  free(s->to_proxy);
  free(s->proxy_src);
  ss_mesh_free(&s->mesh);
  memset(s, 0, sizeof *s);
}

int ss_is_prepared_shape(const void *head, size_t n) {
  return head && n >= sizeof TAG && !memcmp(head, TAG " ", sizeof TAG);
}

ss_status ss_prepared_shape_compute(const ss_mesh *m, const ss_segment_options *seg_opts, int kev,
                                    const ss_autopair_options *autopair, ss_prepared_shape *out, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "prepare: NULL output");
  memset(out, 0, sizeof *out);
  if (!m) return ss_fail(err, SS_ERR_INVALID, "prepare: NULL mesh");
  if (seg_opts) out->seg = *seg_opts;
  else ss_segment_default_options(&out->seg);
  ss_status st = ss_mesh_copy(m, &out->mesh, err);
  ssi_submesh px = {0};
  if (!st) st = ssi_proxy_make(&out->mesh, 0, NULL, &px, err);
  if (!st && px.active) {
    /* matched through its proxy, as ss_match_warn matches it; the input keeps its own segmentation */
    out->has_proxy = 1;
    out->proxy = px.mesh, out->to_proxy = px.to_sub, out->proxy_src = px.to_in;
    memset(&px, 0, sizeof px);
    st = ss_shape_prep_compute(&out->proxy, &out->seg, kev, &out->proxy_prep, err);
    if (!st) {
      double t0 = ss_time();
      out->prep.mesh = &out->mesh;
      out->prep.area = ss_mesh_area(&out->mesh);
      st = ss_segment(&out->mesh, &out->seg, &out->prep.seg, err);
      out->prep.t_segment = ss_time() - t0;
    }
  } else if (!st) {
    st = ss_shape_prep_compute(&out->mesh, &out->seg, kev, &out->prep, err);
  }
  ssi_submesh_free(&px);
  if (st && err && !strncmp(err->msg, "match: ", 7)) { /* the shared stages' prefix: this is prepare */
    char msg[sizeof err->msg];
    snprintf(msg, sizeof msg, "prepare: %s", err->msg + 7);
    memcpy(err->msg, msg, sizeof msg);
  }
  ss_shape_prep *mp = out->has_proxy ? &out->proxy_prep : &out->prep; /* what a match uses */
  if (!st) st = ss_shape_prep_crit_fields(mp, err); /* the landmark pairing's distances, once */
  if (!st) st = ss_shape_prep_probe_cache(mp, NULL, err); /* the default match's shape-only probe parts */
  if (!st && autopair) {
    int *comp = malloc(sizeof(int) * (size_t)out->mesh.nv);
    int nc = comp ? ssi_mesh_components(&out->mesh, comp) : -1;
    free(comp);
    if (nc < 0) st = ss_fail(err, SS_ERR_NOMEM, "prepare: out of memory");
    else if (nc == 1) {
      out->autopair = *autopair;
      if (!(st = ss_centre_signature_compute(mp, autopair, &out->sig, err))) out->has_signature = 1;
    }
  }
  if (st) {
    ss_prepared_shape_free(out);
    return st;
  }
  return SS_OK;
}

const ss_shape_prep *ss_prepared_shape_matched(const ss_prepared_shape *s) {
  return s ? (s->has_proxy ? &s->proxy_prep : &s->prep) : NULL;
}

/* ---- the file ---------------------------------------------------------------------------------- */

static void make_key(const ss_prepared_shape *s, char *key, size_t n) {
  const ss_segment_options *o = &s->seg;
  const ss_autopair_options *a = &s->autopair;
  int len = ssi_snprintf_c(key, n,
                     TAG " %d %s int%d double%d lib %d.%d.%d mesh %d %d %016llx kev %d seg %d %d %d %d %d %.17g %d sig %d",
                     SS_PREPARED_SHAPE_VERSION, ssi_byte_order(), (int)sizeof(int), (int)sizeof(double),
                     SPECSEG_VERSION_MAJOR, SPECSEG_VERSION_MINOR, SPECSEG_VERSION_PATCH, s->mesh.nv, s->mesh.nf,
                     (unsigned long long)ssi_mesh_hash(&s->mesh), ss_prepared_shape_matched(s)->kev, o->target_faces, o->no_streamline,
                     o->cleanup_rings, o->n_eigs, o->cmcf_steps, o->cmcf_dt, o->sanitize, s->has_signature ? 1 : 0);
  if (s->has_signature && len > 0 && (size_t)len < n)
    len += ssi_snprintf_c(key + len, n - (size_t)len, " autopair %d %d %.17g %.17g %.17g %.17g %d %d %d %.17g %.17g",
                    a->descr_k, a->n_energies, a->sigma_factor, a->descr_radius, a->w_descr, a->w_geo, a->exact_max,
                    a->orient_k, a->orient_descr_k, a->min_gap, a->min_mirror);
  if (len > 0 && (size_t)len + 1 < n) key[len] = '\n', key[len + 1] = 0;
}

/* an array: its element count (int64; -1 for NULL), then its elements */
static void put_arr(ssi_blob *b, const void *p, size_t count, size_t size) {
  int64_t c = p ? (int64_t)count : -1;
  SSI_PUT(b, &c, 1);
  if (p) ssi_blob_put(b, p, count * size);
}

/* 1: read (NULL when stored as NULL and may_null); 0: bad */
static int get_arr(ssi_blob *b, void *pp, size_t count, size_t size, int may_null) {
  void **out = pp;
  *out = NULL;
  int64_t c;
  if (!SSI_GET(b, &c, 1)) return 0;
  if (c == -1) return may_null;
  if (c < 0 || (uint64_t)c != (uint64_t)count || (count && size > (b->n - b->pos) / count)) return b->bad = 1, 0;
  void *p = malloc(count ? count * size : 1);
  if (!p) return b->bad = 1, 0;
  if (!ssi_blob_get(b, p, count * size)) return free(p), 0;
  *out = p;
  return 1;
}

/* one ss_shape_prep (its mesh apart): spectrum (absent when kev is 0), masses, segmentation,
 * critical points' fields */
static void put_prep(ssi_blob *b, const ss_shape_prep *p, size_t nv) {
  const ss_segmentation *g = &p->seg;
  const size_t kev = (size_t)p->kev, gm = (size_t)g->m, wn = (size_t)g->work.nv;
  SSI_PUT(b, &p->kev, 1);
  put_arr(b, p->evals, kev, sizeof(double)), put_arr(b, p->evecs, nv * kev, sizeof(double));
  put_arr(b, p->M, nv, sizeof(double));
  SSI_PUT(b, &p->area, 1), SSI_PUT(b, &p->t_segment, 1), SSI_PUT(b, &p->t_eigs, 1);
  SSI_PUT(b, &g->nv, 1), SSI_PUT(b, &g->m, 1), SSI_PUT(b, &g->empty_segments, 1), SSI_PUT(b, &g->ncrit_raw, 1);
  SSI_PUT(b, &g->lambda2, 1);
  put_arr(b, g->labels, nv, sizeof(int)), put_arr(b, g->centers, gm, sizeof(int));
  SSI_PUT(b, &g->work.nv, 1), SSI_PUT(b, &g->work.nf, 1);
  put_arr(b, g->work.V, 3 * wn, sizeof(double)), put_arr(b, g->work.F, 3 * (size_t)g->work.nf, sizeof(int));
  put_arr(b, g->psi, nv, sizeof(int)), put_arr(b, g->phi, wn, sizeof(double));
  put_arr(b, g->crit, gm, sizeof(int)), put_arr(b, g->crit_type, gm, 1);
  put_arr(b, g->work_labels, wn, sizeof(int)), put_arr(b, g->work_dist, wn, sizeof(double));
  const double t[8] = {g->t_read, g->t_smooth, g->t_remesh, g->t_psi, g->t_spectrum, g->t_critical, g->t_ivd, g->t_total};
  SSI_PUT(b, t, 8);
  put_arr(b, p->crit_fields, wn * gm, sizeof(double));
  const int nc = p->probe_cache ? p->nprobe_cache : 0;
  SSI_PUT(b, &nc, 1);
  for (int i = 0; i < nc; i++) {
    const ss_fmap_probe_cache *c = &p->probe_cache[i];
    const int h[6] = {c->k, c->kd, c->n_energies, c->descr_step, c->nwks, c->kt};
    const size_t k = (size_t)c->k, kk = k * (k + 1) / 2;
    SSI_PUT(b, h, 6), SSI_PUT(b, &c->sigma_factor, 1);
    put_arr(b, c->A, k * c->nwks, sizeof(double)), put_arr(b, c->P, kk * c->nwks, sizeof(double));
    put_arr(b, c->O, k * k * c->nwks, sizeof(double)), put_arr(b, c->T, kk * c->kt, sizeof(double));
  }
}

static int all_finite(const double *x, size_t n) {
  for (size_t i = 0; x && i < n; i++)
    if (!isfinite(x[i])) return 0;
  return 1;
}

/* put_prep's probe cache entries (none when the prep has no spectrum), range-checked; 1: read */
static int get_probe_cache(ssi_blob *b, ss_shape_prep *p) {
  int nc;
  if (!SSI_GET(b, &nc, 1) || nc < 0 || nc > 8 || (nc > 0 && p->kev < 1)) return 0;
  if (nc == 0) return 1;
  if (!(p->probe_cache = calloc((size_t)nc, sizeof *p->probe_cache))) return b->bad = 1, 0;
  p->nprobe_cache = nc;
  for (int i = 0; i < nc; i++) {
    ss_fmap_probe_cache *c = &p->probe_cache[i];
    int h[6];
    if (!SSI_GET(b, h, 6) || !SSI_GET(b, &c->sigma_factor, 1)) return 0;
    c->k = h[0], c->kd = h[1], c->n_energies = h[2], c->descr_step = h[3], c->nwks = h[4], c->kt = h[5];
    if (c->k < 1 || c->kd < c->k || c->kd > p->kev || c->n_energies < 1 || c->descr_step < 1 || c->nwks < 0 ||
        c->nwks > c->n_energies || c->kt < 0 || c->kt > p->kev || !(c->sigma_factor > 0) || !isfinite(c->sigma_factor))
      return 0;
    const size_t k = (size_t)c->k, kk = k * (k + 1) / 2;
    if (!get_arr(b, &c->A, k * c->nwks, sizeof(double), 1) || !get_arr(b, &c->P, kk * c->nwks, sizeof(double), 1) ||
        !get_arr(b, &c->O, k * k * c->nwks, sizeof(double), 1) || !get_arr(b, &c->T, kk * c->kt, sizeof(double), 1))
      return 0;
    if ((c->nwks > 0 && (!c->A || !c->P)) || !all_finite(c->A, k * c->nwks) || !all_finite(c->P, kk * c->nwks) ||
        !all_finite(c->O, k * k * c->nwks) || !all_finite(c->T, kk * c->kt))
      return 0;
  }
  return 1;
}

static void put_mesh(ssi_blob *b, const ss_mesh *m) {
  SSI_PUT(b, &m->nv, 1), SSI_PUT(b, &m->nf, 1);
  put_arr(b, m->V, 3 * (size_t)m->nv, sizeof(double)), put_arr(b, m->F, 3 * (size_t)m->nf, sizeof(int));
}

ss_status ss_prepared_shape_write(const char *path, const ss_prepared_shape *s, ss_error *err) {
  if (!path || !s) return ss_fail(err, SS_ERR_INVALID, "prepare: NULL argument");
  const ss_mesh *m = &s->mesh;
  const ss_shape_prep *p = &s->prep, *mp = ss_prepared_shape_matched(s);
  const ss_segmentation *g = &p->seg;
  if (!m->V || !m->F || m->nv < 1 || !mp->evals || !mp->evecs || !mp->M || mp->kev < 1 || !g->labels || !g->centers ||
      g->nv != m->nv || g->m < 1 || (s->has_proxy && (!s->proxy.V || !s->to_proxy || !s->proxy_src || !mp->seg.labels ||
                                                      mp->seg.nv != s->proxy.nv)))
    return ss_fail(err, SS_ERR_INVALID, "prepare: %s: the shape is not prepared", path);
  const size_t nv = (size_t)m->nv;
  char key[SSI_BLOB_MAX_KEY];
  make_key(s, key, sizeof key);
  ssi_blob b = {0};
  put_mesh(&b, m);
  SSI_PUT(&b, &s->has_proxy, 1);
  put_prep(&b, p, nv);
  if (s->has_proxy) {
    put_mesh(&b, &s->proxy);
    put_arr(&b, s->to_proxy, nv, sizeof(int)), put_arr(&b, s->proxy_src, (size_t)s->proxy.nv, sizeof(int));
    put_prep(&b, &s->proxy_prep, (size_t)s->proxy.nv);
  }
  if (s->has_signature) {
    const ss_centre_signature *c = &s->sig;
    const size_t mv = (size_t)mp->seg.nv;
    SSI_PUT(&b, &c->m, 1), SSI_PUT(&b, &c->nd, 1);
    SSI_PUT(&b, &c->volume_ratio, 1), SSI_PUT(&b, &c->orient_sign, 1), SSI_PUT(&b, &c->sigma_score, 1);
    put_arr(&b, c->centers, (size_t)c->m, sizeof(int)), put_arr(&b, c->descr, (size_t)c->m * c->nd, sizeof(double));
    put_arr(&b, c->D, (size_t)c->m * c->m, sizeof(double)), put_arr(&b, c->normals, 3 * mv, sizeof(double));
    put_arr(&b, c->sigma, (size_t)c->m, sizeof(int));
  }
  if (b.bad) {
    ssi_blob_free(&b);
    return ss_fail(err, SS_ERR_NOMEM, "prepare: %s: out of memory", path);
  }
  int rc = ssi_blob_write(path, key, &b);
  ssi_blob_free(&b);
  if (rc) return ss_fail(err, SS_ERR_IO, "%s: cannot write: %s", path, strerror(errno));
  return SS_OK;
}

/* The head of line 1: the format and the machine. 0: fine; else the reason in why. */
static int check_head(const char *line, char *why, size_t n) {
  int version = 0, si = 0, sd = 0, pos = 0;
  char order[3] = "";
  if (strncmp(line, TAG " ", sizeof TAG)) return snprintf(why, n, "not a specseg prepared-shape file"), 1;
  if (sscanf(line, TAG " %d%n", &version, &pos) != 1)
    return snprintf(why, n, "no format version after '" TAG "'"), 1;
  if (version != SS_PREPARED_SHAPE_VERSION)
    return snprintf(why, n, "format version %d; this library (%s) reads version %d only: prepare the shape again", version,
                    ss_version(), SS_PREPARED_SHAPE_VERSION),
           1;
  if (sscanf(line + pos, " %2s int%d double%d", order, &si, &sd) != 3)
    return snprintf(why, n, "no byte order and type sizes"), 1;
  if (strcmp(order, ssi_byte_order()) || si != (int)sizeof(int) || sd != (int)sizeof(double))
    return snprintf(why, n, "written on a machine with %s byte order, %d-byte int and %d-byte double (this one: %s, %d, %d)",
                    order, si, sd, ssi_byte_order(), (int)sizeof(int), (int)sizeof(double)),
           1;
  return 0;
}

/* a mesh of at least 4 vertices and one face, indices in range; 1: read */
static int get_mesh(ssi_blob *b, ss_mesh *m) {
  int ok = SSI_GET(b, &m->nv, 1) && SSI_GET(b, &m->nf, 1) && m->nv >= 4 && m->nf >= 1;
  ok = ok && get_arr(b, &m->V, 3 * (size_t)m->nv, sizeof(double), 0) && get_arr(b, &m->F, 3 * (size_t)m->nf, sizeof(int), 0);
  for (size_t i = 0; ok && i < 3 * (size_t)m->nf; i++) ok = m->F[i] >= 0 && m->F[i] < m->nv;
  return ok;
}

/* put_prep's record for a mesh of nv vertices, range-checked; with_spectrum: kev eigenpairs
 * (3 <= kev < nv) and masses, else none (a proxied input). 1: read */
static int get_prep(ssi_blob *b, ss_shape_prep *p, int nv_i, int with_spectrum) {
  ss_segmentation *g = &p->seg;
  const size_t nv = (size_t)nv_i;
  int ok = SSI_GET(b, &p->kev, 1) && (with_spectrum ? p->kev >= 3 && p->kev < nv_i : p->kev == 0);
  const size_t kev = ok ? (size_t)p->kev : 0;
  ok = ok && get_arr(b, &p->evals, kev, sizeof(double), !with_spectrum) &&
       get_arr(b, &p->evecs, nv * kev, sizeof(double), !with_spectrum) && get_arr(b, &p->M, nv, sizeof(double), !with_spectrum) &&
       SSI_GET(b, &p->area, 1) && SSI_GET(b, &p->t_segment, 1) && SSI_GET(b, &p->t_eigs, 1);
  ok = ok && SSI_GET(b, &g->nv, 1) && SSI_GET(b, &g->m, 1) && SSI_GET(b, &g->empty_segments, 1) &&
       SSI_GET(b, &g->ncrit_raw, 1) && SSI_GET(b, &g->lambda2, 1) && g->nv == nv_i && g->m >= 1 && g->m <= nv_i;
  const size_t gm = ok ? (size_t)g->m : 0;
  ok = ok && get_arr(b, &g->labels, nv, sizeof(int), 0) && get_arr(b, &g->centers, gm, sizeof(int), 0) &&
       SSI_GET(b, &g->work.nv, 1) && SSI_GET(b, &g->work.nf, 1) && g->work.nv >= 1 && g->work.nf >= 1;
  const size_t wn = ok ? (size_t)g->work.nv : 0;
  ok = ok && get_arr(b, &g->work.V, 3 * wn, sizeof(double), 0) &&
       get_arr(b, &g->work.F, 3 * (size_t)g->work.nf, sizeof(int), 0) && get_arr(b, &g->psi, nv, sizeof(int), 1) &&
       get_arr(b, &g->phi, wn, sizeof(double), 1) && get_arr(b, &g->crit, gm, sizeof(int), 0) &&
       get_arr(b, &g->crit_type, gm, 1, 1) && get_arr(b, &g->work_labels, wn, sizeof(int), 1) &&
       get_arr(b, &g->work_dist, wn, sizeof(double), 1);
  double t[8];
  ok = ok && SSI_GET(b, t, 8) && get_arr(b, &p->crit_fields, wn * gm, sizeof(double), 1) && get_probe_cache(b, p);
  if (ok) {
    g->t_read = t[0], g->t_smooth = t[1], g->t_remesh = t[2], g->t_psi = t[3], g->t_spectrum = t[4];
    g->t_critical = t[5], g->t_ivd = t[6], g->t_total = t[7];
  }
  for (size_t i = 0; ok && p->crit_fields && i < wn * gm; i++) ok = p->crit_fields[i] >= 0; /* INFINITY: unreachable */
  for (size_t i = 0; ok && i < nv; i++) ok = g->labels[i] >= 0 && g->labels[i] < g->m && (!g->psi || (g->psi[i] >= -1 && g->psi[i] < g->work.nv));
  for (size_t i = 0; ok && i < gm; i++)
    ok = g->centers[i] >= 0 && g->centers[i] < nv_i && g->crit[i] >= 0 && g->crit[i] < g->work.nv &&
         (!g->crit_type || (g->crit_type[i] >= SS_CRIT_REGULAR && g->crit_type[i] <= SS_CRIT_SADDLE));
  for (size_t i = 0; ok && i < 3 * (size_t)g->work.nf; i++) ok = g->work.F[i] >= 0 && g->work.F[i] < g->work.nv;
  for (size_t i = 0; ok && g->work_labels && i < wn; i++) ok = g->work_labels[i] >= -1 && g->work_labels[i] < g->m;
  return ok;
}

/* ---- the values ------------------------------------------------------------------------------
 * The checksum catches accidental damage only: a file written by another program, or edited and
 * re-checksummed, may hold any bits. Every value a match or a segmentation reads is checked here, so
 * such a file is refused with the reason instead of giving a garbage map (NaN eigenvectors, a zero
 * mass) or crashing (NaN pairing energies leave the pairing's search without a leaf). */

/* 1 when every x[i] is finite and >= lo (lo -INFINITY: any finite value) */
static int all_at_least(const double *x, size_t n, double lo) {
  for (size_t i = 0; x && i < n; i++)
    if (!isfinite(x[i]) || x[i] < lo) return 0;
  return 1;
}

/* distances: >= 0, +inf allowed (unreachable), NaN not */
static int all_distances(const double *x, size_t n) {
  for (size_t i = 0; x && i < n; i++)
    if (!(x[i] >= 0)) return 0;
  return 1;
}

#define BAD_VALUE(...) return snprintf(why, n, __VA_ARGS__), 1

/* the options of the key line, as the writer's library accepts them */
static int check_options(const ss_prepared_shape *s, int sig, char *why, size_t n) {
  const ss_segment_options *o = &s->seg;
  if (o->target_faces < 4 || o->target_faces > SS_REMESH_MAX_FACES || (o->no_streamline != 0 && o->no_streamline != 1) ||
      o->cleanup_rings < 0 || o->cleanup_rings > 1000 || o->n_eigs < 0 || o->n_eigs > 10000 || o->cmcf_steps < 0 ||
      o->cmcf_steps > 1000000 || !(o->cmcf_dt >= 0) || !isfinite(o->cmcf_dt) || (o->sanitize != 0 && o->sanitize != 1))
    BAD_VALUE("value out of range: the segmentation options of the key line");
  const ss_autopair_options *a = &s->autopair;
  if (sig && (a->descr_k < 1 || a->n_energies < 1 || a->exact_max < 0 || a->orient_k < 1 || a->orient_descr_k < 1 ||
              !(a->sigma_factor > 0) || !isfinite(a->sigma_factor) || !isfinite(a->descr_radius) ||
              !(a->w_descr >= 0) || !isfinite(a->w_descr) || !(a->w_geo >= 0) || !isfinite(a->w_geo) ||
              !isfinite(a->min_gap) || !isfinite(a->min_mirror)))
    BAD_VALUE("value out of range: the pairing options of the key line");
  return 0;
}

/* one prep's values; what: "" or "the proxy's " for messages */
static int check_prep_values(const ss_shape_prep *p, const ss_mesh *m, const char *what, char *why, size_t n) {
  const ss_segmentation *g = &p->seg;
  const size_t nv = (size_t)m->nv, kev = (size_t)p->kev, wn = (size_t)g->work.nv, gm = (size_t)g->m;
  ss_error e = {{0}};
  if (ssi_mesh_check_coordinates(m, NULL, &e)) BAD_VALUE("%smesh: %.400s", what, e.msg);
  /* eigenvalues of a positive semi-definite pencil, ascending up to the solver's accuracy */
  const double top = kev ? fabs(p->evals[kev - 1]) : 0, tol = 1e-6 * (top > 1 ? top : 1);
  for (size_t i = 0; i < kev; i++)
    if (!isfinite(p->evals[i]) || p->evals[i] < -tol || (i && p->evals[i] < p->evals[i - 1] - tol))
      BAD_VALUE("value out of range: %seigenvalues (eigenvalue %zu is %g)", what, i, p->evals[i]);
  if (!all_at_least(p->evecs, nv * kev, -INFINITY)) BAD_VALUE("value out of range: %seigenvectors not finite", what);
  for (size_t i = 0; p->M && i < nv; i++)
    if (!(p->M[i] > 0) || !isfinite(p->M[i]))
      BAD_VALUE("value out of range: %smasses (vertex %zu has mass %g; masses must be positive)", what, i, p->M[i]);
  if (!(p->area > 0) || !isfinite(p->area)) BAD_VALUE("value out of range: %sarea %g", what, p->area);
  if (!all_at_least(&p->t_segment, 1, 0) || !all_at_least(&p->t_eigs, 1, 0))
    BAD_VALUE("value out of range: %stimings", what);
  if (g->empty_segments < 0 || g->empty_segments > g->m || g->ncrit_raw < 0)
    BAD_VALUE("value out of range: %ssegment counts", what);
  if (!isfinite(g->lambda2) || !all_at_least(g->phi, wn, -INFINITY))
    BAD_VALUE("value out of range: %sFiedler vector or value not finite", what);
  if (!all_at_least(g->work.V, 3 * wn, -INFINITY)) BAD_VALUE("value out of range: %swork mesh coordinates not finite", what);
  if (!all_distances(g->work_dist, wn)) BAD_VALUE("value out of range: %sdistances to the centres", what);
  if (!all_distances(p->crit_fields, wn * gm)) BAD_VALUE("value out of range: %scritical points' fields", what);
  const double t[8] = {g->t_read, g->t_smooth, g->t_remesh, g->t_psi, g->t_spectrum, g->t_critical, g->t_ivd, g->t_total};
  if (!all_at_least(t, 8, 0)) BAD_VALUE("value out of range: %ssegmentation timings", what);
  return 0;
}

static int check_signature(const ss_centre_signature *c, size_t mv, char *why, size_t n) {
  const size_t m = (size_t)c->m;
  if (!all_at_least(c->descr, m * c->nd, -INFINITY)) BAD_VALUE("value out of range: the pairing signature's descriptors not finite");
  for (size_t i = 0; i < m * m; i++)
    if (!(c->D[i] >= 0) || !isfinite(c->D[i]) || (i % (m + 1) == 0 && c->D[i] != 0))
      BAD_VALUE("value out of range: the pairing signature's distances (entry %zu is %g)", i, c->D[i]);
  if (!all_at_least(c->normals, 3 * mv, -INFINITY)) BAD_VALUE("value out of range: the pairing signature's normals not finite");
  if (!isfinite(c->volume_ratio)) BAD_VALUE("value out of range: the pairing signature's volume ratio %g", c->volume_ratio);
  if (c->orient_sign != 1 && c->orient_sign != -1)
    BAD_VALUE("value out of range: the pairing signature's orientation sign %g", c->orient_sign);
  if (!isfinite(c->sigma_score)) BAD_VALUE("value out of range: the pairing signature's symmetry score %g", c->sigma_score);
  return 0;
}

/* every value of a structurally sound file; 0: fine */
static int check_values(const ss_prepared_shape *s, char *why, size_t n) {
  if (check_options(s, s->has_signature, why, n) || check_prep_values(&s->prep, &s->mesh, "", why, n)) return 1;
  if (s->has_proxy && check_prep_values(&s->proxy_prep, &s->proxy, "the proxy's ", why, n)) return 1;
  const ss_shape_prep *mp = s->has_proxy ? &s->proxy_prep : &s->prep;
  return s->has_signature && check_signature(&s->sig, (size_t)mp->seg.nv, why, n);
}

/* the contents, range-checked; 0: fine */
static int parse_payload(ssi_blob *b, const char *key, ss_prepared_shape *s, char *why, size_t n) {
  ss_mesh *m = &s->mesh;
  ss_segment_options *o = &s->seg;
  ss_autopair_options *a = &s->autopair;
  int knv, knf, kkev, sig, pos = 0;
  unsigned long long khash;
  char lib[32];
  if (ssi_sscanf_c(key, TAG " %*d %*2s int%*d double%*d lib %31s mesh %d %d %16llx kev %d seg %d %d %d %d %d %lf %d sig %d%n",
             lib, &knv, &knf, &khash, &kkev, &o->target_faces, &o->no_streamline, &o->cleanup_rings, &o->n_eigs,
             &o->cmcf_steps, &o->cmcf_dt, &o->sanitize, &sig, &pos) != 13 ||
      (sig != 0 && sig != 1))
    return snprintf(why, n, "key line not understood"), 1;
  if (sig && ssi_sscanf_c(key + pos, " autopair %d %d %lf %lf %lf %lf %d %d %d %lf %lf", &a->descr_k, &a->n_energies,
                    &a->sigma_factor, &a->descr_radius, &a->w_descr, &a->w_geo, &a->exact_max, &a->orient_k,
                    &a->orient_descr_k, &a->min_gap, &a->min_mirror) != 11)
    return snprintf(why, n, "key line: no pairing options"), 1;
  int ok = get_mesh(b, m) && m->nv == knv && m->nf == knf;
  if (ok && ssi_mesh_hash(m) != khash) return snprintf(why, n, "the mesh does not have the hash of the key line"), 1;
  ok = ok && SSI_GET(b, &s->has_proxy, 1) && (s->has_proxy == 0 || s->has_proxy == 1);
  ok = ok && get_prep(b, &s->prep, m->nv, !s->has_proxy);
  if (ok && s->has_proxy) {
    ok = get_mesh(b, &s->proxy) && s->proxy.nv < m->nv && get_arr(b, &s->to_proxy, (size_t)m->nv, sizeof(int), 0) &&
         get_arr(b, &s->proxy_src, (size_t)s->proxy.nv, sizeof(int), 0) &&
         get_prep(b, &s->proxy_prep, s->proxy.nv, 1);
    for (int i = 0; ok && i < m->nv; i++) ok = s->to_proxy[i] >= 0 && s->to_proxy[i] < s->proxy.nv;
    for (int i = 0; ok && i < s->proxy.nv; i++) ok = s->proxy_src[i] >= 0 && s->proxy_src[i] < m->nv;
  }
  ss_shape_prep *mp = s->has_proxy ? &s->proxy_prep : &s->prep;
  ok = ok && mp->kev == kkev;
  if (ok && sig) {
    ss_centre_signature *c = &s->sig;
    const size_t gm = (size_t)mp->seg.m, mv = (size_t)mp->seg.nv;
    ok = SSI_GET(b, &c->m, 1) && SSI_GET(b, &c->nd, 1) && c->m == mp->seg.m && c->nd >= 1 && c->nd <= 1000000 &&
         SSI_GET(b, &c->volume_ratio, 1) && SSI_GET(b, &c->orient_sign, 1) && SSI_GET(b, &c->sigma_score, 1);
    ok = ok && get_arr(b, &c->centers, gm, sizeof(int), 0) && get_arr(b, &c->descr, gm * c->nd, sizeof(double), 0) &&
         get_arr(b, &c->D, gm * gm, sizeof(double), 0) && get_arr(b, &c->normals, 3 * mv, sizeof(double), 0) &&
         get_arr(b, &c->sigma, gm, sizeof(int), 0);
    for (size_t i = 0; ok && i < gm; i++) ok = c->centers[i] == mp->seg.centers[i] && c->sigma[i] >= 0 && c->sigma[i] < c->m;
    s->has_signature = ok;
  }
  ok = ok && !b->bad && b->pos == b->n;
  if (!ok) return snprintf(why, n, "checksum right but contents out of range or of the wrong size"), 1;
  if (check_values(s, why, n)) return 1;
  s->prep.mesh = m;
  if (s->has_proxy) s->proxy_prep.mesh = &s->proxy;
  s->sig.prep = s->has_signature ? mp : NULL;
  return 0;
}

static ss_status read_common(int from_file, const char *path, const void *data, size_t size, const char *name,
                             ss_prepared_shape *out, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "prepared shape: NULL output");
  memset(out, 0, sizeof *out);
  char why[700] = "", key[SSI_BLOB_MAX_KEY];
  /* the format and the machine first: a file of another version is reported as such */
  char head[SSI_BLOB_MAX_KEY] = "";
  if (from_file) {
    FILE *f = fopen(path, "rb");
    if (!f) return ss_fail(err, SS_ERR_IO, "%s: cannot open: %s", name, strerror(errno));
    if (!fgets(head, sizeof head, f)) head[0] = 0;
    fclose(f);
  } else {
    size_t k = size < sizeof head - 1 ? size : sizeof head - 1;
    if (k) memcpy(head, data, k);
    head[k] = 0;
  }
  if (check_head(head, why, sizeof why))
    return ss_fail(err, SS_ERR_PARSE, "%s: %s; not used", name, why);
  ssi_blob b;
  int r = from_file ? ssi_blob_read(path, NULL, key, sizeof key, &b, why, sizeof why)
                    : ssi_blob_read_memory(data, size, NULL, key, sizeof key, &b, why, sizeof why);
  if (r == 0) return ss_fail(err, SS_ERR_IO, "%s: cannot open", name);
  if (r < 0) return ss_fail(err, SS_ERR_PARSE, "%s: damaged prepared shape: %s; not used (prepare it again)", name, why);
  int bad = parse_payload(&b, key, out, why, sizeof why);
  ssi_blob_free(&b);
  if (bad) {
    ss_prepared_shape_free(out);
    return ss_fail(err, SS_ERR_PARSE, "%s: damaged prepared shape: %s; not used (prepare it again)", name, why);
  }
  return SS_OK;
}

ss_status ss_prepared_shape_read(const char *path, ss_prepared_shape *out, ss_error *err) {
  if (!path) return ss_fail(err, SS_ERR_INVALID, "prepared shape: NULL path");
  return read_common(1, path, NULL, 0, path, out, err);
}

ss_status ss_prepared_shape_read_memory(const void *data, size_t size, const char *name, ss_prepared_shape *out,
                                        ss_error *err) {
  if (!data && size) return ss_fail(err, SS_ERR_INVALID, "prepared shape: NULL data");
  return read_common(0, NULL, data ? data : "", size, name ? name : "<memory>", out, err);
}
