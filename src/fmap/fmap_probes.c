/* The probe functions of one shape for Eq. (1), in its reduced basis: WKS descriptors, wave-kernel
 * maps of the landmarks (NO17), and extra paired functions (the segments) raw or wave-filtered.
 *
 * All filtered probes form one virtual column list [WKS | landmark 1 | … | landmark nl | extra 1 | …]
 * with n_energies columns per item, of which every descr_step-th column is kept (as pyFM does). The
 * base probes are the kept columns before the extras; the extra probes are the kept columns after
 * them — so building them apart gives exactly the columns of building them together, and a pair's
 * base probes can be computed once per shape and landmark set and shared by STD, ASA and DIFF. Only
 * the kept columns are synthesised (in the spectral domain, then one dgemm).
 *
 * The filtered probes are synthesised from the first kd = max(k, descr_k) eigenpairs (the WKS
 * filters on kd eigenvalues, the filtered functions' coefficients on kd eigenfunctions) and then
 * projected onto the first k, so a larger descr_k gives probes with more detail in the same basis.
 * kd = k is the NO17 / paper construction, computed by the same operations as before the option. */
#include "fmap/fmap_options.h"
#include "specseg/laplacian.h"
#include "mesh/mesh_topology.h"

#include <cblas.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Kept virtual columns c in [c_from, c_to) (c ≡ 0 mod step) as functions F (n x *nf, malloc'd), from
 * the first k eigenpairs (k here is the descriptor basis kd). Item 0 (columns 0..ne-1) is the WKS;
 * item i ≥ 1 is the wave filter of the function whose spectral coefficients are coef[:, i − item0]
 * (k rows; items below item0 must not be in the range). */
static ss_status kept_columns(int n, int k, const double *evals, const double *evecs, const ss_fmap_match_options *o,
                              int item0, const double *coef, int c_from, int c_to, double **F, int *nf,
                              ss_error *err) {
  const int ne = o->n_energies, step = o->descr_step;
  int first = (c_from + step - 1) / step * step, ncol = first < c_to ? (c_to - first + step - 1) / step : 0;
  int nwks = 0, nflt = 0;
  for (int c = first; c < c_to; c += step) {
    if (c < ne) nwks++;
    else nflt++;
  }
  double *G = malloc(sizeof(double) * (size_t)ne * k), *out = malloc(sizeof(double) * (size_t)n * (ncol > 0 ? ncol : 1));
  double *Gw = malloc(sizeof(double) * (size_t)(nwks > 0 ? nwks : 1) * k);
  double *fc = malloc(sizeof(double) * (size_t)k * (nflt > 0 ? nflt : 1)), *sq = NULL;
  ss_status st = SS_OK;
  if (!G || !out || !Gw || !fc) { st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory"); goto done; }
  if ((st = ss_wks_filters(evals, k, ne, o->sigma_factor, G, err))) goto done;
  int t = 0, f = 0;
  for (int c = first; c < c_to; c += step) {
    int item = c / ne, j = c % ne;
    if (item == 0)
      for (int i = 0; i < k; i++) Gw[t + (size_t)nwks * i] = G[j + (size_t)ne * i];
    else
      for (int i = 0; i < k; i++) fc[i + (size_t)k * f] = G[j + (size_t)ne * i] * coef[i + (size_t)k * (item - item0)];
    t += item == 0, f += item != 0;
  }
  if (nwks > 0) { /* WKS: Σ_i G[j,i] φ_i(x)² */
    if (!(sq = malloc(sizeof(double) * (size_t)n * k))) { st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory"); goto done; }
    for (size_t i = 0; i < (size_t)n * k; i++) sq[i] = evecs[i] * evecs[i];
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, n, nwks, k, 1.0, sq, n, Gw, nwks, 0.0, out, n);
  }
  if (nflt > 0)
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n, nflt, k, 1.0, evecs, n, fc, k, 0.0, out + (size_t)n * nwks, n);
  *F = out;
  *nf = ncol;
  out = NULL;
done:
  free(G), free(out), free(Gw), free(fc), free(sq);
  return st;
}

/* Normalise the columns of F in L²(M), then fill out (A, and the packed operators when asked).
 * Scale: with the shape scaled by s, Φ goes as 1/s, M as s² and a unit-L²(M) function as 1/s, so the
 * coefficients A = Φᵀ M f are scale-free but D = Φᵀ M diag(f) Φ goes as 1/s: the commutativity term of
 * Eq. (1) would weigh 1/s² against the data term (x1e4 made it vanish, x1e-4 swamp the descriptors).
 * The operators are therefore those of the shape scaled to unit area, D·√area (f·√area is the
 * function normalised at unit area; Φ and M scale back); A is the same at any scale. */
