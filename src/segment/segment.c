/* The segmentation pipeline of paper §4: streamline (CMCF + remesh + Ψ) → Fiedler vector →
 * critical points → iVd on the NPP22 graph → labels and centres back on the input. */
#include "util/warnings.h"
#include "specseg/segment.h"
#include "specseg/laplacian.h"
#include "specseg/mesh.h"
#include "specseg/spectrum.h"
#include "specseg/streamline.h"
#include "fill_holes.h"
#include "streamline/decimate.h"
#include "submesh/submesh.h"
#include "mesh/mesh_topology.h"

#include <math.h>
#include <stdio.h>
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

/* Ψ of a coarsened input: proc vertex j → coarse vertex to_coarse[j] → the work vertex nearest to that
 * vertex's smoothed position. A vertex in no face (no coarse vertex; only without the sanitizer) takes
 * the work vertex nearest to its own position. */
static ss_status compose_psi(const ss_mesh *proc, const int *to_coarse, const ss_mesh *smooth_coarse,
                             const ss_mesh *work, int *psi, ss_error *err) {
  const int np = proc->nv;
  int *pc = malloc(sizeof(int) * (size_t)smooth_coarse->nv);
  if (!pc) return ss_fail(err, SS_ERR_NOMEM, "segment: out of memory");
  ss_status st = ss_closest_vertices(smooth_coarse->V, smooth_coarse->nv, work, pc, err);
  int nfree = 0;
  for (int j = 0; !st && j < np; j++) {
    psi[j] = to_coarse[j] >= 0 ? pc[to_coarse[j]] : -1;
    nfree += psi[j] < 0;
  }
  free(pc);
  if (st || nfree == 0) return st;
  double *Q = malloc(sizeof(double) * 3 * (size_t)nfree);
  int *near = malloc(sizeof(int) * (size_t)nfree);
  if (!Q || !near) st = ss_fail(err, SS_ERR_NOMEM, "segment: out of memory");
  for (int j = 0, q = 0; !st && j < np; j++)
    if (psi[j] < 0) memcpy(Q + 3 * (size_t)q++, proc->V + 3 * (size_t)j, 3 * sizeof(double));
  if (!st && !(st = ss_closest_vertices(Q, nfree, work, near, err))) {
    for (int j = 0, q = 0; j < np; j++)
      if (psi[j] < 0) psi[j] = near[q++];
  }
  free(Q), free(near);
  return st;
}

static ss_status segment_components(const ss_mesh *input, const ss_mesh *proc, const int *to_input, const int *comp,
                                    int ncomp, const ss_segment_options *o, ss_segmentation *out, char *warnings,
                                    size_t warnings_size, ss_error *err);

ss_status ss_segment(const ss_mesh *input, const ss_segment_options *opts_in, ss_segmentation *out,
                     ss_error *err) {
  return ss_segment_warn(input, opts_in, out, NULL, 0, err);
}

