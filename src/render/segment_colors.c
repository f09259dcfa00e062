/* Colours of segmentations: per-face colours with neutral boundary triangles (as the paper's figures)
 * and renumbering one segmentation's ids to agree with a reference, so that corresponding parts of
 * different shapes get the same colour in a gallery. */
#include "specseg/render.h"

#include <stdlib.h>
#include <string.h>

ss_status ss_segmentation_face_colors(const ss_mesh *m, const int *labels, const unsigned char *neutral,
                                      unsigned char *face_rgb, ss_error *err) {
  static const unsigned char DEFAULT_NEUTRAL[3] = {225, 225, 220};
  if (!m || !labels || !face_rgb) return ss_fail(err, SS_ERR_INVALID, "segmentation colours: NULL argument");
  if (!neutral) neutral = DEFAULT_NEUTRAL;
  for (int f = 0; f < m->nf; f++) {
    const int *t = m->F + 3 * (size_t)f;
    for (int k = 0; k < 3; k++)
      if (t[k] < 0 || t[k] >= m->nv) return ss_fail(err, SS_ERR_INVALID, "face %d has a vertex index out of range", f);
    int l = labels[t[0]];
    if (l == labels[t[1]] && l == labels[t[2]]) ss_label_color(l, face_rgb + 3 * (size_t)f);
    else memcpy(face_rgb + 3 * (size_t)f, neutral, 3);
  }
  return SS_OK;
}

ss_status ss_labels_align(int *labels, const int *ref, int n, ss_error *err) {
  int m = 0, mr = 0;
  for (int i = 0; i < n; i++) {
    if (labels[i] < -1 || ref[i] < -1)
      return ss_fail(err, SS_ERR_INVALID, "vertex %d: label below -1", i);
    if (labels[i] + 1 > m) m = labels[i] + 1;
    if (ref[i] + 1 > mr) mr = ref[i] + 1;
  }
  if (m == 0) return SS_OK;
  if ((size_t)m * (size_t)(mr > 0 ? mr : 1) > (size_t)1 << 26)
    return ss_fail(err, SS_ERR_INVALID, "%d x %d segments: too many to align", m, mr);
  long *cnt = calloc((size_t)m * (mr > 0 ? mr : 1), sizeof(long));
  int *to = malloc(sizeof(int) * (size_t)m), *used = calloc((size_t)(mr > 0 ? mr : 1), sizeof(int));
  if (!cnt || !to || !used) {
    free(cnt); free(to); free(used);
    return ss_fail(err, SS_ERR_NOMEM, "out of memory aligning %d segments", m);
  }
  for (int i = 0; i < n; i++)
    if (labels[i] >= 0 && ref[i] >= 0) cnt[(size_t)labels[i] * mr + ref[i]]++;
  for (int a = 0; a < m; a++) to[a] = -1;
  /* greedy: the largest remaining overlap first (ties: lower ids), each id used once */
  for (;;) {
    long best = 0;
    int ba = -1, bb = -1;
    for (int a = 0; a < m; a++)
      if (to[a] < 0)
        for (int b = 0; b < mr; b++)
          if (!used[b] && cnt[(size_t)a * mr + b] > best) best = cnt[(size_t)a * mr + b], ba = a, bb = b;
    if (ba < 0) break;
    to[ba] = bb;
    used[bb] = 1;
  }
  int next = mr;
  for (int a = 0; a < m; a++)
    if (to[a] < 0) to[a] = next++;
  for (int i = 0; i < n; i++)
    if (labels[i] >= 0) labels[i] = to[labels[i]];
  free(cnt); free(to); free(used);
  return SS_OK;
}
