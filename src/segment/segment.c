/* The segmentation pipeline of paper §4: streamline (CMCF + remesh + Ψ) → Fiedler vector →
 * critical points → iVd on the NPP22 graph → labels and centres back on the input. */
#include "specseg/segment.h"
#include "specseg/laplacian.h"
#include "specseg/mesh.h"
#include "specseg/spectrum.h"
#include "specseg/streamline.h"
#include "fill_holes.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void ss_segment_default_options(ss_segment_options *o) {
  memset(o, 0, sizeof *o);
  o->target_faces = 15000;
  o->no_streamline = 0;
  o->cleanup_rings = 5;
  o->n_eigs = 2;
  o->cmcf_steps = 0;
  o->cmcf_dt = 0;
  o->sanitize = 1;
}

void ss_segmentation_free(ss_segmentation *s) {
  if (!s) return;
  free(s->labels);
  free(s->centers);
  ss_mesh_free(&s->work);
  free(s->psi);
  free(s->phi);
  free(s->crit);
  free(s->crit_type);
  free(s->work_labels);
  free(s->work_dist);
  memset(s, 0, sizeof *s);
}

/* Fiedler vector of `m`: 2nd smallest eigenpair of W φ = λ M φ. */
static ss_status fiedler(const ss_mesh *m, int k, double *phi, double *lambda, ss_error *err) {
  ss_sparse W = {0};
  double *M = malloc(sizeof(double) * (size_t)m->nv);
  double *evals = malloc(sizeof(double) * (size_t)k);
  double *evecs = malloc(sizeof(double) * (size_t)m->nv * (size_t)k);
  ss_status st = SS_OK;
  if (!M || !evals || !evecs) {
    st = ss_fail(err, SS_ERR_NOMEM, "segment: out of memory for the Fiedler vector");
    goto done;
  }
  if ((st = ss_cotan_stiffness(m, &W, err))) goto done;
  if ((st = ss_mass_lumped(m, SS_MASS_BARYCENTRIC, M, err))) goto done;
  if ((st = ss_eigs(&W, M, k, NULL, evals, evecs, err))) goto done;
  memcpy(phi, evecs + (size_t)m->nv, sizeof(double) * (size_t)m->nv);
  *lambda = evals[1];
  /* a fixed sign makes min/max types reproducible across runs and shapes */
  double mx = 0;
  int imx = 0;
  for (int i = 0; i < m->nv; i++)
    if (fabs(phi[i]) > mx) mx = fabs(phi[i]), imx = i;
  if (phi[imx] < 0)
    for (int i = 0; i < m->nv; i++) phi[i] = -phi[i];
done:
  ss_sparse_free(&W);
  free(M);
  free(evals);
  free(evecs);
  return st;
}

static double dist2(const double *a, const double *b) {
  double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return x * x + y * y + z * z;
}