static ss_status finish(const ss_mesh *mesh, int k, const double *evecs, const double *M, double *F, int p,
                        int with_operators, int orient_from, int n_orient, ss_fmap_probes *out, ss_error *err) {
  const int n = mesh->nv;
  double area = 0;
  for (int x = 0; x < n; x++) area += M[x];
  if (with_operators && !(area > 0 && isfinite(area)))
    return ss_fail(err, SS_ERR_INVALID, "probes: the shape's masses sum to %g (need a positive finite area)", area);
  for (int c = 0; c < p; c++) {
    double *f = F + (size_t)n * c, s = 0;
    for (int x = 0; x < n; x++) s += M[x] * f[x] * f[x];
    if (s > 0) cblas_dscal(n, 1.0 / sqrt(s), f, 1);
  }
  memset(out, 0, sizeof *out);
  out->k = k, out->p = p, out->nd = with_operators ? p : 0;
  out->A = malloc(sizeof(double) * (size_t)k * (p > 0 ? p : 1));
  if (with_operators) out->P = malloc(sizeof(double) * (size_t)k * (k + 1) / 2 * (p > 0 ? p : 1));
  ss_status st = SS_OK;
  if (!out->A || (with_operators && !out->P)) st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory");
  if (!st) st = ss_fmap_project(n, k, evecs, M, p, F, out->A, err);
  if (!st && with_operators) st = ss_fmap_mult_operators_packed(n, k, evecs, M, p, F, out->P, err);
  if (!st && with_operators) cblas_dscal((int)((size_t)k * (k + 1) / 2 * p), sqrt(area), out->P, 1);
  if (!st && with_operators && n_orient > 0) {
    /* the orientation operators of columns orient_from.. orient_from + n_orient − 1, those of the shape
     * at unit area (φ and the unit-L²(M) functions scale back by √area each, O is trilinear in them) */
    out->no = n_orient < p - orient_from ? n_orient : p - orient_from;
    if (!(out->O = malloc(sizeof(double) * (size_t)k * k * out->no))) st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory");
    /* every face wound the same way on both shapes: each mesh's outward orientation (a scan wound
     * inward, or partly each way, gives the same operators) */
    int *Fo = NULL;
    if (!st) st = ssi_mesh_outward_copy(mesh, &Fo, err);
    ss_mesh outward = *mesh;
    if (Fo) outward.F = Fo;
    if (!st) st = ss_fmap_orientation_operators(&outward, k, evecs, out->no, F + (size_t)n * orient_from, out->O, err);
    free(Fo);
    if (!st) cblas_dscal((int)((size_t)k * k * out->no), area * sqrt(area), out->O, 1);
  }
  if (st) ss_fmap_probes_free(out);
  return st;
}

/* Common start of the builders: options (defaults for NULL) checked into *o, the shape checked
 * against them, *out zeroed. */
static ss_status start(const ss_fmap_shape *s, const ss_fmap_match_options *opts, ss_fmap_probes *out,
                       ss_fmap_match_options *o, ss_error *err) {
  if (!out) return ss_fail(err, SS_ERR_INVALID, "probes: NULL output");
  memset(out, 0, sizeof *out);
  ss_status st = ssi_fmap_options_resolve(opts, o, err);
  return st ? st : ssi_fmap_check_shape(s, "of the probes", ssi_fmap_descr_k(o), err);
}

/* the shape's lumped masses: its own, or barycentric ones in *own */
static ss_status masses(const ss_fmap_shape *s, double **own, const double **M, ss_error *err) {
  *own = NULL;
  *M = s->M;
  if (s->M) return SS_OK;
  if (!(*own = malloc(sizeof(double) * (size_t)s->mesh->nv))) return ss_fail(err, SS_ERR_NOMEM, "probes: out of memory");
  ss_status st = ss_mass_lumped(s->mesh, SS_MASS_BARYCENTRIC, *own, err);
  *M = *own;
  return st;
}

