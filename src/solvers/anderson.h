#pragma once
// Anderson acceleration of a fixed-point iteration x -> G(x) (type II, as in Peng et al.
// 2018, "Anderson acceleration for geometry optimization and physics simulation"): from the
// last m residuals f_i = G(x_i) - x_i, the combination of the G(x_i) whose residual
// combination is least in the 2-norm. The caller decides whether to take it (safeguard).
#include <Eigen/Core>
#include <deque>

namespace strictmin {

class Anderson {
 public:
  explicit Anderson(int window) : window_(window) {}
  // x the current iterate, g = G(x). Returns the accelerated point, or g while there is no
  // history yet (the first call) or the least-squares problem is degenerate.
  Eigen::VectorXd mix(const Eigen::VectorXd& x, const Eigen::VectorXd& g);

 private:
  int window_;
  bool has_previous_ = false;
  Eigen::VectorXd previous_f_, previous_g_;
  std::deque<Eigen::VectorXd> df_, dg_;  // differences of successive residuals and images
};

}  // namespace strictmin
