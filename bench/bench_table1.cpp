// The paper's Table 1 on the closed shared meshes (global parametrization, field deviation):
// field + cut time, L2, L-infinity, direct (k_min 0.1, delta-k 1e-3) and relax (50 sweeps
// from the L-infinity map, not counting it) times, beside the paper's row.
//
//   bench_table1 [--out table1.json] [--direct-max-faces N] [--sweeps 50] [mesh.obj ...]
//   bench_table1 --merge a.json b.json ...
//   bench_table1 --only-l2 [mesh.obj ...]   (field, cut and L2 only: no L-infinity, relax, direct)
//   bench_table1 --field unit ...          (the unit field, --field unit, instead of the smoothest)
//   bench_table1 --parallel ...            (the field made parallel with its singularities, --parallel)
//
// Without meshes: every .obj in ../shared/data/closed, then the disks that stand in for the
// paper's hand, fish, dragon and lion rows (../shared/data/disk: parametrized with their
// boundary free, docs/gparam.md "Surfaces with boundary"); skips with a message when absent.
// A row's ratios are printed only where our mesh is within a factor 2 of the paper's size.
// Prints a markdown table (docs/performance.md; ratio = our time / the paper's) and writes
// the JSON after every mesh. Rows can be put together from several runs with --merge.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "args.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/solvers/relax.h"
#include "strictmin/tasks/gparam.h"

