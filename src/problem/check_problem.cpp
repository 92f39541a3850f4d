#include "strictmin/problem/check_problem.h"

#include <cmath>
#include <vector>

#include "strictmin/io/input_error.h"

namespace strictmin {
namespace {

std::string rows_by_cols(Eigen::Index rows, Eigen::Index cols) {
  return std::to_string(rows) + " by " + std::to_string(cols);
}

// One array's shape against the documented one.
void check_shape(const std::string& who, const char* name, Eigen::Index rows, Eigen::Index cols, Eigen::Index want_rows,
                 Eigen::Index want_cols) {
  if (rows != want_rows || cols != want_cols)
    throw InputError(who + ": the problem's " + name + " is " + rows_by_cols(rows, cols) + ", expected " +
                     rows_by_cols(want_rows, want_cols));
}

void check_dimensions(const Problem& p, const std::string& who) {
  const int n = p.image_dim, m = p.domain_dim;
  if (!((n == 2 && m == 2) || (n == 3 && m == 3) || (n == 3 && m == 2)))
    throw InputError(who + ": image and domain dimensions must be 2 and 2, 3 and 3 or 3 and 2, got " +
                     std::to_string(n) + " and " + std::to_string(m));
  if (p.num_vertices < 0) throw InputError(who + ": negative vertex count " + std::to_string(p.num_vertices));
}

void check_elements(const Problem& p, const std::string& who) {
  const Eigen::Index E = p.elements.rows(), c = p.corners();
  if (E > 0) check_shape(who, "element array", E, p.elements.cols(), E, c);
  for (Eigen::Index e = 0; e < E; ++e)
    for (Eigen::Index j = 0; j < c; ++j) {
      const int v = p.elements(e, j);
      if (v < 0 || v >= p.num_vertices)
        throw InputError(who + ": element " + std::to_string(e) + " has vertex " + std::to_string(v) + ", outside 0.." +
                         std::to_string(p.num_vertices - 1));
    }
}

void check_element_arrays(const Problem& p, const std::string& who) {
  const Eigen::Index E = p.num_elements();
  check_shape(who, "gradients", p.gradients.rows(), p.gradients.cols(), E * p.corners(), p.domain_dim);
  check_shape(who, "targets", p.targets.rows(), p.targets.cols(), E * p.image_dim, p.domain_dim);
  if (p.weights.size() != E)
    throw InputError(who + ": the problem has " + std::to_string(p.weights.size()) + " weights for " +
                     std::to_string(E) + " elements");
  for (Eigen::Index e = 0; e < E; ++e) {
    const std::string element = "element " + std::to_string(e);
    if (!(std::isfinite(p.weights(e)) && p.weights(e) >= 0))
      throw InputError(who + ": " + element + "'s weight (its area or volume) is " + std::to_string(p.weights(e)) +
                       ", not a finite non-negative number");
    if (!p.gradients.middleRows(e * p.corners(), p.corners()).allFinite())
      throw InputError(who + ": " + element + "'s gradients are not finite (a degenerate element)");
    if (!p.targets.middleRows(e * p.image_dim, p.image_dim).allFinite())
      throw InputError(who + ": " + element + "'s target is not finite");
  }
}

void check_vertex_arrays(const Problem& p, const std::string& who) {
  if (static_cast<int>(p.fixed.size()) != p.num_vertices)
    throw InputError(who + ": the problem's fixed flags have " + std::to_string(p.fixed.size()) + " entries for " +
                     std::to_string(p.num_vertices) + " vertices");
  check_map(p, p.positions, who);
  for (Eigen::Index v = 0; v < p.positions.rows(); ++v)
    if (!p.positions.row(v).allFinite())
      throw InputError(who + ": vertex " + std::to_string(v) + "'s position is not finite");
}

void check_equalities(const Problem& p, const std::string& who) {
  if (p.eq_matrix.rows() == 0 && p.eq_rhs.size() == 0) return;
  const Eigen::Index dofs = static_cast<Eigen::Index>(p.image_dim) * p.num_vertices;
  if (p.eq_matrix.cols() != dofs)
    throw InputError(who + ": the equality matrix has " + std::to_string(p.eq_matrix.cols()) + " columns, expected " +
                     std::to_string(dofs) + " (image_dim times the vertex count)");
  if (p.eq_rhs.size() != p.eq_matrix.rows())
    throw InputError(who + ": " + std::to_string(p.eq_rhs.size()) + " right-hand sides for " +
                     std::to_string(p.eq_matrix.rows()) + " equality rows");
  if (!p.eq_rhs.allFinite()) throw InputError(who + ": an equality's right-hand side is not finite");
  const Eigen::SparseMatrix<double, Eigen::RowMajor> A = p.eq_matrix;
  for (Eigen::Index row = 0; row < A.rows(); ++row) {
    bool all_fixed = true;
    double residual = -p.eq_rhs(row), size = std::abs(p.eq_rhs(row));
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, row); it; ++it) {
      if (!std::isfinite(it.value()))
        throw InputError(who + ": equality row " + std::to_string(row) + " has a coefficient that is not finite");
      const Eigen::Index v = it.col() / p.image_dim, r = it.col() % p.image_dim;
      if (!p.fixed[v]) {
        all_fixed = false;
        continue;
      }
      residual += it.value() * p.positions(v, r);
      size += std::abs(it.value() * p.positions(v, r));
    }
    // Only fixed unknowns: nothing can make it hold if it does not already (to round-off).
    if (all_fixed && std::abs(residual) > 1e-9 * std::max(1.0, size))
      throw InputError(who + ": equality row " + std::to_string(row) +
                       " involves fixed vertices only and does not hold at their positions (residual " +
                       std::to_string(residual) + ")");
  }
}

