/* OFF, PLY and OBJ writers. Coordinates are written losslessly (%.17g in text, float64 in binary PLY) so
 * that write -> read round trips are exact. Binary output is assembled byte by byte, independent of
 * the host's endianness. */
#include <ctype.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "specseg/io.h"
#include "util/c_locale.h"
#include "util/out_file.h"

static ss_status check_mesh(const char *path, const ss_mesh *m, ss_error *err) {
  if (!m || m->nv < 0 || m->nf < 0 || (m->nv > 0 && !m->V) || (m->nf > 0 && !m->F))
    return ss_fail(err, SS_ERR_INVALID, "%s: invalid mesh (bad sizes or missing arrays)", path);
  for (size_t i = 0; i < 3 * (size_t)m->nf; i++)
    if (m->F[i] < 0 || m->F[i] >= m->nv)
      return ss_fail(err, SS_ERR_INVALID, "%s: face %zu has vertex index %d out of range [0, %d)", path, i / 3, m->F[i], m->nv);
  return SS_OK;
}

/* through util/out_file.h: written whole under a temporary name, then renamed into place */
static ss_status open_out(const char *path, ssi_out *o, FILE **f, ss_error *err) {
  ss_status st = ssi_out_open(o, path, err);
  *f = st ? NULL : o->f;
  return st;
}

static ss_status close_out(const char *path, ssi_out *o, ss_error *err) { return ssi_out_commit(o, path, err); }

ss_status ss_write_off(const char *path, const ss_mesh *m, const unsigned char *rgb, ss_error *err) {
  ss_status st = check_mesh(path, m, err);
  if (st) return st;
  ssi_out o;
  FILE *f;
  if ((st = open_out(path, &o, &f, err))) return st;
  /* COFF: "x y z r g b a" per vertex, the layout most viewers read */
  fprintf(f, "%s\n%d %d 0\n", rgb ? "COFF" : "OFF", m->nv, m->nf);
  for (int i = 0; i < m->nv && !ferror(f); i++) {
    const double *p = m->V + 3 * (size_t)i;
    if (rgb)
      ssi_fprintf_c(f, "%.17g %.17g %.17g %u %u %u 255\n", p[0], p[1], p[2], rgb[3 * (size_t)i], rgb[3 * (size_t)i + 1], rgb[3 * (size_t)i + 2]);
    else
      ssi_fprintf_c(f, "%.17g %.17g %.17g\n", p[0], p[1], p[2]);
  }
  for (int i = 0; i < m->nf && !ferror(f); i++) {
    const int *t = m->F + 3 * (size_t)i;
    fprintf(f, "3 %d %d %d\n", t[0], t[1], t[2]);
  }
  return close_out(path, &o, err);
}

/* Appends an n-byte unsigned value in the requested byte order. */
static void put_bytes(unsigned char *dst, uint64_t u, int n, int big) {
  for (int i = 0; i < n; i++) dst[big ? n - 1 - i : i] = (unsigned char)(u >> (8 * i));
}

ss_status ss_write_ply(const char *path, const ss_mesh *m, const unsigned char *rgb, ss_ply_format fmt, ss_error *err) {
  return ss_write_ply_labels(path, m, rgb, NULL, fmt, err);
}

