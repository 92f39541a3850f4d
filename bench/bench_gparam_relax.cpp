// Relax (50 sweeps) on one global parametrization problem (the Table 1 relax column alone),
// from the L-infinity map, which is computed once and kept in a file so that repeated runs
// (A/B of two builds, profiles) time only relax:
//
//   bench_gparam_relax MESH.obj --start START.bin [--sweeps 50] [--repeat 1] [--threads N]
//
// Without START.bin it runs L-infinity and writes it (#V, 2, then the doubles). Prints per run
// the relax time (the whole relax() call, as bench_table1's relax_s), then the status, the
// final maximum, each sweep's maximum and a checksum of the final map's bits, so that two
// builds can be checked to give the same map.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>

#include <tbb/global_control.h>

#include "strictmin/io/mesh_io.h"
#include "strictmin/solvers/relax.h"
#include "strictmin/tasks/gparam.h"

namespace {

using namespace strictmin;

bool read_start(const std::string& file, Eigen::MatrixXd& X) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  int64_t rows = 0, cols = 0;
  in.read(reinterpret_cast<char*>(&rows), sizeof rows).read(reinterpret_cast<char*>(&cols), sizeof cols);
  X.resize(rows, cols);
  in.read(reinterpret_cast<char*>(X.data()), static_cast<std::streamsize>(sizeof(double) * X.size()));
  return static_cast<bool>(in);
}

void write_start(const std::string& file, const Eigen::MatrixXd& X) {
  std::ofstream out(file, std::ios::binary);
  const int64_t rows = X.rows(), cols = X.cols();
  out.write(reinterpret_cast<const char*>(&rows), sizeof rows).write(reinterpret_cast<const char*>(&cols), sizeof cols);
  out.write(reinterpret_cast<const char*>(X.data()), static_cast<std::streamsize>(sizeof(double) * X.size()));
}

// FNV-1a over the bits of the doubles.
uint64_t checksum(const Eigen::MatrixXd& X) {
  uint64_t h = 1469598103934665603ull;
  for (Eigen::Index i = 0; i < X.size(); ++i) {
    uint64_t bits;
    std::memcpy(&bits, X.data() + i, sizeof bits);
    for (int b = 0; b < 8; ++b) h = (h ^ ((bits >> (8 * b)) & 0xff)) * 1099511628211ull;
  }
  return h;
}

}  // namespace

int main(int argc, char** argv) {
  std::string mesh_file, start_file;
  int sweeps = 50, repeat = 1, threads = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--start" && i + 1 < argc) start_file = argv[++i];
    else if (a == "--sweeps" && i + 1 < argc) sweeps = std::stoi(argv[++i]);
    else if (a == "--repeat" && i + 1 < argc) repeat = std::stoi(argv[++i]);
    else if (a == "--threads" && i + 1 < argc) threads = std::stoi(argv[++i]);
    else mesh_file = a;
  }
  if (mesh_file.empty() || start_file.empty()) {
    std::fprintf(stderr, "usage: bench_gparam_relax MESH.obj --start START.bin [--sweeps 50] [--repeat 1] [--threads N]\n");
    return 1;
  }
  const Mesh mesh = read_mesh(mesh_file);
  GParamOptions o;
  o.solver.method = Method::L2;
  const GParamOutcome g = global_parametrize(mesh, o, mesh_file);
  Eigen::MatrixXd start;
  if (!read_start(start_file, start) || start.rows() != g.problem.num_vertices) {
    SolverOptions linf;
    linf.method = Method::Linf;
    start = run_method(g.problem, linf).positions;
    write_start(start_file, start);
  }
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
  RelaxOptions ro;
  ro.sweeps = sweeps;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const Result res = relax(g.problem, start, ro);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("relax_s %.4f status %s max %.17g checksum %016llx\n", s, status_name(res.status).c_str(),
                res.distortion.maxCoeff(), static_cast<unsigned long long>(checksum(res.positions)));
    if (r == 0) {
      std::printf("sweep maxima:");
      for (const auto& h : res.history) std::printf(" %.17g", h.max_distortion);
      std::printf("\n");
    }
  }
  return 0;
}
