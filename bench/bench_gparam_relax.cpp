// Relax (50 sweeps) on one global parametrization problem (the Table 1 relax column alone),
// from the L-infinity map, which is computed once and kept in a file so that repeated runs
// (A/B of two builds, profiles) time only relax:
//
//   bench_gparam_relax MESH.obj --start START.bin [--sweeps 50] [--repeat 1] [--threads N]
//
// Without START.bin it runs L-infinity and writes it (#V, 2, then the doubles). Prints per run
// the relax time (the whole relax() call, as bench_table1's relax_s), then the status, the
// final maximum, each sweep's maximum and a checksum of the final map's bits, so that two
// builds can be checked to give the same map. A START.bin of the wrong size (another mesh's,
// or corrupt) is refused: delete it to recompute. Exits 1 with a message on bad input.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>

#include <tbb/global_control.h>

#include "args.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/solvers/relax.h"
#include "strictmin/tasks/gparam.h"

namespace {

using namespace strictmin;

// The start map of START.bin, checked against the problem's size before anything is
// allocated (a corrupt header must not ask for 2^40 rows): false when there is no file.
bool read_start(const std::string& file, int rows_expected, int cols_expected, Eigen::MatrixXd& X) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    if (std::filesystem::exists(file)) throw std::runtime_error("--start " + file + ": cannot be read");
    return false;
  }
  int64_t rows = 0, cols = 0;
  in.read(reinterpret_cast<char*>(&rows), sizeof rows).read(reinterpret_cast<char*>(&cols), sizeof cols);
  const std::string why = "--start " + file + ": ";
  if (!in) throw std::runtime_error(why + "shorter than its header (not a start file; delete it to recompute)");
  if (rows != rows_expected || cols != cols_expected)
    throw std::runtime_error(why + std::to_string(rows) + " by " + std::to_string(cols) + ", the problem needs " +
                             std::to_string(rows_expected) + " by " + std::to_string(cols_expected) +
                             " (another mesh's start, or corrupt: delete it to recompute)");
  const auto bytes = static_cast<std::uintmax_t>(2 * sizeof(int64_t) + sizeof(double) * rows * cols);
  if (std::filesystem::file_size(file) != bytes)
    throw std::runtime_error(why + "not " + std::to_string(bytes) + " bytes long (corrupt: delete it to recompute)");
  X.resize(rows, cols);
  in.read(reinterpret_cast<char*>(X.data()), static_cast<std::streamsize>(sizeof(double) * X.size()));
  if (!in) throw std::runtime_error(why + "cannot be read");
  return true;
}

void write_start(const std::string& file, const Eigen::MatrixXd& X) {
  std::ofstream out(file, std::ios::binary);
  const int64_t rows = X.rows(), cols = X.cols();
  out.write(reinterpret_cast<const char*>(&rows), sizeof rows).write(reinterpret_cast<const char*>(&cols), sizeof cols);
  out.write(reinterpret_cast<const char*>(X.data()), static_cast<std::streamsize>(sizeof(double) * X.size()));
  if (!out.flush()) throw std::runtime_error("--start " + file + ": cannot be written");
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

constexpr const char* kUsage =
    "usage: bench_gparam_relax MESH.obj --start START.bin [--sweeps 50] [--repeat 1] [--threads N]\n"
    "Relax from the L-infinity map kept in START.bin (computed and written when the file is absent).\n";

struct Args {
  std::string mesh_file, start_file;
  int sweeps = 50, repeat = 1, threads = 0;
  bool help = false;
};

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string w = argv[i];
    if (w == "--help" || w == "-h") {
      a.help = true;
      return a;
    }
    if (w == "--start") a.start_file = bench::flag_value(argc, argv, i);
    else if (w == "--sweeps") a.sweeps = bench::parse_count(w, bench::flag_value(argc, argv, i));
    else if (w == "--repeat") a.repeat = bench::parse_count(w, bench::flag_value(argc, argv, i), 1);
    else if (w == "--threads") a.threads = bench::parse_count(w, bench::flag_value(argc, argv, i));
    else if (w.rfind("-", 0) == 0) throw std::invalid_argument(w + ": unknown option\n" + kUsage);
    else if (!a.mesh_file.empty()) throw std::invalid_argument(w + ": one mesh only (have " + a.mesh_file + ")\n" + kUsage);
    else a.mesh_file = w;
  }
  if (a.mesh_file.empty()) throw std::invalid_argument(std::string("no mesh given\n") + kUsage);
  if (a.start_file.empty()) throw std::invalid_argument(std::string("--start START.bin is required\n") + kUsage);
  bench::check_output_folder("--start", a.start_file);
  return a;
}

// The start of relax: START.bin, or L-infinity written to it when the file is absent.
Eigen::MatrixXd start_map(const Problem& p, const std::string& file) {
  Eigen::MatrixXd start;
  if (read_start(file, p.num_vertices, p.image_dim, start)) return start;
  SolverOptions linf;
  linf.method = Method::Linf;
  start = run_method(p, linf).positions;
  write_start(file, start);
  return start;
}

int run(int argc, char** argv) {
  const Args a = parse_args(argc, argv);
  if (a.help) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  const Mesh mesh = read_mesh(a.mesh_file);
  GParamOptions o;
  o.solver.method = Method::L2;
  const GParamOutcome g = global_parametrize(mesh, o, a.mesh_file);
  const Eigen::MatrixXd start = start_map(g.problem, a.start_file);
  std::unique_ptr<tbb::global_control> limit;
  if (a.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, a.threads);
  RelaxOptions ro;
  ro.sweeps = a.sweeps;
  for (int r = 0; r < a.repeat; ++r) {
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
    std::fflush(stdout);  // a later run's error must not lose this line
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::guarded_main("bench_gparam_relax", run, argc, argv); }
