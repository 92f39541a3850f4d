// Greedy rounding to an integer-grid map (include/strictmin/tasks/integer_grid.h).
#include "strictmin/tasks/integer_grid.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <complex>
#include <optional>
#include <stdexcept>

#include "strictmin/io/input_error.h"
#include "strictmin/solvers/interrupt.h"
#include "strictmin/solvers/timing.h"
#include "strictmin/tasks/seamless_problem.h"
#include "tasks/bordered_l2.h"
#include "tasks/grid_completion.h"
#include "tasks/node_relations.h"

namespace strictmin {
namespace {

// Each rounding step takes this share of the values left (at least one), nearest first.
constexpr double kStepShare = 0.25;

// The bordered L2 solver's rows contradict each other when they miss by more than this,
// relative to the map's extent (RoundingState::tolerance).
constexpr double kRowTolerance = 1e-8;

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

// The values being rounded: the singular vertices' held wedges, then the branch translations
// (UV units).
struct GridValues {
  std::vector<int> wedges;       // per singular vertex: its held wedge
  std::vector<BranchEnds> ends;  // per branch
  double h = 1;

  Eigen::Vector2d singular(int i, const Eigen::MatrixXd& X) const { return X.row(wedges[i]).transpose() / h; }
  // The vertices these values read (the bordered solver's watched ones).
  std::vector<int> watched() const {
    std::vector<int> out = wedges;
    for (const BranchEnds& e : ends) {
      out.push_back(e.left);
      out.push_back(e.right);
    }
    return out;
  }
  // The largest coordinate of X on those vertices.
  double extent(const Eigen::MatrixXd& X) const {
    double largest = 0;
    for (int w : watched()) largest = std::max(largest, X.row(w).cwiseAbs().maxCoeff());
    return largest;
  }
  Eigen::Vector2d translation(int i, const Eigen::MatrixXd& X) const {
    const BranchEnds& e = ends[i];
    return (X.row(e.left).transpose() - e.rotation * X.row(e.right).transpose()) / h;
  }
};

// What the rounding has decided, with snapshots to undo a step: the holds (singular vertices
// at grid points, branch translations on the grid), each also a row of the bordered L2 solver
// (tasks/bordered_l2.h) whose solves judge the steps. The problem takes the holds once, at
// the end (apply).
//
// The bordered solver keeps the seamless problem's anchor (wedge 0 at the origin). The map
// may be translated as a whole (the free branch translations absorb it: t changes by
// (I - R) c), so the first singular vertex held, s0 at P0, is reached by translating the
// solution by c = P0 - z(s0), and every later hold is written in that frame:
//   singular vertex w held at P:     z_w - z_s0 = P - P0
//   branch translation rounded to T: z_left - r z_right - (1 - r) z_s0 = T - (1 - r) P0
// (r: the branch's rotation as a complex number; surface units).
struct RoundingState {
  using Complex = std::complex<double>;
  BorderedL2 bordered;
  double tolerance = 0;   // how far the bordered rows may miss (contradiction above)
  int frame_wedge = -1;   // s0 (-1: none held yet)
  Complex frame_point;    // P0
  std::vector<std::pair<int, Eigen::Vector2d>> held_vertices;          // (wedge, P)
  std::vector<std::pair<const BranchEnds*, Eigen::Vector2d>> held_translations;  // (branch, T)

  RoundingState(const Problem& p, const std::vector<int>& watched) : bordered(p, watched) {}

  struct Snapshot {
    std::size_t rows, vertices, translations;
    int frame_wedge;
    Complex frame_point;
  };
  Snapshot save() const {
    return {bordered.size(), held_vertices.size(), held_translations.size(), frame_wedge, frame_point};
  }
  void restore(const Snapshot& s) {
    bordered.truncate(s.rows);
    held_vertices.resize(s.vertices);
    held_translations.resize(s.translations);
    frame_wedge = s.frame_wedge;
    frame_point = s.frame_point;
  }

