#pragma once
// L2 maps of a seamless problem under rows added and removed one by one, on one
// factorization: the integer-grid rounding's solves (tasks/integer_grid.h). Private to the
// library.
//
// The problem's own equalities are taken in complex form (problem/complex_equality_basis.h:
// z = Z y + z0, one complex unknown per node) and its L2 matrix K = Z^H K Z is factored once
// (src/solvers/l2_complex.h). Extra complex-linear rows sum_w a_w z_w = b, i.e. g y = c with
// g = a Z and c = b - a z0, make the bordered system
//   [K  G^H] [y     ]   [r]
//   [G  0  ] [lambda] = [c]
// which its Schur complement solves: y0 = K^-1 r, W = K^-1 G^H, S = G W,
// S lambda = G y0 - c, y = y0 - W lambda. Rows that depend on each other (the rounding's
// redundant ones) make S singular (then G^H lambda = 0 along its null space, so y does not
// depend on that part of lambda): S is solved by a rank-revealing decomposition, and the
// rows contradict each other when G y misses c by more than the tolerance.
//
// Only the positions of a few vertices are wanted (the rounding reads its singular wedges and
// branch ends), so y is formed on their nodes alone: a step costs one solve with K for the
// targets, one pass over the factor for the step's new rows (their columns of W, kept on
// those nodes while the row is) and a dense m x m decomposition (m: the rows so far, a few
// hundred). A fresh L2 solve of the problem with the rows costs a new equality basis,
// analysis and factorization instead (horse: 0.29 s a step).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <complex>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "strictmin/problem/problem.h"

namespace strictmin {

class ComplexL2;

class BorderedL2 {
 public:
  using Complex = std::complex<double>;
  struct Row {
    std::vector<std::pair<int, Complex>> terms;  // (vertex w, a_w); w among the watched
    Complex rhs;                                 // b
  };

  // Factors p's L2 matrix. `watched`: the vertices whose positions solve() returns, and the
  // only ones rows may name. ok() is false when p's equalities have no complex form (a
  // seamless problem always has one) or the matrix is not positive definite.
  BorderedL2(const Problem& p, const std::vector<int>& watched);
  ~BorderedL2();
  bool ok() const { return l2_ != nullptr; }

  void push(const Row& row);
  std::size_t size() const { return c_.size(); }
  void truncate(std::size_t count);  // drops the rows after the first `count`

  // The L2 map for the targets of p (the problem given at construction, with any targets)
  // that meets every row, #V by 2 with the watched vertices' rows set and NaN elsewhere; or
  // nothing when the rows miss their right-hand sides by more than `tolerance` (they
  // contradict each other).
  std::optional<Eigen::MatrixXd> solve(const Problem& p, double tolerance) const;

 private:
  struct Decomposition;
  const Decomposition& decomposition() const;
  void solve_new_rows() const;  // W's columns for the rows pushed since the last solve
  Eigen::VectorXcd rows_times(const Eigen::VectorXcd& y_local) const;  // G y (y on the local nodes)

  std::unique_ptr<ComplexL2> l2_;
  std::vector<int> watched_;
  std::vector<int> local_of_node_;  // node -> its index among the watched vertices' nodes (-1: none)
  std::vector<int> nodes_;          // local index -> node
  std::vector<std::vector<std::pair<int, Complex>>> g_;  // per row: a Z, on local nodes
  std::vector<Eigen::SparseVector<Complex>> g_full_;     // per row: a Z, on all nodes (for its W column)
  std::vector<Complex> c_;                               // per row: b - a z0
  mutable Eigen::MatrixXcd w_;        // local nodes by rows solved so far: K^-1 g^H on the local nodes
  mutable Eigen::Index w_rows_ = 0;   // how many rows w_ holds
  mutable std::unique_ptr<Decomposition> cached_;  // of S, for the rows as they are
};

}  // namespace strictmin
