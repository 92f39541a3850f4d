#include "solvers/strict_pinning.h"

#include <algorithm>
#include <cmath>

#include "mesh/union_find.h"

namespace strictmin {

int PinnedElements::pin_essential(const Eigen::VectorXd& bounds, const Eigen::VectorXd& multipliers,
                                  double threshold) {
  int now = 0;
  for (Eigen::Index e = 0; e < multipliers.size(); ++e)
    if (!pinned_[e] && bounds(e) >= 0 && multipliers(e) >= threshold) {
      pinned_[e] = 1;
      ++now;
    }
  count_ += now;
  return now;
}

PinnedLevel PinnedElements::level_problem(const Problem& p, const std::vector<char>& moving,
                                          const Eigen::MatrixXd& X) const {
  const int V = p.num_vertices, E = p.num_elements(), c = p.corners(), n = p.image_dim;
  // Groups: vertices joined by pinned elements.
  UnionFind groups(V);
  std::vector<char> grouped(V, 0);
  for (int e = 0; e < E; ++e)
    if (pinned_[e])
      for (int j = 0; j < c; ++j) {
        grouped[p.elements(e, j)] = 1;
        groups.unite(p.elements(e, 0), p.elements(e, j));
      }
  // A group touching a vertex that does not move is held still.
  std::vector<char> held(V, 0);
  for (int v = 0; v < V; ++v)
    if (grouped[v] && (p.fixed[v] || !moving[v])) held[groups.find(v)] = 1;
  std::vector<char> movable(V, 0);
  for (int v = 0; v < V; ++v) movable[v] = moving[v] && !(grouped[v] && held[groups.find(v)]);
  std::vector<char> kept(E, 0);
  for (int e = 0; e < E; ++e) kept[e] = !pinned_[e];

  PinnedLevel out;
  out.sub = restrict_to_movable(p, movable, X, &kept);
  // The free groups: one root among each group's vertices in the sub-problem, a translation
  // equality (n rows) per other member there, and every member for the translation after.
  std::vector<int> local(V, -1);
  for (size_t i = 0; i < out.sub.vertex.size(); ++i) local[out.sub.vertex[i]] = static_cast<int>(i);
  std::vector<int> group_of_root(V, -1);
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<double> rhs;
  auto tie = [&](int v, int to) {  // q_v - q_to = X_v - X_to, n rows
    for (int r = 0; r < n; ++r) {
      const int row = static_cast<int>(rhs.size());
      triplets.emplace_back(row, local[v] * n + r, 1.0);
      triplets.emplace_back(row, local[to] * n + r, -1.0);
      rhs.push_back(X(v, r) - X(to, r));
    }
  };
  // Members of the free groups: each group's root and its members outside the sub-problem.
  std::vector<char> in_free_group(V, 0);
  for (int v = 0; v < V; ++v) {
    if (!grouped[v] || !movable[v]) continue;
    in_free_group[v] = 1;
    const int g = groups.find(v);
    if (group_of_root[g] < 0) {
      group_of_root[g] = static_cast<int>(out.groups.size());
      out.groups.push_back({});
    }
    PinnedLevel::Group& group = out.groups[group_of_root[g]];
    if (local[v] < 0) {
      group.outside.push_back(v);
    } else if (group.root < 0) {
      group.root = v;
      group.root_local = local[v];
      group.root_start = X.row(v);
    }
  }
  // The rows follow a spanning forest of the members in the sub-problem along the pinned
  // elements' edges (a star on the root would make A A^T dense over a large group: the
  // equalities' least squares factor it), and each tree's root is tied to its group's root.
  std::vector<std::vector<int>> adjacent(V);
  for (int e = 0; e < E; ++e) {
    if (!pinned_[e]) continue;
    for (int i = 0; i < c; ++i)
      for (int j = i + 1; j < c; ++j) {
        const int a = p.elements(e, i), b = p.elements(e, j);
        if (in_free_group[a] && in_free_group[b] && local[a] >= 0 && local[b] >= 0) {
          adjacent[a].push_back(b);
          adjacent[b].push_back(a);
        }
      }
  }
  std::vector<char> reached(V, 0);
  std::vector<int> queue;
  for (int start = 0; start < V; ++start) {
    if (!in_free_group[start] || local[start] < 0 || reached[start]) continue;
    // The root is its group's first member in the sub-problem, so its tree comes first.
    const int root = out.groups[group_of_root[groups.find(start)]].root;
    if (start != root) tie(start, root);
    reached[start] = 1;
    queue.assign(1, start);
    for (size_t head = 0; head < queue.size(); ++head)
      for (int w : adjacent[queue[head]])
        if (!reached[w]) {
          reached[w] = 1;
          tie(w, queue[head]);
          queue.push_back(w);
        }
  }
  Problem& s = out.sub.problem;
  if (p.has_equalities()) {
    // The problem's own equalities (gparam's seams) on the level: a member of a free group
    // outside the sub-problem moves with its group's root (q_v = q_root + X_v - X_root), a
    // vertex neither inside nor in a free group stays at X. Rows with nothing left to move go;
    // rows that the translations make redundant but not empty stay (the null space drops
    // them, null_space.h).
    std::vector<int> root_of(V, -1);
    for (const PinnedLevel::Group& group : out.groups)
      if (group.root >= 0)
        for (int v : group.outside) root_of[v] = group.root;
    const Eigen::SparseMatrix<double, Eigen::RowMajor> A = p.eq_matrix;
    std::vector<Eigen::Triplet<double>> own;
    std::vector<double> own_rhs;
    std::vector<std::pair<int, double>> terms, merged;  // (level column, coefficient) of one row
    for (int row = 0; row < A.rows(); ++row) {
      double b = p.eq_rhs[row];
      terms.clear();
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, row); it; ++it) {
        const int v = static_cast<int>(it.col()) / n, r = static_cast<int>(it.col()) % n;
        const int w = local[v] >= 0 ? v : root_of[v];
        if (w < 0) {
          b -= it.value() * X(v, r);
          continue;
        }
        if (w != v) b -= it.value() * (X(v, r) - X(w, r));
        terms.emplace_back(local[w] * n + r, it.value());
      }
      // Two corners on one root add up; a seam edge inside one group on both sides cancels.
      std::sort(terms.begin(), terms.end());
      merged.clear();
      for (const auto& [column, value] : terms)
        if (!merged.empty() && merged.back().first == column)
          merged.back().second += value;
        else
          merged.emplace_back(column, value);
      bool moves = false;
      for (const auto& [column, value] : merged) moves = moves || (value != 0 && !s.fixed[column / n]);
      if (!moves) continue;
      for (const auto& [column, value] : merged)
        if (value != 0) own.emplace_back(static_cast<int>(own_rhs.size()), column, value);
      own_rhs.push_back(b);
    }
    // Own rows first, the translation rows after them.
    const int m = static_cast<int>(own_rhs.size());
    for (auto& t : triplets) t = Eigen::Triplet<double>(t.row() + m, t.col(), t.value());
    triplets.insert(triplets.end(), own.begin(), own.end());
    own_rhs.insert(own_rhs.end(), rhs.begin(), rhs.end());
    rhs = std::move(own_rhs);
  }
  if (!rhs.empty()) {
    s.eq_matrix.resize(static_cast<Eigen::Index>(rhs.size()), static_cast<Eigen::Index>(s.num_vertices) * n);
    s.eq_matrix.setFromTriplets(triplets.begin(), triplets.end());
    s.eq_rhs = Eigen::Map<const Eigen::VectorXd>(rhs.data(), static_cast<Eigen::Index>(rhs.size()));
  } else if (p.has_equalities()) {
    s.eq_matrix.resize(0, static_cast<Eigen::Index>(s.num_vertices) * n);
    s.eq_rhs.resize(0);
  }
  return out;
}