  void hold_vertex(int w, const Eigen::Vector2d& point) {
    held_vertices.emplace_back(w, point);
    const Complex P(point.x(), point.y());
    if (frame_wedge < 0) {
      frame_wedge = w;
      frame_point = P;
      return;
    }
    bordered.push({{{w, 1.0}, {frame_wedge, -1.0}}, P - frame_point});
  }
  void hold_translation(const BranchEnds& ends, const Eigen::Vector2d& t) {
    held_translations.emplace_back(&ends, t);
    const Complex r(ends.rotation(0, 0), ends.rotation(1, 0));
    BorderedL2::Row row{{{ends.left, 1.0}, {ends.right, -r}}, Complex(t.x(), t.y())};
    if (frame_wedge >= 0) {
      row.terms.push_back({frame_wedge, -(1.0 - r)});
      row.rhs -= (1.0 - r) * frame_point;
    }
    bordered.push(row);
  }
  // The bordered L2 map for p's targets in the frame of s0, or nothing when the rows
  // contradict each other.
  std::optional<Eigen::MatrixXd> l2(const Problem& p) const {
    std::optional<Eigen::MatrixXd> X = bordered.solve(p, tolerance);
    if (X && frame_wedge >= 0) {
      const Eigen::RowVector2d c(frame_point.real() - (*X)(frame_wedge, 0), frame_point.imag() - (*X)(frame_wedge, 1));
      X->rowwise() += c;
    }
    return X;
  }
  // The holds into the problem: the held singular vertices as fixed vertices (wedge 0, which
  // held the map only against translation, let go when a vertex of the rounding is held and
  // it is none of theirs) and the translations as equality rows.
  void apply(Problem& problem, bool release_anchor) const {
    if (release_anchor && !held_vertices.empty())
      for (int w = 0; w < problem.num_vertices; ++w) problem.fixed[w] = 0;
    for (const auto& [w, point] : held_vertices) problem.fix({Handle{w, point}});
    for (const auto& [ends, t] : held_translations) add_translation_rows(problem, *ends, t);
  }
};

// The grid points around v, nearest first: the nearest, then the other three corners of the
// unit cell around v (without the exact check a value rounded alone tries them before it is
// given up).
std::vector<Eigen::Vector2d> grid_points_around(const Eigen::Vector2d& v) {
  const Eigen::Vector2d low(std::floor(v.x()), std::floor(v.y()));
  std::vector<Eigen::Vector2d> points;
  for (int dx = 0; dx < 2; ++dx)
    for (int dy = 0; dy < 2; ++dy) points.push_back(low + Eigen::Vector2d(dx, dy));
  std::stable_sort(points.begin(), points.end(), [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - v).squaredNorm() < (b - v).squaredNorm();
  });
  return points;
}

// Where a step puts its values. With the exact check (tasks/grid_completion.h) every value is
// fixed in the integer completion as it is chosen: the step's first value goes to the point
// of its completable coset nearest the map's value (its nearest grid point when that can be
// completed, so a dead end cannot arise), each later value to its nearest grid point if that
// can still be completed with the step's earlier choices, else it waits for the next step
// (the L2 map then shows what the step's values imply). Without it, the nearest grid point,
// and a value alone tries the four around it.
struct Chooser {
  GridCompletion* exact = nullptr;  // null: no exact check
  int moved_past_nearest = 0;      // first values held at a coset point other than their nearest grid point
  double time_s = 0;               // in the exact check

