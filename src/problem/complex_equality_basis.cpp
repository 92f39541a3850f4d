#include "strictmin/problem/complex_equality_basis.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>

namespace strictmin {
namespace {

using Complex = std::complex<double>;
using Terms = std::vector<std::pair<int, Complex>>;  // node -> coefficient, a few terms

constexpr double kDrop = 1e-13;

Complex* find(Terms& t, int node) {
  for (auto& [n, c] : t)
    if (n == node) return &c;
  return nullptr;
}

void erase(Terms& t, int node) {
  for (size_t k = 0; k < t.size(); ++k)
    if (t[k].first == node) {
      t[k] = t.back();
      t.pop_back();
      return;
    }
}

void erase(std::vector<int>& users, int vertex) {
  const auto it = std::find(users.begin(), users.end(), vertex);
  if (it != users.end()) {
    *it = users.back();
    users.pop_back();
  }
}

class ComplexEliminator {
 public:
  // Every free vertex starts as its own node; fixed ones have no terms (their value is z0).
  explicit ComplexEliminator(const Problem& p) : expr_(p.num_vertices), users_(p.num_vertices) {
    for (int w = 0; w < p.num_vertices; ++w)
      if (!p.fixed[w]) {
        expr_[w].emplace_back(w, Complex(1, 0));
        users_[w].push_back(w);
      }
  }

  // sum_w c_w z_w = 0 with the current expressions substituted; eliminates one node.
  void add_row(const Terms& row) {
    Terms sum;
    for (const auto& [w, a] : row)
      for (const auto& [n, c] : expr_[w]) {
        if (Complex* s = find(sum, n)) *s += a * c;
        else sum.emplace_back(n, a * c);
      }
    double largest = 0;
    for (size_t k = 0; k < sum.size();) {
      if (std::abs(sum[k].second) < kDrop) {
        sum[k] = sum.back();
        sum.pop_back();
      } else {
        largest = std::max(largest, std::abs(sum[k++].second));
      }
    }
    if (sum.empty()) return;  // redundant (the right-hand sides are 0)
    int pivot = -1;
    Complex cp;
    for (const auto& [n, c] : sum)
      if (std::abs(c) >= 0.5 * largest &&
          (pivot < 0 || users_[n].size() < users_[pivot].size() ||
           (users_[n].size() == users_[pivot].size() && n < pivot))) {
        pivot = n;
        cp = c;
      }
    Terms value;  // y_pivot = -sum_{o != p} (c_o / c_p) y_o
    for (const auto& [n, c] : sum)
      if (n != pivot) value.emplace_back(n, -c / cp);
    substitute(pivot, value);
  }

  // One translation node per seam branch (see the header): where node p (a_0) is used with
  // coefficient P, node q (b_0) is used with -P m by every user of p but p itself; then
  // P p - P m q = P t with t = p - m q, and p's own vertex becomes t + m q.
  void merge_translations() {
    std::vector<int> order;
    for (int p = 0; p < static_cast<int>(users_.size()); ++p)
      if (users_[p].size() > 2) order.push_back(p);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return users_[a].size() > users_[b].size() || (users_[a].size() == users_[b].size() && a < b);
    });
    for (int p : order) {
      std::vector<int> others;
      for (int u : users_[p])
        if (u != p) others.push_back(u);
      if (others.size() < 2 || expr_[p].size() != 1 || expr_[p][0].first != p) continue;
      std::sort(others.begin(), others.end());
      const Complex p0 = *find(expr_[others[0]], p);
      if (std::norm(p0) < 0.5) continue;
      const Terms candidates = expr_[others[0]];  // a copy: it changes below
      for (const auto& [q, q0] : candidates) {
        if (q == p) continue;
        const Complex m = -q0 / p0;
        const bool all = std::all_of(others.begin(), others.end(), [&](int u) {
          const Complex* qu = find(expr_[u], q);
          return qu && std::abs(*qu + *find(expr_[u], p) * m) <= kDrop;
        });
        if (!all) continue;
        for (int u : others) {
          erase(expr_[u], q);
          erase(users_[q], u);
        }
        expr_[p].emplace_back(q, m);
        users_[q].push_back(p);
        break;
      }
    }
  }

