#include "solvers/linf_relaxed_equalities.h"

#include <Eigen/Dense>
#include <algorithm>
#include <map>
#include <queue>
#include <set>

#include "mesh/union_find.h"

namespace strictmin {
namespace {

constexpr double kZero = 1e-12;          // entries are sums of quarter turns' 0, +-1 (and halves)
constexpr size_t kMaxBlocks = 64;        // a projected row wider than this: give up (old relaxation)
constexpr int kMaxComponentParts = 400;  // parts coupled by rows, solved as one dense system
constexpr double kMinShare = 1e-6;       // smallest singular value of a part's share of S worth holding

struct BlockRow {
  std::map<int, Eigen::MatrixXd> blocks;  // vertex -> n x n coefficient block
  Eigen::VectorXd rhs;
  bool alive = true;
};

double size_of(const Eigen::MatrixXd& b) { return b.cwiseAbs().maxCoeff(); }

bool read_block_rows(const Problem& p, std::vector<BlockRow>& rows) {
  const int n = p.image_dim;
  const Eigen::SparseMatrix<double, Eigen::RowMajor> A = p.eq_matrix;
  if (A.rows() % n != 0) return false;
  rows.assign(A.rows() / n, BlockRow());
  for (Eigen::Index row = 0; row < A.rows(); ++row) {
    BlockRow& br = rows[row / n];
    if (br.rhs.size() == 0) br.rhs = p.eq_rhs.segment(row - row % n, n);
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, row); it; ++it) {
      auto [slot, added] = br.blocks.try_emplace(static_cast<int>(it.col()) / n, Eigen::MatrixXd::Zero(n, n));
      slot->second(row % n, it.col() % n) += it.value();
    }
  }
  return true;
}

// Block Gaussian elimination of the vertices not kept: each is solved for from one row (a
// block of largest |det|, then the shortest row) and substituted into the others; rows where
// it has no invertible block are dropped. Vertices with the fewest rows go first, so a
// chain of cut edges through dropped elements collapses into one row between its kept ends.
bool eliminate(std::vector<BlockRow>& rows, const std::vector<char>& keep, int n) {
  const int V = static_cast<int>(keep.size());
  std::vector<std::set<int>> users(V);
  for (size_t r = 0; r < rows.size(); ++r)
    for (const auto& [v, b] : rows[r].blocks)
      if (!keep[v]) users[v].insert(static_cast<int>(r));
  auto drop = [&](int r) {
    for (const auto& [v, b] : rows[r].blocks)
      if (!keep[v]) users[v].erase(r);
    rows[r].alive = false;
  };
  using Entry = std::pair<size_t, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (int v = 0; v < V; ++v)
    if (!users[v].empty()) queue.emplace(users[v].size(), v);
  while (!queue.empty()) {
    const auto [count, v] = queue.top();
    queue.pop();
    if (users[v].empty()) continue;
    if (count != users[v].size()) {  // stale: requeue with the current count
      queue.emplace(users[v].size(), v);
      continue;
    }
    double best = 0;
    for (int r : users[v]) best = std::max(best, std::abs(rows[r].blocks.at(v).determinant()));
    int pivot = -1;
    for (int r : users[v])
      if (std::abs(rows[r].blocks.at(v).determinant()) >= 0.5 * best &&
          (pivot < 0 || rows[r].blocks.size() < rows[pivot].blocks.size()))
        pivot = r;
    const std::vector<int> others(users[v].begin(), users[v].end());
    if (!(best > 1e-10)) {  // v cannot be solved for: its rows constrain nothing kept
      for (int r : others) drop(r);
      continue;
    }
    const BlockRow& pr = rows[pivot];
    const Eigen::MatrixXd inv = pr.blocks.at(v).inverse();
    for (int r : others) {
      if (r == pivot) continue;
      BlockRow& s = rows[r];
      const Eigen::MatrixXd f = s.blocks.at(v) * inv;
      for (const auto& [u, b] : pr.blocks) {
        auto [slot, added] = s.blocks.try_emplace(u, Eigen::MatrixXd::Zero(n, n));
        slot->second -= f * b;
        if (added && !keep[u]) users[u].insert(r);
      }
      s.rhs -= f * pr.rhs;
      s.blocks.erase(v);  // exactly cancelled
      users[v].erase(r);
      for (auto it = s.blocks.begin(); it != s.blocks.end();) {
        if (size_of(it->second) >= kZero) {
          ++it;
          continue;
        }
        if (!keep[it->first]) users[it->first].erase(r);
        it = s.blocks.erase(it);
      }
      if (s.blocks.size() > kMaxBlocks) return false;
      if (s.blocks.empty()) drop(r);
    }
    drop(pivot);
  }
  return true;
}

Eigen::MatrixXd orthonormal(const Eigen::MatrixXd& m) {
  if (m.cols() == 0) return m;
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(m);
  return qr.householderQ() * Eigen::MatrixXd::Identity(m.rows(), m.cols());
}

using Action = std::vector<std::pair<int, Eigen::MatrixXd>>;  // part -> sum of a row's blocks over it

