#pragma once
// The integer-grid rounding's exact check (docs/gparam.md, "Integer-grid maps"): which
// integer values can still be completed to an integer solution of every node relation
// (tasks/node_relations.h), given the values fixed so far. Private to the library.
//
// The integer solutions of A x = 0 are x = K z (K: a basis of A's integer kernel, from its
// column Hermite normal form, solvers/integer_hermite.h). Fixing values keeps the completable
// ones an affine lattice x = x0 + M z. Fixing value k at v asks M_k z = v - x0_k (its two
// rows): Euclid's column steps on M (unimodular: the same lattice) leave those rows in echelon
// form [a 0; b c], so the system is solvable iff a divides the first coordinate's difference
// and c what is left of the second; then x0 takes that solution and M drops the pivot
// columns (the rest is zero on value k's rows). The completable positions of a value not
// fixed yet are x0_k + (the lattice of M_k's columns), a coset of a sublattice of Z^2.
#include <Eigen/Core>
#include <vector>

#include "solvers/integer_hermite.h"

namespace strictmin {

// The completable positions of one value: p + Z u + Z v in Z^2 with u = (a, b), v = (0, c)
// (the echelon form; a = b = 0 or c = 0 when the lattice has rank below 2).
struct GridCoset {
  mpz_class p0, p1, a, b, c;
  bool contains(const Eigen::Vector2d& point) const;  // point: integer-valued
  // Its point nearest y (Euclidean distance).
  Eigen::Vector2d nearest(const Eigen::Vector2d& y) const;
};

class GridCompletion {
 public:
  // relations: two columns per value (NodeRelations::matrix).
  explicit GridCompletion(const IntegerMatrix& relations);

  GridCoset coset(int value) const;
  // Fixes value k at an integer point; false (nothing fixed) when no integer solution
  // has it there together with the values fixed so far.
  bool fix(int value, const Eigen::Vector2d& point);
  std::size_t size() const { return fixed_.size(); }
  void truncate(std::size_t count);  // keeps the first `count` values fixed
  int free_dimension() const { return static_cast<int>(m_.size()); }  // the rank of M

 private:
  std::vector<IntegerVector> kernel_;  // K, by columns
  IntegerVector x0_;
  std::vector<IntegerVector> m_;       // M, by columns
  std::vector<std::pair<int, Eigen::Vector2d>> fixed_;
};

}  // namespace strictmin
