/* Reads a mesh, segments it (the paper's pipeline with default options) and prints the number of
 * input vertices in each segment. Built against the installed library by CI, both through
 * pkg-config and through CMake's find_package(specseg).
 *   segment_sizes MESH.off|.obj|.ply */
#include <specseg/specseg.h>

#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: %s MESH\n", argv[0]);
    return 2;
  }
  ss_error err;
  ss_mesh mesh = {0};
  if (ss_read_mesh(argv[1], &mesh, &err) != SS_OK) {
    fprintf(stderr, "segment_sizes: error: %s\n", err.msg);
    return 1;
  }
  ss_segmentation seg;
  if (ss_segment(&mesh, NULL, &seg, &err) != SS_OK) {
    fprintf(stderr, "segment_sizes: error: %s\n", err.msg);
    ss_mesh_free(&mesh);
    return 1;
  }
  int *size = calloc((size_t)seg.m, sizeof(int));
  if (!size) {
    ss_segmentation_free(&seg);
    ss_mesh_free(&mesh);
    return 1;
  }
  for (int i = 0; i < seg.nv; i++) size[seg.labels[i]]++;
  printf("specseg %s: %d vertices, %d segments\n", ss_version(), mesh.nv, seg.m);
  for (int s = 0; s < seg.m; s++) printf("segment %d: centre vertex %d, %d vertices\n", s, seg.centers[s], size[s]);
  free(size);
  ss_segmentation_free(&seg);
  ss_mesh_free(&mesh);
  return 0;
}
