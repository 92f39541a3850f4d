#include "strictmin/report/histogram.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace strictmin {

Histogram distortion_histogram(const Eigen::VectorXd& d, const Eigen::VectorXd& w, double hi, int bins) {
  if (d.size() != w.size()) throw std::invalid_argument("distortion_histogram: distortion and weights differ in size");
  if (bins < 1) throw std::invalid_argument("distortion_histogram: bins must be >= 1");
  if (!(hi > 0) || !std::isfinite(hi)) throw std::invalid_argument("distortion_histogram: hi must be finite and > 0");
  Histogram h;
  h.lo = 0;
  h.hi = hi;
  h.percent.assign(bins, 0.0);
  double total = 0;
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    if (!(std::isfinite(w(i)) && w(i) >= 0))
      throw std::invalid_argument("distortion_histogram: weight " + std::to_string(i) + " is not a finite non-negative number");
    const double x = d(i);
    int b = bins - 1;
    if (!std::isnan(x) && x < hi) b = std::clamp(static_cast<int>(std::floor(x / hi * bins)), 0, bins - 1);
    h.percent[b] += w(i);
    total += w(i);
  }
  if (!(total > 0)) throw std::invalid_argument("distortion_histogram: total weight must be > 0");
  for (double& p : h.percent) p *= 100.0 / total;
  return h;
}

double histogram_upper(const std::vector<const Eigen::VectorXd*>& distortions, double at_least) {
  double top = at_least;
  for (const Eigen::VectorXd* d : distortions)
    for (Eigen::Index i = 0; i < d->size(); ++i)
      if (std::isfinite((*d)(i))) top = std::max(top, (*d)(i));
  // Distortion at rounding level (1e-14 on an exact map) is zero: an axis up to 2e-14 drew
  // its noise as a full histogram.
  if (!(top > kZeroDistortionShown)) return 1.0;
  const double p = std::pow(10.0, std::floor(std::log10(top)));
  for (double m : {1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0})
    if (m * p >= top * (1 + 1e-12)) return m * p;
  return 10 * p;
}

}  // namespace strictmin
