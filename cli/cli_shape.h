/* Shape arguments of the specseg program: a mesh file or a prepared shape (specseg prepare, .sss),
 * told apart by content (or the .sss extension). */
#ifndef SPECSEG_CLI_SHAPE_H
#define SPECSEG_CLI_SHAPE_H

#include "cli.h"
#include "specseg/match.h"

typedef struct cli_shape {
  int prepared;          /* 1: read from a prepared-shape file (all of ps); 0: a mesh (ps.mesh only) */
  ss_prepared_shape ps;
} cli_shape;

/* 1 when path names a prepared shape: its first bytes (files and streams) or, for a file that is
 * not there or cannot be read, the .sss extension. */
int cli_is_prepared_shape(const char *path);
/* Reads a mesh or a prepared shape ("-": standard input). */
ss_status cli_read_shape(const char *path, cli_shape *s, ss_error *err);
void cli_shape_free(cli_shape *s);
/* specseg match on two shapes of which at least one is prepared: the mesh one is prepared here (with
 * the other's segmentation options and the eigenpairs the match needs), then
 * ss_match_prepared_shapes; its preparation times go into out->t_segment / t_eigs. */
ss_status cli_match_shapes(cli_shape *X, cli_shape *Y, int nl, const int *lx, const int *ly, const ss_match_options *o,
                           ss_match_result *out, char *warnings, size_t warnings_size, ss_error *err);

/* Warnings for what the pipeline repairs internally in mesh m (its name for the messages): pinched
 * vertices when it is segmented, holes when they are closed (segmented and streamlined), faces not
 * consistently oriented (with a note on the landmark-free decision when landmark_free). */
void cli_warn_repairs(const ss_mesh *m, const char *name, int segmented, int closes_holes, int landmark_free);

/* The bytes of a stream input (standard input, a pipe) in *buf, *len with *is_stream 1; 0 for a regular
 * file (cli_io.c). */
ss_status cli_read_stream(const char *path, int *is_stream, const char **buf, size_t *len, ss_error *err);

int cmd_prepare(int argc, char **argv);

#endif
