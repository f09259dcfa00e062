/* Consistent orientation of a triangle mesh: faces glued across edges shared by exactly two faces
 * (with three distinct vertex indices each) must traverse that edge in opposite directions. A
 * breadth-first search over that face graph gives every face a parity relative to the first face of
 * its component; a contradiction means the component is not orientable (a Möbius-like band). Each
 * orientable component keeps the orientation of the majority of its faces (ties: that of its
 * lowest-numbered face), so a mesh with a few flipped faces gets those flipped back. O(n log n). */
#include "mesh/mesh_topology.h"

#include <stdlib.h>
#include <string.h>

typedef struct {
  int lo, hi, h;
} or_key;

static int or_cmp(const void *x, const void *y) {
  const or_key *a = x, *b = y;
  if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
  if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
  return (a->h > b->h) - (a->h < b->h);
}

void ssi_orientation_free(ssi_orientation *o) {
  if (!o) return;
  free(o->flip);
  memset(o, 0, sizeof *o);
}

ss_status ssi_mesh_orientation(const ss_mesh *m, const unsigned char *use, ssi_orientation *o, ss_error *err) {
  memset(o, 0, sizeof *o);
  o->orientable = 1;
  o->bad_face = -1;
  size_t nf = (size_t)(m->nf > 0 ? m->nf : 0), nh = 3 * nf;
  or_key *K = malloc(sizeof(or_key) * (nh ? nh : 1));
  int *nb = malloc(sizeof(int) * (nh ? nh : 1));           /* neighbour face across half-edge h, or -1 */
  unsigned char *rel = malloc(nh ? nh : 1);                /* 1: that neighbour runs the edge the same way */
  signed char *par = malloc(nf ? nf : 1);                  /* parity; -1 unvisited */
  int *queue = malloc(sizeof(int) * (nf ? nf : 1)); /* one component's faces, breadth first */
  o->flip = calloc(nf ? nf : 1, 1);
  if (!K || !nb || !rel || !par || !queue || !o->flip) {
    free(K), free(nb), free(rel), free(par), free(queue);
    ssi_orientation_free(o);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory orienting a mesh of %d faces", m->nf);
  }
  size_t nk = 0;
  for (size_t f = 0; f < nf; f++) {
    const int *t = m->F + 3 * f;
    int ok = (!use || use[f]) && t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
    for (int j = 0; j < 3; j++) {
      nb[3 * f + (size_t)j] = -1;
      if (!ok) continue;
      int a = t[j], b = t[(j + 1) % 3];
      K[nk].lo = a < b ? a : b;
      K[nk].hi = a < b ? b : a;
      K[nk].h = (int)(3 * f + (size_t)j);
      nk++;
    }
  }
  qsort(K, nk, sizeof *K, or_cmp);
  for (size_t i = 0; i < nk;) {
    size_t j = i + 1;
    while (j < nk && K[j].lo == K[i].lo && K[j].hi == K[i].hi) j++;
    if (j - i == 2) {
      int h0 = K[i].h, h1 = K[i + 1].h;
      int same = m->F[h0] == m->F[h1]; /* both half-edges start at the same vertex */
      nb[h0] = h1 / 3, nb[h1] = h0 / 3;
      rel[h0] = rel[h1] = (unsigned char)same;
      o->misoriented_edges += same;
    }
    i = j;
  }
  free(K);
  memset(par, -1, nf ? nf : 1);
  for (size_t f0 = 0; f0 < nf; f0++) {
    const int *t = m->F + 3 * f0;
    if (par[f0] >= 0 || (use && !use[f0]) || t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    /* one component of the face graph, breadth first from its lowest face */
    size_t qh = 0, qt = 0, n1 = 0;
    int conflict = 0;
    par[f0] = 0;
    queue[qt++] = (int)f0;
    while (qh < qt) {
      int f = queue[qh++];
      for (int j = 0; j < 3; j++) {
        int g = nb[3 * (size_t)f + (size_t)j];
        if (g < 0) continue;
        int want = par[f] ^ rel[3 * (size_t)f + (size_t)j];
        if (par[g] < 0) {
          par[g] = (signed char)want;
          queue[qt++] = g;
        } else if (par[g] != want && !conflict) {
          conflict = 1;
          if (o->orientable) o->bad_face = (int)f0;
          o->orientable = 0;
        }
      }
    }
    o->components++;
    if (conflict) {
      o->nonorientable_components++;
      continue;
    }
    for (size_t q = 0; q < qt; q++) n1 += par[queue[q]] == 1;
    if (n1 == 0) continue;
    int flip_par = 2 * n1 > qt ? 0 : 1; /* flip the minority; a tie keeps the lowest face's orientation */
    o->components_flipped++;
    for (size_t q = 0; q < qt; q++)
      if (par[queue[q]] == flip_par) {
        o->flip[queue[q]] = 1;
        o->flipped_faces++;
      }
  }
  free(nb), free(rel), free(par), free(queue);
  return SS_OK;
}

ss_status ssi_mesh_orient_copy(const ss_mesh *m, int **F_out, int *flipped, ss_error *err) {
  *F_out = NULL;
  if (flipped) *flipped = 0;
  ssi_orientation o;
  ss_status st = ssi_mesh_orientation(m, NULL, &o, err);
  if (st) return st;
  if (!o.orientable) {
    st = ss_fail(err, SS_ERR_INVALID,
                 "the surface is not orientable (the faces around face %d cannot all be oriented "
                 "consistently: a Moebius-like band); split it into orientable pieces first",
                 o.bad_face);
    ssi_orientation_free(&o);
    return st;
  }
  if (o.flipped_faces) {
    int *F = malloc(sizeof(int) * 3 * (size_t)m->nf);
    if (!F) {
      ssi_orientation_free(&o);
      return ss_fail(err, SS_ERR_NOMEM, "out of memory orienting a mesh of %d faces", m->nf);
    }
    memcpy(F, m->F, sizeof(int) * 3 * (size_t)m->nf);
    for (int f = 0; f < m->nf; f++)
      if (o.flip[f]) {
        int s = F[3 * (size_t)f + 1];
        F[3 * (size_t)f + 1] = F[3 * (size_t)f + 2];
        F[3 * (size_t)f + 2] = s;
      }
    *F_out = F;
    if (flipped) *flipped = o.flipped_faces;
  }
  ssi_orientation_free(&o);
  return SS_OK;
}

double ssi_mesh_signed_volume6(const ss_mesh *m, const int *F) {
  if (!F) F = m->F;
  double vol = 0;
  for (int t = 0; t < m->nf; t++) {
    const double *a = m->V + 3 * (size_t)F[3 * (size_t)t], *b = m->V + 3 * (size_t)F[3 * (size_t)t + 1],
                 *c = m->V + 3 * (size_t)F[3 * (size_t)t + 2];
    vol += a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return vol;
}

ss_status ssi_mesh_outward_copy(const ss_mesh *m, int **F_out, ss_error *err) {
  int *Fo = NULL;
  ss_status st = ssi_mesh_orient_copy(m, &Fo, NULL, err);
  if (st) return st;
  if (ssi_mesh_signed_volume6(m, Fo) < 0) {
    if (!Fo) {
      if (!(Fo = malloc(sizeof(int) * 3 * (size_t)m->nf)))
        return ss_fail(err, SS_ERR_NOMEM, "out of memory orienting a mesh of %d faces", m->nf);
      memcpy(Fo, m->F, sizeof(int) * 3 * (size_t)m->nf);
    }
    for (int t = 0; t < m->nf; t++) {
      int tmp = Fo[3 * (size_t)t + 1];
      Fo[3 * (size_t)t + 1] = Fo[3 * (size_t)t + 2], Fo[3 * (size_t)t + 2] = tmp;
    }
  }
  *F_out = Fo;
  return SS_OK;
}
