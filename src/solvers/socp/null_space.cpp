#include "solvers/socp/null_space.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace strictmin::socp {
namespace {

using Block = Eigen::Matrix3d;  // the top-left n x n part is used
using Expr = std::unordered_map<int, Block>;  // y node -> coefficient block

constexpr double kDrop = 1e-13;

class BlockEliminator {
 public:
  BlockEliminator(int vertices, int n) : n_(n), expr_(vertices), users_(vertices) {
    for (int f = 0; f < vertices; ++f) {
      expr_[f][f] = Block::Identity();
      users_[f].insert(f);
    }
  }

  // sum_v B_v x_v = 0 with the current expressions substituted; false when no block of the
  // reduced row is invertible (the row is not block-eliminable).
  bool add_row(const std::vector<std::pair<int, Block>>& row) {
    Expr sum;
    for (const auto& [v, b] : row)
      for (const auto& [node, c] : expr_[v]) {
        auto it = sum.find(node);
        if (it == sum.end())
          sum.emplace(node, b * c);
        else
          it->second += b * c;
      }
    double largest_det = 0, largest_entry = 0;
    for (auto it = sum.begin(); it != sum.end();) {
      const double size = it->second.cwiseAbs().maxCoeff();
      if (size < kDrop) {
        it = sum.erase(it);
        continue;
      }
      largest_entry = std::max(largest_entry, size);
      largest_det = std::max(largest_det, std::abs(det(it->second)));
      ++it;
    }
    if (sum.empty()) return true;  // redundant
    if (!(largest_det > 1e-10 * std::pow(largest_entry, n_))) return false;
    int pivot = -1;
    for (const auto& [node, c] : sum)
      if (std::abs(det(c)) >= 0.5 * largest_det &&
          (pivot < 0 || users_[node].size() < users_[pivot].size() ||
           (users_[node].size() == users_[pivot].size() && node < pivot)))
        pivot = node;
    // y_pivot = -C_p^{-1} sum_{o != p} C_o y_o
    const Eigen::MatrixXd inv = sum[pivot].topLeftCorner(n_, n_).inverse();
    Expr value;
    for (const auto& [node, c] : sum)
      if (node != pivot) {
        Block b = Block::Zero();
        b.topLeftCorner(n_, n_) = -inv * c.topLeftCorner(n_, n_);
        value.emplace(node, b);
      }
    substitute(pivot, value);
    return true;
  }

  // A change of basis that gives each seam branch one translation node instead of two
  // anchors: along a branch every pivoted wedge is a_j = R b_j + a_0 - R b_0, so wherever
  // node p (a_0) is used with block P, node q (b_0) is used with -P M (M = R). Then
  // P p - P M q = P t with t = p - M q: p's users drop q, and p's own vertex becomes t + M q.
  // Exact (M is a product of the blocks), and it halves the nodes that couple a whole branch.
  void merge_translations() {
    const int F = static_cast<int>(expr_.size());
    std::vector<int> order;
    for (int p = 0; p < F; ++p)
      if (users_[p].size() > 2) order.push_back(p);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return users_[a].size() > users_[b].size() || (users_[a].size() == users_[b].size() && a < b);
    });
    for (int p : order) {
      std::vector<int> others;
      for (int u : users_[p])
        if (u != p) others.push_back(u);
      if (others.size() < 2 || expr_[p].size() != 1) continue;  // p's vertex must be p itself
      std::sort(others.begin(), others.end());
      const Expr& first = expr_[others[0]];
      const Block& p0 = first.at(p);
      if (std::abs(det(p0)) < 0.5) continue;
      const Eigen::MatrixXd p0_inv = p0.topLeftCorner(n_, n_).inverse();
      std::vector<std::pair<int, Block>> candidates(first.begin(), first.end());  // copies: first changes below
      for (const auto& [q, q0] : candidates) {
        if (q == p) continue;
        Block m = Block::Zero();
        m.topLeftCorner(n_, n_) = -p0_inv * q0.topLeftCorner(n_, n_);  // q0 = -P0 M
        bool all = true;
        for (int u : others) {
          const auto pu = expr_[u].find(p), qu = expr_[u].find(q);
          if (qu == expr_[u].end() || ((qu->second + pu->second * m).cwiseAbs().maxCoeff() > kDrop)) {
            all = false;
            break;
          }
        }
        if (!all) continue;
        for (int u : others) {
          expr_[u].erase(q);
          users_[q].erase(u);
        }
        expr_[p][q] = m;  // x_p = t + M q
        users_[q].insert(p);
        break;
      }
    }
  }

  BlockNullSpace finish() const {
    BlockNullSpace out;
    out.ok = true;
    const int F = static_cast<int>(expr_.size());
    std::vector<int> column(F, -1);
    for (int f = 0; f < F; ++f)
      if (!users_[f].empty()) {
        column[f] = out.num_nodes++;
        out.node_vertex.push_back(f);
      }
    out.offset.assign(F + 1, 0);
    for (int f = 0; f < F; ++f) {
      std::vector<std::pair<int, const Block*>> terms;
      for (const auto& [node, b] : expr_[f]) terms.emplace_back(column[node], &b);
      std::sort(terms.begin(), terms.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      for (const auto& [node, b] : terms) {
        out.node.push_back(node);
        for (int r = 0; r < n_; ++r)
          for (int s = 0; s < n_; ++s) out.block.push_back((*b)(r, s));
      }
      out.offset[f + 1] = static_cast<int>(out.node.size());
    }
    return out;
  }

 private:
  double det(const Block& b) const { return b.topLeftCorner(n_, n_).determinant(); }

  void substitute(int pivot, const Expr& value) {
    const std::vector<int> users(users_[pivot].begin(), users_[pivot].end());
    for (int f : users) {
      Expr& e = expr_[f];
      const Block a = e.at(pivot);
      e.erase(pivot);
      for (const auto& [node, v] : value) {
        auto it = e.find(node);
        if (it == e.end()) it = e.emplace(node, Block::Zero()).first;
        it->second += a * v;
        if (it->second.cwiseAbs().maxCoeff() < kDrop) {
          e.erase(it);
          users_[node].erase(f);
        } else {
          users_[node].insert(f);
        }
      }
    }
    users_[pivot].clear();
  }

  int n_;
  std::vector<Expr> expr_;
  std::vector<std::unordered_set<int>> users_;  // y node -> vertices whose expression uses it
};

}  // namespace

