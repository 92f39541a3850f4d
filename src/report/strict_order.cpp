#include "strictmin/report/strict_order.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>

namespace strictmin {
namespace {

// Element indices sorted by decreasing value.
std::vector<int> descending(const Eigen::VectorXd& d) {
  std::vector<int> order(d.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int i, int j) { return d(i) > d(j); });
  return order;
}

// Advances `pos` over the values >= threshold; returns their total weight.
double take_level(const Eigen::VectorXd& d, const Eigen::VectorXd& w, const std::vector<int>& order, size_t& pos,
                  double threshold) {
  double area = 0;
  while (pos < order.size() && d(order[pos]) >= threshold) area += w(order[pos++]);
  return area;
}

}  // namespace

std::vector<DistortionLevel> distortion_levels(const Eigen::VectorXd& d, const Eigen::VectorXd& w, double tolerance) {
  if (w.size() != d.size())
    throw std::invalid_argument("distortion_levels: " + std::to_string(d.size()) + " values and " +
                                std::to_string(w.size()) + " weights");
  const std::vector<int> order = descending(d);
  std::vector<DistortionLevel> levels;
  size_t pos = 0;
  while (pos < order.size()) {
    DistortionLevel level;
    level.value = d(order[pos]);
    const size_t start = pos;
    level.area = take_level(d, w, order, pos, level.value - tolerance);
    level.count = static_cast<int>(pos - start);
    levels.push_back(level);
  }
  return levels;
}

StrictComparison compare_strict(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& w,
                                double value_tolerance, double area_tolerance) {
  if (a.size() != b.size() || w.size() != a.size())
    throw std::invalid_argument("compare_strict: the two distortion vectors and the weights must have one entry per "
                                "element (got " + std::to_string(a.size()) + ", " + std::to_string(b.size()) + ", " +
                                std::to_string(w.size()) + ")");
  const std::vector<int> oa = descending(a), ob = descending(b);
  const double area_eps = area_tolerance * w.sum();
  StrictComparison c;
  size_t ia = 0, ib = 0;
  for (int level = 0; ia < oa.size() || ib < ob.size(); ++level) {
    const double za = ia < oa.size() ? a(oa[ia]) : -INFINITY;
    const double zb = ib < ob.size() ? b(ob[ib]) : -INFINITY;
    c.value_a = za;
    c.value_b = zb;
    c.level = level;
    // Equal values tie (both infinite too: inf - inf is NaN, which ranked inf against inf).
    if (!(za == zb || std::abs(za - zb) <= value_tolerance)) {
      c.order = za < zb ? StrictOrder::Less : StrictOrder::Greater;
      c.by_value = true;
      c.area_a = ia < oa.size() ? w(oa[ia]) : 0.0;
      c.area_b = ib < ob.size() ? w(ob[ib]) : 0.0;
      return c;
    }
    const double threshold = std::max(za, zb) - value_tolerance;
    c.area_a = take_level(a, w, oa, ia, threshold);
    c.area_b = take_level(b, w, ob, ib, threshold);
    if (std::abs(c.area_a - c.area_b) > area_eps) {
      c.order = c.area_a < c.area_b ? StrictOrder::Less : StrictOrder::Greater;
      return c;
    }
  }
  return StrictComparison{};
}

std::string describe(const StrictComparison& c, const std::string& name_a, const std::string& name_b) {
  std::ostringstream s;
  if (c.order == StrictOrder::Equivalent) {
    s << name_a << " and " << name_b << " are equivalent (the same distortion distribution)";
    return s.str();
  }
  const bool less = c.order == StrictOrder::Less;
  s << (less ? name_a : name_b) << " is less distorting than " << (less ? name_b : name_a);
  if (c.by_value)
    s << ": at level " << c.level << " its distortion is " << (less ? c.value_a : c.value_b) << " against "
      << (less ? c.value_b : c.value_a);
  else
    s << ": at distortion " << c.value_a << " it covers area " << (less ? c.area_a : c.area_b) << " against "
      << (less ? c.area_b : c.area_a);
  return s.str();
}

}  // namespace strictmin
