/* Benchmark: streamlining against CGAL. Isotropic remeshing to 15,000 faces, specseg's ss_remesh
 * against CGAL's Polygon_mesh_processing::isotropic_remeshing, and (when CGAL has Eigen) CMCF,
 * ss_cmcf_smooth against PMP::smooth_shape, on the same meshes in one process, interleaved
 * (ours, CGAL, ours, CGAL, ... per shape), timed in CPU seconds of this process (single-threaded:
 * OpenMP and OpenBLAS are set to one thread, CGAL's remeshing is sequential), with the quality of
 * both outputs measured by the same code (ss_remesh_quality_measure).
 *
 *   bench_remesh_cgal [--data DIR] [--count N] [--first I] [--rounds R] [--raw] [--threads T]
 *                     [--cgal-iterations I] [--cmcf-count N] [--cgal-time T]
 *
 * Input: the pipeline's remeshing input, FAUST tr_reg_I.. smoothed by ss_cmcf_smooth (defaults), or
 * the raw scans with --raw. CGAL's settings: target edge length L = 1.08 · the edge of an equilateral
 * triangle of area A / 15,000 (the 8% that lands CGAL's rules on 15,000 faces, paper-notes), 5
 * iterations (--cgal-iterations; CGAL's own default is 1), nothing protected, one relaxation step,
 * projection onto the input (its defaults).
 * Ours: the defaults (15,000 faces, 5 rounds + 2 flip/relax rounds, count snapped to the target).
 * CGAL's timing covers the isotropic_remeshing call only (the Surface_mesh is copied beforehand);
 * ours covers the whole ss_remesh call (conversion in and out included).
 *
 * CMCF (--cmcf-count N shapes first, default 10, 0 skips): ours with its defaults (12 steps, δ = 2.2e-5
 * at unit area) on the raw scans; CGAL's smooth_shape (the curvature flow of Kazhdan et al. too) with
 * 12 iterations and time 1e-5 (--cgal-time; the authors' step, here in metres: it moves the vertices
 * about as far as ours, mean 0.020 vs 0.026 of the bbox diagonal on tr_reg_000; 2.2e-5 · area moved
 * them 0.060) and its default solver (Eigen BiCGSTAB with incomplete LU). Printed: both CPU medians,
 * the ratio, and the mean vertex displacement / bbox diagonal of both.
 *
 * Prints per shape the median CPU times and their ratio, then the median over shapes of both, the
 * ratio CGAL / specseg (> 1: specseg faster), and the quality figures of both (median and worst over
 * shapes: fraction of triangles with min angle >= 30°, fraction of valence-6 vertices, face count,
 * smallest angle, max deviation from the input / bbox diagonal). Built only when CMake finds CGAL
 * (Debian: libcgal-dev). */
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#ifdef SS_HAVE_CGAL_EIGEN
#include <CGAL/Polygon_mesh_processing/smooth_shape.h>
#endif
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <vector>

#include <omp.h>

#include "specseg/specseg.h"

extern "C" void openblas_set_num_threads(int num_threads);

#ifndef SS_DATA_DIR_DEFAULT
#define SS_DATA_DIR_DEFAULT "../shared/data"
#endif

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
namespace PMP = CGAL::Polygon_mesh_processing;

static double cpu_time() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static Mesh to_cgal(const ss_mesh &m) {
  Mesh out;
  std::vector<Mesh::Vertex_index> vi((size_t)m.nv);
  for (int v = 0; v < m.nv; v++) vi[(size_t)v] = out.add_vertex(K::Point_3(m.V[3 * v], m.V[3 * v + 1], m.V[3 * v + 2]));
  for (int f = 0; f < m.nf; f++) out.add_face(vi[(size_t)m.F[3 * f]], vi[(size_t)m.F[3 * f + 1]], vi[(size_t)m.F[3 * f + 2]]);
  return out;
}

