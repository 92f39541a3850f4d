#pragma once
// The Newton systems of the interior-point method, reduced to the normal equations
//
//   [ H + P   A~^T ] [dv]   [r1]      H = M^T W^{-2} M  over v = (x, k),
//   [ A~      0    ] [w ] = [r2],     A~ = [A 0],
//
// and solved with one sparse Cholesky factorisation per iteration (supernodal LLT on
// CHOLMOD's analysis, in our ordering: supernodal_cholesky.h, ordering.h):
// - H_xx (free dofs) has the sparsity of the vertex adjacency, n by n blocks per vertex pair:
//   element i adds (1/beta_i^2)(I_n (x) L_i + 2 p_i p_i^T), L_i its corners' gradient Gram
//   matrix and p_i = G_i^T v_i,1 (soc.h: W^{-2} = (1/beta^2)(2 v v^T - J)). The pattern is
//   built (in the fill-reducing order of the vertex graph) and analysed (supernodes) once;
//   every iteration only refills values.
// - k couples to every dof (a dense row and column). It is eliminated by bordering: one extra
//   solve per factorisation gives u = H_xx^{-1} h_xk and the Schur complement
//   S = h_kk - h_xk^T u, then every right-hand side costs one sparse solve.
// - Equalities in vertex-block form (the seams of global parametrization) are eliminated
//   exactly: dx = x_p + Z dy with Z a block null-space basis of A (null_space.h), and the
//   factorised matrix is Z^T (H_xx + P) Z over the y nodes' dofs (an element along a seam
//   spreads its pairs over its corners' terms). x_p (A x_p = r2) and the multipliers w come
//   from A A^T. Other equalities take a penalty (H_xx + A^T A / rho, pattern fixed).
// - A small static diagonal regularises H_xx. Each solve is refined by preconditioned
//   conjugate gradients on the normal equations (applied matrix-free through the cones, the
//   factor as preconditioner): near the optimum the matrix is so ill-conditioned that the
//   factor is accurate only up to a few directions, which CG removes in a few steps. With
//   penalised equalities, an outer refinement on the unreduced system removes the penalty's
//   effect.
#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "solvers/socp/cone_program.h"
#include "solvers/socp/cones.h"
#include "solvers/socp/null_space.h"
#include "solvers/socp/settings.h"
#include "solvers/socp/split_cholesky.h"
#include "solvers/socp/supernodal_cholesky.h"

namespace strictmin::socp {

// Where the linear algebra's time went (wall and process CPU seconds) and how often.
struct KktTimers {
  double analyze_wall = 0, analyze_cpu = 0;      // ordering, pattern, symbolic analysis (once)
  double assemble_wall = 0, assemble_cpu = 0;    // element contributions and gather
  double factorize_wall = 0, factorize_cpu = 0;  // CHOLMOD numeric factorisation (with retries)
  double border_wall = 0, border_cpu = 0;        // the k column's extra solve and Schur complement
  double solve_wall = 0, solve_cpu = 0;          // triangular solves (every right-hand side)
  double apply_wall = 0, apply_cpu = 0;          // matrix-free products (CG and residual checks)
  int factorizations = 0, solves = 0, applies = 0;
};

// A Newton direction: dv = (dx, dk), dy, and the cone parts ds, dz with their scaled forms
// dst = W^{-1} ds, dzt = W dz.
struct Direction {
  Eigen::VectorXd dx, dy, ds, dz, dst, dzt;
  double dk = 0;
  double residual = 0;  // relative residual of the Newton system reached
  int refinement = 0;   // refinement steps used
};

class NormalEquations {
 public:
  NormalEquations(const ConeProgram& program, const IpmSettings& settings);

  // Fills and factorises the matrix for the scaling (kept by reference until the next call).
  // False when the factorisation fails even after raising the regularisation.
  bool factor(const Scaling& scaling);

  // The Newton direction for the residuals of the current iterate (residuals.h) and the
  // linearised complementarity W^{-1} ds + W dz = q:
  //   -P dv + M^T dz + A~^T dy = r_d,   W^{-1} M dv + W dz = q + W^{-1} r_s,   A dx = -r_eq,
  //   ds = M dv - r_s.
  // Solved by the normal equations, then refined against this (unreduced) system, so that the
  // dual equations hold to round-off in G and dz (not in the far larger W^{-2}).
  // An empty rs stands for r_s = 0.
  // tolerance: relative residual the refinement aims at (<= 0: settings.refinement_tolerance);
  // the predictor and the centrality correctors need far less than the step's direction.
  // need_dy false (the predictor, which only sets sigma and the second-order term): d.dy is
  // left zero and, with eliminated equalities, an equality residual at round-off is not
  // corrected, which spares two products through the cones.
  void solve_newton(const Eigen::VectorXd& q, const Eigen::VectorXd& rs, const Eigen::VectorXd& rdx, double rdk,
                    const Eigen::VectorXd& req, Direction& d, double tolerance = 0, bool need_dy = true);

  // True when the last factorisation turned out unusable at its first solve (the bordering's
  // Schur complement not positive: see finish_bordering); the directions are then not finite.
  bool bordering_failed() const { return border_failed_; }
  double regularization() const { return delta_; }
  Eigen::Index matrix_nonzeros() const { return matrix_.nonZeros(); }
  double analyze_flops() const;  // CHOLMOD's flop count of one factorisation
  double factor_nonzeros() const;  // CHOLMOD's nnz(L)
  const KktTimers& timers() const { return timers_; }
  // Whether the equalities are eliminated (null_space.h) rather than penalised.
  bool eliminates_equalities() const { return elim_; }

