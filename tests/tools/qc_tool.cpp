// qc_tool: one feasibility program of the qc / iso bisection (solvers/qc/qc_program.h) on
// Figure 2's set-up, solved by our sparse interior-point method with the bisection's settings
// and slack scales, written as JSON (G as triplets, h, cone dimensions, c, our optimum, the
// certificate: the best corrected dual bound, null when none) for tests/py/test_qc_cvxopt.py.
//
//   qc_tool CELLS SHIFT MEASURE LEVEL [--out FILE]
// MEASURE: qc or iso; LEVEL: K (qc) or S (iso) for every element; frames from the L2 map.
// MEASURE iso-min: the iso level program instead (qc_program.h: iso_program, minimize S; LEVEL
// ignored), solved with iso_level.cpp's settings; "pobj" is then its optimum S and
// "corrected_bound" the certified bound (with the heads' bounds at S_max = our optimum).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "strictmin/solvers/l2.h"
#include "solvers/qc/bisection.h"
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
  const bool iso_min = measure == "iso-min";
  const Measure m = measure == "iso" || iso_min ? Measure::Isometric : Measure::Quasiconformal;
  const qc::ConformalParts parts = qc::conformal_parts(p);
  const Eigen::VectorXd x = p.free_dofs(solve_l2(p).positions);
  const Eigen::VectorXd frames = qc::frames_of(parts, x);
  const Eigen::VectorXd levels = Eigen::VectorXd::Constant(parts.count(), level);
  const qc::IsoProgram iso = qc::iso_program(parts, frames, Eigen::VectorXd());
  const qc::SparseSocp prog = iso_min ? iso.program
                                      : qc::slack_program(m, parts, frames, levels, 1.0,
                                                          qc::slack_scales(m, parts, x));  // as the bisection's
  // 2. Solved with the bisection's settings, without its early stop; the certificate as the
  //    bisection tries it: the best corrected dual bound over the iterates with a positive
  //    slack and the gap below it.
  qc::SparseSocpSettings settings = qc::feasibility_settings(80);
  settings.verbose = std::getenv("QC_TOOL_VERBOSE") != nullptr;
  double bound = -std::numeric_limits<double>::infinity();
  if (iso_min) settings.gap_tolerance = 1e-12;
  auto monitor = [&](const qc::SparseSocpIterate& it) {
    if (iso_min) return false;
    if (it.pobj > 0 && it.gap < it.pobj && it.dres <= 1e-4)
      bound = std::max(bound, qc::corrected_dual_bound(prog, *it.z, nullptr));
    return false;
  };
  const double start_value = qc::frame_values(m, parts, frames, x).maxCoeff();
  const Eigen::VectorXd start = iso_min ? qc::iso_start(iso, parts, frames, x, start_value) : qc::slack_start(m, parts, x);
  const qc::SparseSocpOutcome r = qc::solve_sparse_socp(prog, start, settings, monitor);
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
  bound = std::max(bound, iso_min ? std::min(r.pobj, qc::corrected_dual_bound(prog, r.z, nullptr, iso.head_bounds(r.pobj)))
                                  : qc::corrected_dual_bound(prog, r.z, nullptr));
  if (std::isfinite(bound))
    j["corrected_bound"] = bound;
  else
    j["corrected_bound"] = nullptr;  // no certificate
  j["status"] = r.status == qc::SparseSocpStatus::Converged ? "converged" : r.message;
  if (out.empty())
    std::cout << j.dump() << "\n";
  else
    std::ofstream(out) << j.dump() << "\n";
  return 0;
}
