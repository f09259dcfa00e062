/* Matching two prepared shapes (ss_prepared_shape) with the result ss_match_warn gives from their
 * meshes: what ss_match_warn does before ss_match_prepared (landmark checks, the components it keeps,
 * the eigenpairs it computes) is checked here against what the shapes carry. See match.h. */
#include "specseg/match.h"
#include "match/match_submesh.h"
#include "match/landmark_check.h"
#include "match/hypotheses.h"
#include "mesh/mesh_topology.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const NAME[2] = {"X (the first shape)", "Y (the second shape)"};

/* 1 when ss_match_warn keeps every component of m (one component, or every one holds a landmark;
 * landmark-free: one component); 0 when it would match a part; -1 out of memory */
static int keeps_whole(const ss_mesh *m, int nl, const int *lm) {
  int *comp = malloc(sizeof(int) * (size_t)m->nv);
  int nc = comp ? ssi_mesh_components(m, comp) : -1, whole = 1;
  if (nc < 0) return free(comp), -1;
  if (nc > 1) {
    unsigned char *has = calloc((size_t)nc, 1);
    if (!has) return free(comp), -1;
    for (int i = 0; i < nl; i++)
      if (comp[lm[i]] >= 0) has[comp[lm[i]]] = 1;
    for (int c = 0; c < nc; c++) whole = whole && has[c] && nl > 0;
    free(has);
  }
  free(comp);
  return whole;
}

static int same_autopair(const ss_autopair_options *a, const ss_autopair_options *b) {
  return a->descr_k == b->descr_k && a->n_energies == b->n_energies && a->sigma_factor == b->sigma_factor &&
         a->descr_radius == b->descr_radius && a->w_descr == b->w_descr && a->w_geo == b->w_geo &&
         a->exact_max == b->exact_max && a->orient_k == b->orient_k && a->orient_descr_k == b->orient_descr_k &&
         a->min_gap == b->min_gap && a->min_mirror == b->min_mirror;
}

static int same_seg(const ss_segment_options *a, const ss_segment_options *b) {
  return a->target_faces == b->target_faces && a->no_streamline == b->no_streamline &&
         a->cleanup_rings == b->cleanup_rings && a->n_eigs == b->n_eigs && a->cmcf_steps == b->cmcf_steps &&
         a->cmcf_dt == b->cmcf_dt && a->sanitize == b->sanitize;
}