BlockNullSpace block_null_space(const ConeProgram& p) {
  const int n = p.n;
  if (n > 3 || p.num_eq() == 0 || p.A.rows() % n != 0) return {};
  BlockEliminator elim(p.num_x / n, n);
  std::vector<std::pair<int, Block>> row;
  for (Eigen::Index g = 0; g < p.A.rows() / n; ++g) {
    std::unordered_map<int, Block> blocks;
    for (int r = 0; r < n; ++r)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(p.A, g * n + r); it; ++it) {
        const int v = static_cast<int>(it.col()) / n, s = static_cast<int>(it.col()) % n;
        auto b = blocks.find(v);
        if (b == blocks.end()) b = blocks.emplace(v, Block::Zero()).first;
        b->second(r, s) += it.value();
      }
    row.assign(blocks.begin(), blocks.end());
    if (!elim.add_row(row)) return {};
  }
  elim.merge_translations();
  return elim.finish();
}

void apply_z(const BlockNullSpace& z, int n, const Eigen::VectorXd& y, Eigen::VectorXd& x) {
  const int F = static_cast<int>(z.offset.size()) - 1;
  x.setZero(static_cast<Eigen::Index>(F) * n);
  parallel_for_index(F, 4096, [&](int begin, int end) {
    for (int f = begin; f < end; ++f)
      for (int t = z.offset[f]; t < z.offset[f + 1]; ++t) {
        const double* b = z.block.data() + static_cast<size_t>(t) * n * n;
        const double* yy = y.data() + static_cast<Eigen::Index>(z.node[t]) * n;
        for (int r = 0; r < n; ++r)
          for (int s = 0; s < n; ++s) x[f * n + r] += b[r * n + s] * yy[s];
      }
  });
}

void apply_zt(const BlockNullSpace& z, int n, const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  const int F = static_cast<int>(z.offset.size()) - 1;
  y.setZero(static_cast<Eigen::Index>(z.num_nodes) * n);
  for (int f = 0; f < F; ++f)  // serial: several vertices share a node
    for (int t = z.offset[f]; t < z.offset[f + 1]; ++t) {
      const double* b = z.block.data() + static_cast<size_t>(t) * n * n;
      double* yy = y.data() + static_cast<Eigen::Index>(z.node[t]) * n;
      for (int r = 0; r < n; ++r)
        for (int s = 0; s < n; ++s) yy[s] += b[r * n + s] * x[f * n + r];
    }
}

}  // namespace strictmin::socp
