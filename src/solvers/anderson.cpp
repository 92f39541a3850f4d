#include "anderson.h"

#include <Eigen/QR>

namespace strictmin {

Eigen::VectorXd Anderson::mix(const Eigen::VectorXd& x, const Eigen::VectorXd& g) {
  const Eigen::VectorXd f = g - x;
  if (has_previous_) {
    df_.push_back(f - previous_f_);
    dg_.push_back(g - previous_g_);
    if (static_cast<int>(df_.size()) > window_) {
      df_.pop_front();
      dg_.pop_front();
    }
  }
  has_previous_ = true;
  previous_f_ = f;
  previous_g_ = g;
  if (df_.empty()) return g;
  // gamma = argmin || f - dF gamma ||, then G(x) - dG gamma.
  const int k = static_cast<int>(df_.size());
  Eigen::MatrixXd dF(f.size(), k);
  for (int i = 0; i < k; ++i) dF.col(i) = df_[i];
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(dF);
  if (qr.rank() == 0) return g;
  const Eigen::VectorXd gamma = qr.solve(f);
  if (!gamma.allFinite()) return g;
  Eigen::VectorXd out = g;
  for (int i = 0; i < k; ++i) out -= gamma(i) * dg_[i];
  return out;
}

}  // namespace strictmin