ss_status ss_match_prepared_shapes(const ss_prepared_shape *X, const ss_prepared_shape *Y, int nl, const int *lmX,
                                   const int *lmY, const ss_match_options *opts, ss_match_result *out, char *warnings,
                                   size_t warnings_size, ss_error *err) {
  if (warnings && warnings_size) warnings[0] = '\0';
  if (!out) return ss_fail(err, SS_ERR_INVALID, "match: NULL output");
  memset(out, 0, sizeof *out);
  ss_match_options o;
  if (opts) o = *opts;
  else ss_match_default_options(&o);
  const ss_prepared_shape *S[2] = {X, Y};
  for (int s = 0; s < 2; s++)
    if (!S[s] || !S[s]->mesh.V || !ss_prepared_shape_matched(S[s])->evecs || !S[s]->prep.seg.centers ||
        S[s]->prep.seg.nv != S[s]->mesh.nv || (S[s]->has_proxy && (!S[s]->to_proxy || !S[s]->proxy_src ||
                                                                   S[s]->proxy_prep.seg.nv != S[s]->proxy.nv)))
      return ss_fail(err, SS_ERR_INVALID, "match: %s: not a prepared shape", NAME[s]);
  if (nl < 0 || (nl > 0 && (!lmX || !lmY))) return ss_fail(err, SS_ERR_INVALID, "match: bad landmarks");
  for (int i = 0; i < nl; i++) {
    if (lmX[i] < 0 || lmX[i] >= X->mesh.nv)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on X [0,%d)", i, lmX[i], X->mesh.nv);
    if (lmY[i] < 0 || lmY[i] >= Y->mesh.nv)
      return ss_fail(err, SS_ERR_INVALID, "match: landmark %d: vertex %d out of range on Y [0,%d)", i, lmY[i], Y->mesh.nv);
  }
  ss_status lst = ss_landmarks_check(nl, lmX, lmY, NULL, NULL, err); /* too many, two partners */
  if (lst) return lst;
  int whole[2];
  for (int s = 0; s < 2; s++)
    if ((whole[s] = keeps_whole(&S[s]->mesh, nl, s ? lmY : lmX)) < 0)
      return ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
  /* ss_match_warn matches a part of the mesh (the components with landmarks; landmark-free the
   * largest), or a proxied mesh at full size with the caller's descriptors (their rows are the
   * mesh's): then that is done from the meshes, as ss_match_warn does it */
  const int descr = o.ndescr > 0 && o.descrX && o.descrY;
  if (!whole[0] || !whole[1] || (descr && (X->has_proxy || Y->has_proxy))) {
    if (!same_seg(&X->seg, &Y->seg))
      return ss_fail(err, SS_ERR_INVALID,
                     "match: the shapes were prepared with different segmentation options, and %s is matched from "
                     "its mesh here (%s): prepare both with the same options",
                     NAME[!whole[0] || (descr && X->has_proxy) ? 0 : 1],
                     !whole[0] || !whole[1] ? "the match drops components" : "the descriptors are the mesh's");
    o.seg = X->seg;
    ss_status st = ss_match_warn(&X->mesh, &Y->mesh, nl, lmX, lmY, &o, out, warnings, warnings_size, err);
    if (!st && warnings && warnings_size) {
      const int fx = !whole[0] || (descr && X->has_proxy), fy = !whole[1] || (descr && Y->has_proxy);
      size_t n = strlen(warnings);
      snprintf(warnings + n, warnings_size - n, "%s%s%s%s: prepared data not used (%s)", n ? "; " : "",
               fx ? "X" : "", fx && fy ? " and " : "", fy ? "Y" : "",
               !whole[0] || !whole[1] ? "the kept components were prepared again" : "matched at full size with the "
                                                                                     "descriptors");
    }
    return st;
  }
  const ss_shape_prep *P[2] = {ss_prepared_shape_matched(X), ss_prepared_shape_matched(Y)};
  /* the least the match needs: the kept map's further refinement (hyp_final_kmax) stops at the
   * eigenpairs the shapes hold, with a note (files prepared for an earlier default) */
  ss_match_options least = o;
  least.autopair.hyp_final_kmax = 0;
  const int need = ss_match_eigenpairs(&least, nl);
  for (int s = 0; s < 2; s++)
    if (P[s]->kev < need)
      return ss_fail(err, SS_ERR_INVALID,
                     "match: %s was prepared with %d eigenpairs but this match needs %d (k %d, ZoomOut %d, "
                     "descriptors %d%s): prepare it with at least %d",
                     NAME[s], P[s]->kev, need, o.fmap.k, o.refine != SS_REFINE_NONE ? o.fmap.zoomout_kmax : 0,
                     o.fmap.descr_k, nl == 0 ? ", landmark-free pairing" : "", need);
  /* the stored proxies as sub-meshes of the input meshes (views, not owned) */
  const ssi_submesh vx = {X->has_proxy, X->proxy, X->to_proxy, X->proxy_src},
                    vy = {Y->has_proxy, Y->proxy, Y->to_proxy, Y->proxy_src};
  /* landmarks on the matched meshes (the proxies' vertices where there are proxies) */
  int *lm = malloc(sizeof(int) * (size_t)(2 * nl > 0 ? 2 * nl : 1));
  if (!lm) return ss_fail(err, SS_ERR_NOMEM, "match: out of memory");
  for (int i = 0; i < nl; i++) {
    lm[i] = ssi_submesh_sub_vertex(&vx, lmX[i]);
    lm[nl + i] = ssi_submesh_sub_vertex(&vy, lmY[i]);
  }
  ss_status cst = ssi_check_landmarks_segmented(P[0], P[1], nl, lm, lm + nl, lmX, lmY, err);
  if (cst) {
    free(lm);
    return cst;
  }
  /* the shapes as ss_match_prepared takes them, pointing into X and Y (which may have been copied);
   * no segmentation or eigensolve happens in this call */
  ss_shape_prep px = *P[0], py = *P[1];
  px.mesh = X->has_proxy ? &X->proxy : &X->mesh, py.mesh = Y->has_proxy ? &Y->proxy : &Y->mesh;
  px.t_segment = px.t_eigs = py.t_segment = py.t_eigs = 0;
  ss_status st;
  {
    ss_centre_signature sx = X->sig, sy = Y->sig;
    sx.prep = &px, sy.prep = &py;
    const int use_x = X->has_signature && same_autopair(&X->autopair, &o.autopair);
    const int use_y = Y->has_signature && same_autopair(&Y->autopair, &o.autopair);
    st = ssi_match_prepared_signed(&px, &py, use_x ? &sx : NULL, use_y ? &sy : NULL, nl, lm, lm + nl, &o, out, err);
  }
  free(lm);
  /* back to the input meshes' vertices */
  if (!st) st = ssi_match_lift(&vx, &vy, &X->mesh, out, err);
  if (st) ss_match_result_free(out);
  return st;
}
