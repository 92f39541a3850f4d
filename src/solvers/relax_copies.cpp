// Relaxation (paper Algorithm 3) on a problem whose points have copies related by the
// seams' transitions (Problem::copy_base; docs/gparam.md, "relax with seams"). A group (the
// copies of one surface vertex) moves as one point q: copy v is R_v q + t_v with t_v held,
// so each element T of the group's ring still has D_T^2 = a_T ||q - R_v^T (c_T - t_v)||^2 + b_T
// and the 1-ring problem is the planar one (one_ring.h). Moving a group keeps every
// equality: every transition's translation is unchanged.
#include "relax_copies.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <vector>

#include <tbb/parallel_for.h>

#include "strictmin/measures/field_deviation.h"
#include "strictmin/solvers/interrupt.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/one_ring.h"
#include "strictmin/solvers/vertex_colouring.h"

namespace strictmin::relax_detail {
namespace {

struct RingEntry {
  int element, corner, copy;
};

struct Groups {
  std::vector<int> order;                  // group bases, colour by colour
  std::vector<int> colour_offsets;
  std::vector<std::vector<int>> members;   // per position in order
  std::vector<std::vector<RingEntry>> ring;
};

// Groups that may move: every copy free and the group's transitions closing (base >= 0).
Groups make_groups(const Problem& p) {
  const int V = p.num_vertices, c = p.corners();
  std::vector<char> held(V, 0);
  for (int v = 0; v < V; ++v) {
    const int b = p.copy_base[v] >= 0 ? p.copy_base[v] : v;
    if (p.copy_base[v] < 0 || p.fixed[v]) held[b] = 1;
  }
  Eigen::MatrixXi grouped(p.num_elements(), c);
  for (int e = 0; e < p.num_elements(); ++e)
    for (int j = 0; j < c; ++j) {
      const int v = p.elements(e, j);
      grouped(e, j) = p.copy_base[v] >= 0 ? p.copy_base[v] : v;
    }
  const VertexColouring col = colour_free_vertices(grouped, held);
  Groups g;
  g.order = col.order;
  g.colour_offsets = col.offsets;
  std::vector<int> position(V, -1);
  for (size_t i = 0; i < g.order.size(); ++i) position[g.order[i]] = static_cast<int>(i);
  g.members.resize(g.order.size());
  g.ring.resize(g.order.size());
  for (int v = 0; v < V; ++v)
    if (p.copy_base[v] >= 0 && position[p.copy_base[v]] >= 0) g.members[position[p.copy_base[v]]].push_back(v);
  for (int e = 0; e < p.num_elements(); ++e)
    for (int j = 0; j < c; ++j) {
      const int v = p.elements(e, j);
      if (p.copy_base[v] >= 0 && position[p.copy_base[v]] >= 0) g.ring[position[p.copy_base[v]]].push_back({e, j, v});
    }
  return g;
}

// True when `after` is below `before` in the strict order, values within tol counting equal.
// Sorts both in place.
bool strictly_better(std::vector<double>& before, std::vector<double>& after, double tol) {
  if (*std::max_element(after.begin(), after.end()) < *std::max_element(before.begin(), before.end()) - tol) return true;
  std::sort(before.rbegin(), before.rend());
  std::sort(after.rbegin(), after.rend());
  for (size_t i = 0; i < before.size(); ++i) {
    if (after[i] < before[i] - tol) return true;
    if (after[i] > before[i] + tol) return false;
  }
  return false;
}

Eigen::Matrix2d jacobian2(const Problem& p, int e, const Eigen::MatrixXd& X) {
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  for (int k = 0; k < 3; ++k) {
    const int v = p.elements(e, k);
    J.noalias() += Eigen::Vector2d(X(v, 0), X(v, 1)) * Eigen::RowVector2d(p.gradients(e * 3 + k, 0), p.gradients(e * 3 + k, 1));
  }
  return J;
}

Eigen::Matrix2d target2(const Problem& p, int e) {
  Eigen::Matrix2d R;
  R << p.targets(2 * e, 0), p.targets(2 * e, 1), p.targets(2 * e + 1, 0), p.targets(2 * e + 1, 1);
  return R;
}

Eigen::Matrix2d rotation2(const Problem& p, int v) {
  Eigen::Matrix2d R;
  R << p.copy_rotation(2 * v, 0), p.copy_rotation(2 * v, 1), p.copy_rotation(2 * v + 1, 0), p.copy_rotation(2 * v + 1, 1);
  return R;
}

// One group's 1-ring move; returns how far its base moved.
double move_group(const Problem& p, const Groups& g, size_t i, double accept_tolerance, Eigen::MatrixXd& X) {
  thread_local std::vector<RingTerm<2>> terms;
  thread_local std::vector<double> before, after;
  const int base = g.order[i];
  const Eigen::Vector2d q0(X(base, 0), X(base, 1));
  const auto& ring = g.ring[i];
  terms.resize(ring.size());
  before.resize(ring.size());
  after.resize(ring.size());
  for (size_t k = 0; k < ring.size(); ++k) {
    const auto [e, j, v] = ring[k];
    const Eigen::Matrix2d Rv = rotation2(p, v);
    const Eigen::Vector2d xv(X(v, 0), X(v, 1));
    const Eigen::Vector2d tv = xv - Rv * q0;
    const Eigen::Matrix2d D = jacobian2(p, e, X) - target2(p, e);
    const Eigen::Vector2d gj(p.gradients(e * 3 + j, 0), p.gradients(e * 3 + j, 1));
    before[k] = D.norm();
    // J - R_T = M + (R_v q + t_v) g^T with M the other corners' part; ||.|| = ||R_v^T (M + t_v g^T) + q g^T||.
    const Eigen::Matrix2d M = D - (xv - tv) * gj.transpose();
    terms[k] = ring_term<2>(Rv.transpose() * M, gj, 1.0 / gj.squaredNorm());
  }
  const RingSolution<2> s = solve_one_ring<2>(terms.data(), static_cast<int>(terms.size()));
  const double ring_max = *std::max_element(before.begin(), before.end());
  for (size_t k = 0; k < ring.size(); ++k)
    after[k] = std::sqrt(std::max(0.0, terms[k].a * (s.q - terms[k].centre).squaredNorm() + terms[k].b));
  if (!s.q.allFinite() || !strictly_better(before, after, accept_tolerance * ring_max)) return 0;
  for (int v : g.members[i]) {
    const Eigen::Vector2d d = rotation2(p, v) * (s.q - q0);
    X(v, 0) += d(0);
    X(v, 1) += d(1);
  }
  return (s.q - q0).norm();
}

}  // namespace

Result relax_with_copies(const Problem& p, const Eigen::MatrixXd& initial, const RelaxOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  const Groups g = make_groups(p);
  Result result;
  Eigen::MatrixXd X = initial;
  const int colours = static_cast<int>(g.colour_offsets.size()) - 1;
  bool moves_settled = false;
  for (int s = 1; s <= options.sweeps; ++s) {
    check_interrupt();  // solvers/interrupt.h
    double move = 0;
    for (int c = 0; c < colours; ++c) {
      std::vector<double> moved(g.colour_offsets[c + 1] - g.colour_offsets[c], 0.0);
      tbb::parallel_for(g.colour_offsets[c], g.colour_offsets[c + 1], [&](int i) {
        moved[i - g.colour_offsets[c]] = move_group(p, g, static_cast<size_t>(i), options.accept_tolerance, X);
      });
      for (double m : moved) move = std::max(move, m);
    }
    IterationRecord record;
    record.iteration = s;
    record.max_distortion = field_deviation(p, X).maxCoeff();
    record.largest_move = move;
    record.time_s = elapsed();
    if ((moves_settled = record_sweep(result, options, record))) break;
  }
  result.positions = std::move(X);
  result.distortion = field_deviation(p, result.positions);
  set_relax_status(result, options, moves_settled);
  result.time_s = elapsed();
  return result;
}

}  // namespace strictmin::relax_detail
