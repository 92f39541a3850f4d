#include "solvers/linf_active_set.h"

#include <algorithm>
#include <limits>

#include "solvers/linf_relaxed_equalities.h"
#include "strictmin/measures/field_deviation.h"
#include "strictmin/problem/parts.h"
#include "strictmin/problem/subproblem.h"

namespace strictmin {
namespace {

// The problem over `elements` only (see the header), in the numbering of its movable
// vertices (restrict_to_movable): `elements` with their vertices, the rest held at X; in a
// relaxation (not hold_rim) the equalities through a vertex outside are dropped, and one
// vertex is held per part that no fixed vertex anchors; with hold_rim every vertex that
// another element touches is held and every equality kept.
Subproblem restricted_problem(const Problem& p, const std::vector<int>& elements, const Eigen::MatrixXd& X,
                              bool hold_rim) {
  const int V = p.num_vertices, c = p.corners(), n = p.image_dim;
  std::vector<char> chosen(p.num_elements(), 0), rim(V, 0);
  for (int e : elements) chosen[e] = 1;
  if (hold_rim)
    for (int e = 0; e < p.num_elements(); ++e)
      if (!chosen[e])
        for (int a = 0; a < c; ++a) rim[p.elements(e, a)] = 1;
  // Parts of the restriction: those that neither a fixed vertex nor (hold_rim) the rim
  // anchors float; a translation of such a part changes no distortion, so one vertex of it
  // is held.
  const ElementParts parts = element_parts(p, &chosen);
  std::vector<char> anchor(V, 0), floating_part(parts.count, 0), movable(V, 0), floating(V, 0);
  for (int v = 0; v < V; ++v) anchor[v] = p.fixed[v] || rim[v];
  const std::vector<int> held = unanchored_parts(parts, anchor);
  for (int v : held) floating_part[parts.part[v]] = 1;
  for (int v = 0; v < V; ++v) {
    if (parts.part[v] < 0 || anchor[v]) continue;
    movable[v] = 1;
    floating[v] = floating_part[parts.part[v]];
  }
  for (int v : held) movable[v] = 0;
  Problem q = p;
  if (!hold_rim && p.has_equalities()) {
    // The equalities projected onto the restriction's vertices, with the translations they
    // allow held (linf_relaxed_equalities.h); failing that, the rows through a vertex outside
    // or through a part held are dropped.
    std::vector<char> inside(V, 0);
    for (int v = 0; v < V; ++v) inside[v] = parts.part[v] >= 0;
    RelaxedEqualities relaxed = relaxed_equalities(p, inside, parts, anchor);
    if (relaxed.ok) {
      for (int v = 0; v < V; ++v) movable[v] = parts.part[v] >= 0 && !anchor[v];
      for (int v : relaxed.held) movable[v] = 0;
      q.eq_matrix = std::move(relaxed.A);
      q.eq_rhs = std::move(relaxed.b);
      return restrict_to_movable(q, movable, X, &chosen);
    }
  }
  if (!hold_rim && p.has_equalities()) {
    const Eigen::SparseMatrix<double, Eigen::RowMajor> A = p.eq_matrix;
    std::vector<Eigen::Triplet<double>> kept;
    std::vector<double> rhs;
    for (int row = 0; row < A.rows(); ++row) {
      bool keep = true;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, row); it && keep; ++it) {
        const int v = static_cast<int>(it.col()) / n;
        keep = p.fixed[v] || (parts.part[v] >= 0 && !floating[v]);
      }
      if (!keep) continue;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, row); it; ++it)
        kept.emplace_back(static_cast<int>(rhs.size()), static_cast<int>(it.col()), it.value());
      rhs.push_back(p.eq_rhs[row]);
    }
    q.eq_matrix.resize(static_cast<Eigen::Index>(rhs.size()), p.eq_matrix.cols());
    q.eq_matrix.setFromTriplets(kept.begin(), kept.end());
    q.eq_rhs = Eigen::Map<const Eigen::VectorXd>(rhs.data(), static_cast<Eigen::Index>(rhs.size()));
  }
  return restrict_to_movable(q, movable, X, &chosen);
}

