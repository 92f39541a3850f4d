// Greedy rounding to an integer-grid map (include/strictmin/tasks/integer_grid.h).
#include "strictmin/tasks/integer_grid.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <tuple>

#include "strictmin/io/input_error.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/timing.h"
#include "strictmin/tasks/seamless_problem.h"

namespace strictmin {
namespace {

// Each rounding step takes this share of the values left (at least one), nearest first.
constexpr double kStepShare = 0.25;

// The distance of v (UV units) to the nearest integer point, per coordinate.
double grid_distance(const Eigen::Vector2d& v) {
  return std::max(std::abs(v.x() - std::round(v.x())), std::abs(v.y() - std::round(v.y())));
}

Eigen::Vector2d nearest_grid_point(const Eigen::Vector2d& v) { return {std::round(v.x()), std::round(v.y())}; }

// One wedge per singular vertex: the wedge of its first corner in its fan.
std::vector<int> singular_wedges(const SurfaceGraph& g, const CutGraph& c, const std::vector<Singularity>& singular) {
  std::vector<int> wedges;
  for (const Singularity& s : singular) {
    const int k = g.fan_start[s.vertex];
    wedges.push_back(c.corner_wedge(g.fan_faces[k], g.fan_corners[k]));
  }
  return wedges;
}

// Appends f_left - R f_right = t (two rows) to the problem's equalities.
void add_translation_rows(Problem& p, const BranchEnds& ends, const Eigen::Vector2d& t) {
  std::vector<Eigen::Triplet<double>> triplets;
  for (int k = 0; k < p.eq_matrix.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(p.eq_matrix, k); it; ++it)
      triplets.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
  const int first = static_cast<int>(p.eq_matrix.rows());
  for (int r = 0; r < 2; ++r) {
    triplets.emplace_back(first + r, 2 * ends.left + r, 1.0);
    for (int s = 0; s < 2; ++s)
      if (ends.rotation(r, s) != 0) triplets.emplace_back(first + r, 2 * ends.right + s, -ends.rotation(r, s));
  }
  p.eq_matrix.resize(first + 2, 2 * p.num_vertices);
  p.eq_matrix.setFromTriplets(triplets.begin(), triplets.end());
  p.eq_rhs.conservativeResize(first + 2);
  p.eq_rhs.segment<2>(first) = t;
}

// The greedy loop over one kind of value: `value(i, X)` (UV units) of the pending items,
// `hold(i, point)` rounds item i to the grid point in `problem`, and `solve` returns the L2
// map, or nothing when the equalities contradict each other. A step rounds the nearest
// kStepShare of the values left, the `first` ones before any other; values rounded together
// can contradict (three free translations around one node, 0.4 + 0.4 - 0.8 = 0, round to
// 0 + 0 - 1), so a step that fails is undone and tried again with half as many. A single
// value that still contradicts is fixed by the others off the grid (a loop's parity, see the
// header): it is left to them and returned.
template <class Value, class Hold, class Solve, class First>
std::vector<int> round_greedily(std::vector<int> pending, Problem& problem, Eigen::MatrixXd& X, Value value, Hold hold,
                                Solve solve, First first, double& largest_rounding) {
  std::vector<int> off_grid;
  while (!pending.empty()) {
    std::vector<std::tuple<bool, double, int>> order;
    for (int i : pending) order.emplace_back(!first(i), grid_distance(value(i, X)), i);
    std::sort(order.begin(), order.end());
    size_t take = std::max<size_t>(1, static_cast<size_t>(std::ceil(kStepShare * order.size())));
    for (;; take = (take + 1) / 2) {
      const Problem before = problem;
      for (size_t j = 0; j < take; ++j) hold(std::get<2>(order[j]), nearest_grid_point(value(std::get<2>(order[j]), X)));
      if (std::optional<Eigen::MatrixXd> next = solve()) {
        X = std::move(*next);
        break;
      }
      problem = before;
      if (take == 1) {
        off_grid.push_back(std::get<2>(order[0]));
        break;
      }
    }
    pending.clear();
    for (size_t j = 0; j < order.size(); ++j)
      if (j >= take)
        pending.push_back(std::get<2>(order[j]));
      else if (off_grid.empty() || off_grid.back() != std::get<2>(order[j]))
        largest_rounding = std::max(largest_rounding, std::get<1>(order[j]));
  }
  return off_grid;
}

}  // namespace

IntegerGridRounding round_to_integer_grid(const Mesh& mesh, const SurfaceGraph& graph, const CutGraph& cut,
                                          const std::vector<Singularity>& singular, double h, Problem& problem,
                                          const std::function<void(const std::string&)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  IntegerGridRounding out;
  std::string step = "before rounding";
  // The L2 map, or nothing after a contradiction that a smaller step may avoid (`last`: it
  // cannot, and the contradiction is an error like any other failure).
  auto solve = [&]() -> std::optional<Eigen::MatrixXd> {
    const Result r = solve_l2(problem);
    ++out.solves;
    if (r.ok()) return r.positions;
    if (r.status == SolveStatus::Infeasible) {
      ++out.retried_steps;
      return std::nullopt;
    }
    throw InputError("integer-grid rounding: the L2 map " + step + " failed (" + status_name(r.status) + "): " +
                     r.message);
  };
  std::optional<Eigen::MatrixXd> start = solve();
  if (!start) throw InputError("integer-grid rounding: the seamless problem's L2 map failed before rounding");
  Eigen::MatrixXd X = std::move(*start);

  // 1. The singular vertices. The seamless problem holds wedge 0 at the origin only to fix
  // the map's translation: the grid takes that role once a singular vertex is held (in the
  // first step), so wedge 0 is let go (unless it is a singular vertex's: on the grid already).
  const std::vector<int> wedges = singular_wedges(graph, cut, singular);
  std::vector<int> pending;
  for (size_t i = 0; i < wedges.size(); ++i)
    if (!problem.fixed[wedges[i]]) pending.push_back(static_cast<int>(i));
  if (!pending.empty() && pending.size() == wedges.size())
    for (int w = 0; w < problem.num_vertices; ++w) problem.fixed[w] = 0;
  out.singularities = static_cast<int>(pending.size());
  step = "with the singular vertices rounded";
  const std::vector<int> off_grid_singular = round_greedily(
      pending, problem, X, [&](int i, const Eigen::MatrixXd& Y) -> Eigen::Vector2d { return Y.row(wedges[i]).transpose() / h; },
      [&](int i, const Eigen::Vector2d& point) { problem.fix({Handle{wedges[i], h * point}}); }, solve,
      [](int) { return false; }, out.largest_rounding);
  out.singularities_off_grid = static_cast<int>(off_grid_singular.size());

  // 2. The branch translations.
  std::vector<BranchEnds> ends;
  for (const SeamBranch& b : cut.branches) ends.push_back(branch_ends(mesh, graph, cut, b));
  pending.clear();
  for (size_t i = 0; i < ends.size(); ++i) pending.push_back(static_cast<int>(i));
  out.translations = static_cast<int>(pending.size());
  step = "with the seam translations rounded";
  auto translation = [&](int i, const Eigen::MatrixXd& Y) -> Eigen::Vector2d {
    const BranchEnds& e = ends[i];
    return (Y.row(e.left).transpose() - e.rotation * Y.row(e.right).transpose()) / h;
  };
  // A branch from a node back to itself (a loop of the cut, on surfaces of genus >= 1) enters
  // its node's relation twice, with a coefficient such as I - R (determinant 2): left last, it
  // could be fixed at a half-integer. Loops go first.
  auto is_loop = [&](int i) { return cut.branches[i].vertices.front() == cut.branches[i].vertices.back(); };
  const std::vector<int> off_grid_translations = round_greedily(
      pending, problem, X, translation,
      [&](int i, const Eigen::Vector2d& point) { add_translation_rows(problem, ends[i], h * point); }, solve, is_loop,
      out.largest_rounding);
  out.translations_off_grid = static_cast<int>(off_grid_translations.size());
  out.time_s = seconds_since(t0);
  if (progress) {
    char line[240];
    std::snprintf(line, sizeof line,
                  "integer grid: %d singular vertices and %d seam translations rounded (largest move %.3g grid "
                  "units; %d and %d left off the grid), %d L2 solves (%d steps halved), %.3f s",
                  out.singularities - out.singularities_off_grid, out.translations - out.translations_off_grid,
                  out.largest_rounding, out.singularities_off_grid, out.translations_off_grid, out.solves,
                  out.retried_steps, out.time_s);
    progress(line);
  }
  return out;
}

double integer_grid_error(const Mesh& mesh, const SurfaceGraph& graph, const CutGraph& cut,
                          const std::vector<Singularity>& singular, double h, const Eigen::MatrixXd& X) {
  double worst = 0;
  for (const Singularity& s : singular)
    for (int k = graph.fan_start[s.vertex]; k < graph.fan_start[s.vertex + 1]; ++k) {
      const int w = cut.corner_wedge(graph.fan_faces[k], graph.fan_corners[k]);
      worst = std::max(worst, grid_distance(X.row(w).transpose() / h));
    }
  const Eigen::MatrixXd T = branch_translations(mesh, graph, cut, X, nullptr);
  for (Eigen::Index i = 0; i < T.rows(); ++i) worst = std::max(worst, grid_distance(T.row(i).transpose() / h));
  return worst;
}

}  // namespace strictmin
