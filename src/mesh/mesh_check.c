/* ss_mesh_check: everything `specseg info` reports, in O(n log n) (one sort of half-edge keys, one
 * of face triples, union-find for components, fans and boundary loops).
 *
 * Conventions: faces with a repeated vertex index count as degenerate and take no part in the
 * topology (edges, fans, loops, Euler characteristic); zero-area faces with three distinct vertices
 * are counted as degenerate but stay in the topology, as do duplicate faces (so a duplicated face also
 * shows up as non-manifold edges — that is what the mesh as given is). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/mesh_geometry.h"
#include "mesh/mesh_topology.h"
#include "specseg/mesh.h"

static int vfind(int *p, int x) {
  while (p[x] != x) {
    p[x] = p[p[x]];
    x = p[x];
  }
  return x;
}

ss_status ss_mesh_check(const ss_mesh *m, ss_mesh_report *r, ss_error *err) {
  memset(r, 0, sizeof *r);
  ss_status st = topo_check_indices(m, err);
  if (st) return st;
  r->vertices = m->nv;
  r->faces = m->nf;
  size_t nv = (size_t)m->nv, nf = (size_t)m->nf;

  /* geometry: area over all faces, bounding box over finite vertices */
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  int any = 0;
  for (size_t i = 0; i < nv; i++) {
    const double *p = m->V + 3 * i;
    if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
      r->nonfinite_vertices++;
      continue;
    }
    any = 1;
    for (int d = 0; d < 3; d++) {
      lo[d] = fmin(lo[d], p[d]);
      hi[d] = fmax(hi[d], p[d]);
    }
  }
  if (any) r->bbox_diagonal = ssi_box_diagonal(lo, hi);
  r->area = ss_mesh_area(m);

  int *vpar = malloc(sizeof(int) * (nv ? nv : 1));
  unsigned char *vref = calloc(nv ? nv : 1, 2); /* [2i]: used by any face, [2i+1]: by a proper one */
  int *nfan = calloc(nv ? nv : 1, sizeof(int));
  topo_tri *tk = malloc(sizeof(topo_tri) * (nf ? nf : 1));
  topo T = {0};
  if (!vpar || !vref || !nfan || !tk) {
    st = ss_fail(err, SS_ERR_NOMEM, "out of memory checking a mesh of %d vertices", m->nv);
    goto done;
  }

  /* components: vertices joined through faces */
  for (size_t i = 0; i < nv; i++) vpar[i] = (int)i;
  for (size_t f = 0; f < nf; f++) {
    const int *t = m->F + 3 * f;
    int deg = topo_face_degenerate(m, (int)f);
    if (deg) r->degenerate_faces++;
    for (int j = 0; j < 3; j++) {
      vref[2 * (size_t)t[j]] = 1;
      if (deg != 1) vref[2 * (size_t)t[j] + 1] = 1;
      int a = vfind(vpar, t[j]), b = vfind(vpar, t[(j + 1) % 3]);
      if (a != b) vpar[a < b ? b : a] = a < b ? a : b;
    }
  }
  int nref_proper = 0;
  for (size_t i = 0; i < nv; i++) {
    if (!vref[2 * i]) r->unreferenced_vertices++;
    else if (vfind(vpar, (int)i) == (int)i) r->components++;
    if (vref[2 * i + 1]) nref_proper++;
  }

  /* duplicates: same vertex set as an earlier face */
  size_t ntk = topo_collect_tris(m, NULL, tk);
  if (topo_sort_tris(tk, ntk, m->nv)) {
    st = ss_fail(err, SS_ERR_NOMEM, "out of memory checking a mesh of %d vertices", m->nv);
    goto done;
  }
  for (size_t i = 1; i < ntk; i++)
    if (!memcmp(tk[i].v, tk[i - 1].v, sizeof tk[i].v)) r->duplicate_faces++;

  if ((st = topo_build(m, NULL, &T, err))) goto done;
  r->boundary_edges = T.boundary_edges;
  r->nonmanifold_edges = T.nonmanifold_edges;
  /* fans per vertex: each fan representative is one corner, so counting representatives per vertex
   * counts fans; more than one is a pinch */
  size_t nc = 3 * nf;
  for (size_t c = 0; c < nc; c++)
    if (T.fan[c] == (int)c) nfan[m->F[c]]++;
  for (size_t i = 0; i < nv; i++)
    if (nfan[i] > 1) r->nonmanifold_vertices++;
  for (size_t c = 0; c < nc; c++)
    if (T.loop[c] == (int)c) r->boundary_loops++;
  r->euler_characteristic = nref_proper - T.nedges + (int)ntk;
  r->manifold = r->nonmanifold_edges == 0 && r->nonmanifold_vertices == 0;
  {
    ssi_orientation o;
    if ((st = ssi_mesh_orientation(m, NULL, &o, err))) goto done;
    r->misoriented_edges = o.misoriented_edges;
    r->oriented = o.misoriented_edges == 0;
    r->orientable = o.orientable;
    r->reorient_faces = o.orientable ? o.flipped_faces : 0;
    ssi_orientation_free(&o);
  }

done:
  topo_free(&T);
  free(vpar);
  free(vref);
  free(nfan);
  free(tk);
  return st;
}
