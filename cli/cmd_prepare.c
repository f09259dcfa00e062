/* specseg prepare MESH -o SHAPE.sss [-k K] [--faces N] [--no-streamline] [--no-signature] */
#include "cli_shape.h"

#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

static const char USAGE[] =
    "usage: specseg prepare MESH -o SHAPE.sss [-k K] [--faces N] [--no-streamline] [--no-signature]\n"
    "\n"
    "Computes once what a match needs from one shape and writes it to a prepared-shape file: the mesh,\n"
    "its segmentation (streamlined work mesh, the input -> work map, critical points, segments and the\n"
    "distances to their centres), K Laplace-Beltrami eigenpairs and the masses, and (one component)\n"
    "the landmark-free pairing's centre signature. 'specseg match' and 'specseg segment' take the file\n"
    "wherever they take a mesh and give the same output as from the mesh, faster. The file is\n"
    "versioned and checksummed: a damaged file or one of another format version is refused. It also\n"
    "holds the critical points' geodesic fields (no geodesic is computed when matching it with\n"
    "landmarks) and, for a mesh above 100,000 vertices, the coarse proxy 'match' matches it through.\n"
    "\n"
    "  MESH                OFF, OBJ or PLY file; - reads standard input\n"
    "  -o, --output FILE   the prepared shape (required; a file, not standard output)\n"
    "  -k K                eigenpairs, 3..10000 (default 150: what the default match needs; with 110 a\n"
    "                      match still runs, its map kept refined only to 110, with a note; a match\n"
    "                      with a larger --k / --zoomout / --descr-k needs more, and says so). The map\n"
    "                      equals the one from the meshes when K is exactly what the match needs.\n"
    "  --faces N           remeshing target of the segmentation, 4..2000000 (default 15000)\n"
    "  --no-streamline     segment straight on the input (no smoothing, no remeshing)\n"
    "  --no-signature      leave out the landmark-free pairing's signature (computed by each match)\n";

int cmd_prepare(int argc, char **argv) {
  const char *in = NULL, *outp = NULL;
  int kev = ss_match_eigenpairs(NULL, 0), no_sig = 0;
  ss_segment_options so;
  ss_segment_default_options(&so);
  ss_match_options mo;
  ss_match_default_options(&mo);
  const cli_opt opts[] = {CLI_OPT_POS("MESH", &in, NULL),
                          CLI_OPT_STR("-o|--output", &outp),
                          CLI_OPT_INT("-k", &kev, 3, 10000, NULL),
                          CLI_OPT_INT("--faces", &so.target_faces, 4, SS_REMESH_MAX_FACES, NULL),
                          CLI_OPT_FLAG("--no-streamline", &so.no_streamline, 1),
                          CLI_OPT_FLAG("--no-signature", &no_sig, 1),
                          CLI_OPT_END};
  cli_args A;
  cli_args_init(&A, argc, argv, USAGE, opts);
  int rc = cli_parse(&A);
  if (rc >= 0) return rc;
  if (!in) return cli_bad(&A, "missing MESH");
  if (!outp) return cli_bad(&A, "missing -o SHAPE.sss");
  if (cli_is_std(outp)) return cli_bad(&A, "-o needs a file name (the prepared shape is written to a file)");
  const char *ins[1] = {in}, *outs[1] = {outp};
  if (cli_check_outputs(&A, outs, 1, ins, 1) >= 0) return A.rc;

  ss_error err = {{0}};
  ss_mesh m = {0};
  ss_prepared_shape ps = {0};
  rc = SS_EXIT_OK;
  if (cli_read_mesh(in, &m, &err)) return cli_error("%s", err.msg);
  if (kev >= m.nv) {
    rc = cli_error("%s: %d eigenpairs asked for, the mesh has %d vertices: use -k below %d", cli_in_name(in), kev, m.nv,
                   m.nv);
    goto done;
  }
  cli_warn_repairs(&m, cli_in_name(in), 1, !so.no_streamline, !no_sig);
  if (ss_prepared_shape_compute(&m, &so, kev, no_sig ? NULL : &mo.autopair, &ps, &err)) {
    rc = cli_error("%s: %s", cli_in_name(in), err.msg);
    goto done;
  }
  if (ss_prepared_shape_write(outp, &ps, &err)) {
    rc = cli_error("%s", err.msg);
    goto done;
  }
  struct stat sb;
  long long bytes = stat(outp, &sb) == 0 ? (long long)sb.st_size : -1;
  char proxy[96] = "";
  if (ps.has_proxy) snprintf(proxy, sizeof proxy, " (matched through a %d-vertex proxy, as match does)", ps.proxy.nv);
  printf("%d vertices, %d segments, %d eigenpairs%s%s -> %s (%lld bytes)\n", ps.mesh.nv, ps.prep.seg.m,
         ss_prepared_shape_matched(&ps)->kev, proxy,
         ps.has_signature ? ", pairing signature" : no_sig ? "" : ", no pairing signature (several components)", outp,
         bytes);
done:
  ss_prepared_shape_free(&ps);
  ss_mesh_free(&m);
  return rc;
}
