/* ss_mesh_sanitize: turn a real-world triangle soup into a mesh the pipeline can process.
 * Drops degenerate faces (repeated vertex or zero area) and later copies of duplicate faces, then
 * gives every fan of faces around a vertex its own vertex copy (a pinched vertex shared by two cones
 * becomes two vertices), drops vertices no face uses, and orients each component consistently (the
 * minority orientation of a component is reversed; a non-orientable surface is refused). Output vertices keep the input order (copies
 * of one input vertex are adjacent), so a mesh that needs nothing keeps its numbering exactly. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/mesh_geometry.h"
#include "mesh/mesh_topology.h"
#include "specseg/mesh.h"

ss_status ss_mesh_sanitize(const ss_mesh *in, ss_mesh *out, int **to_input, char *warnings, size_t warnings_size,
                           ss_error *err) {
  if (out) memset(out, 0, sizeof *out);
  if (to_input) *to_input = NULL;
  if (warnings && warnings_size) warnings[0] = '\0';
  if (!out || !to_input) return ss_fail(err, SS_ERR_INVALID, "sanitize: NULL output");
  ss_status st = topo_check_indices(in, err);
  if (!st) st = ssi_mesh_check_coordinates(in, NULL, err); /* non-finite, beyond ±1e70 */
  if (st) return st;
  size_t nv = (size_t)in->nv, nf = (size_t)in->nf;

  unsigned char *use = malloc(nf ? nf : 1);
  topo_tri *tk = malloc(sizeof(topo_tri) * (nf ? nf : 1));
  int *cstart = calloc(nv + 1, sizeof(int)); /* corners grouped by vertex (counting sort) */
  size_t ncs = nf ? 3 * nf : 1;
  int *corners = malloc(sizeof(int) * ncs);
  int *newid = malloc(sizeof(int) * ncs); /* per fan representative corner */
  int *map = malloc(sizeof(int) * ncs);   /* output vertex -> input vertex */
  topo T = {0};
  ssi_orientation O = {0};
  if (!use || !tk || !cstart || !corners || !newid || !map) {
    st = ss_fail(err, SS_ERR_NOMEM, "out of memory sanitizing a mesh of %d faces", in->nf);
    goto done;
  }

  int ndeg = 0, ndup = 0;
  for (size_t f = 0; f < nf; f++) {
    use[f] = topo_face_degenerate(in, (int)f) == 0;
    if (!use[f]) ndeg++;
  }
  /* keep the first face of each vertex set (sorted by face index within a group) */
  size_t ntk = topo_collect_tris(in, use, tk);
  if (topo_sort_tris(tk, ntk, in->nv)) {
    st = ss_fail(err, SS_ERR_NOMEM, "out of memory sanitizing a mesh");
    goto done;
  }
  for (size_t i = 1; i < ntk; i++)
    if (!memcmp(tk[i].v, tk[i - 1].v, sizeof tk[i].v)) {
      use[tk[i].f] = 0;
      ndup++;
    }

  if ((st = topo_build(in, use, &T, err))) goto done;
  if (T.nonmanifold_edges > 0) {
    st = ss_fail(err, SS_ERR_INVALID, "%d non-manifold edge%s (e.g. edge %d-%d shared by %d faces): cannot be repaired by splitting vertices",
                 T.nonmanifold_edges, T.nonmanifold_edges > 1 ? "s" : "", T.first_nm_a, T.first_nm_b, T.first_nm_count);
    goto done;
  }

  /* corners of used faces grouped by input vertex, ascending corner index within a vertex */
  size_t nc = 3 * nf;
  for (size_t c = 0; c < nc; c++)
    if (T.fan[c] >= 0) cstart[in->F[c] + 1]++;
  for (size_t i = 0; i < nv; i++) cstart[i + 1] += cstart[i];
  {
    int *fill = malloc(sizeof(int) * (nv ? nv : 1));
    if (!fill) {
      st = ss_fail(err, SS_ERR_NOMEM, "out of memory sanitizing a mesh");
      goto done;
    }
    memcpy(fill, cstart, sizeof(int) * (nv ? nv : 1));
    for (size_t c = 0; c < nc; c++)
      if (T.fan[c] >= 0) corners[fill[in->F[c]]++] = (int)c;
    free(fill);
  }
  int nout = 0, npinched = 0, ncopies = 0, nunref = 0;
  for (size_t c = 0; c < nc; c++) newid[c] = -1;
  for (size_t v = 0; v < nv; v++) {
    int before = nout;
    for (int k = cstart[v]; k < cstart[v + 1]; k++) {
      int r = T.fan[corners[k]];
      if (newid[r] < 0) {
        newid[r] = nout;
        map[nout++] = (int)v;
      }
    }
    if (nout == before) nunref++;
    if (nout - before > 1) {
      npinched++;
      ncopies += nout - before;
    }
  }
  int nfo = (int)(nf - (size_t)ndeg - (size_t)ndup);
  if (nfo <= 0 || nout == 0) {
    st = ss_fail(err, SS_ERR_INVALID, "no usable faces left after removing %d degenerate and %d duplicate faces", ndeg, ndup);
    goto done;
  }
  /* orientation of the kept faces: each component consistently, as the majority of its faces */
  if ((st = ssi_mesh_orientation(in, use, &O, err))) goto done;
  if (!O.orientable) {
    st = ss_fail(err, SS_ERR_INVALID,
                 "the surface is not orientable: the faces around face %d cannot all be oriented "
                 "consistently (a Moebius-like band); the pipeline needs orientable surfaces, so cut it "
                 "into orientable pieces first",
                 O.bad_face);
    goto done;
  }
  if ((st = ss_mesh_alloc(out, nout, nfo, err))) goto done;
  for (int i = 0; i < nout; i++) memcpy(out->V + 3 * (size_t)i, in->V + 3 * (size_t)map[i], 3 * sizeof(double));
  int k = 0;
  for (size_t f = 0; f < nf; f++) {
    if (!use[f]) continue;
    for (int j = 0; j < 3; j++) out->F[3 * (size_t)k + (size_t)j] = newid[T.fan[3 * f + (size_t)j]];
    if (O.flip[f]) {
      int s = out->F[3 * (size_t)k + 1];
      out->F[3 * (size_t)k + 1] = out->F[3 * (size_t)k + 2];
      out->F[3 * (size_t)k + 2] = s;
    }
    k++;
  }
  int *ti = realloc(map, sizeof(int) * (size_t)nout);
  *to_input = ti ? ti : map;
  map = NULL;
  if (warnings && warnings_size) {
    size_t len = 0;
    warnings[0] = '\0';
#define SS_APPEND(...)                                                                            \
  do {                                                                                            \
    if (len < warnings_size) {                                                                    \
      int w_ = snprintf(warnings + len, warnings_size - len, "%s", len ? "; " : "");              \
      if (w_ > 0) len += (size_t)w_;                                                              \
      if (len < warnings_size) {                                                                  \
        w_ = snprintf(warnings + len, warnings_size - len, __VA_ARGS__);                          \
        if (w_ > 0) len += (size_t)w_;                                                            \
      }                                                                                           \
    }                                                                                             \
  } while (0)
    if (ndeg) SS_APPEND("dropped %d degenerate face%s", ndeg, ndeg > 1 ? "s" : "");
    if (ndup) SS_APPEND("dropped %d duplicate face%s", ndup, ndup > 1 ? "s" : "");
    if (nunref) SS_APPEND("dropped %d unreferenced vertex%s", nunref, nunref > 1 ? "es" : "");
    if (npinched) SS_APPEND("split %d non-manifold (pinched) vertex%s into %d copies", npinched, npinched > 1 ? "es" : "", ncopies);
    if (O.flipped_faces)
      SS_APPEND("re-oriented %d face%s (in %d component%s) to agree with their neighbours: the faces were not "
                "consistently oriented", O.flipped_faces, O.flipped_faces > 1 ? "s" : "", O.components_flipped,
                O.components_flipped > 1 ? "s" : "");
#undef SS_APPEND
  }

done:
  topo_free(&T);
  ssi_orientation_free(&O);
  free(use);
  free(tk);
  free(cstart);
  free(corners);
  free(newid);
  free(map);
  return st;
}