// The copies of one point (relax's seam groups): copy_base's entries and copy_rotation's
// blocks are read by vertex index, so sizes and indices out of range read out of bounds.
void check_copies(const Problem& p, const std::string& who) {
  if (p.copy_base.empty()) return;
  if (static_cast<int>(p.copy_base.size()) != p.num_vertices)
    throw InputError(who + ": copy_base has " + std::to_string(p.copy_base.size()) + " entries for " +
                     std::to_string(p.num_vertices) + " vertices (empty, or one per vertex)");
  for (int v = 0; v < p.num_vertices; ++v)
    if (p.copy_base[v] < -1 || p.copy_base[v] >= p.num_vertices)
      throw InputError(who + ": copy_base of vertex " + std::to_string(v) + " is " + std::to_string(p.copy_base[v]) +
                       ", outside -1.." + std::to_string(p.num_vertices - 1));
  const Eigen::Index n = p.image_dim;
  check_shape(who, "copy_rotation", p.copy_rotation.rows(), p.copy_rotation.cols(), n * p.num_vertices, n);
  if (!p.copy_rotation.allFinite()) throw InputError(who + ": copy_rotation is not finite");
}

// A free vertex that no element and no equality involves has no position to find: every
// solver's system is singular there (they ended numerical-error without saying why).
void check_every_free_vertex_is_used(const Problem& p, const std::string& who) {
  std::vector<char> used(p.num_vertices, 0);
  for (Eigen::Index e = 0; e < p.elements.rows(); ++e)
    for (Eigen::Index j = 0; j < p.elements.cols(); ++j) used[p.elements(e, j)] = 1;
  for (int k = 0; k < p.eq_matrix.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(p.eq_matrix, k); it; ++it)
      if (it.value() != 0) used[it.col() / p.image_dim] = 1;
  for (int v = 0; v < p.num_vertices; ++v)
    if (!used[v] && !p.fixed[v])
      throw InputError(who + ": vertex " + std::to_string(v) +
                       " is free but belongs to no element and no equality, so nothing determines it (fix it, as "
                       "make_problem does)");
}

}  // namespace

void check_map(const Problem& p, const Eigen::MatrixXd& X, const std::string& who) {
  if (X.rows() != p.num_vertices || X.cols() != p.image_dim)
    throw InputError(who + ": the map is " + rows_by_cols(X.rows(), X.cols()) + ", expected " +
                     rows_by_cols(p.num_vertices, p.image_dim) + " (one row per vertex)");
}

void check_problem(const Problem& p, const std::string& who) {
  check_dimensions(p, who);
  check_elements(p, who);
  check_element_arrays(p, who);
  check_vertex_arrays(p, who);
  check_equalities(p, who);
  check_every_free_vertex_is_used(p, who);
  check_copies(p, who);
}

}  // namespace strictmin
