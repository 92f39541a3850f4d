#pragma once
// Sparse Cholesky L L^H of a complex Hermitian positive definite matrix (CHOLMOD's
// supernodal analysis in AMD order; the numeric factorization hermitian_factor.h, or
// CHOLMOD's with STRICTMIN_CHOLMOD_NUMERIC set; the substitutions complex_supernodal_solve.h,
// or CHOLMOD's with STRICTMIN_CHOLMOD_SOLVE set): the cross field's connection Laplacian
// factored as the complex F by F form, half the flops and a quarter of the entries of its
// 2F by 2F real form (docs/gparam.md, "The field"); also the L2 solve of seamless problems in
// complex form (src/solvers/l2_complex.h). Private to the library.
#include <Eigen/Core>
#include <complex>
#include <vector>

namespace strictmin {

// A Hermitian matrix by its lower triangle, column major: column j holds rows
// row[start[j] .. start[j+1]) (sorted, the diagonal first) with values value[...].
struct HermitianLower {
  int n = 0;
  std::vector<int> start, row;
  std::vector<std::complex<double>> value;
};

class HermitianCholesky {
 public:
  HermitianCholesky();
  ~HermitianCholesky();
  HermitianCholesky(const HermitianCholesky&) = delete;
  HermitianCholesky& operator=(const HermitianCholesky&) = delete;

  // AMD order and symbolic analysis of the pattern (kept when the pattern is the last
  // successful factorization's), then the numeric factorization. False when the matrix is
  // not (numerically) positive definite.
  bool factorize(const HermitianLower& A);
  // Before many solves: a copy of the factor without its stored zeros, which the
  // substitutions then read instead (complex_supernodal_solve.h; on horse's field the Lanczos
  // solves take 0.37 s instead of 0.57, the copy 0.02 s). Dropped by the next factorize().
  void compact_for_solves();
  // x = A^-1 b.
  Eigen::VectorXcd solve(const Eigen::VectorXcd& b) const;
  // x <- A^-1 x, without allocating (a workspace of the factor's: one solve at a time).
  void solve_in_place(Eigen::VectorXcd& x) const;
  // B <- A^-1 B for several right-hand sides (columns) at once: the factor is read once for
  // all of them where the compact factor is available (compact_for_solves), else column by column.
  void solve_many_in_place(Eigen::MatrixXcd& B) const;

  double analyze_s = 0, factorize_s = 0;  // wall seconds of the last factorize()

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace strictmin
