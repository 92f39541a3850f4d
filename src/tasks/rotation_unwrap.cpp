#include "strictmin/tasks/rotation_unwrap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <numeric>
#include <queue>
#include <utility>

#include "strictmin/measures/polar.h"

namespace strictmin {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Visits every element in BFS order, calling fix(element, parent) (parent -1 for the root
// of each connected part: its first element in `root_order`, by default 0, 1, 2, ...).
void breadth_first(const std::vector<std::vector<int>>& neighbours, const std::function<void(int, int)>& fix,
                   std::vector<int> root_order = {}) {
  const int E = static_cast<int>(neighbours.size());
  if (root_order.empty()) {
    root_order.resize(E);
    std::iota(root_order.begin(), root_order.end(), 0);
  }
  std::vector<char> seen(E, 0);
  std::queue<int> queue;
  for (int root : root_order) {
    if (seen[root]) continue;
    seen[root] = 1;
    fix(root, -1);
    queue.push(root);
    while (!queue.empty()) {
      const int e = queue.front();
      queue.pop();
      for (int f : neighbours[e])
        if (!seen[f]) {
          seen[f] = 1;
          fix(f, e);
          queue.push(f);
        }
    }
  }
}

}  // namespace

std::vector<std::vector<int>> element_neighbours(const Eigen::MatrixXi& F) {
  const int E = static_cast<int>(F.rows()), c = static_cast<int>(F.cols());
  // One sorted key per facet (the element minus one corner), then equal keys are neighbours.
  std::vector<std::pair<std::array<int, 3>, int>> facets;
  facets.reserve(static_cast<size_t>(E) * c);
  for (int e = 0; e < E; ++e)
    for (int skip = 0; skip < c; ++skip) {
      std::array<int, 3> key{-1, -1, -1};  // triangles: an edge and a -1
      for (int j = 0, k = 0; j < c; ++j)
        if (j != skip) key[k++] = F(e, j);
      std::sort(key.begin(), key.end());
      facets.emplace_back(key, e);
    }
  std::sort(facets.begin(), facets.end());
  std::vector<std::vector<int>> out(E);
  for (size_t i = 0; i < facets.size();) {
    size_t j = i + 1;
    while (j < facets.size() && facets[j].first == facets[i].first) ++j;
    for (size_t a = i; a < j; ++a)
      for (size_t b = a + 1; b < j; ++b)
        if (facets[a].second != facets[b].second) {
          out[facets[a].second].push_back(facets[b].second);
          out[facets[b].second].push_back(facets[a].second);
        }
    i = j;
  }
  return out;
}

Eigen::VectorXd unwrap_angles(const std::vector<std::vector<int>>& neighbours, const Eigen::VectorXd& angles) {
  Eigen::VectorXd out = angles;
  breadth_first(neighbours, [&](int e, int parent) {
    const double reference = parent < 0 ? 0.0 : out(parent);
    out(e) = angles(e) - kTwoPi * std::round((angles(e) - reference) / kTwoPi);
  });
  return out;
}

Eigen::MatrixXd unwrap_rotation_vectors(const std::vector<std::vector<int>>& neighbours, const Eigen::MatrixXd& w,
                                        int* jumps) {
  Eigen::MatrixXd out = w;
  if (jumps) *jumps = 0;
  breadth_first(neighbours, [&](int e, int parent) {
    if (parent < 0) return;
    const Eigen::Vector3d v = w.row(e).transpose(), reference = out.row(parent).transpose();
    const double angle = v.norm();
    if (angle < 1e-12) {  // the identity: its other logarithms are 2 pi k turns about any axis
      const double r = reference.norm();
      if (r > 0) out.row(e) = (kTwoPi * std::round(r / kTwoPi) / r) * reference.transpose();
      return;
    }
    const Eigen::Vector3d axis = v / angle;
    Eigen::Vector3d best = v;
    for (int k = -2; k <= 2; ++k) {
      const Eigen::Vector3d candidate = (angle + kTwoPi * k) * axis;
      if ((candidate - reference).norm() < (best - reference).norm()) best = candidate;
    }
    out.row(e) = best.transpose();
    if (jumps && (best - reference).norm() > std::numbers::pi) ++*jumps;
  });
  return out;
}

TreeRotationBlend::TreeRotationBlend(const std::vector<std::vector<int>>& neighbours,
                                     const std::vector<Eigen::Matrix3d>& rotations) {
  const int E = static_cast<int>(neighbours.size());
  parent_.assign(E, -1);
  order_.reserve(E);
  // Each part's root: its least turned element (its own rotation blended the short way), the
  // first of its part in the order of increasing angle.
  std::vector<double> angle(E);
  for (int e = 0; e < E; ++e) angle[e] = rotation_log(rotations[e]).norm();
  std::vector<int> by_angle(E);
  std::iota(by_angle.begin(), by_angle.end(), 0);
  std::stable_sort(by_angle.begin(), by_angle.end(), [&](int a, int b) { return angle[a] < angle[b]; });
  breadth_first(
      neighbours,
      [&](int e, int parent) {
        parent_[e] = parent;
        order_.push_back(e);
      },
      by_angle);
  logs_.resize(E, 3);
  for (int e : order_) {
    const Eigen::Matrix3d relative = parent_[e] < 0 ? rotations[e] : Eigen::Matrix3d(rotations[parent_[e]].transpose() * rotations[e]);
    logs_.row(e) = rotation_log(relative).transpose();
  }
}

std::vector<Eigen::Matrix3d> TreeRotationBlend::at(double t) const {
  std::vector<Eigen::Matrix3d> out(parent_.size());
  for (int e : order_) {
    const Eigen::Matrix3d step = rotation_exp(t * logs_.row(e).transpose());
    out[e] = parent_[e] < 0 ? step : Eigen::Matrix3d(out[parent_[e]] * step);
  }
  return out;
}

int count_disagreeing_neighbours(const std::vector<std::vector<int>>& neighbours,
                                 const std::vector<Eigen::Matrix3d>& rotations,
                                 const std::vector<Eigen::Matrix3d>& blended, double t, double angle) {
  int count = 0;
  for (size_t e = 0; e < neighbours.size(); ++e)
    for (int f : neighbours[e]) {
      if (f < static_cast<int>(e)) continue;
      const Eigen::Vector3d relative = rotation_log(rotations[e].transpose() * rotations[f]);
      const Eigen::Matrix3d proposed = blended[e] * rotation_exp(t * relative);
      if (rotation_log(proposed.transpose() * blended[f]).norm() > angle) ++count;
    }
  return count;
}

}  // namespace strictmin