ss_status ss_segment(const ss_mesh *input, const ss_segment_options *opts_in, ss_segmentation *out,
                     ss_error *err) {
  double t_start = ss_time();
  ss_segment_options o;
  if (opts_in) o = *opts_in;
  else ss_segment_default_options(&o);
  if (!out) return ss_fail(err, SS_ERR_INVALID, "segment: NULL output");
  memset(out, 0, sizeof *out);
  if (!input || input->nv <= 0 || input->nf <= 0 || !input->V || !input->F)
    return ss_fail(err, SS_ERR_INVALID, "segment: empty mesh");
  if (o.n_eigs < 2) return ss_fail(err, SS_ERR_INVALID, "segment: n_eigs must be at least 2 (got %d)", o.n_eigs);
  if (!o.no_streamline && o.target_faces < 4)
    return ss_fail(err, SS_ERR_INVALID, "segment: target face count %d is too small", o.target_faces);
  if (o.cleanup_rings < 0) return ss_fail(err, SS_ERR_INVALID, "segment: negative clean-up radius");

  ss_status st = SS_OK;
  ss_mesh clean = {0}, closed = {0}, smooth = {0};
  int *to_input = NULL; /* vertex of `proc` → input vertex (NULL: identity) */
  int *pts = NULL, *count = NULL, *input_src = NULL, *psi = NULL;
  signed char *types = NULL;
  ss_graph g = {0};
  const ss_mesh *proc = input;
  int nv = input->nv;
  out->nv = nv;

  /* 0. optional repair of what would break the Laplacian / remesher */
  if (o.sanitize) {
    if ((st = ss_mesh_sanitize(input, &clean, &to_input, NULL, 0, err))) goto fail;
    proc = &clean;
  }

  /* 1. the shape the Fiedler function lives on (`work`) and Ψ: proc vertex → work vertex */
  int np = proc->nv;
  psi = malloc(sizeof(int) * (size_t)np);
  if (!psi) goto nomem;
  if (o.no_streamline) {
    if ((st = ss_mesh_copy(proc, &out->work, err))) goto fail;
    for (int i = 0; i < np; i++) psi[i] = i;
  } else {
    /* the remesher takes closed surfaces: close small holes (TOSCA) with centroid fans first; the
     * extra vertices are smoothed and remeshed with the rest but no input vertex maps to them */
    int nholes = 0;
    if ((st = ssi_fill_holes_fan(proc, &closed, &nholes, err))) goto fail;
    double t0 = ss_time();
    ss_cmcf_options co;
    ss_cmcf_default_options(&co);
    if (o.cmcf_steps > 0) co.steps = o.cmcf_steps;
    if (o.cmcf_dt > 0) co.dt = o.cmcf_dt;
    if ((st = ss_cmcf_smooth(&closed, &co, &smooth, err))) goto fail;
    double t1 = ss_time();
    ss_remesh_options ro;
    ss_remesh_default_options(&ro);
    ro.target_faces = o.target_faces;
    if ((st = ss_remesh(&smooth, &ro, &out->work, err))) goto fail;
    double t2 = ss_time();
    if ((st = ss_closest_vertices(smooth.V, np, &out->work, psi, err))) goto fail;
    out->t_smooth = t1 - t0;
    out->t_remesh = t2 - t1;
    out->t_psi = ss_time() - t2;
  }
  const ss_mesh *w = &out->work;

  /* 2. Fiedler vector */
  double t0 = ss_time();
  out->phi = malloc(sizeof(double) * (size_t)w->nv);
  if (!out->phi) goto nomem;
  if ((st = fiedler(w, o.n_eigs, out->phi, &out->lambda2, err))) goto fail;
  double t1 = ss_time();
  out->t_spectrum = t1 - t0;

  /* 3. critical points */
  types = malloc((size_t)w->nv);
  if (!types) goto nomem;
  int npts = 0;
  if ((st = ss_fiedler_critical_points(w, out->phi, o.cleanup_rings, types, &pts, &npts, &out->ncrit_raw, err)))
    goto fail;
  if (npts == 0) { /* cannot happen on a finite mesh (the global min is one), but be safe */
    st = ss_fail(err, SS_ERR_NUMERIC, "segment: the Fiedler vector has no critical point");
    goto fail;
  }
  double t2 = ss_time();
  out->t_critical = t2 - t1;

  /* 4. iVd on the NPP22 graph */
  out->work_labels = malloc(sizeof(int) * (size_t)w->nv);
  out->work_dist = malloc(sizeof(double) * (size_t)w->nv);
  if (!out->work_labels || !out->work_dist) goto nomem;
  if ((st = ss_graph_npp22(w, &g, err))) goto fail;
  if ((st = ss_ivd(&g, pts, npts, out->work_dist, out->work_labels, err))) goto fail;
  out->t_ivd = ss_time() - t2;

  /* 5. back on the input: input vertex i takes the tag of Ψ(its smoothed twin). An input vertex the
   * sanitizer dropped (unreferenced) has no twin: it takes its nearest kept vertex's label. */
  out->m = npts;
  out->crit = pts;
  pts = NULL;
  out->crit_type = malloc((size_t)npts);
  out->labels = malloc(sizeof(int) * (size_t)nv);
  out->centers = malloc(sizeof(int) * (size_t)npts);
  input_src = malloc(sizeof(int) * (size_t)nv); /* input vertex → one proc vertex, or -1 */
  if (!out->crit_type || !out->labels || !out->centers || !input_src) goto nomem;
  for (int s = 0; s < npts; s++) out->crit_type[s] = types[out->crit[s]];
  for (int i = 0; i < nv; i++) input_src[i] = -1;
  for (int j = 0; j < np; j++) {
    int i = to_input ? to_input[j] : j;
    if (i >= 0 && i < nv && input_src[i] < 0) input_src[i] = j;
  }
  out->psi = malloc(sizeof(int) * (size_t)nv);
  if (!out->psi) goto nomem;
  for (int i = 0; i < nv; i++) out->psi[i] = input_src[i] >= 0 ? psi[input_src[i]] : -1;
  int nlost = 0;
  for (int i = 0; i < nv; i++) {
    if (input_src[i] < 0) {
      nlost++;
      out->labels[i] = -1;
      continue;
    }
    out->labels[i] = out->work_labels[psi[input_src[i]]];
    if (out->labels[i] < 0) nlost++; /* a component without a centre: handled below */
  }
  if (nlost) {
    /* nearest labelled input vertex (Euclidean, input positions) */
    int nk = 0;
    for (int i = 0; i < nv; i++) nk += out->labels[i] >= 0;
    if (nk == 0) {
      st = ss_fail(err, SS_ERR_NUMERIC, "segment: no input vertex received a label");
      goto fail;
    }
    ss_mesh kept = {0};
    double *Q = malloc(sizeof(double) * 3 * (size_t)nlost);
    int *qi = malloc(sizeof(int) * (size_t)nlost), *nn = malloc(sizeof(int) * (size_t)nlost);
    int *kidx = malloc(sizeof(int) * (size_t)nk);
    if (!Q || !qi || !nn || !kidx || ss_mesh_alloc(&kept, nk, 0, NULL)) {
      free(Q), free(qi), free(nn), free(kidx), ss_mesh_free(&kept);
      goto nomem;
    }
    int a = 0, b = 0;
    for (int i = 0; i < nv; i++) {
      if (out->labels[i] >= 0) {
        memcpy(kept.V + 3 * (size_t)a, input->V + 3 * (size_t)i, 3 * sizeof(double));
        kidx[a++] = i;
      } else {
        memcpy(Q + 3 * (size_t)b, input->V + 3 * (size_t)i, 3 * sizeof(double));
        qi[b++] = i;
      }
    }
    st = ss_closest_vertices(Q, nlost, &kept, nn, err);
    if (!st)
      for (int k = 0; k < nlost; k++) out->labels[qi[k]] = out->labels[kidx[nn[k]]];
    free(Q), free(qi), free(nn), free(kidx), ss_mesh_free(&kept);
    if (st) goto fail;
  }

  /* 6. centres on the input: among the input vertices of segment s, the one whose smoothed twin is
   * closest to the critical point (falls back to all vertices when the segment is empty on the
   * input, which a tiny cell between Ψ's samples could be). */
  {
    const double *P = o.no_streamline ? proc->V : smooth.V;
    double *best = malloc(sizeof(double) * (size_t)npts);
    count = calloc((size_t)npts, sizeof(int));
    if (!best || !count) {
      free(best);
      goto nomem;
    }
    for (int s = 0; s < npts; s++) best[s] = INFINITY, out->centers[s] = -1;
    for (int i = 0; i < nv; i++) {
      int j = input_src[i], s = out->labels[i];
      count[s]++;
      if (j < 0) continue;
      double d = dist2(P + 3 * (size_t)j, w->V + 3 * (size_t)out->crit[s]);
      if (d < best[s]) best[s] = d, out->centers[s] = i;
    }
    for (int s = 0; s < npts; s++) out->empty_segments += count[s] == 0;
    for (int s = 0; s < npts; s++) {
      if (out->centers[s] >= 0) continue;
      for (int i = 0; i < nv; i++) {
        int j = input_src[i];
        if (j < 0) continue;
        double d = dist2(P + 3 * (size_t)j, w->V + 3 * (size_t)out->crit[s]);
        if (d < best[s]) best[s] = d, out->centers[s] = i;
      }
    }
    free(best);
  }
  out->t_total = ss_time() - t_start;
  goto done;

nomem:
  st = ss_fail(err, SS_ERR_NOMEM, "segment: out of memory");
fail:
  ss_segmentation_free(out);
done:
  ss_mesh_free(&clean);
  ss_mesh_free(&closed);
  ss_mesh_free(&smooth);
  free(to_input);
  free(pts);
  free(types);
  free(count);
  free(input_src);
  free(psi);
  ss_graph_free(&g);
  return st;
}
