#include "linf_phase1.h"

#include <algorithm>
#include <vector>

#include "strictmin/problem/parts.h"
#include "solvers/socp/certificate.h"
#include "solvers/socp/ipm.h"

namespace strictmin::linf_detail {
namespace {

// Whether an equality row couples a moving vertex (vertex_dof >= 0) with a vertex that is
// held although it is not fixed (outside the bounded elements).
bool equalities_tie_held_vertices(const Problem& p, const std::vector<int>& vertex_dof) {
  if (!p.has_equalities()) return false;
  const int n = p.image_dim;
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = p.eq_matrix;
  for (Eigen::Index r = 0; r < rows.outerSize(); ++r) {
    bool moving = false, held = false;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, r); it; ++it) {
      const int v = static_cast<int>(it.col()) / n;
      if (vertex_dof[v] >= 0) moving = true;
      else if (!p.fixed[v]) held = true;
    }
    if (moving && held) return true;
  }
  return false;
}

}  // namespace

Phase1 run_phase1(const Problem& p, const socp::ElementClasses& cls, const Eigen::VectorXd& bounds,
                  const Eigen::MatrixXd& X0, const LinfOptions& options) {
  const int n = p.image_dim;
  const std::vector<int>& elems = cls.bounded_elements;
  std::vector<char> bounded(p.num_elements(), 0), held(p.fixed.begin(), p.fixed.end());
  for (int e : elems) bounded[e] = 1;
  const ElementParts parts = element_parts(p, &bounded);
  if (!p.has_equalities())
    for (int v : unanchored_parts(parts, p.fixed)) held[v] = 1;
  std::vector<int> vertex_dof(p.num_vertices, -1);
  int num_x = 0;
  for (int v = 0; v < p.num_vertices; ++v) {
    if (parts.part[v] < 0) held[v] = 1;  // outside: constant here
    if (!held[v]) {
      vertex_dof[v] = num_x;
      num_x += n;
    }
  }
  socp::ConeProgram prog = socp::element_program(p, elems, vertex_dof, num_x, X0);
  for (size_t i = 0; i < elems.size(); ++i) prog.head_b[static_cast<Eigen::Index>(i)] = bounds[elems[i]];
  socp::restrict_equalities(p, vertex_dof, num_x, X0, held, prog);

  Eigen::VectorXd x0(num_x);
  for (int v = 0; v < p.num_vertices; ++v)
    if (vertex_dof[v] >= 0) x0.segment(vertex_dof[v], n) = X0.row(v).transpose();

  Phase1 out;
  auto excess_at = [&](const Eigen::VectorXd& x) {
    const Eigen::VectorXd d = socp::cone_distortions(prog, x);
    double t = -kInf;
    for (int i = 0; i < prog.num_element_cones(); ++i) t = std::max(t, d[i] - prog.head_b[i]);
    return t;
  };
  const double scale = std::max(1.0, prog.head_b.maxCoeff());
  const double tol = options.infeasibility_tolerance * scale;
  double best_t = excess_at(x0), best_lb = -kInf;
  Eigen::VectorXd best_x = x0;
  socp::WeightedLeastSquares ls(prog);
  socp::IpmState st;
  socp::initialize(prog, x0, start_above(best_t), 1e-2 * scale, 1.0, st);
  const socp::IpmSettings settings = ipm_settings(options);
  const auto outcome = socp::run_ipm(prog, st, settings, [&](const socp::IpmState& s, const socp::Residuals&,
                                                             const socp::IpmIteration&) {
    const double t = excess_at(s.x);
    if (t < best_t) {
      best_t = t;
      best_x = s.x;
    }
    best_lb = std::max(best_lb, socp::certified_lower_bound(prog, ls, s.z, s.y));
    // Done when strictly feasible, certainly infeasible, or converged where the least miss
    // is certified positive but small enough to absorb (<= tol). A converged gap alone does
    // not decide: while the bound is <= 0 a map that meets every bound may exist, and one is
    // wanted (a start that misses its bounds by round-off, handed on from solve to solve as
    // in local-global's global steps of a direct level, would otherwise drift further out).
    return best_t < 0 || best_lb > tol ||
           (best_t - best_lb <= options.gap_tolerance * scale && best_lb > 0 && best_t <= tol);
  });
  out.iterations = outcome.iterations;
  out.t = best_t;
  out.lower_bound = best_lb;
  out.X = X0;
  for (int v = 0; v < p.num_vertices; ++v)
    if (vertex_dof[v] >= 0) out.X.row(v) = best_x.segment(vertex_dof[v], n).transpose();
  out.restricted = equalities_tie_held_vertices(p, vertex_dof);
  if (best_lb > tol && out.restricted) {
    out.feasible = false;
    out.message = "could not decide whether the fixed bounds can be met: phase 1 holds the vertices outside the "
                  "bounded elements, and the equalities tie some of them to its vertices (under that restriction "
                  "some bound is missed by at least " + format(best_lb) + ")";
  } else if (best_lb > tol) {  // certified: every map misses some bound by more than tol
    out.feasible = false;
    out.certified = true;
    out.message = "the fixed bounds cannot all be met: some bounded element exceeds its bound k_T by at least " +
                  format(std::max(best_lb, 0.0)) + " (best map found: " + format(best_t) + ")";
  } else if (best_t > tol) {
    out.feasible = false;
    out.message = "could not decide whether the fixed bounds can be met (phase 1: " + outcome.message +
                  "; excess " + format(best_t) + ", bound " + format(best_lb) + ")";
  }
  return out;
}

}  // namespace strictmin::linf_detail