void PinnedLevel::scatter(const Eigen::MatrixXd& level_positions, Eigen::MatrixXd& positions) const {
  for (size_t i = 0; i < sub.vertex.size(); ++i)
    positions.row(sub.vertex[i]) = level_positions.row(static_cast<Eigen::Index>(i));
  // Members of a free group outside the sub-problem (every element around them pinned)
  // follow their group's translation.
  for (const Group& group : groups) {
    if (group.root_local < 0 || group.outside.empty()) continue;
    const Eigen::RowVectorXd shift = level_positions.row(group.root_local) - group.root_start;
    for (int v : group.outside) positions.row(v) += shift;
  }
}

Result solve_on_level(const Problem& p, const PinnedLevel& level, const Eigen::VectorXd& bounds,
                      const Result& previous, const LinfOptions& linf, const LevelSolver& solve,
                      std::vector<int>* immobile_free, Eigen::MatrixXd* duals, Eigen::MatrixXd* level_duals) {
  const Subproblem& sub = level.sub;
  const int E = p.num_elements();
  std::vector<char> in_level(E, 0);
  for (int e : sub.element) in_level[e] = 1;
  // The level's free elements that cannot move bound its optimum from below.
  double immobile = -INFINITY;
  if (immobile_free) immobile_free->clear();
  for (int e = 0; e < E; ++e) {
    if (bounds(e) >= 0 || in_level[e]) continue;
    bool movable = false;
    for (int j = 0; j < p.corners() && !movable; ++j) movable = !p.fixed[p.elements(e, j)];
    if (!movable) continue;
    immobile = std::max(immobile, previous.distortion(e));
    if (immobile_free) immobile_free->push_back(e);
  }
  Result full = previous;
  full.multipliers = Eigen::VectorXd::Zero(E);
  full.history.clear();
  if (sub.problem.num_free() == 0) {
    full.status = SolveStatus::Solved;
    full.message = "no vertex can move: the map in hand is the level's optimum";
    full.iterations = 0;
    full.lower_bound = immobile_free ? 0.0 : std::max(0.0, immobile);
    return full;
  }
  LinfOptions o = linf;
  o.element_bounds.resize(static_cast<Eigen::Index>(sub.element.size()));
  for (size_t i = 0; i < sub.element.size(); ++i) o.element_bounds[static_cast<Eigen::Index>(i)] = bounds(sub.element[i]);
  const bool move_duals = duals && level_duals;
  const auto n_level = static_cast<Eigen::Index>(sub.element.size());
  if (move_duals) {
    level_duals->resize(n_level, duals->cols());
    for (Eigen::Index i = 0; i < n_level; ++i) level_duals->row(i) = duals->row(sub.element[i]);
  }
  Result r = solve(sub.problem, o, sub.problem.positions);
  if (move_duals && level_duals->rows() == n_level) {
    duals->setConstant(NAN);  // the elements left out have none from this level
    for (Eigen::Index i = 0; i < n_level; ++i) duals->row(sub.element[i]) = level_duals->row(i);
  }
  full.status = r.status;
  full.message = r.message;
  full.iterations = r.iterations;
  full.lower_bound = immobile_free ? r.lower_bound : std::max(r.lower_bound, immobile);
  full.history = r.history;
  full.time_s = r.time_s;
  if (r.positions.rows() == sub.problem.num_vertices) level.scatter(r.positions, full.positions);
  const auto n_sub = static_cast<Eigen::Index>(sub.element.size());
  if (r.distortion.size() == n_sub)
    for (Eigen::Index i = 0; i < n_sub; ++i) full.distortion[sub.element[i]] = r.distortion[i];
  if (r.multipliers.size() == n_sub)
    for (Eigen::Index i = 0; i < n_sub; ++i) full.multipliers[sub.element[i]] = r.multipliers[i];
  return full;
}

}  // namespace strictmin
