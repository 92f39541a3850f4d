#pragma once
// Sparse Cholesky (CHOLMOD, supernodal, through Eigen's CholmodSupport) with the symbolic
// analysis kept: analyze() once per sparsity pattern, factorize() for every new matrix with
// that pattern, solve() as often as needed.
#include <Eigen/CholmodSupport>
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

class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // A is symmetric; only its lower triangle is read.
  void analyze(const Eigen::SparseMatrix<double>& A);
  // False when A is not (numerically) positive definite.
  bool factorize(const Eigen::SparseMatrix<double>& A);
  // A^{-1} B, column by column with one-column supernodal substitutions (socp/supernodal_solve.h:
  // no BLAS call per supernode, no allocation inside), or CHOLMOD's solve for other factors.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  bool analyzed() const { return analyzed_; }

 private:
  // Eigen's wrapper, with access to CHOLMOD's factor for our own substitutions.
  struct Llt : Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> {
    const cholmod_factor* factor() const { return this->m_cholmodFactor; }
  };
  std::unique_ptr<Llt> llt_;
  bool analyzed_ = false;
};

}  // namespace strictmin