ActiveSetSolve solve_restricted(const Problem& p, const std::vector<int>& elements, const Eigen::MatrixXd& X,
                                const Eigen::VectorXd& bounds, const LinfOptions& options, bool hold_rim) {
  ActiveSetSolve out;
  out.lower_bound = -std::numeric_limits<double>::infinity();
  if (elements.empty()) return out;
  const Subproblem sub = restricted_problem(p, elements, X, hold_rim);
  out.elements = static_cast<int>(sub.element.size());
  // The restriction's free elements without a movable vertex (every vertex fixed) are
  // constants: min over x of max(f(x), c) is max(min f, c).
  double constant = -std::numeric_limits<double>::infinity();
  {
    std::vector<char> kept(p.num_elements(), 0);
    for (int e : sub.element) kept[e] = 1;
    for (int e : elements)
      if (!kept[e] && !(bounds.size() > 0 && bounds[e] >= 0))
        constant = std::max(constant, field_deviation(p, X, e));
  }
  LinfOptions o = options;
  o.progress = nullptr;
  o.verbose = 0;
  o.minimize_l2_among_optimal = false;
  o.active_set_bounds = false;
  o.gap_tolerance = 0.1 * options.gap_tolerance;
  o.element_bounds.resize(0);
  if (bounds.size() > 0) {
    o.element_bounds.resize(out.elements);
    for (int j = 0; j < out.elements; ++j) o.element_bounds[j] = bounds[sub.element[j]];
  }
  const Result r = solve_linf(sub.problem, o);
  out.iterations = r.iterations;
  if (r.status == SolveStatus::Infeasible || r.positions.rows() != static_cast<Eigen::Index>(sub.vertex.size()))
    return out;
  out.positions = X;
  for (size_t i = 0; i < sub.vertex.size(); ++i) out.positions.row(sub.vertex[i]) = r.positions.row(i);
  if (hold_rim || !std::isfinite(r.lower_bound)) return out;  // a restriction bounds nothing
  out.lower_bound = std::max(r.lower_bound, constant);
  // The dual weights: the restricted solve's, or none on the free elements when a constant
  // element sets the bound (its own weight, as in solve_linf, is not an element's).
  out.multipliers = Eigen::VectorXd::Zero(p.num_elements());
  if (r.multipliers.size() == out.elements && r.lower_bound >= constant)
    for (int j = 0; j < out.elements; ++j) out.multipliers[sub.element[j]] = r.multipliers[j];
  return out;
}

}  // namespace

ActiveSetSolve active_set_bound(const Problem& p, const std::vector<int>& elements, const Eigen::MatrixXd& X,
                                const Eigen::VectorXd& bounds, const LinfOptions& options) {
  return solve_restricted(p, elements, X, bounds, options, false);
}

ActiveSetSolve active_set_map(const Problem& p, const std::vector<int>& elements, const Eigen::MatrixXd& X,
                              const Eigen::VectorXd& bounds, const LinfOptions& options) {
  return solve_restricted(p, elements, X, bounds, options, true);
}

std::vector<int> widen_by_rings(const Problem& p, const std::vector<int>& elements, int rings, double max_growth,
                                int min_rings, size_t enough) {
  std::vector<int> out = elements;
  std::vector<char> in(p.num_elements(), 0), touched(p.num_vertices, 0);
  for (int e : out) in[e] = 1;
  const double limit = max_growth * static_cast<double>(elements.size());
  for (int ring = 0; ring < rings; ++ring) {
    if (min_rings >= 0 && ring >= min_rings && out.size() >= enough) break;
    for (int e : out)
      for (int a = 0; a < p.corners(); ++a) touched[p.elements(e, a)] = 1;
    std::vector<int> next;
    for (int e = 0; e < p.num_elements(); ++e) {
      if (in[e]) continue;
      for (int a = 0; a < p.corners(); ++a)
        if (touched[p.elements(e, a)]) {
          next.push_back(e);
          break;
        }
    }
    if (static_cast<double>(out.size() + next.size()) > limit) break;
    for (int e : next) in[e] = 1;
    out.insert(out.end(), next.begin(), next.end());
  }
  return out;
}

}  // namespace strictmin
