/* Per-shape preparation for matching: the segmentation and the Laplace–Beltrami eigenpairs of one
 * shape, computed once and shared by every pair the shape takes part in. */
#include "specseg/match.h"
#include "specseg/geodesic.h"
#include "specseg/laplacian.h"
#include "specseg/mesh.h"
#include "specseg/spectrum.h"
#include "util/side_by_side.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void ss_shape_prep_free(ss_shape_prep *p) {
  if (!p) return;
  ss_segmentation_free(&p->seg);
  free(p->evals);
  free(p->evecs);
  free(p->M);
  free(p->crit_fields);
  for (int i = 0; i < p->nprobe_cache && p->probe_cache; i++) ss_fmap_probe_cache_free(&p->probe_cache[i]);
  free(p->probe_cache);
  memset(p, 0, sizeof *p);
}

ss_status ss_shape_prep_crit_fields(ss_shape_prep *p, ss_error *err) {
  if (!p) return ss_fail(err, SS_ERR_INVALID, "crit fields: NULL shape");
  if (p->crit_fields) return SS_OK;
  const ss_segmentation *s = &p->seg;
  if (!s->crit || s->m < 1 || s->work.nv < 1) return ss_fail(err, SS_ERR_INVALID, "crit fields: incomplete segmentation");
  double *f = malloc(sizeof(double) * (size_t)s->work.nv * s->m);
  if (!f) return ss_fail(err, SS_ERR_NOMEM, "crit fields: out of memory");
  ss_geodesic_mesh *gm = NULL;
  ss_status st = ss_geodesic_mesh_build(&s->work, &gm, err);
  if (!st) st = ss_geodesic_fields(gm, s->crit, s->m, 0.0, f, err);
  ss_geodesic_mesh_free(gm);
  if (st) free(f);
  else p->crit_fields = f;
  return st;
}

/* The mesh must be usable as it is (its vertex indices are what landmarks and maps refer to, and the
 * eigenpairs are computed on it): no face the sanitizer would drop (degenerate, duplicate) and no
 * vertex it would drop (unreferenced: zero mass). Pinched (non-manifold) vertices are fine: the
 * segmentation splits them internally and maps its labels back, and the Laplacian of the mesh as
 * given is well defined there. A non-orientable surface is refused by the sanitizer. */
static ss_status check_clean(const ss_mesh *m, ss_error *err) {
  ss_mesh clean = {0};
  int *to_input = NULL;
  ss_status st = ss_mesh_sanitize(m, &clean, &to_input, NULL, 0, err);
  if (st) return st;
  int nf_dropped = m->nf - clean.nf, nv_dropped = 0;
  unsigned char *seen = calloc((size_t)m->nv, 1);
  if (!seen) {
    ss_mesh_free(&clean);
    free(to_input);
    return ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
  }
  for (int i = 0; i < clean.nv; i++) seen[to_input[i]] = 1;
  int first_unref = -1;
  for (int i = 0; i < m->nv; i++)
    if (!seen[i]) {
      if (first_unref < 0) first_unref = i;
      nv_dropped++;
    }
  free(seen);
  ss_mesh_free(&clean);
  free(to_input);
  if (nf_dropped || nv_dropped) {
    char fs[64] = "", vs[96] = "";
    if (nf_dropped) snprintf(fs, sizeof fs, "%d degenerate or duplicate face%s", nf_dropped, nf_dropped == 1 ? "" : "s");
    if (nv_dropped)
      snprintf(vs, sizeof vs, "%d unreferenced vert%s (e.g. vertex %d)", nv_dropped, nv_dropped == 1 ? "ex" : "ices",
               first_unref);
    return ss_fail(err, SS_ERR_INVALID,
                   "match: the mesh has %s%s%s; remove them first (`specseg info` counts them): landmarks and maps "
                   "refer to its vertex indices",
                   fs, fs[0] && vs[0] ? " and " : "", vs);
  }
  return SS_OK;
}

void ss_shape_prep_unit_area(double area, int nv, int kev, double *evals, double *evecs, double *M) {
  /* the shape scaled by 1/√area: λ·area, φ·√area (M-orthonormal again), M/area */
  const double r = sqrt(area);
  if (evals)
    for (int i = 0; i < kev; i++) evals[i] *= area;
  if (evecs)
    for (size_t i = 0; i < (size_t)nv * kev; i++) evecs[i] *= r;
  if (M)
    for (int i = 0; i < nv; i++) M[i] /= area;
}