// One component of parts coupled by rows: the translations the rows allow, S = ker C (C: the
// rows' actions), and parts held one after another, each removing n dimensions of S (its
// share of S has rank n), until none is left. False when a part's share is rank-deficient.
bool hold_component(const std::vector<int>& members, const std::vector<const Action*>& rows, int n,
                    std::vector<int>& held_parts) {
  const int m = static_cast<int>(members.size());
  std::map<int, int> local;
  for (int j = 0; j < m; ++j) local[members[j]] = j;
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows.size()) * n, m * n);
  for (size_t r = 0; r < rows.size(); ++r)
    for (const auto& [part, b] : *rows[r]) C.block(r * n, local.at(part) * n, n, n) = b;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(C);
  lu.setThreshold(1e-9);
  Eigen::MatrixXd N = lu.rank() == C.cols() ? Eigen::MatrixXd(m * n, 0) : orthonormal(lu.kernel());
  // N is orthonormal, so a part's share of S is judged by its singular values: the part
  // whose smallest one is largest is held next (a share of round-off is no freedom at all).
  std::vector<char> held(m, 0);
  while (N.cols() > 0) {
    int chosen = -1;
    double best = kMinShare;
    for (int j = 0; j < m; ++j) {
      if (held[j]) continue;
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(N.middleRows(j * n, n));
      const double smallest = svd.singularValues()[n - 1];
      if (smallest > best) {
        best = smallest;
        chosen = j;
      }
    }
    if (chosen < 0) return false;
    held[chosen] = 1;
    held_parts.push_back(members[chosen]);
    if (N.cols() == n) break;
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(N.middleRows(chosen * n, n), Eigen::ComputeFullV);
    N = orthonormal(N * svd.matrixV().rightCols(N.cols() - n));
  }
  return true;
}

// The vertices to hold: for the parts that no anchor holds, the translations the rows allow.
// Rows of a component too large or not removable by whole parts are dropped, and each of its
// parts held.
std::vector<int> held_vertices(std::vector<BlockRow>& rows, const ElementParts& parts, const std::vector<char>& anchor,
                               int n) {
  std::vector<int> representative(parts.count, -1);
  for (int v : unanchored_parts(parts, anchor)) representative[parts.part[v]] = v;
  std::vector<Action> action(rows.size());
  UnionFind sets(parts.count);
  std::vector<char> coupled(parts.count, 0);
  for (size_t r = 0; r < rows.size(); ++r) {
    if (!rows[r].alive) continue;
    std::map<int, Eigen::MatrixXd> net;
    for (const auto& [v, b] : rows[r].blocks) {
      const int q = parts.part[v];
      if (q < 0 || representative[q] < 0) continue;  // fixed, or in an anchored part
      auto [slot, added] = net.try_emplace(q, Eigen::MatrixXd::Zero(n, n));
      slot->second += b;
    }
    for (const auto& [q, b] : net)
      if (size_of(b) >= kZero) action[r].emplace_back(q, b);
    for (const auto& [q, b] : action[r]) {
      coupled[q] = 1;
      sets.unite(q, action[r][0].first);
    }
  }
  std::map<int, std::vector<int>> members, component_rows;
  for (int q = 0; q < parts.count; ++q)
    if (coupled[q]) members[sets.find(q)].push_back(q);
  for (size_t r = 0; r < rows.size(); ++r)
    if (!action[r].empty()) component_rows[sets.find(action[r][0].first)].push_back(static_cast<int>(r));
  std::vector<int> held_parts;
  for (int q = 0; q < parts.count; ++q)
    if (representative[q] >= 0 && !coupled[q]) held_parts.push_back(q);
  for (const auto& [root, parts_of] : members) {
    std::vector<const Action*> crows;
    for (int r : component_rows[root]) crows.push_back(&action[r]);
    std::vector<int> chosen;
    if (static_cast<int>(parts_of.size()) <= kMaxComponentParts && hold_component(parts_of, crows, n, chosen)) {
      held_parts.insert(held_parts.end(), chosen.begin(), chosen.end());
      continue;
    }
    for (int r : component_rows[root]) rows[r].alive = false;
    held_parts.insert(held_parts.end(), parts_of.begin(), parts_of.end());
  }
  std::vector<int> out;
  for (int q : held_parts) out.push_back(representative[q]);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

RelaxedEqualities relaxed_equalities(const Problem& p, const std::vector<char>& inside, const ElementParts& parts,
                                     const std::vector<char>& anchor) {
  RelaxedEqualities out;
  const int n = p.image_dim;
  std::vector<BlockRow> rows;
  if (!read_block_rows(p, rows)) return out;
  std::vector<char> keep(p.num_vertices, 0);
  for (int v = 0; v < p.num_vertices; ++v) keep[v] = inside[v] || p.fixed[v];
  if (!eliminate(rows, keep, n)) return out;
  out.held = held_vertices(rows, parts, anchor, n);
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<double> rhs;
  for (const BlockRow& br : rows) {
    if (!br.alive || br.blocks.empty()) continue;
    const int base = static_cast<int>(rhs.size());
    for (int r = 0; r < n; ++r) {
      rhs.push_back(br.rhs[r]);
      for (const auto& [v, b] : br.blocks)
        for (int c = 0; c < n; ++c)
          if (std::abs(b(r, c)) >= kZero) triplets.emplace_back(base + r, v * n + c, b(r, c));
    }
  }
  out.A.resize(static_cast<Eigen::Index>(rhs.size()), p.eq_matrix.cols());
  out.A.setFromTriplets(triplets.begin(), triplets.end());
  out.b = Eigen::Map<const Eigen::VectorXd>(rhs.data(), static_cast<Eigen::Index>(rhs.size()));
  out.ok = true;
  return out;
}

std::vector<int> free_translations(const Problem& p) {
  const ElementParts parts = element_parts(p);
  std::vector<BlockRow> rows;
  if (!p.has_equalities() || !read_block_rows(p, rows)) return unanchored_parts(parts, p.fixed);
  return held_vertices(rows, parts, p.fixed, p.image_dim);
}

}  // namespace strictmin
