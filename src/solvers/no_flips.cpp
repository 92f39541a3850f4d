#include "strictmin/solvers/no_flips.h"

#include <string>

#include "strictmin/measures/field_deviation.h"

#include <Eigen/LU>

namespace strictmin {
namespace {

bool positive(const Eigen::MatrixXd& J) { return J.rows() != J.cols() || J.determinant() > 0; }

}  // namespace

Eigen::VectorXi positively_oriented(const Problem& p, const Eigen::MatrixXd& X) {
  Eigen::VectorXi out(p.num_elements());
  for (int e = 0; e < p.num_elements(); ++e) out(e) = positive(p.jacobian(e, X)) ? 1 : 0;
  return out;
}

int flips_added(const Problem& p, const Eigen::MatrixXd& from, const Eigen::MatrixXd& to) {
  const Eigen::VectorXi before = positively_oriented(p, from), after = positively_oriented(p, to);
  int count = 0;
  for (int e = 0; e < p.num_elements(); ++e) count += before(e) == 1 && after(e) == 0 ? 1 : 0;
  return count;
}

Eigen::MatrixXd cut_back_to_no_new_flips(const Problem& p, const Eigen::MatrixXd& from, const Eigen::MatrixXd& to,
                                         double* fraction) {
  const Eigen::VectorXi before = positively_oriented(p, from);
  double t = 1;
  for (int halving = 0; halving <= 30; ++halving, t *= 0.5) {
    const Eigen::MatrixXd X = from + t * (to - from);
    bool adds = false;
    for (int e = 0; e < p.num_elements() && !adds; ++e) adds = before(e) == 1 && !positive(p.jacobian(e, X));
    if (!adds) {
      if (fraction) *fraction = t;
      return X;
    }
  }
  if (fraction) *fraction = 0;
  return from;
}

void cut_back_result(const Problem& problem, const Eigen::MatrixXd& start, Result& result) {
  if (!result.usable()) return;
  double fraction = 1;
  result.positions = cut_back_to_no_new_flips(problem, start, result.positions, &fraction);
  if (fraction == 1) return;
  result.distortion = field_deviation(problem, result.positions);
  result.status = worse_status(result.status, SolveStatus::Stalled);
  result.message += std::string(result.message.empty() ? "" : "; ") + "cut back to " + std::to_string(fraction) +
                    " of the step from the start to add no flip";
}

}  // namespace strictmin
