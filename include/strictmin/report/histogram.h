#pragma once
// Area-weighted distortion histograms: the share of the mesh (by area / volume) whose
// distortion falls in each bin, the quantity the paper's log-scale histograms show.
#include <Eigen/Core>
#include <vector>

namespace strictmin {

struct Histogram {
  double lo = 0, hi = 1;        // bins split [lo, hi] evenly
  std::vector<double> percent;  // per bin: share of the total weight, in percent (sums to 100)
  int bins() const { return static_cast<int>(percent.size()); }
  double bin_width() const { return (hi - lo) / bins(); }
  double edge(int i) const { return lo + i * bin_width(); }
};

// Bins `distortion` (#E) weighted by `weights` (#E, e.g. rest areas) into `bins` bins over
// [0, hi]. Values below 0 go in the first bin, values >= hi (+infinity, NaN) in the last one,
// so the shares always sum to 100 %. Throws std::invalid_argument on mismatched sizes,
// bins < 1, hi <= 0, a weight that is negative or not finite, or a total weight <= 0.
Histogram distortion_histogram(const Eigen::VectorXd& distortion, const Eigen::VectorXd& weights, double hi,
                               int bins = 40);

// Distortion values at or below this are zero to rounding in reports (an exact map's 1e-14).
inline constexpr double kZeroDistortionShown = 1e-9;

// A round upper end for histograms of these vectors: the largest finite value rounded up to
// 1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6 or 8 times a power of ten (at least `at_least`; 1 when
// nothing is finite or every value is zero to rounding).
double histogram_upper(const std::vector<const Eigen::VectorXd*>& distortions, double at_least = 0);

}  // namespace strictmin
