#pragma once
// Summary statistics of a per-element distortion vector.
#include <Eigen/Core>

namespace strictmin {

struct DistortionStats {
  double max = 0;         // largest value (+inf when some element is infinite, e.g. qc of a flip;
                          // NaN when some element is NaN)
  double l2 = 0;          // area-weighted RMS: sqrt(sum A_T D_T^2 / sum A_T)
  double mean = 0;        // area-weighted mean
  int max_element = -1;   // index of the largest value
  int flipped = 0;        // elements with det J <= 0; -1: not defined (a surface in 3D, 3x2 Jacobians)
  int elements = 0;
};

// flipped is filled by the caller (it needs the Jacobians, not the distortion).
DistortionStats distortion_stats(const Eigen::VectorXd& distortion, const Eigen::VectorXd& weights);

}  // namespace strictmin