  ComplexEqualityBasis finish(const Problem& p) const {
    ComplexEqualityBasis out;
    const int V = p.num_vertices;
    std::vector<int> column(V, -1);
    for (int w = 0; w < V; ++w)
      if (!users_[w].empty()) column[w] = out.num_nodes++;
    out.offset.assign(V + 1, 0);
    out.z0 = Eigen::VectorXcd::Zero(V);
    Terms terms;
    for (int w = 0; w < V; ++w) {
      if (p.fixed[w]) out.z0(w) = Complex(p.positions(w, 0), p.positions(w, 1));
      terms = expr_[w];
      for (auto& [n, c] : terms) n = column[n];
      std::sort(terms.begin(), terms.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      for (const auto& [n, c] : terms) {
        out.node.push_back(n);
        out.coefficient.push_back(c);
      }
      out.offset[w + 1] = static_cast<int>(out.node.size());
    }
    return out;
  }

 private:
  void substitute(int pivot, const Terms& value) {
    const std::vector<int> users = users_[pivot];
    for (int f : users) {
      Terms& e = expr_[f];
      const Complex a = *find(e, pivot);
      erase(e, pivot);
      for (const auto& [n, v] : value) {
        Complex* slot = find(e, n);
        if (!slot) {  // f becomes a user of n
          e.emplace_back(n, a * v);
          users_[n].push_back(f);
          slot = &e.back().second;
        } else {
          *slot += a * v;
        }
        if (std::abs(*slot) < kDrop) {
          erase(e, n);
          erase(users_[n], f);
        }
      }
    }
    users_[pivot].clear();
  }

  std::vector<Terms> expr_;                // vertex -> its terms
  std::vector<std::vector<int>> users_;    // node -> vertices whose expression uses it
};

// The block row (rows 2g, 2g+1) as complex terms; false when it is not of the form.
bool block_row(const Eigen::SparseMatrix<double, Eigen::RowMajor>& A, const Problem& p, Eigen::Index g, Terms& row) {
  row.clear();
  std::vector<std::pair<int, Eigen::Matrix2d>> blocks;
  for (int r = 0; r < 2; ++r)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, 2 * g + r); it; ++it) {
      const int w = static_cast<int>(it.col()) / 2, s = static_cast<int>(it.col()) % 2;
      auto b = std::find_if(blocks.begin(), blocks.end(), [&](const auto& x) { return x.first == w; });
      if (b == blocks.end()) {
        blocks.emplace_back(w, Eigen::Matrix2d::Zero());
        b = blocks.end() - 1;
      }
      b->second(r, s) += it.value();
    }
  for (const auto& [w, B] : blocks) {
    const double scale = B.cwiseAbs().maxCoeff();
    if (std::abs(B(0, 0) - B(1, 1)) > 1e-14 * scale || std::abs(B(0, 1) + B(1, 0)) > 1e-14 * scale) return false;
    if (p.fixed[w]) {
      if (p.positions(w, 0) != 0 || p.positions(w, 1) != 0) return false;
      continue;  // its value is 0: the term drops
    }
    if (scale > 0) row.emplace_back(w, Complex(B(0, 0), B(1, 0)));
  }
  return true;
}

}  // namespace

std::optional<ComplexEqualityBasis> complex_equality_basis(const Problem& p) {
  if (p.image_dim != 2 || !p.has_equalities() || p.eq_matrix.rows() % 2 != 0 ||
      p.eq_matrix.cols() != 2 * static_cast<Eigen::Index>(p.num_vertices) || p.eq_rhs.lpNorm<Eigen::Infinity>() != 0)
    return std::nullopt;
  const Eigen::SparseMatrix<double, Eigen::RowMajor> A = p.eq_matrix;
  ComplexEliminator elim(p);
  Terms row;
  for (Eigen::Index g = 0; g < A.rows() / 2; ++g) {
    if (!block_row(A, p, g, row)) return std::nullopt;
    elim.add_row(row);
  }
  elim.merge_translations();
  return elim.finish(p);
}

}  // namespace strictmin