/* Surface_mesh (possibly with removed elements) as a compact ss_mesh. */
static int from_cgal(const Mesh &cm, ss_mesh *out) {
  std::vector<int> idx(cm.num_vertices() + cm.number_of_removed_vertices() + 1, -1);
  int nv = 0, nf = 0;
  for (auto v : cm.vertices()) idx[(size_t)v] = nv++;
  for (auto f : cm.faces()) { (void)f; nf++; }
  ss_error e;
  if (ss_mesh_alloc(out, nv, nf, &e) != SS_OK) return -1;
  for (auto v : cm.vertices()) {
    const K::Point_3 &p = cm.point(v);
    int i = idx[(size_t)v];
    out->V[3 * i] = p.x();
    out->V[3 * i + 1] = p.y();
    out->V[3 * i + 2] = p.z();
  }
  int f = 0;
  for (auto fa : cm.faces()) {
    int c = 0;
    for (auto v : CGAL::vertices_around_face(cm.halfedge(fa), cm)) {
      if (c < 3) out->F[3 * f + c] = idx[(size_t)v];
      c++;
    }
    if (c != 3) return -1;
    f++;
  }
  return 0;
}

struct quality_stats {
  std::vector<double> ang, val, faces, minang, dev;
  void add(const ss_remesh_quality &q) {
    ang.push_back(q.frac_min_angle_30);
    val.push_back(q.frac_valence_6);
    faces.push_back(q.faces);
    minang.push_back(q.min_angle_deg);
    dev.push_back(q.max_deviation);
  }
  void print(const char *who, int target) const {
    double worst_face = 0;
    for (double f : faces) worst_face = std::max(worst_face, std::fabs(f - target));
    std::printf("  %-8s min angle >= 30: median %.3f%% worst %.3f%% | valence 6: median %.2f%% worst %.2f%% | faces: "
                "median %.0f, worst |faces - %d| = %.0f | smallest angle: worst %.2f deg | max deviation / diag: "
                "worst %.1e\n",
                who, 100 * median(ang), 100 * *std::min_element(ang.begin(), ang.end()), 100 * median(val),
                100 * *std::min_element(val.begin(), val.end()), median(faces), target, worst_face,
                *std::min_element(minang.begin(), minang.end()), *std::max_element(dev.begin(), dev.end()));
  }
};

/* mean |x_out - x_in| / bbox diagonal of the input */
static double mean_displacement(const ss_mesh &in, const double *out) {
  double s = 0;
  for (int v = 0; v < in.nv; v++) {
    double dx = out[3 * v] - in.V[3 * v], dy = out[3 * v + 1] - in.V[3 * v + 1], dz = out[3 * v + 2] - in.V[3 * v + 2];
    s += std::sqrt(dx * dx + dy * dy + dz * dz);
  }
  return s / in.nv / ss_mesh_bbox_diagonal(&in);
}