ss_status ss_write_ply_labels(const char *path, const ss_mesh *m, const unsigned char *rgb, const int *labels,
                              ss_ply_format fmt, ss_error *err) {
  ss_status st = check_mesh(path, m, err);
  if (st) return st;
  if (fmt != SS_PLY_ASCII && fmt != SS_PLY_BINARY_LE && fmt != SS_PLY_BINARY_BE)
    return ss_fail(err, SS_ERR_INVALID, "%s: unknown PLY format %d", path, (int)fmt);
  ssi_out o;
  FILE *f;
  if ((st = open_out(path, &o, &f, err))) return st;
  static const char *names[] = {"ascii", "binary_little_endian", "binary_big_endian"};
  fprintf(f, "ply\nformat %s 1.0\ncomment written by specseg\nelement vertex %d\n", names[fmt], m->nv);
  fprintf(f, "property double x\nproperty double y\nproperty double z\n");
  if (rgb) fprintf(f, "property uchar red\nproperty uchar green\nproperty uchar blue\n");
  if (labels) fprintf(f, "property int label\n");
  fprintf(f, "element face %d\nproperty list uchar int vertex_indices\nend_header\n", m->nf);
  if (fmt == SS_PLY_ASCII) {
    for (int i = 0; i < m->nv && !ferror(f); i++) {
      const double *p = m->V + 3 * (size_t)i;
      ssi_fprintf_c(f, "%.17g %.17g %.17g", p[0], p[1], p[2]);
      if (rgb) fprintf(f, " %u %u %u", rgb[3 * (size_t)i], rgb[3 * (size_t)i + 1], rgb[3 * (size_t)i + 2]);
      if (labels) fprintf(f, " %d", labels[i]);
      fputc('\n', f);
    }
    for (int i = 0; i < m->nf && !ferror(f); i++) {
      const int *t = m->F + 3 * (size_t)i;
      fprintf(f, "3 %d %d %d\n", t[0], t[1], t[2]);
    }
  } else {
    int big = fmt == SS_PLY_BINARY_BE;
    unsigned char rec[31];
    for (int i = 0; i < m->nv && !ferror(f); i++) {
      for (int d = 0; d < 3; d++) {
        uint64_t u;
        memcpy(&u, &m->V[3 * (size_t)i + d], 8);
        put_bytes(rec + 8 * d, u, 8, big);
      }
      size_t n = 24;
      if (rgb) {
        memcpy(rec + 24, rgb + 3 * (size_t)i, 3);
        n = 27;
      }
      if (labels) {
        put_bytes(rec + n, (uint32_t)labels[i], 4, big);
        n += 4;
      }
      fwrite(rec, 1, n, f);
    }
    for (int i = 0; i < m->nf && !ferror(f); i++) {
      rec[0] = 3;
      for (int d = 0; d < 3; d++) put_bytes(rec + 1 + 4 * d, (uint32_t)m->F[3 * (size_t)i + d], 4, big);
      fwrite(rec, 1, 13, f);
    }
  }
  return close_out(path, &o, err);
}

ss_status ss_write_obj(const char *path, const ss_mesh *m, const unsigned char *rgb, ss_error *err) {
  ss_status st = check_mesh(path, m, err);
  if (st) return st;
  ssi_out o;
  FILE *f;
  if ((st = open_out(path, &o, &f, err))) return st;
  fprintf(f, "# written by specseg\n");
  for (int i = 0; i < m->nv && !ferror(f); i++) {
    const double *p = m->V + 3 * (size_t)i;
    ssi_fprintf_c(f, "v %.17g %.17g %.17g", p[0], p[1], p[2]);
    /* the common "v x y z r g b" extension, colours in [0, 1] */
    if (rgb)
      ssi_fprintf_c(f, " %.9g %.9g %.9g", rgb[3 * (size_t)i] / 255.0, rgb[3 * (size_t)i + 1] / 255.0, rgb[3 * (size_t)i + 2] / 255.0);
    fputc('\n', f);
  }
  for (int i = 0; i < m->nf && !ferror(f); i++) {
    const int *t = m->F + 3 * (size_t)i;
    fprintf(f, "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1);
  }
  return close_out(path, &o, err);
}

ss_status ss_write_mesh_labels(const char *path, const ss_mesh *m, const unsigned char *rgb, const int *labels,
                               ss_error *err) {
  const char *dot = strrchr(path, '.');
  char ext[8] = {0};
  if (dot && !strchr(dot, '/') && strlen(dot + 1) < sizeof ext)
    for (size_t i = 0; dot[1 + i]; i++) ext[i] = (char)tolower((unsigned char)dot[1 + i]);
  if (!strcmp(ext, "ply")) return ss_write_ply_labels(path, m, rgb, labels, SS_PLY_BINARY_LE, err);
  return ss_write_mesh(path, m, rgb, err);
}

ss_status ss_write_mesh(const char *path, const ss_mesh *m, const unsigned char *rgb, ss_error *err) {
  const char *dot = strrchr(path, '.');
  char ext[8] = {0};
  if (dot && !strchr(dot, '/') && strlen(dot + 1) < sizeof ext)
    for (size_t i = 0; dot[1 + i]; i++) ext[i] = (char)tolower((unsigned char)dot[1 + i]);
  if (!strcmp(ext, "off")) return ss_write_off(path, m, rgb, err);
  if (!strcmp(ext, "ply")) return ss_write_ply(path, m, rgb, SS_PLY_BINARY_LE, err);
  if (!strcmp(ext, "obj")) return ss_write_obj(path, m, rgb, err);
  return ss_fail(err, SS_ERR_UNSUPPORTED, "%s: cannot choose a mesh format from the extension (use .off, .ply or .obj)", path);
}
