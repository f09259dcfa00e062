/* Figure 3: the segmentation gallery of the FAUST poses. Each shape goes through the library's
 * segmentation (ss_segment, default options, as `specseg segment`); segment ids are renumbered to agree
 * with the first shape's (FAUST shares vertex order, so the ground truth is the identity) so that
 * corresponding parts share a colour; boundary triangles are neutral and segment centres black
 * spheres, as in the paper's figures; panels at one common scale, 5 a row. */
#include "specseg/eval.h"
#include "specseg/io.h"
#include "specseg/segment.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const unsigned char NEUTRAL[3] = {225, 225, 220}, CENTRE_RGB[3] = {20, 20, 20};

ss_status ss_eval_faust_gallery(const char *data_dir, int count, const ss_render_options *o, const char *png,
                                int *segments, ss_error *err) {
  if (!data_dir || !o || !png || count < 1 || count > 100)
    return ss_fail(err, SS_ERR_INVALID, "gallery: bad arguments (%d shapes)", count);
  ss_mesh *M = calloc((size_t)count, sizeof *M);
  ss_panel *P = calloc((size_t)count, sizeof *P);
  int *ref = NULL;
  unsigned char **frgb = calloc((size_t)count, sizeof *frgb), **mrgb = calloc((size_t)count, sizeof *mrgb);
  double **mk = calloc((size_t)count, sizeof *mk);
  char (*title)[64] = calloc((size_t)count, sizeof *title);
  unsigned char *img = NULL;
  ss_status st = M && P && frgb && mrgb && mk && title ? SS_OK : ss_fail(err, SS_ERR_NOMEM, "gallery: out of memory");
  for (int i = 0; i < count && !st; i++) {
    char path[4096];
    snprintf(path, sizeof path, "%s/faust/tr_reg_%03d.off", data_dir, i);
    ss_segmentation seg;
    memset(&seg, 0, sizeof seg);
    if ((st = ss_read_mesh(path, &M[i], err))) break;
    if ((st = ss_segment(&M[i], NULL, &seg, err))) {
      ss_status s2 = st;
      char msg[sizeof err->msg];
      snprintf(msg, sizeof msg, "%s", err ? err->msg : "");
      st = ss_fail(err, s2, "%s: %s", path, msg);
      break;
    }
    if (i == 0) {
      ref = malloc(sizeof(int) * (size_t)M[0].nv);
      if (!ref) st = ss_fail(err, SS_ERR_NOMEM, "gallery: out of memory");
      else memcpy(ref, seg.labels, sizeof(int) * (size_t)M[0].nv);
    } else if (M[i].nv != M[0].nv) {
      st = ss_fail(err, SS_ERR_INVALID, "%s: %d vertices, tr_reg_000 has %d (FAUST shapes share vertices)", path,
                   M[i].nv, M[0].nv);
    } else {
      st = ss_labels_align(seg.labels, ref, M[i].nv, err);
    }
    frgb[i] = malloc(3 * (size_t)M[i].nf + 1);
    mk[i] = malloc(sizeof(double) * 3 * (size_t)seg.m + 1);
    mrgb[i] = malloc(3 * (size_t)seg.m + 1);
    if (!st && (!frgb[i] || !mk[i] || !mrgb[i])) st = ss_fail(err, SS_ERR_NOMEM, "gallery: out of memory");
    if (!st) st = ss_segmentation_face_colors(&M[i], seg.labels, NEUTRAL, frgb[i], err);
    if (!st) {
      for (int j = 0; j < seg.m; j++) {
        memcpy(mk[i] + 3 * (size_t)j, M[i].V + 3 * (size_t)seg.centers[j], 3 * sizeof(double));
        memcpy(mrgb[i] + 3 * (size_t)j, CENTRE_RGB, 3);
      }
      ss_render_scene_init(&P[i].scene, &M[i]);
      P[i].scene.face_rgb = frgb[i];
      P[i].scene.nmarkers = seg.m, P[i].scene.markers = mk[i], P[i].scene.marker_rgb = mrgb[i];
      snprintf(title[i], sizeof title[i], "tr_reg_%03d (%d)", i, seg.m);
      P[i].title = title[i];
      if (segments) segments[i] = seg.m;
    }
    ss_segmentation_free(&seg);
  }
  int w = 0, h = 0;
  if (!st) {
    ss_panel_layout L;
    ss_panel_layout_init(&L);
    L.cols = count < 5 ? count : 5;
    st = ss_render_panels(P, count, o, &L, &img, &w, &h, err);
  }
  if (!st) st = ss_write_png(png, img, w, h, err);
  for (int i = 0; M && i < count; i++) ss_mesh_free(&M[i]);
  for (int i = 0; frgb && mk && mrgb && i < count; i++) free(frgb[i]), free(mk[i]), free(mrgb[i]);
  free(M), free(P), free(ref), free(frgb), free(mrgb), free(mk), free(title), free(img);
  return st;
}