/* CMCF: ss_cmcf_smooth vs CGAL's smooth_shape; 77 when the data is missing, 1 on failure */
static int run_cmcf(const char *data, int first, int count, int rounds, double cgal_time) {
#ifndef SS_HAVE_CGAL_EIGEN
  (void)data; (void)first; (void)count; (void)rounds; (void)cgal_time;
  std::printf("CMCF: CGAL's smooth_shape needs Eigen (Debian libeigen3-dev): not compared\n");
  return 0;
#else
  std::vector<double> ours, cgal, dvo, dvc;
  std::printf("CMCF, 12 steps: specseg ss_cmcf_smooth vs CGAL smooth_shape (raw FAUST, %d rounds interleaved, CPU seconds)\n",
              rounds);
  int n = 0;
  for (int i = first; i < first + count; i++) {
    char path[4096];
    std::snprintf(path, sizeof path, "%s/faust/tr_reg_%03d.off", data, i);
    ss_mesh m;
    ss_error e;
    if (ss_read_mesh(path, &m, &e) != SS_OK) {
      if (n == 0) {
        std::fprintf(stderr, "SKIP: %s\n", e.msg);
        return 77;
      }
      break;
    }
    const Mesh input = to_cgal(m);
    const double time = cgal_time > 0 ? cgal_time : 1e-5;
    std::vector<double> to, tc;
    std::vector<double> cout_pts(3 * (size_t)m.nv);
    ss_mesh s = {0, 0, NULL, NULL};
    for (int r = 0; r < rounds; r++) {
      ss_mesh_free(&s);
      double c0 = cpu_time();
      if (ss_cmcf_smooth(&m, NULL, &s, &e) != SS_OK) {
        std::fprintf(stderr, "%s: %s\n", path, e.msg);
        return 1;
      }
      to.push_back(cpu_time() - c0);
      Mesh cm = input;
      c0 = cpu_time();
      PMP::smooth_shape(faces(cm), cm, time, CGAL::parameters::number_of_iterations(12));
      tc.push_back(cpu_time() - c0);
      int v = 0;
      for (auto vd : cm.vertices()) {
        const K::Point_3 &p = cm.point(vd);
        cout_pts[3 * (size_t)v] = p.x();
        cout_pts[3 * (size_t)v + 1] = p.y();
        cout_pts[3 * (size_t)v + 2] = p.z();
        v++;
      }
    }
    double mo = median(to), mc = median(tc);
    ours.push_back(mo);
    cgal.push_back(mc);
    dvo.push_back(mean_displacement(m, s.V));
    dvc.push_back(mean_displacement(m, cout_pts.data()));
    std::printf("tr_reg_%03d: specseg %.1f ms  CGAL %.1f ms  ratio %.2fx | mean displacement / diag %.4f vs %.4f\n", i,
                1e3 * mo, 1e3 * mc, mc / mo, dvo.back(), dvc.back());
    std::fflush(stdout);
    ss_mesh_free(&s);
    ss_mesh_free(&m);
    n++;
  }
  std::printf("RESULT cmcf FAUST shapes=%d: specseg median %.1f ms CPU, CGAL smooth_shape median %.1f ms CPU, ratio "
              "CGAL/specseg %.2fx\n",
              n, 1e3 * median(ours), 1e3 * median(cgal), median(cgal) / median(ours));
  return 0;
#endif
}