  std::vector<Eigen::Vector2d> first_choices(int value, const Eigen::Vector2d& y, bool alone) {
    if (exact) {
      const auto t0 = std::chrono::steady_clock::now();
      const Eigen::Vector2d nearest = exact->coset(value).nearest(y);
      time_s += seconds_since(t0);
      return {nearest};
    }
    if (alone) return grid_points_around(y);
    return {nearest_grid_point(y)};
  }
  // Fixes the point in the integer completion; false when it cannot be completed.
  bool accept(int value, const Eigen::Vector2d& point) {
    if (!exact) return true;
    const auto t0 = std::chrono::steady_clock::now();
    const bool fixed = exact->fix(value, point);
    time_s += seconds_since(t0);
    return fixed;
  }
  std::size_t save() const { return exact ? exact->size() : 0; }
  void restore(std::size_t count) {
    if (exact) exact->truncate(count);
  }
};

// The greedy loop over one kind of value: `value(i, X)` (UV units) of the pending items,
// `lattice(i)` its index among the node relations' values, `hold(i, point)` rounds item i to
// the grid point, and `solve` returns the L2 map after the step, or nothing when the step's
// equalities contradict each other. A step rounds the nearest kStepShare of the values left
// (where the chooser puts them). Values rounded together can contradict (three free
// translations around one node, 0.4 + 0.4 - 0.8 = 0, round to 0 + 0 - 1): without the exact
// check the L2 solve finds it, and the step is undone and tried again with half as many (with
// it, the third waits for the next step, and a contradiction is round-off only). One that
// fails alone is left to the others off the grid, and returned.
template <class Value, class Lattice, class Hold, class Solve>
std::vector<int> round_greedily(std::vector<int> pending, RoundingState& state, Chooser& chooser, Eigen::MatrixXd& X,
                                Value value, Lattice lattice, Hold hold, Solve solve, double& largest_rounding) {
  std::vector<int> off_grid;
  while (!pending.empty()) {
    std::vector<std::pair<double, int>> order;
    for (int i : pending) order.emplace_back(grid_distance(value(i, X)), i);
    std::sort(order.begin(), order.end());
    size_t take = std::max<size_t>(1, static_cast<size_t>(std::ceil(kStepShare * order.size())));
    std::vector<char> settled(order.size(), 0);  // rounded in this step, or given up
    bool placed = false;
    while (!placed) {
      const int first = order[0].second;
      const Eigen::Vector2d first_nearest = nearest_grid_point(value(first, X));
      const std::vector<Eigen::Vector2d> choices = chooser.first_choices(lattice(first), value(first, X), take == 1);
      for (size_t t = 0; t < choices.size() && !placed; ++t) {
        const auto before = state.save();
        const std::size_t fixed_before = chooser.save();
        double largest_move = 0;  // this try's, per coordinate, in grid units
        for (size_t j = 0; j < take; ++j) {
          const int i = order[j].second;
          const Eigen::Vector2d point = j == 0 ? choices[t] : nearest_grid_point(value(i, X));
          if (!chooser.accept(lattice(i), point)) {
            if (j == 0) throw std::logic_error("integer-grid rounding: a point of the completable coset was refused");
            continue;  // waits for the next step
          }
          largest_move = std::max(largest_move, (point - value(i, X)).cwiseAbs().maxCoeff());
          hold(i, point);
          settled[j] = 1;
        }
        if (std::optional<Eigen::MatrixXd> next = solve()) {
          X = std::move(*next);
          largest_rounding = std::max(largest_rounding, largest_move);
          if (chooser.exact && choices[t] != first_nearest) ++chooser.moved_past_nearest;
          placed = true;
          break;
        }
        state.restore(before);
        chooser.restore(fixed_before);
        std::fill(settled.begin(), settled.end(), 0);
      }
      if (placed) break;
      if (take == 1) {
        off_grid.push_back(first);  // left to the others: not rounded again
        settled[0] = 1;
        break;
      }
      take = (take + 1) / 2;
    }
    pending.clear();
    for (size_t j = 0; j < order.size(); ++j)
      if (!settled[j]) pending.push_back(order[j].second);
  }
  return off_grid;
}

}  // namespace