namespace {

using namespace strictmin;
namespace fs = std::filesystem;

struct PaperRow {
  double faces_k, linf_s, direct_levels, direct_s, relax_s;
};

// Table 1 of Levi & Zorin 2014 (Intel Core i7-2720QM laptop, MOSEK), the rows whose models
// are in the shared data (igea_100k is the paper's igea; hand, fish, dragon and lion are
// disks of other sizes standing in for the paper's models).
const std::map<std::string, PaperRow> kPaper = {
    {"cow", {8, 1.3, 28, 45, 1.2}},           {"elephant", {50, 9, 34, 558, 7}},
    {"homer", {10, 1, 43, 67, 1.3}},          {"horse", {102, 17, 49, 1480, 13}},
    {"igea_100k", {100, 19, 99, 3208, 13}},   {"hand", {3, 0.3, 58, 6, 0.3}},
    {"fish", {35, 6, 54, 354, 5}},            {"dragon", {104, 18, 59, 1810, 15}},
    {"lion", {55, 8, 24, 363, 8}},
};

// The disks of the shared data that stand in for Table 1 rows.
const char* const kDiskStandIns[] = {"hand", "fish", "dragon", "lion"};

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

nlohmann::json run_mesh(const fs::path& file, int direct_max_faces, int sweeps, bool only_l2, bool unit_field,
                        bool parallel) {
  const Mesh mesh = read_mesh(file.string());
  nlohmann::json row;
  row["mesh"] = file.stem().string();
  row["faces"] = mesh.num_elements();
  GParamOptions o;
  o.solver.method = Method::L2;
  o.field_options.unit = unit_field;
  o.parallel_field = parallel;
  const GParamOutcome g = global_parametrize(mesh, o, file.string());
  row["field"] = unit_field ? "unit" : "smoothest";
  row["field_parallel"] = parallel;
  row["field_energy"] = g.field.energy;
  row["singularities"] = g.singular.size();
  row["euler_characteristic"] = g.graph.euler_characteristic();
  row["boundary_loops"] = g.graph.num_boundary_loops;
  row["graph_s"] = g.graph_time_s;
  row["field_s"] = g.field_time_s;
  row["cut_s"] = g.cut_time_s;
  row["field_cut_s"] = g.graph_time_s + g.field_time_s + g.cut_time_s;
  row["l2_s"] = g.solve_time_s;
  row["field_cut_l2_s"] = g.graph_time_s + g.field_time_s + g.cut_time_s + g.solve_time_s;
  row["l2_max"] = g.measured.stats.max;
  row["seam_error"] = g.seam_error;
  row["field_iterations"] = g.field.iterations;
  nlohmann::json indices = nlohmann::json::array();
  for (const auto& s : g.singular) indices.push_back({s.vertex, s.quarters});
  row["singularity_indices"] = indices;
  if (only_l2) return row;

  SolverOptions linf;
  linf.method = Method::Linf;
  auto t0 = std::chrono::steady_clock::now();
  const Result l = run_method(g.problem, linf);
  row["linf_s"] = since(t0);
  row["linf_status"] = status_name(l.status);
  row["linf_max"] = l.distortion.maxCoeff();
  row["linf_lower_bound"] = l.lower_bound;

  RelaxOptions ro;
  ro.sweeps = sweeps;
  t0 = std::chrono::steady_clock::now();
  const Result r = relax(g.problem, l.positions, ro);
  row["relax_s"] = since(t0);
  row["relax_max"] = r.distortion.maxCoeff();

  if (mesh.num_elements() <= direct_max_faces) {
    SolverOptions d;
    d.method = Method::Direct;
    d.direct.k_min = 0.1;
    d.direct.delta_k = 1e-3;
    t0 = std::chrono::steady_clock::now();
    const Result dr = run_method(g.problem, d);
    row["direct_s"] = since(t0);
    row["direct_levels"] = dr.iterations;
    row["direct_status"] = status_name(dr.status);
    row["direct_max"] = dr.distortion.maxCoeff();
  }
  return row;
}

std::string cell(const nlohmann::json& row, const char* key, const char* fmt = "%.2f") {
  if (!row.contains(key)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, row[key].get<double>());
  return buf;
}

// A text cell: the row's string KEY, "-" when the row has none (an --only-l2 row has no linf_status).
std::string text(const nlohmann::json& row, const char* key) {
  return row.contains(key) && row[key].is_string() ? row[key].get<std::string>() : "-";
}

std::string ratio(const nlohmann::json& row, const char* key, double paper) {
  if (!row.contains(key) || !(paper > 0)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f", row[key].get<double>() / paper);  // ours / paper's
  return buf;
}

void print_l2_table(const nlohmann::json& rows) {
  std::printf("| mesh | faces | sing. | field iterations | field (s) | cut (s) | L2 (s) | field+cut+L2 (s) | L2 max | seam error |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (const auto& row : rows)
    std::printf("| %s | %d | %d | %d | %s | %s | %s | %s | %s | %s |\n", row["mesh"].get<std::string>().c_str(),
                row["faces"].get<int>(), row["singularities"].get<int>(), row["field_iterations"].get<int>(),
                cell(row, "field_s").c_str(), cell(row, "cut_s").c_str(), cell(row, "l2_s").c_str(),
                cell(row, "field_cut_l2_s").c_str(), cell(row, "l2_max", "%.12g").c_str(),
                cell(row, "seam_error", "%.2g").c_str());
}

void print_table(const nlohmann::json& rows) {
  std::printf("| mesh | faces | sing. | field+cut+L2 (s) | L-inf (s) | paper | ratio | direct # | direct (s) | paper # | paper (s) | ratio | relax 50 (s) | paper | ratio |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (const auto& row : rows) {
    const std::string name = row["mesh"];
    const auto p = kPaper.find(name);
    // The paper's row, when its model is within a factor 2 of ours in size.
    const bool has = p != kPaper.end() && row["faces"].get<double>() <= 2000 * p->second.faces_k &&
                     row["faces"].get<double>() >= 500 * p->second.faces_k;
    const PaperRow pr = has ? p->second : PaperRow{0, 0, 0, 0, 0};
    auto paper = [&](double v) { return has ? cell(nlohmann::json{{"v", v}}, "v", "%g") : std::string("-"); };
    std::printf("| %s | %d | %d | %s | %s (%s) | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", name.c_str(),
                row["faces"].get<int>(), row["singularities"].get<int>(), cell(row, "field_cut_l2_s").c_str(),
                cell(row, "linf_s").c_str(), text(row, "linf_status").c_str(), paper(pr.linf_s).c_str(),
                ratio(row, "linf_s", pr.linf_s).c_str(), cell(row, "direct_levels", "%.0f").c_str(),
                cell(row, "direct_s").c_str(), paper(pr.direct_levels).c_str(), paper(pr.direct_s).c_str(),
                ratio(row, "direct_s", pr.direct_s).c_str(), cell(row, "relax_s").c_str(), paper(pr.relax_s).c_str(),
                ratio(row, "relax_s", pr.relax_s).c_str());
  }
}

}  // namespace

// The rows of earlier runs' JSON files as one table (the L2 table when no row has L-infinity,
// i.e. all are --only-l2 runs).
int print_merged(const std::vector<fs::path>& files) {
  if (files.empty()) throw std::invalid_argument("--merge: no JSON files given");
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& f : files) {
    std::ifstream in(f);
    if (!in) throw std::invalid_argument("--merge " + f.string() + ": cannot open");
    const nlohmann::json run = nlohmann::json::parse(in, nullptr, false);
    if (!run.is_array()) throw std::invalid_argument("--merge " + f.string() + ": not a bench_table1 JSON (an array of rows)");
    for (const auto& r : run) {
      if (!r.is_object() || !r.contains("mesh") || !r.contains("faces") || !r.contains("singularities"))
        throw std::invalid_argument("--merge " + f.string() + ": a row without mesh, faces or singularities");
      rows.push_back(r);
    }
  }
  const bool any_linf = std::any_of(rows.begin(), rows.end(), [](const auto& r) { return r.contains("linf_s"); });
  if (any_linf) print_table(rows);
  else print_l2_table(rows);
  return 0;
}

void write_rows(const std::string& out, const nlohmann::json& rows) {
  std::ofstream f(out);
  f << rows.dump(2) << "\n";
  if (!f.flush()) throw std::runtime_error("--out " + out + ": cannot be written");
}

constexpr const char* kUsage =
    "usage: bench_table1 [--out FILE.json] [--direct-max-faces N] [--sweeps N] [--only-l2] [--field smoothest|unit] [--parallel]\n"
    "                    [MESH.obj ...]\n"
    "       bench_table1 --merge RUN.json ...   (print earlier runs' rows as one table)\n"
    "Without meshes: every .obj in the shared data's closed/ folder and the disks hand, fish, dragon and lion\n"
    "(skipped when absent).\n";

int run(int argc, char** argv) {
  std::string out = "table1.json";
  int direct_max_faces = 10000, sweeps = 50;
  std::vector<fs::path> meshes;
  bool merge = false, only_l2 = false, unit_field = false, parallel = false;  // the arguments are JSON files of earlier runs: print their rows as one table
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (a == "--out" && i + 1 < argc) out = argv[++i];
    else if (a == "--direct-max-faces" && i + 1 < argc) direct_max_faces = bench::parse_count(a, argv[++i]);
    else if (a == "--sweeps" && i + 1 < argc) sweeps = bench::parse_count(a, argv[++i]);
    else if (a == "--merge") merge = true;
    else if (a == "--only-l2") only_l2 = true;
    else if (a == "--parallel") parallel = true;
    else if (a == "--field" && i + 1 < argc) {
      const std::string f = argv[++i];
      if (f != "smoothest" && f != "unit") throw std::invalid_argument("--field " + f + ": smoothest or unit");
      unit_field = f == "unit";
    }
    else if (a.rfind("--", 0) == 0) throw std::invalid_argument(a + ": unknown option or missing value\n" + kUsage);
    else meshes.emplace_back(a);
  }
  if (merge) return print_merged(meshes);
  bench::check_output_folder("--out", out);  // before the first mesh's minutes
  if (meshes.empty()) {
    const fs::path dir = fs::path(STRICTMIN_SHARED_DATA) / "closed";
    if (!fs::is_directory(dir)) {
      std::fprintf(stderr, "bench_table1: no meshes given and no %s; skipping\n", dir.c_str());
      return 0;
    }
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".obj") meshes.push_back(e.path());
    std::sort(meshes.begin(), meshes.end());
    for (const char* name : kDiskStandIns) {
      const fs::path disk = fs::path(STRICTMIN_SHARED_DATA) / "disk" / (std::string(name) + ".obj");
      if (fs::exists(disk)) meshes.push_back(disk);
    }
  }
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& m : meshes) {
    std::fprintf(stderr, "bench_table1: %s\n", m.c_str());
    rows.push_back(run_mesh(m, direct_max_faces, sweeps, only_l2, unit_field, parallel));
    write_rows(out, rows);
  }
  if (only_l2) print_l2_table(rows);
  else print_table(rows);
  return 0;
}

int main(int argc, char** argv) { return bench::guarded_main("bench_table1", run, argc, argv); }