int main(int argc, char **argv) {
  const char *data = std::getenv("SS_DATA_DIR") ? std::getenv("SS_DATA_DIR") : SS_DATA_DIR_DEFAULT;
  int count = 20, first = 0, rounds = 3, raw = 0, threads = 1, cgal_iter = 5, cmcf_count = 10;
  double cgal_time = 0;
  for (int i = 1; i < argc; i++) {
    if (!std::strcmp(argv[i], "--data") && i + 1 < argc) data = argv[++i];
    else if (!std::strcmp(argv[i], "--count") && i + 1 < argc) count = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--first") && i + 1 < argc) first = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--rounds") && i + 1 < argc) rounds = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--cgal-iterations") && i + 1 < argc) cgal_iter = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--cmcf-count") && i + 1 < argc) cmcf_count = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--cgal-time") && i + 1 < argc) cgal_time = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--raw")) raw = 1;
    else {
      std::fprintf(stderr,
                   "usage: bench_remesh_cgal [--data DIR] [--count N] [--first I] [--rounds R] [--raw] [--threads T]\n"
                   "                         [--cgal-iterations I] [--cmcf-count N] [--cgal-time T]\n");
      return 2;
    }
  }
  if (count < 1) count = 1;
  if (rounds < 1) rounds = 1;
  if (threads < 1) threads = 1;
  if (cgal_iter < 1) cgal_iter = 1;
  omp_set_num_threads(threads);
  openblas_set_num_threads(1);
  if (cmcf_count > 0 && run_cmcf(data, first, cmcf_count, rounds, cgal_time) == 77) return 77;
  ss_remesh_options ro;
  ss_remesh_default_options(&ro);
  const int target = ro.target_faces;
  std::vector<double> ours_med, cgal_med, ratio;
  quality_stats qo, qc;
  int n = 0;
  std::printf("isotropic remeshing to %d faces: specseg ss_remesh vs CGAL %d.%d isotropic_remeshing, %d iteration%s "
              "(%s FAUST, %d rounds interleaved, CPU seconds, %d thread%s for ours)\n",
              target, CGAL_VERSION_MAJOR, CGAL_VERSION_MINOR, cgal_iter, cgal_iter > 1 ? "s" : "",
              raw ? "raw" : "CMCF-smoothed", rounds, threads, threads > 1 ? "s" : "");
  for (int i = first; i < first + count; i++) {
    char path[4096];
    std::snprintf(path, sizeof path, "%s/faust/tr_reg_%03d.off", data, i);
    ss_mesh m, s;
    ss_error e;
    if (ss_read_mesh(path, &m, &e) != SS_OK) {
      if (n == 0) {
        std::fprintf(stderr, "SKIP: %s\n", e.msg);
        return 77;
      }
      break;
    }
    if (raw) {
      s = m;
    } else {
      if (ss_cmcf_smooth(&m, NULL, &s, &e) != SS_OK) {
        std::fprintf(stderr, "%s: %s\n", path, e.msg);
        return 1;
      }
      ss_mesh_free(&m);
    }
    const Mesh input = to_cgal(s);
    const double area = ss_mesh_area(&s);
    const double L = 1.08 * std::sqrt(4.0 * area / (std::sqrt(3.0) * target));
    std::vector<double> to, tc;
    ss_mesh ro_out = {0, 0, NULL, NULL}, rc_out = {0, 0, NULL, NULL};
    for (int r = 0; r < rounds; r++) {
      ss_mesh_free(&ro_out);
      double c0 = cpu_time();
      if (ss_remesh(&s, &ro, &ro_out, &e) != SS_OK) {
        std::fprintf(stderr, "%s: ss_remesh: %s\n", path, e.msg);
        return 1;
      }
      to.push_back(cpu_time() - c0);
      Mesh cm = input;
      c0 = cpu_time();
      PMP::isotropic_remeshing(faces(cm), L, cm, CGAL::parameters::number_of_iterations(cgal_iter));
      tc.push_back(cpu_time() - c0);
      if (r == rounds - 1) {
        ss_mesh_free(&rc_out);
        if (from_cgal(cm, &rc_out)) {
          std::fprintf(stderr, "%s: CGAL output is not a triangle mesh\n", path);
          return 1;
        }
      }
    }
    ss_remesh_quality q1, q2;
    if (ss_remesh_quality_measure(&ro_out, &s, &q1, &e) != SS_OK || ss_remesh_quality_measure(&rc_out, &s, &q2, &e) != SS_OK) {
      std::fprintf(stderr, "%s: quality: %s\n", path, e.msg);
      return 1;
    }
    qo.add(q1);
    qc.add(q2);
    double mo = median(to), mc = median(tc);
    ours_med.push_back(mo);
    cgal_med.push_back(mc);
    ratio.push_back(mc / mo);
    std::printf("tr_reg_%03d: specseg %.1f ms  CGAL %.1f ms  ratio %.2fx | faces %d vs %d, >=30 deg %.2f%% vs %.2f%%, "
                "valence 6 %.1f%% vs %.1f%%\n",
                i, 1e3 * mo, 1e3 * mc, mc / mo, q1.faces, q2.faces, 100 * q1.frac_min_angle_30,
                100 * q2.frac_min_angle_30, 100 * q1.frac_valence_6, 100 * q2.frac_valence_6);
    std::fflush(stdout);
    ss_mesh_free(&ro_out);
    ss_mesh_free(&rc_out);
    ss_mesh_free(&s);
    n++;
  }
  std::printf("RESULT remesh FAUST shapes=%d (%s): specseg median %.1f ms CPU, CGAL median %.1f ms CPU, ratio CGAL/specseg "
              "%.2fx (median of per-shape ratios %.2fx, range %.2f-%.2f)\n",
              n, raw ? "raw" : "smoothed", 1e3 * median(ours_med), 1e3 * median(cgal_med),
              median(cgal_med) / median(ours_med), median(ratio), *std::min_element(ratio.begin(), ratio.end()),
              *std::max_element(ratio.begin(), ratio.end()));
  std::printf("quality over the %d shapes:\n", n);
  qo.print("specseg", target);
  qc.print("CGAL", target);
  return 0;
}