IntegerGridRounding round_to_integer_grid(const Mesh& mesh, const SurfaceGraph& graph, const CutGraph& cut,
                                          const std::vector<Singularity>& singular, double h, Problem& problem,
                                          const std::function<void(const std::string&)>& progress,
                                          const IntegerGridOptions& options) {
  if (graph.has_boundary())  // gparam refuses the flag by name first
    throw InputError("integer-grid rounding takes closed surfaces only (the surface has " +
                     std::to_string(graph.num_boundary_loops) + " boundary loop(s))");
  const auto t0 = std::chrono::steady_clock::now();
  IntegerGridRounding out;
  GridValues values;
  values.h = h;
  values.wedges = singular_wedges(graph, cut, singular);
  for (const SeamBranch& b : cut.branches) values.ends.push_back(branch_ends(mesh, graph, cut, b));
  RoundingState state(problem, values.watched());
  if (!state.bordered.ok())
    throw InputError("integer-grid rounding: the seamless problem's L2 matrix is not positive definite");
  // The exact check: the integer solutions of the node relations (tasks/node_relations.h),
  // from their Hermite normal form.
  const NodeRelations relations = node_relations(graph, cut, singular);
  const auto check_start = std::chrono::steady_clock::now();
  std::optional<GridCompletion> completion;
  if (options.look_ahead) completion.emplace(relations.matrix);
  Chooser chooser{completion ? &*completion : nullptr};
  chooser.time_s = seconds_since(check_start);
  auto solve = [&]() -> std::optional<Eigen::MatrixXd> {
    check_interrupt();  // solvers/interrupt.h: once per step (horse's 31 solves take 2 s)
    ++out.solves;
    std::optional<Eigen::MatrixXd> X = state.l2(problem);
    if (!X) ++out.retried_steps;
    return X;
  };
  ++out.solves;
  std::optional<Eigen::MatrixXd> start = state.l2(problem);
  if (!start) throw InputError("integer-grid rounding: the seamless problem's L2 map failed before rounding");
  Eigen::MatrixXd X = std::move(*start);
  // Rows miss by round-off (relative to the map's extent) unless they contradict, by a
  // fraction of a grid unit or more.
  state.tolerance = kRowTolerance * std::max(h, values.extent(X));

  // 1. The singular vertices. The seamless problem holds wedge 0 at the origin only to fix
  // the map's translation: the grid takes that role once a singular vertex is held (in the
  // first step), so wedge 0 is let go (unless it is a singular vertex's: on the grid already).
  std::vector<int> pending;
  for (size_t i = 0; i < values.wedges.size(); ++i) {
    if (!problem.fixed[values.wedges[i]]) {
      pending.push_back(static_cast<int>(i));
      continue;
    }
    const Eigen::Vector2d at = problem.positions.row(values.wedges[i]).transpose();
    if (!chooser.accept(relations.singular_value(static_cast<int>(i)), nearest_grid_point(at / h)))
      throw std::logic_error("integer-grid rounding: a held singular vertex cannot be completed");
    if (state.frame_wedge < 0) {  // on the grid already: the bordered rows' frame
      state.frame_wedge = values.wedges[i];
      state.frame_point = {at(0), at(1)};
    }
  }
  const bool release_anchor = !pending.empty() && pending.size() == values.wedges.size();
  out.singularities = static_cast<int>(pending.size());
  const std::vector<int> off_grid_singular = round_greedily(
      pending, state, chooser, X, [&](int i, const Eigen::MatrixXd& Y) { return values.singular(i, Y); },
      [&](int i) { return relations.singular_value(i); },
      [&](int i, const Eigen::Vector2d& point) { state.hold_vertex(values.wedges[i], h * point); }, solve,
      out.largest_rounding);
  out.singularities_off_grid = static_cast<int>(off_grid_singular.size());
  out.singularities -= out.singularities_off_grid;

  // 2. The branch translations.
  pending.clear();
  for (size_t i = 0; i < values.ends.size(); ++i) pending.push_back(static_cast<int>(i));
  out.translations = static_cast<int>(pending.size());
  const std::vector<int> off_grid_translations = round_greedily(
      pending, state, chooser, X, [&](int i, const Eigen::MatrixXd& Y) { return values.translation(i, Y); },
      [&](int i) { return relations.branch_value(i); },
      [&](int i, const Eigen::Vector2d& point) { state.hold_translation(values.ends[i], h * point); }, solve,
      out.largest_rounding);
  out.translations_off_grid = static_cast<int>(off_grid_translations.size());
  out.translations -= out.translations_off_grid;
  out.moved_past_nearest = chooser.moved_past_nearest;
  out.check_time_s = chooser.time_s;
  state.apply(problem, release_anchor);
  out.time_s = seconds_since(t0);
  if (progress) {
    char line[300];
    std::snprintf(line, sizeof line,
                  "integer grid: %d singular vertices and %d seam translations rounded (largest move %.3g grid "
                  "units; %d and %d left off the grid; %d moved past their nearest grid point by the exact "
                  "check, %.3f s), %d L2 solves (%d steps tried again), %.3f s",
                  out.singularities, out.translations, out.largest_rounding, out.singularities_off_grid,
                  out.translations_off_grid, out.moved_past_nearest, out.check_time_s, out.solves, out.retried_steps,
                  out.time_s);
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
