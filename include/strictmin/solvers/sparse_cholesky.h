#pragma once
// Sparse Cholesky (supernodal: CHOLMOD's symbolic analysis and fill-reducing order, our
// numeric factorisation and substitutions, src/solvers/socp/supernodal_cholesky.h) with the
// symbolic analysis kept: analyze() once per sparsity pattern, factorize() for every new
// matrix with that pattern (a matrix with another pattern is analysed again), solve() as
// often as needed. CHOLMOD stays behind the private implementation.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

namespace strictmin {

// While alive, keeps CHOLMOD's own OpenMP loops and OpenBLAS on one thread each.
// - Debian's CHOLMOD runs a few loops of its supernodal factorisation with a compiled-in 4
//   OpenMP threads (CHOLMOD_OMP_NUM_THREADS, no run-time control): on 2 cores that
//   oversubscribes, and on our normal equations (supernodes mostly 2 columns wide) the
//   fork/join and spinning cost more than the loops (100k square: 0.23 -> 0.15-0.20 s per
//   factorisation). OpenMP's max-active-levels is set to 0 for the calling thread.
// - OpenBLAS's own threads (by default one per core) fight with ours (TBB, the two halves
//   of SplitCholesky) for the same cores: 50k square, default threads against one, under
//   load: 30-36 s against 17-22 s wall, 3-4 s against 0.9 s system time. OpenBLAS is set to
//   one thread for the process while any scope is alive (a count: nested and concurrent
//   scopes are fine) and restored when the last one ends.
// Both are found at run time (dlsym) and are no-ops when absent.
class SerialCholmodScope {
 public:
  SerialCholmodScope();
  ~SerialCholmodScope();
  SerialCholmodScope(const SerialCholmodScope&) = delete;
  SerialCholmodScope& operator=(const SerialCholmodScope&) = delete;

 private:
  int saved_ = -1;
};

namespace socp {
class SupernodalCholesky;
}

class SparseCholesky {
 public:
  // amd_only: AMD for the fill-reducing order (no METIS: safe to run beside another thread's
  // METIS, whose random generator is global); otherwise CHOLMOD's default choice.
  explicit SparseCholesky(bool amd_only = false);
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // A is symmetric; only its lower triangle is read.
  void analyze(const Eigen::SparseMatrix<double>& A);
  // False when A is not (numerically) positive definite.
  bool factorize(const Eigen::SparseMatrix<double>& A);
  // A^{-1} B, two columns per pass over the factor.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  bool analyzed() const { return analyzed_; }

 private:
  bool same_pattern(const Eigen::SparseMatrix<double>& A) const;
  bool amd_only_ = false;
  Eigen::SparseMatrix<double> pattern_;  // compressed copy of the analysed matrix
  std::unique_ptr<socp::SupernodalCholesky> cholesky_;
  bool analyzed_ = false, factorized_ = false;
};

}  // namespace strictmin
