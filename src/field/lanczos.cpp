#include "field/lanczos.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "strictmin/solvers/interrupt.h"

namespace strictmin {

LanczosResult lanczos_smallest(const HermitianCholesky& A, const Eigen::VectorXd& mass, const Eigen::VectorXcd& x0,
                               int max_steps, double tolerance) {
  using Complex = std::complex<double>;
  const Eigen::VectorXcd m = mass.cast<Complex>();
  auto m_norm = [&](const Eigen::VectorXcd& v) { return std::sqrt(mass.dot(v.cwiseAbs2())); };
  max_steps = std::max(1, max_steps);
  // The M-orthonormal basis, grown 16 columns at a time.
  Eigen::MatrixXcd V(x0.size(), std::min(max_steps, 16));
  V.col(0) = x0 / m_norm(x0);
  std::vector<double> alpha, beta;
  Eigen::VectorXd s;
  LanczosResult out;
  Eigen::VectorXcd w(x0.size()), mw(x0.size());  // kept: no allocation per step
  for (int j = 0; j < max_steps; ++j) {
    check_interrupt();  // solvers/interrupt.h
    w = m.cwiseProduct(V.col(j));
    A.solve_in_place(w);
    ++out.steps;
    // The three-term recurrence (alpha_j real: T is M-self-adjoint), then one classical
    // Gram-Schmidt pass against the whole basis ("twice is enough": the recurrence is the
    // first pass, the full one keeps the basis orthogonal to rounding).
    alpha.push_back(V.col(j).dot(m.cwiseProduct(w)).real());
    w -= alpha.back() * V.col(j);
    if (j > 0) w -= beta[j - 1] * V.col(j - 1);
    const auto basis = V.leftCols(j + 1);
    mw = m.cwiseProduct(w);
    const Eigen::VectorXcd c = basis.adjoint() * mw;
    w.noalias() -= basis * c;
    beta.push_back(m_norm(w));
    // The Ritz pair of the tridiagonal matrix's largest eigenvalue.
    const int k = j + 1;
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(k, k);
    for (int i = 0; i < k; ++i) {
      T(i, i) = alpha[i];
      if (i + 1 < k) T(i, i + 1) = T(i + 1, i) = beta[i];
    }
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(T);
    const double theta = eig.eigenvalues()(k - 1);
    s = eig.eigenvectors().col(k - 1);
    out.residual = beta.back() * std::abs(s(k - 1)) / theta;
    if (out.residual <= tolerance || !(beta.back() > 0) || k >= max_steps) break;
    if (V.cols() == k) V.conservativeResize(Eigen::NoChange, std::min<Eigen::Index>(max_steps, 2 * k));
    V.col(k) = w / beta.back();
  }
  out.vector = V.leftCols(s.size()) * s.cast<Complex>();
  if (out.vector.dot(m.cwiseProduct(x0)).real() < 0) out.vector = -out.vector;
  out.vector /= m_norm(out.vector);
  return out;
}

}  // namespace strictmin
