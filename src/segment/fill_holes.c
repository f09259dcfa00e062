/* Close boundary loops with a centroid fan (see fill_holes.h). */
#include "fill_holes.h"

#include <stdlib.h>
#include <string.h>

ss_status ssi_fill_holes_fan(const ss_mesh *in, ss_mesh *out, int *nholes, ss_error *err) {
  memset(out, 0, sizeof *out);
  *nholes = 0;
  int nv = in->nv, nf = in->nf;
  size_t nh = 3 * (size_t)nf;
  /* half-edges grouped by their origin (counting sort): list[start[a] ..] = heads b of a→b */
  int *start = calloc((size_t)nv + 1, sizeof(int)), *list = malloc(sizeof(int) * (nh ? nh : 1));
  int *next = malloc(sizeof(int) * (size_t)(nv ? nv : 1)); /* boundary half-edge a→next[a] */
  int *loop = NULL;
  ss_status st = SS_OK;
  if (!start || !list || !next) {
    st = ss_fail(err, SS_ERR_NOMEM, "fill holes: out of memory");
    goto done;
  }
  for (size_t h = 0; h < nh; h++) start[in->F[h] + 1]++;
  for (int v = 0; v < nv; v++) start[v + 1] += start[v];
  for (int v = 0; v < nv; v++) next[v] = start[v];
  for (size_t h = 0; h < nh; h++) list[next[in->F[h]]++] = in->F[h - h % 3 + (h % 3 + 1) % 3];
  {
    /* an edge run twice in the same direction: report the lowest (a, b) */
    int da = -1, db = -1;
    for (int a = 0; a < nv && da < 0; a++)
      for (int p = start[a]; p < start[a + 1]; p++)
        for (int q = p + 1; q < start[a + 1]; q++)
          if (list[p] == list[q] && (da < 0 || list[p] < db)) da = a, db = list[p];
    if (da >= 0) {
      st = ss_fail(err, SS_ERR_UNSUPPORTED,
                   "segment: two faces run the edge %llu-%llu in the same direction: the faces are not consistently "
                   "oriented (or the edge is non-manifold); orient them first, or keep the segmentation's sanitize "
                   "option on (the default: it re-orients each component and splits non-manifold vertices)",
                   (unsigned long long)da, (unsigned long long)db);
      goto done;
    }
  }
  for (int i = 0; i < nv; i++) next[i] = -1;
  size_t nb = 0;
  for (size_t h = 0; h < nh; h++) {
    int a = in->F[h], b = in->F[h - h % 3 + (h % 3 + 1) % 3], twin = 0;
    for (int p = start[b]; p < start[b + 1] && !twin; p++) twin = list[p] == a;
    if (twin) continue;
    if (next[a] >= 0) {
      st = ss_fail(err, SS_ERR_UNSUPPORTED,
                   "segment: two boundary loops pass through vertex %d (a pinched vertex on a hole): split it first, "
                   "or keep the segmentation's sanitize option on (the default: it splits such vertices)",
                   a);
      goto done;
    }
    next[a] = b;
    nb++;
  }
  if (nb == 0) {
    st = ss_mesh_copy(in, out, err);
    goto done;
  }
  /* trace loops; each boundary edge becomes one fan triangle, each loop one vertex */
  loop = malloc(sizeof(int) * nb);
  if (!loop) {
    st = ss_fail(err, SS_ERR_NOMEM, "fill holes: out of memory");
    goto done;
  }
  int nloops = 0;
  {
    /* count loops first so the output can be sized */
    unsigned char *seen = calloc((size_t)nv, 1);
    if (!seen) {
      st = ss_fail(err, SS_ERR_NOMEM, "fill holes: out of memory");
      goto done;
    }
    for (int s = 0; s < nv; s++) {
      if (next[s] < 0 || seen[s]) continue;
      int v = s;
      size_t len = 0;
      while (!seen[v]) {
        seen[v] = 1;
        if (next[v] < 0 || ++len > nb) break;
        v = next[v];
      }
      if (v != s || next[v] < 0) {
        free(seen);
        st = ss_fail(err, SS_ERR_UNSUPPORTED,
                     "segment: the boundary through vertex %d is not a simple loop (holes are closed with a fan of "
                     "triangles); repair the mesh around it (`specseg info` counts boundary loops and non-manifold "
                     "vertices)",
                     s);
        goto done;
      }
      nloops++;
    }
    free(seen);
  }
  if ((st = ss_mesh_alloc(out, nv + nloops, nf + (int)nb, err))) goto done;
  memcpy(out->V, in->V, sizeof(double) * 3 * (size_t)nv);
  memcpy(out->F, in->F, sizeof(int) * 3 * (size_t)nf);
  int fo = nf, c = nv;
  for (int s = 0; s < nv; s++) {
    if (next[s] < 0) continue;
    size_t len = 0;
    int v = s;
    do {
      loop[len++] = v;
      int w = next[v];
      next[v] = -1; /* consumed */
      v = w;
    } while (v != s);
    double cen[3] = {0, 0, 0};
    for (size_t k = 0; k < len; k++)
      for (int d = 0; d < 3; d++) cen[d] += in->V[3 * (size_t)loop[k] + d] / (double)len;
    for (int d = 0; d < 3; d++) out->V[3 * (size_t)c + d] = cen[d];
    for (size_t k = 0; k < len; k++) {
      int a = loop[k], b = loop[(k + 1) % len];
      out->F[3 * (size_t)fo] = b;
      out->F[3 * (size_t)fo + 1] = a;
      out->F[3 * (size_t)fo + 2] = c;
      fo++;
    }
    c++;
  }
  *nholes = nloops;
done:
  free(start);
  free(list);
  free(next);
  free(loop);
  return st;
}