/* the checks of a mesh to prepare (out cleared) */
static ss_status check_input(const ss_mesh *m, int kev, ss_shape_prep *out, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  memset(out, 0, sizeof *out);
  if (!m || !m->V || !m->F || m->nv < 1 || m->nf < 1) return ss_fail(err, SS_ERR_INVALID, "match: empty mesh (no faces)");
  if (m->nv < 4)
    return ss_fail(err, SS_ERR_INVALID,
                   "match: the mesh has %d vertices and %d face%s: too small to match (a surface of at least 4 "
                   "vertices, and more vertices than the basis size, is needed)",
                   m->nv, m->nf, m->nf == 1 ? "" : "s");
  if (kev < 3) return ss_fail(err, SS_ERR_INVALID, "match: %d eigenpairs requested; at least 3 are needed", kev);
  if (kev >= m->nv)
    return ss_fail(err, SS_ERR_INVALID,
                   "match: the basis needs %d eigenpairs but the mesh has only %d vertices; use a basis size (k, "
                   "ZoomOut's kmax) below %d",
                   kev, m->nv, m->nv);
  return check_clean(m, err);
}

/* the eigenpairs and masses of out->mesh, scaled to unit area */
static ss_status compute_spectral(const ss_mesh *m, int kev, ss_shape_prep *out, ss_error *err) {
  double t1 = ss_time();
  out->kev = kev;
  out->evals = malloc(sizeof(double) * (size_t)kev);
  out->evecs = malloc(sizeof(double) * (size_t)m->nv * kev);
  out->M = malloc(sizeof(double) * (size_t)m->nv);
  if (!out->evals || !out->evecs || !out->M) return ss_fail(err, SS_ERR_NOMEM, "match: out of memory for %d eigenpairs", kev);
  ss_status st = ss_mesh_eigs(m, kev, out->evals, out->evecs, err);
  if (!st) st = ss_mass_lumped(m, SS_MASS_BARYCENTRIC, out->M, err);
  if (st) return st;
  out->area = 0;
  for (int i = 0; i < m->nv; i++) out->area += out->M[i];
  ss_shape_prep_unit_area(out->area, m->nv, kev, out->evals, out->evecs, out->M);
  out->t_eigs = ss_time() - t1;
  return SS_OK;
}

/* The two parts of ss_shape_prep_compute, as tasks of ssi_run_both: they write different fields. */
typedef struct prep_parts {
  const ss_mesh *m;
  const ss_segment_options *seg_opts;
  int kev;
  ss_shape_prep *out;
} prep_parts;
static ss_status segment_part(void *arg, ss_error *err) {
  prep_parts *t = arg;
  double t0 = ss_time();
  ss_status st = ss_segment(t->m, t->seg_opts, &t->out->seg, err);
  t->out->t_segment = ss_time() - t0;
  return st;
}
static ss_status spectral_part(void *arg, ss_error *err) {
  prep_parts *t = arg;
  return compute_spectral(t->m, t->kev, t->out, err);
}

ss_status ss_shape_prep_compute(const ss_mesh *m, const ss_segment_options *seg_opts, int kev, ss_shape_prep *out,
                                ss_error *err) {
  ss_status st = check_input(m, kev, out, err);
  if (st) return st;
  out->mesh = m;
  /* the segmentation and the eigenpairs depend on the mesh alone: side by side (ssi_run_both; a
   * segmentation error is reported first, as when they run one after the other) */
  prep_parts t = {m, seg_opts, kev, out};
  if ((st = ssi_run_both(segment_part, &t, spectral_part, &t, 1, err))) ss_shape_prep_free(out);
  return st;
}

ss_status ss_shape_prep_compute_spectral(const ss_mesh *m, int kev, ss_shape_prep *out, ss_error *err) {
  ss_status st = check_input(m, kev, out, err);
  if (st) return st;
  out->mesh = m;
  if ((st = compute_spectral(m, kev, out, err))) ss_shape_prep_free(out);
  return st;
}
