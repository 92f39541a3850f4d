// qc_tool: one feasibility program of the qc / iso bisection (solvers/qc/qc_program.h) on
// Figure 2's set-up, solved to convergence by our sparse interior-point method, written as
// JSON (G as triplets, h, cone dimensions, c, our optimum) for tests/py/test_qc_cvxopt.py.
//
//   qc_tool CELLS SHIFT MEASURE LEVEL [--out FILE]
// MEASURE: qc or iso; LEVEL: K (qc) or S (iso) for every element; frames from the L2 map.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "strictmin/solvers/l2.h"
#include "solvers/qc/qc_program.h"
#include "solvers/qc/sparse_socp.h"
#include "strictmin/tasks/examples.h"

using namespace strictmin;

int main(int argc, char** argv) {
  if (argc < 5) {
    std::cerr << "usage: qc_tool CELLS SHIFT qc|iso LEVEL [--out FILE]\n";
    return 2;
  }
  const int cells = std::atoi(argv[1]);
  const double shift = std::atof(argv[2]);
  const std::string measure = argv[3];
  const double level = std::atof(argv[4]);
  const std::string out = argc >= 7 && std::string(argv[5]) == "--out" ? argv[6] : "";
  // 1. The problem, the L2 map, its frames, the slack program at the level.
  const Problem p = example_problem(make_square_example(cells, shift));
  const Measure m = measure == "iso" ? Measure::Isometric : Measure::Quasiconformal;
  const qc::ConformalParts parts = qc::conformal_parts(p);
  const Eigen::VectorXd x = p.free_dofs(solve_l2(p).positions);
  const Eigen::VectorXd frames = qc::frames_of(parts, x);
  const Eigen::VectorXd levels = Eigen::VectorXd::Constant(parts.count(), level);
  const qc::SparseSocp prog = qc::slack_program(m, parts, frames, levels, 1.0);
  // 2. Solved to convergence (no early stop).
  qc::SparseSocpSettings settings;
  settings.gap_tolerance = 1e-9;
  settings.verbose = std::getenv("QC_TOOL_VERBOSE") != nullptr;
  const qc::SparseSocpOutcome r = qc::solve_sparse_socp(prog, qc::slack_start(m, parts, x), settings);
  // 3. The dump.
  nlohmann::json j;
  std::vector<int> rows, cols;
  std::vector<double> vals;
  for (int c = 0; c < prog.G.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(prog.G, c); it; ++it) {
      rows.push_back(static_cast<int>(it.row()));
      cols.push_back(static_cast<int>(it.col()));
      vals.push_back(it.value());
    }
  j["rows"] = rows;
  j["cols"] = cols;
  j["vals"] = vals;
  j["shape"] = {prog.G.rows(), prog.G.cols()};
  j["h"] = std::vector<double>(prog.h.data(), prog.h.data() + prog.h.size());
  j["c"] = std::vector<double>(prog.c.data(), prog.c.data() + prog.c.size());
  j["dims"] = prog.dims;
  j["pobj"] = r.pobj;
  j["dobj"] = r.dobj;
  j["converged"] = r.status == qc::SparseSocpStatus::Converged;
  j["iterations"] = r.iterations;
  j["corrected_bound"] = qc::corrected_dual_bound(prog, r.z, nullptr);
  j["status"] = r.status == qc::SparseSocpStatus::Converged ? "converged" : r.message;
  if (out.empty())
    std::cout << j.dump() << "\n";
  else
    std::ofstream(out) << j.dump() << "\n";
  return 0;
}
