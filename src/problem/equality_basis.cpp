#include "strictmin/problem/equality_basis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace strictmin {
namespace {

// A dof as an affine combination of the still-independent dofs.
struct Expr {
  std::unordered_map<int, double> terms;
  double constant = 0;
};

class Eliminator {
 public:
  explicit Eliminator(const Problem& p) : expr_(static_cast<size_t>(p.num_vertices) * p.image_dim),
                                          users_(expr_.size()) {
    const int n = p.image_dim;
    for (int v = 0; v < p.num_vertices; ++v)
      for (int r = 0; r < n; ++r) {
        const int d = v * n + r;
        if (p.fixed[v]) {
          expr_[d].constant = p.positions(v, r);
        } else {
          expr_[d].terms[d] = 1.0;
          users_[d].insert(d);
        }
      }
  }

  // Substitutes the current expressions into sum a_d q_d = b; eliminates one dof.
  void add_row(const std::vector<std::pair<int, double>>& row, double b) {
    Expr sum;
    sum.constant = -b;
    for (auto [d, a] : row) {
      sum.constant += a * expr_[d].constant;
      for (auto [var, c] : expr_[d].terms) sum.terms[var] += a * c;
    }
    double largest = 0;
    for (auto it = sum.terms.begin(); it != sum.terms.end();) {
      if (std::abs(it->second) < 1e-13) {
        it = sum.terms.erase(it);
      } else {
        largest = std::max(largest, std::abs(it->second));
        ++it;
      }
    }
    if (sum.terms.empty()) {
      redundant_residual_ = std::max(redundant_residual_, std::abs(sum.constant));
      return;
    }
    int pivot = -1;
    for (auto [var, c] : sum.terms)
      if (std::abs(c) >= 0.5 * largest &&
          (pivot < 0 || users_[var].size() < users_[pivot].size() ||
           (users_[var].size() == users_[pivot].size() && var < pivot)))
        pivot = var;
    // pivot = -(sum of the other terms + constant) / c_pivot
    const double cp = sum.terms[pivot];
    Expr value;
    value.constant = -sum.constant / cp;
    for (auto [var, c] : sum.terms)
      if (var != pivot) value.terms[var] = -c / cp;
    substitute(pivot, value);
  }

  EqualityBasis finish() {
    EqualityBasis out;
    std::unordered_map<int, int> column;
    std::vector<int> vars;
    for (size_t d = 0; d < expr_.size(); ++d)
      for (auto [var, c] : expr_[d].terms) vars.push_back(var);
    std::sort(vars.begin(), vars.end());
    vars.erase(std::unique(vars.begin(), vars.end()), vars.end());
    for (size_t i = 0; i < vars.size(); ++i) column[vars[i]] = static_cast<int>(i);
    std::vector<Eigen::Triplet<double>> t;
    out.z0.resize(static_cast<Eigen::Index>(expr_.size()));
    for (size_t d = 0; d < expr_.size(); ++d) {
      out.z0(static_cast<Eigen::Index>(d)) = expr_[d].constant;
      for (auto [var, c] : expr_[d].terms) t.emplace_back(static_cast<int>(d), column[var], c);
    }
    out.Z.resize(static_cast<Eigen::Index>(expr_.size()), static_cast<Eigen::Index>(vars.size()));
    out.Z.setFromTriplets(t.begin(), t.end());
    out.redundant_residual = redundant_residual_;
    return out;
  }

 private:
  void substitute(int pivot, const Expr& value) {
    const std::vector<int> users(users_[pivot].begin(), users_[pivot].end());
    for (int d : users) {
      Expr& e = expr_[d];
      const double a = e.terms[pivot];
      e.terms.erase(pivot);
      e.constant += a * value.constant;
      for (auto [var, c] : value.terms) {
        double& slot = e.terms[var];
        slot += a * c;
        if (std::abs(slot) < 1e-13) {
          e.terms.erase(var);
          users_[var].erase(d);
        } else {
          users_[var].insert(d);
        }
      }
    }
    users_[pivot].clear();
  }

  std::vector<Expr> expr_;
  std::vector<std::unordered_set<int>> users_;  // var -> dofs whose expression uses it
  double redundant_residual_ = 0;
};

}  // namespace

EqualityBasis equality_basis(const Problem& p) {
  Eliminator elim(p);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> A = p.eq_matrix;
  std::vector<std::pair<int, double>> row;
  for (int r = 0; r < A.rows(); ++r) {
    row.clear();
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, r); it; ++it)
      row.emplace_back(static_cast<int>(it.col()), it.value());
    elim.add_row(row, p.eq_rhs[r]);
  }
  return elim.finish();
}

std::string equalities_contradiction(const Problem& p, const EqualityBasis& basis) {
  const double scale = 1.0 + (p.eq_rhs.size() ? p.eq_rhs.lpNorm<Eigen::Infinity>() : 0.0);
  if (!(basis.redundant_residual > 1e-9 * scale)) return "";
  char residual[32];
  std::snprintf(residual, sizeof residual, "%g", basis.redundant_residual);
  return std::string("the linear equalities contradict each other (residual ") + residual + ")";
}

}  // namespace strictmin
