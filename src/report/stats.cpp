#include "strictmin/report/stats.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace strictmin {

DistortionStats distortion_stats(const Eigen::VectorXd& d, const Eigen::VectorXd& w) {
  if (w.size() != d.size())
    throw std::invalid_argument("distortion_stats: " + std::to_string(d.size()) + " values and " +
                                std::to_string(w.size()) + " weights");
  DistortionStats s;
  s.elements = static_cast<int>(d.size());
  if (d.size() == 0) return s;
  double sum_w = 0, sum_wd = 0, sum_wd2 = 0;
  s.max = -std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    // A NaN value makes the maximum NaN (at the first such element): a comparison would skip it.
    if (!std::isnan(s.max) && (d(i) > s.max || std::isnan(d(i)))) {
      s.max = d(i);
      s.max_element = static_cast<int>(i);
    }
    sum_w += w(i);
    sum_wd += w(i) * d(i);
    sum_wd2 += w(i) * d(i) * d(i);
  }
  s.mean = sum_wd / sum_w;
  s.l2 = std::sqrt(sum_wd2 / sum_w);
  return s;
}

}  // namespace strictmin
