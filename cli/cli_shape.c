/* Shape arguments: a mesh or a prepared shape (see cli_shape.h). */
#include "cli_shape.h"

#include <stdio.h>
#include <string.h>

static int has_sss_ext(const char *path) {
  size_t n = strlen(path);
  return n > 4 && !strcmp(path + n - 4, ".sss");
}

int cli_is_prepared_shape(const char *path) {
  int is = 0;
  const char *b;
  size_t n;
  ss_error e;
  if (cli_read_stream(path, &is, &b, &n, &e)) return 0;
  if (is) return ss_is_prepared_shape(b, n);
  FILE *f = fopen(path, "rb");
  if (!f) return has_sss_ext(path);
  char head[32];
  n = fread(head, 1, sizeof head, f);
  fclose(f);
  return ss_is_prepared_shape(head, n) || (n == 0 && has_sss_ext(path));
}

ss_status cli_read_shape(const char *path, cli_shape *s, ss_error *err) {
  memset(s, 0, sizeof *s);
  if (!cli_is_prepared_shape(path)) return cli_read_mesh(path, &s->ps.mesh, err);
  s->prepared = 1;
  int is = 0;
  const char *b;
  size_t n;
  ss_status st = cli_read_stream(path, &is, &b, &n, err);
  if (st) return st;
  return is ? ss_prepared_shape_read_memory(b, n, cli_in_name(path), &s->ps, err) : ss_prepared_shape_read(path, &s->ps, err);
}

void cli_shape_free(cli_shape *s) {
  ss_prepared_shape_free(&s->ps);
  memset(s, 0, sizeof *s);
}

ss_status cli_match_shapes(cli_shape *X, cli_shape *Y, int nl, const int *lx, const int *ly, const ss_match_options *o,
                           ss_match_result *out, char *warnings, size_t warnings_size, ss_error *err) {
  cli_shape *S[2] = {X, Y};
  double t_seg = 0, t_eigs = 0;
  for (int s = 0; s < 2; s++) {
    if (S[s]->prepared) continue;
    const cli_shape *other = S[1 - s];
    ss_mesh m = S[s]->ps.mesh; /* moved into the prepared shape (which copies it) */
    memset(&S[s]->ps.mesh, 0, sizeof m);
    ss_status st = ss_prepared_shape_compute(&m, &other->ps.seg, ss_match_eigenpairs(o, nl), &o->autopair, &S[s]->ps, err);
    ss_mesh_free(&m);
    if (st) {
      char msg[sizeof err->msg];
      snprintf(msg, sizeof msg, "match: %s: %.900s", s ? "Y (the second mesh)" : "X (the first mesh)", err->msg);
      memcpy(err->msg, msg, sizeof msg);
      return st;
    }
    S[s]->prepared = 1;
    t_seg += S[s]->ps.prep.t_segment, t_eigs += S[s]->ps.prep.t_eigs;
  }
  ss_status st = ss_match_prepared_shapes(&X->ps, &Y->ps, nl, lx, ly, o, out, warnings, warnings_size, err);
  if (!st) out->t_segment += t_seg, out->t_eigs += t_eigs, out->t_total += t_seg + t_eigs;
  return st;
}

void cli_warn_repairs(const ss_mesh *m, const char *name, int segmented, int closes_holes, int landmark_free) {
  ss_mesh_report rep;
  if (ss_mesh_check(m, &rep, NULL)) return;
  if (segmented && rep.nonmanifold_vertices)
    cli_warn("%s: %d pinched (non-manifold) vertices: split internally for the segmentation", name,
             rep.nonmanifold_vertices);
  if (!rep.oriented && rep.orientable)
    cli_warn("%s: faces not consistently oriented: %d re-oriented internally%s", name, rep.reorient_faces,
             landmark_free ? "; the landmark-free left / right decision needs consistently oriented meshes" : "");
  if (closes_holes && rep.boundary_loops)
    cli_warn("%s: %d hole%s (boundary loop%s) closed internally for the segmentation", name, rep.boundary_loops,
             rep.boundary_loops > 1 ? "s" : "", rep.boundary_loops > 1 ? "s" : "");
}
