#pragma once
// Sparse Cholesky (LL^T) of a symmetric matrix given by one triangle: CHOLMOD's supernodal
// symbolic analysis, then our numeric factorisation (supernodal_factor.h) and one-column
// substitutions (supernodal_solve.h) on it. The fill-reducing order is either the matrix's
// own (computed by the caller, e.g. ordering.h: CHOLMOD only postorders it), AMD, or
// CHOLMOD's default choice (AMD, METIS where AMD fills badly). Should the factor not suit our
// routines (it always does for the matrices CHOLMOD analyses here), CHOLMOD's own
// factorisation and solve are used.
//
// The pattern is analysed once; every factorisation only refills values.
#include <Eigen/SparseCore>
#include <cholmod.h>

#include <memory>
#include <vector>

namespace strictmin::socp {

class SupernodalFactor;

class SupernodalCholesky {
 public:
  enum class Ordering { Given, Amd, Cholmod };
  enum class Triangle { Upper, Lower };
  explicit SupernodalCholesky(Ordering ordering = Ordering::Given, Triangle triangle = Triangle::Upper);
  ~SupernodalCholesky();
  SupernodalCholesky(const SupernodalCholesky&) = delete;
  SupernodalCholesky& operator=(const SupernodalCholesky&) = delete;

  // The pattern (compressed, column major; kept by reference until the next analyze): only
  // the triangle given at construction is read. False when CHOLMOD cannot analyse it.
  bool analyze(const Eigen::SparseMatrix<double>& pattern);
  // values: the analysed matrix's values (same pattern). False when the matrix is not
  // (numerically) positive definite.
  bool factorize(const double* values);
  // x = A^-1 b in the matrix's order (x may alias b).
  void solve(const double* b, double* x) const;
  // x0 = A^-1 b0 and x1 = A^-1 b1 with one pass over the factor.
  void solve2(const double* b0, const double* b1, double* x0, double* x1) const;

  // The factor is of P A P^T with P from CHOLMOD's postorder: row k of P A P^T is row
  // permutation()[k] of A. In place, in that order: y <- L^-1 y and y <- L^-T y.
  const cholmod_factor& factor() const { return *L_; }
  const std::vector<int>& permutation() const { return perm_; }
  void forward_in_place(double* y) const;
  void backward_in_place(double* y) const;
  // The same for two right-hand sides, interleaved (y[2 k], y[2 k + 1]).
  void forward2_in_place(double* y) const;
  void backward2_in_place(double* y) const;

  double flops() const { return common_.fl; }      // of one factorisation
  double nonzeros() const { return common_.lnz; }  // nnz(L)

 private:
  void substitute(int system, int columns, double* y) const;
  void cholmod_solve_in_place(int system, double* y) const;
  void cholmod_solve2_in_place(int system, double* y) const;
  const Eigen::SparseMatrix<double>* pattern_ = nullptr;
  int stype_ = 1;  // CHOLMOD's: 1 upper, -1 lower
  mutable cholmod_common common_;
  cholmod_factor* L_ = nullptr;
  std::vector<int> perm_;
  std::unique_ptr<SupernodalFactor> numeric_;  // null: CHOLMOD's numeric factorisation
  bool own_solve_ = false;
};

}  // namespace strictmin::socp
