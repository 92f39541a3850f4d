#include "strictmin/solvers/lp.h"

#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <vector>

#include "solvers/element_assembly.h"
#include "strictmin/problem/check_problem.h"
#include "strictmin/measures/field_deviation.h"
#include "strictmin/problem/equality_basis.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/sparse_cholesky.h"
#include "strictmin/io/input_error.h"
#include "strictmin/solvers/interrupt.h"
#include "option_check.h"

namespace strictmin {
namespace {

// sum_T A_T (||r_T|| / scale)^q for the residuals r = G x - h (blocks of nm entries).
double lp_energy(const Eigen::VectorXd& r, const Eigen::VectorXd& weights, int nm, double q, double scale) {
  double f = 0;
  for (Eigen::Index e = 0; e < weights.size(); ++e) f += weights(e) * std::pow(r.segment(e * nm, nm).norm() / scale, q);
  return f;
}

// With seams: the rows of Z (problem/equality_basis.h) for the free dofs, in free_dofs'
// layout. Newton steps dx = Zf dy keep every equality that the L2 start meets.
Eigen::SparseMatrix<double> free_basis(const Problem& p) {
  const EqualityBasis b = equality_basis(p);
  const std::vector<int> free = p.free_index();
  const int n = p.image_dim;
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < b.Z.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(b.Z, k); it; ++it) {
      const int v = static_cast<int>(it.row()) / n, r = static_cast<int>(it.row()) % n;
      if (free[v] >= 0) t.emplace_back(free[v] * n + r, static_cast<int>(it.col()), it.value());
    }
  Eigen::SparseMatrix<double> Z(static_cast<Eigen::Index>(p.num_free()) * n, b.Z.cols());
  Z.setFromTriplets(t.begin(), t.end());
  return Z;
}

}  // namespace

bool LpOptions::is_valid(std::string* why) const {
  return OptionCheck(why)
      .at_least("p", p, 2)
      .at_least("max_iterations", max_iterations, 1)
      .positive("tolerance", tolerance)
      .ok();
}

Result solve_lp(const Problem& p, const LpOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw InputError("lp: " + why);
  check_problem(p, "lp");
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  Result r = solve_l2(p);
  if (!r.ok() || options.p <= 2 || p.num_free() == 0) return r;

  const int nm = p.jacobian_size();
  const Problem::Reduced red = p.reduced();
  const ElementAssembler assembler(p);
  SparseCholesky cholesky;
  Eigen::SparseMatrix<double> H;
  Eigen::VectorXd x = p.free_dofs(r.positions);
  const bool seams = p.has_equalities();
  const Eigen::SparseMatrix<double> Zf = seams ? free_basis(p) : Eigen::SparseMatrix<double>();
  int iteration = 0;
  bool converged = true, zero = false;

  std::vector<double> stages;
  for (double q = 4; q < options.p; q *= 2) stages.push_back(q);
  stages.push_back(options.p);

  for (const double q : stages) {
    Eigen::VectorXd res = red.G * x - red.h;
    double scale = 0;
    for (int e = 0; e < p.num_elements(); ++e) scale = std::max(scale, res.segment(e * nm, nm).norm());
    // Every element at zero distortion to rounding (the distortion is dimensionless): nothing
    // to lower, and a Newton decrement relative to f = round-off never settled (an exact map
    // ran to the iteration cap at p = 4).
    if (!std::isfinite(scale)) {
      converged = false;
      r.status = SolveStatus::NumericalError;
      r.message = "L_p: the map's distortion is not finite";
      break;
    }
    if (!(scale > kZeroDistortion)) {
      zero = true;
      break;
    }
    bool stage_done = false;
    while (!stage_done && iteration < options.max_iterations) {
      check_interrupt();  // solvers/interrupt.h
      // Gradient and Hessian of f = sum A (s/K)^q with s = ||r_T||:
      // grad = sum c_T B^T r_T, Hessian = sum B^T c_T (I + (q-2) r r^T / s^2) B, c_T = A q s^(q-2) / K^q.
      const double f = lp_energy(res, p.weights, nm, q, scale);
      Eigen::VectorXd grad = Eigen::VectorXd::Zero(x.size());
      Eigen::VectorXd coef(p.num_elements());
      for (int e = 0; e < p.num_elements(); ++e) {
        const double s = res.segment(e * nm, nm).norm();
        coef(e) = p.weights(e) * q * std::pow(s / scale, q - 2) / (scale * scale);
        assembler.add_transpose_product(e, coef(e) * res.segment(e * nm, nm), grad);
      }
      assembler.assemble(
          [&](int e, Eigen::Ref<Eigen::MatrixXd> W) {
            const Eigen::VectorXd re = res.segment(e * nm, nm);
            const double s2 = re.squaredNorm();
            W.diagonal().setConstant(coef(e));
            if (s2 > 0) W.noalias() += coef(e) * (q - 2) / s2 * re * re.transpose();
          },
          H);
      // A tiny diagonal shift keeps H positive definite where elements reach D_T = 0.
      const double shift = 1e-12 * H.diagonal().cwiseAbs().maxCoeff();
      for (int i = 0; i < H.rows(); ++i) H.coeffRef(i, i) += shift;
      if (seams) {
        const Eigen::SparseMatrix<double> full = H.selfadjointView<Eigen::Lower>();
        H = (Eigen::SparseMatrix<double>(Zf.transpose()) * full * Zf).pruned();
      }
      if (!cholesky.analyzed()) cholesky.analyze(H);
      if (!cholesky.factorize(H)) {
        // The last accepted iterate stays: a usable map that stopped improving.
        r.status = SolveStatus::Stalled;
        r.message = "L_p: the Newton system is not positive definite at p = " + std::to_string(q);
        converged = false;
        break;
      }
      const Eigen::VectorXd dx = seams ? Eigen::VectorXd(-(Zf * cholesky.solve(Zf.transpose() * grad))) : Eigen::VectorXd(-cholesky.solve(grad));
      const double slope = grad.dot(dx);
      ++iteration;
      if (-slope / 2 <= options.tolerance * f) stage_done = true;
      // Backtracking (Armijo) line search on f.
      double t = 1;
      Eigen::VectorXd trial_res;
      for (int k = 0; k < 60; ++k, t *= 0.5) {
        trial_res = red.G * (x + t * dx) - red.h;
        if (lp_energy(trial_res, p.weights, nm, q, scale) <= f + 0.25 * t * slope) break;
      }
      x += t * dx;
      res = trial_res;
      IterationRecord rec;
      rec.iteration = iteration;
      for (int e = 0; e < p.num_elements(); ++e) rec.max_distortion = std::max(rec.max_distortion, res.segment(e * nm, nm).norm());
      rec.decrement = -slope / 2 / std::max(f, 1e-300);
      rec.time_s = elapsed();
      r.history.push_back(rec);
      if (options.progress) options.progress(rec);
    }
    if (!converged) break;
    if (!stage_done) {
      converged = false;
      r.status = SolveStatus::MaxIterations;
      r.message = "L_p: " + std::to_string(options.max_iterations) + " Newton iterations did not converge at p = " +
                  std::to_string(q);
      break;
    }
  }
  if (converged)
    r.message = zero ? "converged: the distortion is zero to rounding (the map is exact)"
                     : "converged: Newton decrement within tolerance at every p up to " + std::to_string(options.p);
  r.positions = p.with_free_dofs(x);
  r.distortion = field_deviation(p, r.positions);
  r.iterations = iteration;
  r.time_s = elapsed();
  return r;
}

}  // namespace strictmin
