#pragma once
// A general second-order cone program with a sparse constraint matrix, for the cones of the
// paper's Section 7 measures (qc_program.h):
//
//   minimize c^T x   subject to   G x + s = h,   s in K = Q^{d_0} x Q^{d_1} x ...
//
// (a cone of dimension 1 is the half-line s >= 0). Unlike socp::ConeProgram (the field
// deviation's cones (a k + b, J - R), heads depending on k only, applied matrix-free with
// I_n (x) L normal blocks), a row of G may mix any variables: the quasiconformal cone
// |b_T(x)| <= k <a_T(x), r_T> + tau has a head linear in the map itself. Its normal
// equations G^T W^{-2} G have a fixed pattern, found once with each cone's slots in it and
// refilled in place every iteration (CHOLMOD's symbolic analysis once per pattern, kept in a
// SparseCholeskyCache across programs), and are solved by SparseCholesky.
//
// Method: primal-dual path following from an infeasible start, Nesterov-Todd scaling and
// Mehrotra's predictor-corrector (the algebra of socp/soc.h, the structure of CVXOPT's
// coneqp). The caller's monitor sees every iterate and may stop early (a feasibility test
// stops on the first iterate that settles its question).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace strictmin::qc {

struct SparseSocp {
  Eigen::SparseMatrix<double> G;  // #rows = sum of dims, by #x
  Eigen::VectorXd h, c;
  std::vector<int> dims;          // cone dimensions, in row order
};

struct SparseSocpSettings {
  int max_iterations = 80;
  double gap_tolerance = 1e-9;          // relative: gap <= tol * max(1, |pobj|)
  double feasibility_tolerance = 1e-9;  // relative primal and dual residuals
  double step_fraction = 0.99;
  double regularization = 1e-13;        // each diagonal entry raised by this fraction of itself (and 1e-6 of it of the largest)
  int refinement_steps = 3;             // iterative refinement of each normal solve
  bool verbose = false;                 // one line per iteration on stderr
};

struct SparseSocpIterate {
  int iteration = 0;
  const Eigen::VectorXd* x = nullptr;
  const Eigen::VectorXd* z = nullptr;
  double pobj = 0, dobj = 0, gap = 0;
  double pres = 0, dres = 0;  // relative residuals (max norm)
};

enum class SparseSocpStatus { Converged, Stopped, MaxIterations, NumericalError };

struct SparseSocpOutcome {
  SparseSocpStatus status = SparseSocpStatus::MaxIterations;
  int iterations = 0;
  Eigen::VectorXd x, s, z;
  double pobj = 0, dobj = 0, pres = 0, dres = 0;
  std::string message;
};

// Returns true to stop (the monitor's question is settled).
using SparseSocpMonitor = std::function<bool(const SparseSocpIterate&)>;

class SparseCholeskyCache;  // keeps the symbolic analysis between programs of one pattern

// x0: the starting x (warm start; s is moved inside the cones where G x0 misses them).
SparseSocpOutcome solve_sparse_socp(const SparseSocp& p, const Eigen::VectorXd& x0,
                                    const SparseSocpSettings& settings = {},
                                    const SparseSocpMonitor& monitor = nullptr,
                                    SparseCholeskyCache* cache = nullptr);

// A certified lower bound on the optimum from a dual iterate z that is only nearly feasible
// (G^T z + c = r != 0): z is corrected to z + dz with dz = -D G (G^T D G)^{-1} r, so that
// G^T (z + dz) + c = 0 exactly (to round-off); when z + dz lies in the cones, weak duality
// gives c^T x >= -h^T (z + dz) for every feasible x. D holds each cone's margin squared,
// (z_i0 - |z_i1|)^2: the least correction in that metric moves every cone by about the same
// fraction of its margin, so that cones with small multipliers (far from active) stay inside.
// Cones still left are raised back inside by twice their miss and the new residual corrected
// again (3 rounds at most). Returns -inf when no round ends inside the cones. One
// factorisation of G^T D G per round (analysis kept in the cache).
// head_bounds B (one per cone, or empty): cone i's head s_i0 is <= B_i on every feasible x
// that matters (the caller's: e.g. those with an objective no larger than a known value, see
// iso_level); then a corrected z still out of some cones also bounds: raised by exactly its
// misses it is in the cones, and c^T x >= -h^T z - sum_i B_i miss_i for those x (the best
// over the rounds is returned).
double corrected_dual_bound(const SparseSocp& p, const Eigen::VectorXd& z, SparseCholeskyCache* cache,
                            const Eigen::VectorXd& head_bounds = Eigen::VectorXd());

class SparseCholeskyCache {
 public:
  SparseCholeskyCache();
  ~SparseCholeskyCache();
  SparseCholeskyCache(const SparseCholeskyCache&) = delete;  // owns impl_
  SparseCholeskyCache& operator=(const SparseCholeskyCache&) = delete;
  struct Impl;
  Impl& impl() { return *impl_; }

 private:
  Impl* impl_;
};

}  // namespace strictmin::qc