 private:
  void build_pattern();
  // An element pair that spreads over several nonzeros (along the seams, with elimination):
  // its slot, the two y dofs (before the fill-reducing order) and the coefficient.
  struct SeamPair {
    int slot, a, b;
    double coef;
  };
  // The first system dof of a corner's vertex (dof base): itself, or with elimination the
  // first dof of its vertex's first y node (simple corners have just that one).
  int corner_dof(int base) const;
  std::vector<char> simple_elements() const;  // per element cone: its pairs map one to one
  std::vector<SeamPair> expand_seam_pairs(const std::vector<char>& simple) const;
  // The normal equations (H + P) dv + A~^T w = (r1x, r1k), A~ dv = r2 with the factor
  // (regularised, penalised equalities; w = -dy).
  void solve_normal(const Eigen::VectorXd& r1x, double r1k, const Eigen::VectorXd& r2, Eigen::VectorXd& dx,
                    double& dk, Eigen::VectorXd& w) const;
  // (ox, ok) = (H + P + A^T A / rho) (dx, dk), matrix-free through the cones; with
  // elimination Z^T (H + P) Z on the system's dofs.
  void apply_normal(const Eigen::VectorXd& dx, double dk, Eigen::VectorXd& ox, double& ok) const;
  // Preconditioned CG on that system until the residual (max norm) is below threshold;
  // returns the number of CG steps.
  int pcg(const Eigen::VectorXd& bx, double bk, double threshold, Eigen::VectorXd& x, double& k) const;
  // dv, w and dz for the residuals (rd, rc, re) of the unreduced system (rc scaled: W^{-1} row);
  // dz null: the caller forms it (with the direction's other cone parts, in one pass).
  void solve_unreduced(const Eigen::VectorXd& rdx, double rdk, const Eigen::VectorXd& rc, const Eigen::VectorXd& re,
                       Eigen::VectorXd& dx, double& dk, Eigen::VectorXd& w, Eigen::VectorXd* dz, double threshold,
                       int& steps, bool need_w = true) const;

  // (ox, ok) = (H + P) (dx, dk) on the program's dofs.
  void apply_full(const Eigen::VectorXd& dx, double dk, Eigen::VectorXd& ox, double& ok) const;
  Eigen::VectorXd to_dofs(const Eigen::VectorXd& y) const;  // Z y (y itself without elimination)
  void factor_aat();

  const ConeProgram& p_;
  const IpmSettings& settings_;
  const Scaling* scaling_ = nullptr;
  int npairs_ = 0;                         // local lower-triangle pairs per element
  Eigen::SparseMatrix<double> matrix_;     // H_xx (+ P + penalty + delta), upper triangle
  std::vector<int> slot_target_;           // #cones * npairs: nonzero index or -1
  std::vector<int> gather_offset_, gather_;  // nonzero -> slots
  std::vector<int> diagonal_;              // dof -> nonzero index of its diagonal
  Eigen::VectorXd p_values_, ata_values_;  // constant parts, by nonzero
  Eigen::VectorXd slot_values_, cone_k_;   // per-iteration element contributions
  Eigen::SparseMatrix<double, Eigen::RowMajor> at_;  // A^T (dofs by equalities)
  std::vector<int> perm_;                  // system dof -> row of matrix_ (fill-reducing order)
  // Elimination of the equalities: the basis, the system's size (y dofs, or num_x), the
  // element pairs that spread over several nonzeros, and A A^T's factor.
  BlockNullSpace null_space_;
  bool elim_ = false;
  int nsys_ = 0;
  struct ExtraSlot {
    int slot, target;
    double coef;
  };
  std::vector<ExtraSlot> extra_;
  std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> aat_;
  std::unique_ptr<SupernodalCholesky> cholesky_;  // the whole matrix (small problems)
  std::unique_ptr<SplitCholesky> split_;          // or its halves in parallel (large ones)
  int split_sizes_[3] = {0, 0, 0};         // dofs of the halves and the separator
  Eigen::VectorXd llt_solve(const Eigen::VectorXd& b) const;  // in dof numbering
  // Two right-hand sides with one pass over the factor.
  void llt_solve2(const Eigen::VectorXd& b0, const Eigen::VectorXd& b1, Eigen::VectorXd& x0,
                  Eigen::VectorXd& x1) const;
  // x = H_xx^{-1} b for the first right-hand side after a factorisation, solved together with
  // u = H_xx^{-1} h_xk, and the Schur complement S from u.
  void finish_bordering(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  double delta_ = 0, inv_rho_ = 0;
  Eigen::VectorXd diag_saved_;
  // k column and H_xx^{-1} h_xk, the Schur complement; u and S are computed with the first
  // solve after a factorisation (finish_bordering: mutable, filled in by a const solve).
  Eigen::VectorXd hxk_;
  mutable Eigen::VectorXd u_;
  double hkk_ = 0;
  mutable double schur_ = 1;
  mutable bool border_pending_ = false, border_failed_ = false;
  mutable KktTimers timers_;
};

}  // namespace strictmin::socp