ss_status ss_fmap_base_probes(const ss_fmap_shape *s, int nl, const int *lm, const ss_fmap_match_options *opts,
                              int with_operators, ss_fmap_probes *out, ss_error *err) {
  ss_fmap_match_options o;
  ss_status st = start(s, opts, out, &o, err);
  if (st) return st;
  const int n = s->mesh->nv, k = o.k, kd = ssi_fmap_descr_k(&o);
  if (nl < 0 || (nl > 0 && !lm)) return ss_fail(err, SS_ERR_INVALID, "probes: missing landmarks");
  for (int l = 0; l < nl; l++)
    if (lm[l] < 0 || lm[l] >= n) return ss_fail(err, SS_ERR_INVALID, "landmark %d: vertex %d out of range [0,%d)", l, lm[l], n);
  if (s->ndescr < 0 || (s->ndescr > 0 && !s->descr))
    return ss_fail(err, SS_ERR_INVALID, "probes: %d descriptors without their values", s->ndescr);
  for (size_t i = 0; i < (size_t)n * (size_t)(s->ndescr > 0 ? s->ndescr : 0); i++)
    if (!isfinite(s->descr[i]))
      return ss_fail(err, SS_ERR_INVALID, "probes: descriptor %d is not finite at vertex %d", (int)(i / (size_t)n),
                     (int)(i % (size_t)n));
  double *own = NULL, *coef = malloc(sizeof(double) * (size_t)kd * (nl > 0 ? nl : 1)), *F = NULL;
  const double *M = NULL;
  int p = 0;
  if (!coef) { st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory"); goto done; }
  if ((st = masses(s, &own, &M, err))) goto done;
  /* landmark deltas in the spectral domain: φ_i(l) (the L²-delta δ_l / M_l projects to these) */
  for (int l = 0; l < nl; l++)
    for (int i = 0; i < kd; i++) coef[i + (size_t)kd * l] = s->evecs[lm[l] + (size_t)n * i];
  /* without the WKS the list starts at the first landmark item: the same landmark columns are kept */
  if ((st = kept_columns(n, kd, s->evals, s->evecs, &o, 1, coef, o.no_wks ? o.n_energies : 0, o.n_energies * (1 + nl),
                         &F, &p, err)))
    goto done;
  if (s->ndescr > 0) { /* the shape's own descriptors after the kept columns, as they are */
    double *G = realloc(F, sizeof(double) * (size_t)n * (size_t)(p + s->ndescr));
    if (!G) { st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory"); goto done; }
    F = G;
    memcpy(F + (size_t)n * p, s->descr, sizeof(double) * (size_t)n * s->ndescr);
    p += s->ndescr;
  }
  if (p == 0) { st = ss_fail(err, SS_ERR_INVALID, "probes: no WKS, no landmark and no descriptor"); goto done; }
  /* orientation operators (when the term is weighted) of the WKS columns, the first kept ones, or
   * without the WKS of as many of the shape's own descriptors that replace it */
  const int nwks = (o.n_energies + o.descr_step - 1) / o.descr_step;
  const int n_orient = !(o.w_orient > 0) ? 0 : !o.no_wks ? nwks : s->ndescr < nwks ? s->ndescr : nwks;
  st = finish(s->mesh, k, s->evecs, M, F, p, with_operators, o.no_wks ? p - s->ndescr : 0, n_orient, out, err);
done:
  free(own), free(coef), free(F);
  return st;
}

ss_status ss_fmap_extra_probes(const ss_fmap_shape *s, int nl, int nextra, const double *extra, ss_probe_filter filter,
                               const ss_fmap_match_options *opts, int with_operators, ss_fmap_probes *out,
                               ss_error *err) {
  ss_fmap_match_options o;
  ss_status st = start(s, opts, out, &o, err);
  if (st) return st;
  if (nl < 0 || nextra < 0 || (nextra > 0 && !extra)) return ss_fail(err, SS_ERR_INVALID, "probes: missing extra probes");
  if (filter != SS_PROBE_RAW && filter != SS_PROBE_WAVE) return ss_fail(err, SS_ERR_INVALID, "probes: unknown filter %d", (int)filter);
  const int n = s->mesh->nv, k = o.k, kd = ssi_fmap_descr_k(&o), ne = o.n_energies;
  double *own = NULL, *coef = NULL, *F = NULL;
  const double *M = NULL;
  int p = 0;
  if ((st = masses(s, &own, &M, err))) goto done;
  if (filter == SS_PROBE_WAVE) {
    if (!(coef = malloc(sizeof(double) * (size_t)kd * (nextra > 0 ? nextra : 1)))) {
      st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory");
      goto done;
    }
    if ((st = ss_fmap_project(n, kd, s->evecs, M, nextra, extra, coef, err))) goto done;
    if ((st = kept_columns(n, kd, s->evals, s->evecs, &o, 1 + nl, coef, ne * (1 + nl), ne * (1 + nl + nextra), &F, &p, err)))
      goto done;
  } else {
    if (!(F = malloc(sizeof(double) * (size_t)n * (nextra > 0 ? nextra : 1)))) {
      st = ss_fail(err, SS_ERR_NOMEM, "probes: out of memory");
      goto done;
    }
    memcpy(F, extra, sizeof(double) * (size_t)n * nextra);
    p = nextra;
  }
  st = finish(s->mesh, k, s->evecs, M, F, p, with_operators, 0, 0, out, err);
done:
  free(own), free(coef), free(F);
  return st;
}
