#pragma once
// What every solver returns (DESIGN.md "Result"): numerical outcomes are reported here,
// never thrown.
#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

namespace strictmin {

enum class SolveStatus { Solved, MaxIterations, NumericalError, Infeasible };

std::string status_name(SolveStatus s);  // "solved", "max-iterations", "numerical-error", "infeasible"

struct IterationRecord {
  int iteration = 0;
  double max_distortion = 0;  // primal objective (largest field deviation) after the iteration
  double lower_bound = std::numeric_limits<double>::quiet_NaN();  // certified, where there is one
  double gap = std::numeric_limits<double>::quiet_NaN();
  double time_s = 0;  // since the solve started
};

struct Result {
  Eigen::MatrixXd positions;  // #V by image_dim: the map
  Eigen::VectorXd distortion; // #E: field deviation ||J_T - R_T||_F of the map
  SolveStatus status = SolveStatus::Solved;
  std::string message;        // why, when status is not Solved
  int iterations = 0;
  double lower_bound = std::numeric_limits<double>::quiet_NaN();  // no map does better (linf)
  // linf: per element, the dual multiplier lambda_T of its constraint in the certificate of
  // lower_bound (0 for elements with every vertex fixed); over the free elements they sum to
  // 1, and every map x meeting the fixed bounds k_T has
  //   sum_free lambda_T D_T(x) + sum_bounded lambda_T (D_T(x) - k_T) >= lower_bound,
  // so a free element with lambda_T > 0 cannot drop below k by more than
  // (k - lower_bound) / lambda_T while the others stay at most k (strict_exact.cpp).
  Eigen::VectorXd multipliers;
  std::vector<IterationRecord> history;
  double time_s = 0;
  bool ok() const { return status == SolveStatus::Solved; }
};

}  // namespace strictmin