ss_status ss_segment_warn(const ss_mesh *input, const ss_segment_options *opts_in, ss_segmentation *out,
                          char *warnings, size_t warnings_size, ss_error *err) {
  double t_start = ss_time();
  if (warnings && warnings_size) warnings[0] = '\0';
  ss_segment_options o;
  if (opts_in) o = *opts_in;
  else ss_segment_default_options(&o);
  if (!out) return ss_fail(err, SS_ERR_INVALID, "segment: NULL output");
  memset(out, 0, sizeof *out);
  if (!input || input->nv <= 0 || input->nf <= 0 || !input->V || !input->F)
    return ss_fail(err, SS_ERR_INVALID, "segment: empty mesh");
  if (o.n_eigs < 2) return ss_fail(err, SS_ERR_INVALID, "segment: n_eigs must be at least 2 (got %d)", o.n_eigs);
  if (!o.no_streamline && (o.target_faces < 4 || o.target_faces > SS_REMESH_MAX_FACES))
    return ss_fail(err, SS_ERR_INVALID,
                   "segment: target face count %d of the remeshing is outside the supported 4 .. %d (the default "
                   "15000 is what the paper uses)",
                   o.target_faces, SS_REMESH_MAX_FACES);
  if (o.cleanup_rings < 0) return ss_fail(err, SS_ERR_INVALID, "segment: negative clean-up radius");

  ss_status st = SS_OK;
  ss_mesh clean = {0}, closed = {0}, smooth = {0};
  ssi_submesh coarse = {0}; /* `closed` coarsened (active only for a very large input) */
  int *to_input = NULL; /* vertex of `proc` → input vertex (NULL: identity) */
  int *pts = NULL, *count = NULL, *input_src = NULL, *psi = NULL;
  signed char *types = NULL;
  ss_graph g = {0};
  const ss_mesh *proc = input;
  int nv = input->nv;
  out->nv = nv;

  /* 0. optional repair of what would break the Laplacian / remesher */
  if (o.sanitize) {
    char sw[512];
    if ((st = ss_mesh_sanitize(input, &clean, &to_input, sw, sizeof sw, err))) goto fail;
    if (sw[0]) ssi_warn_append(warnings, warnings_size, sw);
    proc = &clean;
  }

  /* several components: each one of significant area is segmented on its own */
  {
    int *comp = malloc(sizeof(int) * (size_t)proc->nv);
    if (!comp) goto nomem;
    int nc = ssi_mesh_components(proc, comp);
    if (nc < 0) { free(comp); goto nomem; }
    if (nc > 1) {
      st = segment_components(input, proc, to_input, comp, nc, &o, out, warnings, warnings_size, err);
      free(comp);
      if (st) goto fail;
      out->t_total = ss_time() - t_start;
      goto done;
    }
    free(comp);
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
    if (nholes > 0) {
      char hw[128];
      snprintf(hw, sizeof hw, "%d hole%s (boundary loop%s) closed internally for smoothing and remeshing", nholes,
               nholes > 1 ? "s" : "", nholes > 1 ? "s" : "");
      ssi_warn_append(warnings, warnings_size, hw);
    }
    double t0 = ss_time();
    /* a very large input is coarsened first (topology kept): the flow and the remeshing see the
     * coarse mesh, and Ψ is composed input → coarse → work */
    const ss_mesh *flow_in = &closed;
    if (closed.nv > SSI_COARSEN_ABOVE_NV && closed.nf > SSI_COARSE_FACES) {
      if ((st = ssi_submesh_decimate(&closed, SSI_COARSE_FACES, &coarse, err))) goto fail;
      ss_mesh_free(&closed);
      flow_in = &coarse.mesh;
    }
    ss_cmcf_options co;
    ss_cmcf_default_options(&co);
    if (o.cmcf_steps > 0) co.steps = o.cmcf_steps;
    if (o.cmcf_dt > 0) co.dt = o.cmcf_dt;
    if ((st = ss_cmcf_smooth(flow_in, &co, &smooth, err))) goto fail;
    double t1 = ss_time();
    ss_remesh_options ro;
    ss_remesh_default_options(&ro);
    ro.target_faces = o.target_faces;
    if ((st = ss_remesh(&smooth, &ro, &out->work, err))) goto fail;
    double t2 = ss_time();
    if (!coarse.active) {
      if ((st = ss_closest_vertices(smooth.V, np, &out->work, psi, err))) goto fail;
    } else if ((st = compose_psi(proc, coarse.to_sub, &smooth, &out->work, psi, err))) goto fail;
    out->t_smooth = t1 - t0; /* the coarsening of a very large input included */
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
  if (nlost && (st = ssi_fill_from_nearest(input, out->labels, "segment", err))) goto fail;

  /* 6. centres on the input: among the input vertices of segment s, the one whose smoothed twin is
   * closest to the critical point (falls back to all vertices when the segment is empty on the
   * input, which a tiny cell between Ψ's samples could be). */
  {
    const double *P = o.no_streamline ? proc->V : smooth.V;
    double *Pc = NULL; /* coarsened: the smoothed twin of proc vertex j is estimated as its coarse
                          vertex's smoothed position plus j's offset from that vertex before the flow */
    if (coarse.active) {
      Pc = malloc(sizeof(double) * 3 * (size_t)np);
      if (!Pc) goto nomem;
      for (int j = 0; j < np; j++) {
        int c = coarse.to_sub[j];
        for (int k = 0; k < 3; k++)
          Pc[3 * (size_t)j + k] = c < 0 ? proc->V[3 * (size_t)j + k]
                                        : smooth.V[3 * (size_t)c + k] + proc->V[3 * (size_t)j + k] - coarse.mesh.V[3 * (size_t)c + k];
      }
      P = Pc;
    }
    double *best = malloc(sizeof(double) * (size_t)npts);
    count = calloc((size_t)npts, sizeof(int));
    if (!best || !count) {
      free(best);
      free(Pc);
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
    free(Pc);
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
  ssi_submesh_free(&coarse);
  free(to_input);
  free(pts);
  free(types);
  free(count);
  free(input_src);
  free(psi);
  ss_graph_free(&g);
  return st;
}

/* ---- meshes of several components -------------------------------------------------------------
 * A component whose area is at least SSI_SIGNIFICANT_AREA of the total is segmented on its own, as
 * if it were the only shape (its own CMCF, remeshing to the full target, Fiedler vector, critical
 * points and iVd), and so is the largest component when none reaches that share; its segment indices follow those of the components before it (components ordered
 * by their lowest vertex). Smaller components (crumbs of a scan, a stray triangle) get no segments of
 * their own: each of their vertices takes the segment of the nearest vertex (Euclidean, input
 * positions) of a significant component, and a warning names them. */
#define SSI_SIGNIFICANT_AREA 0.01

static double face_area(const ss_mesh *m, int f) {
  const double *a = m->V + 3 * (size_t)m->F[3 * f], *b = m->V + 3 * (size_t)m->F[3 * f + 1],
               *c = m->V + 3 * (size_t)m->F[3 * f + 2];
  double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
  return 0.5 * sqrt(x * x + y * y + z * z);
}

static ss_status segment_components(const ss_mesh *input, const ss_mesh *proc, const int *to_input, const int *comp,
                                    int ncomp, const ss_segment_options *o, ss_segmentation *out, char *warnings,
                                    size_t warnings_size, ss_error *err) {
  ss_status st = SS_OK;
  const int np = proc->nv, nv = input->nv;
  double *carea = calloc((size_t)ncomp, sizeof(double));
  int *cnv = calloc((size_t)ncomp, sizeof(int));
  int *cfirst = malloc(sizeof(int) * (size_t)ncomp);
  unsigned char *one = calloc((size_t)ncomp, 1);      /* the component segmented now */
  int *plabel = malloc(sizeof(int) * (size_t)np);     /* proc vertex -> segment (or -1) */
  int *pwork = malloc(sizeof(int) * (size_t)np);      /* proc vertex -> work vertex (or -1) */
  ss_segmentation *part = calloc((size_t)ncomp, sizeof *part);
  ssi_submesh sub = {0};                              /* the component as a mesh of its own */
  if (!carea || !cnv || !cfirst || !one || !plabel || !pwork || !part) goto nomem;
  double total = 0;
  for (int c = 0; c < ncomp; c++) cfirst[c] = -1;
  for (int i = 0; i < np; i++) {
    if (comp[i] < 0) continue;
    if (cfirst[comp[i]] < 0) cfirst[comp[i]] = i;
    cnv[comp[i]]++;
  }
  for (int f = 0; f < proc->nf; f++) {
    int c = comp[proc->F[3 * f]];
    double a = face_area(proc, f);
    carea[c] += a;
    total += a;
  }
  int nsig = 0, ntiny = 0, seg_off = 0, work_nv = 0, work_nf = 0, largest = -1;
  char tiny_list[256] = "";
  size_t tl = 0;
  for (int i = 0; i < np; i++) plabel[i] = -1, pwork[i] = -1;
  int biggest = 0; /* always segmented, so that a soup of small pieces still gets segments */
  for (int c = 1; c < ncomp; c++)
    if (carea[c] > carea[biggest]) biggest = c;
  for (int c = 0; c < ncomp; c++) {
    if (!(carea[c] >= SSI_SIGNIFICANT_AREA * total) && c != biggest) {
      if (tl + 32 < sizeof tiny_list)
        tl += (size_t)snprintf(tiny_list + tl, sizeof tiny_list - tl, "%s%d", ntiny ? ", " : "",
                               to_input ? to_input[cfirst[c]] : cfirst[c]);
      else if (tl + 5 < sizeof tiny_list && tiny_list[tl - 1] != '.')
        tl += (size_t)snprintf(tiny_list + tl, sizeof tiny_list - tl, ", ...");
      ntiny++;
      continue;
    }
    /* the component as a mesh of its own */
    one[c] = 1;
    st = ssi_submesh_components(proc, comp, one, &sub, err);
    one[c] = 0;
    if (st) goto fail;
    ss_segment_options oc = *o;
    oc.sanitize = 0; /* proc is clean already */
    char cw[256];
    st = ss_segment_warn(&sub.mesh, &oc, &part[c], cw, sizeof cw, err);
    if (!st && cw[0]) { /* e.g. its holes closed */
      char line[400];
      snprintf(line, sizeof line, "component %d (input vertex %d onwards): %s", c + 1,
               to_input ? to_input[cfirst[c]] : cfirst[c], cw);
      ssi_warn_append(warnings, warnings_size, line);
    }
    if (st) {
      char msg[sizeof err->msg];
      snprintf(msg, sizeof msg, "%s", err ? err->msg : "");
      st = ss_fail(err, st,
                   "segment: component %d of %d (input vertex %d onwards, %d vertices, %.3g%% of the area): %s",
                   c + 1, ncomp, to_input ? to_input[cfirst[c]] : cfirst[c], cnv[c], 100 * carea[c] / total, msg);
      goto fail;
    }
    for (int l = 0; l < cnv[c]; l++) {
      int i = sub.to_in[l];
      plabel[i] = part[c].labels[l] + seg_off;
      pwork[i] = part[c].psi[l] >= 0 ? part[c].psi[l] + work_nv : -1;
    }
    /* centres: sub-mesh vertex -> proc vertex for now (input indices below) */
    ssi_submesh_lift_indices(&sub, part[c].m, part[c].centers);
    seg_off += part[c].m;
    work_nv += part[c].work.nv;
    work_nf += part[c].work.nf;
    if (largest < 0 || carea[c] > carea[largest]) largest = c;
    nsig++;
    ssi_submesh_free(&sub);
  }
  if (nsig == 0) {
    st = ss_fail(err, SS_ERR_INVALID, "segment: none of the %d components has a significant area", ncomp);
    goto fail;
  }

  /* the union of the parts */
  const int m = seg_off;
  out->m = m;
  out->labels = malloc(sizeof(int) * (size_t)nv);
  out->centers = malloc(sizeof(int) * (size_t)m);
  out->psi = malloc(sizeof(int) * (size_t)nv);
  out->phi = malloc(sizeof(double) * (size_t)work_nv);
  out->crit = malloc(sizeof(int) * (size_t)m);
  out->crit_type = malloc((size_t)m);
  out->work_labels = malloc(sizeof(int) * (size_t)work_nv);
  out->work_dist = malloc(sizeof(double) * (size_t)work_nv);
  if (!out->labels || !out->centers || !out->psi || !out->phi || !out->crit || !out->crit_type || !out->work_labels ||
      !out->work_dist)
    goto nomem;
  if ((st = ss_mesh_alloc(&out->work, work_nv, work_nf, err))) goto fail;
  {
    int vo = 0, fo = 0, so = 0;
    for (int c = 0; c < ncomp; c++) {
      const ss_segmentation *p = &part[c];
      if (!p->labels) continue;
      memcpy(out->work.V + 3 * (size_t)vo, p->work.V, sizeof(double) * 3 * (size_t)p->work.nv);
      for (int i = 0; i < 3 * p->work.nf; i++) out->work.F[3 * (size_t)fo + (size_t)i] = p->work.F[i] + vo;
      memcpy(out->phi + vo, p->phi, sizeof(double) * (size_t)p->work.nv);
      memcpy(out->work_dist + vo, p->work_dist, sizeof(double) * (size_t)p->work.nv);
      for (int i = 0; i < p->work.nv; i++) out->work_labels[vo + i] = p->work_labels[i] >= 0 ? p->work_labels[i] + so : -1;
      for (int s2 = 0; s2 < p->m; s2++) {
        out->crit[so + s2] = p->crit[s2] + vo;
        out->crit_type[so + s2] = p->crit_type[s2];
        out->centers[so + s2] = to_input ? to_input[p->centers[s2]] : p->centers[s2];
      }
      out->ncrit_raw += p->ncrit_raw;
      out->empty_segments += p->empty_segments;
      out->t_smooth += p->t_smooth, out->t_remesh += p->t_remesh, out->t_psi += p->t_psi;
      out->t_spectrum += p->t_spectrum, out->t_critical += p->t_critical, out->t_ivd += p->t_ivd;
      vo += p->work.nv, fo += p->work.nf, so += p->m;
    }
    out->lambda2 = part[largest].lambda2;
  }

  /* input vertices: through the proc vertex they came from; the rest (tiny components, vertices the
   * sanitizer dropped) take the label of the nearest labelled input vertex */
  for (int i = 0; i < nv; i++) out->labels[i] = -1, out->psi[i] = -1;
  for (int j = np - 1; j >= 0; j--) { /* the first proc copy of an input vertex wins */
    int i = to_input ? to_input[j] : j;
    if (i < 0 || i >= nv || plabel[j] < 0) continue;
    out->labels[i] = plabel[j];
    out->psi[i] = pwork[j];
  }
  if ((st = ssi_fill_from_nearest(input, out->labels, "segment", err))) goto fail;
  {
    char w[512];
    snprintf(w, sizeof w, "%d components: %d segmented on their own (%d segments)", ncomp, nsig, m);
    ssi_warn_append(warnings, warnings_size, w);
    if (ntiny) {
      snprintf(w, sizeof w,
               "%d small component%s (under %g%% of the area each; first input vertex %s) got no segment of "
               "their own: their vertices take the segment of the nearest vertex of a larger component",
               ntiny, ntiny > 1 ? "s" : "", 100 * SSI_SIGNIFICANT_AREA, tiny_list);
      ssi_warn_append(warnings, warnings_size, w);
    }
  }
  goto done;

nomem:
  st = ss_fail(err, SS_ERR_NOMEM, "segment: out of memory");
fail:
  ss_segmentation_free(out);
done:
  if (part)
    for (int c = 0; c < ncomp; c++) ss_segmentation_free(&part[c]);
  ssi_submesh_free(&sub);
  free(carea), free(cnv), free(cfirst), free(one), free(plabel), free(pwork), free(part);
  return st;
}
