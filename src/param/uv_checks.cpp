#include "strictmin/param/uv_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace strictmin {
namespace {

double orient(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

bool on_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= p.y() &&
         p.y() <= std::max(a.y(), b.y());
}

// Closed segments ab and cd touch or cross.
bool segments_meet(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) || (o3 == 0 && on_segment(c, d, a)) ||
         (o4 == 0 && on_segment(c, d, b));
}

}  // namespace

double signed_uv_area2(const Eigen::MatrixXi& F, const Eigen::MatrixXd& X, int f) {
  return orient(X.row(F(f, 0)).transpose(), X.row(F(f, 1)).transpose(), X.row(F(f, 2)).transpose());
}

int count_flips(const Eigen::MatrixXi& F, const Eigen::MatrixXd& X) {
  int positive = 0, negative = 0, zero = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const double a = signed_uv_area2(F, X, f);
    (a > 0 ? positive : a < 0 ? negative : zero)++;
  }
  return std::min(positive, negative) + zero;
}

bool polygon_self_intersects(const Eigen::MatrixXd& X, const std::vector<int>& loop) {
  const int n = static_cast<int>(loop.size());
  if (n < 4) return false;
  const auto point = [&](int i) -> Eigen::Vector2d { return X.row(loop[((i % n) + n) % n]).transpose(); };
  double length = 0;
  Eigen::Vector2d lo = point(0), hi = point(0);
  for (int i = 0; i < n; ++i) {
    length += (point(i + 1) - point(i)).norm();
    lo = lo.cwiseMin(point(i));
    hi = hi.cwiseMax(point(i));
  }
  // Cells about two average edges wide: each edge lands in a few cells, each cell holds a few edges.
  const double cell = std::max(2 * length / n, 1e-300);
  std::unordered_map<std::uint64_t, std::vector<int>> grid;
  const auto key = [](std::int64_t i, std::int64_t j) {
    return (static_cast<std::uint64_t>(i) << 32) ^ static_cast<std::uint64_t>(j & 0xffffffff);
  };
  for (int s = 0; s < n; ++s) {
    const Eigen::Vector2d a = point(s), b = point(s + 1);
    const auto i0 = static_cast<std::int64_t>(std::floor((std::min(a.x(), b.x()) - lo.x()) / cell));
    const auto i1 = static_cast<std::int64_t>(std::floor((std::max(a.x(), b.x()) - lo.x()) / cell));
    const auto j0 = static_cast<std::int64_t>(std::floor((std::min(a.y(), b.y()) - lo.y()) / cell));
    const auto j1 = static_cast<std::int64_t>(std::floor((std::max(a.y(), b.y()) - lo.y()) / cell));
    for (auto i = i0; i <= i1; ++i)
      for (auto j = j0; j <= j1; ++j) {
        auto& bucket = grid[key(i, j)];
        for (int t : bucket) {
          const int gap = std::abs(s - t);
          if (gap == 1 || gap == n - 1) continue;  // neighbours share a corner
          if (segments_meet(a, b, point(t), point(t + 1))) return true;
        }
        bucket.push_back(s);
      }
  }
  return false;
}

void orient_and_scale(const Eigen::MatrixXi& F, Eigen::MatrixXd& X, double surface_area) {
  int positive = 0, negative = 0;
  double area = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const double a = signed_uv_area2(F, X, f);
    positive += a > 0 ? 1 : 0;
    negative += a < 0 ? 1 : 0;
    area += std::abs(a) / 2;
  }
  if (negative > positive) X.col(0) = -X.col(0);
  const Eigen::RowVector2d centre = X.colwise().mean();
  const double s = area > 0 ? std::sqrt(surface_area / area) : 1.0;
  X = ((X.rowwise() - centre) * s).eval();
}

}  // namespace strictmin
