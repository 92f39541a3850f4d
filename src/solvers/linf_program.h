#pragma once
// The L-infinity problem as the cone program the interior-point method solves (private to
// solve_linf; docs/maths.md section 3):
//   free elements     ||G_T x - h_T|| <= k      (the first num_free_cones cones)
//   bounded elements  ||G_T x - h_T|| <= k_T    (the rest of the element cones)
//   constant elements k >= their largest D_T    (one scalar cone, when there are any)
//   the problem's equalities over the free dofs.
// and the figures of a candidate map x that the phases judge it by.
#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/linf.h"
#include "solvers/socp/cone_program.h"
#include "solvers/socp/fd_program.h"
#include "solvers/socp/settings.h"

namespace strictmin::linf_detail {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A number for messages (6 significant digits).
std::string format(double v);

// The interior-point settings of the options.
socp::IpmSettings ipm_settings(const LinfOptions& options);

// A starting k above every value: max + 10% + 1% of the scale.
inline double start_above(double max_value) {
  return max_value + 0.1 * std::abs(max_value) + 1e-2 * (1.0 + std::abs(max_value));
}

// A candidate map's figures: its k (largest free distortion, constants included) and by how
// much it misses the fixed bounds at worst (-inf: no bounded element).
struct Candidate {
  Eigen::VectorXd x;
  double kmax = -kInf, excess = -kInf;
};

struct MainProgram {
  MainProgram(const Problem& p, const LinfOptions& options, const socp::ElementClasses& classes);

  const Problem& problem;
  const LinfOptions& options;
  const socp::ElementClasses& cls;
  std::vector<int> elems;       // the program's element cones: free ones first, then bounded
  int num_free_cones = 0;
  bool has_kmin = false;        // the scalar cone k >= constant_max
  bool has_k = false;           // something bounds k (else every element is bounded)
  std::vector<int> vertex_dof;  // first dof of each free vertex, -1 for fixed ones
  int num_x = 0;
  socp::ConeProgram prog;

  // The largest distortion of a free element (constant ones included), from the cones'
  // distortions d at some x.
  double max_free(const Eigen::VectorXd& d) const;
  // Every bounded cone within the feasibility tolerance of its (possibly widened) bound.
  bool bounds_met(const Eigen::VectorXd& d) const;
  bool equalities_met(const Eigen::VectorXd& x) const;
  Candidate evaluate(const Eigen::VectorXd& x) const;
  // Raises every fixed bound by `amount` (a start that misses them by round-off only).
  void widen_bounds(double amount);
  // The largest fixed bound, at least 1: the scale of the bounds' tolerances.
  double bound_scale() const;
};

// x moved onto the program's equalities A x = b by the least-norm step (to round-off), or x
// itself when they hold exactly, when there are none, or when A A^T cannot be factored. The
// interior-point iterates keep A x = b only to the method's feasibility tolerance when they
// start off it (the steps stay in the null space once on it).
Eigen::VectorXd onto_equalities(const socp::ConeProgram& prog, Eigen::VectorXd x);

}  // namespace strictmin::linf_detail
