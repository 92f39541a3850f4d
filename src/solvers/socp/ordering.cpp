#include "solvers/socp/ordering.h"

#include <Eigen/SparseCore>
#include <cholmod.h>
#include <algorithm>
#include <deque>
#include <mutex>
#include <numeric>

#include "solvers/cholmod_view.h"

namespace strictmin::socp {

namespace {

// The graph's lower triangle with a diagonal, as CHOLMOD's ordering routines take it.
struct LowerGraph {
  Eigen::SparseMatrix<double> lower;
  cholmod_sparse A;
  LowerGraph(const std::vector<int>& offset, const std::vector<int>& adj) {
    const int n = static_cast<int>(offset.size()) - 1;
    std::vector<Eigen::Triplet<double>> pattern;
    pattern.reserve(adj.size() / 2 + n);
    for (int v = 0; v < n; ++v) {
      pattern.emplace_back(v, v, 1.0);
      for (int e = offset[v]; e < offset[v + 1]; ++e)
        if (adj[e] > v) pattern.emplace_back(adj[e], v, 1.0);
    }
    lower.resize(n, n);
    lower.setFromTriplets(pattern.begin(), pattern.end());
    lower.makeCompressed();
    A = cholmod_view(lower, -1);
  }
};

// The last few orderings and their graphs. A sequence of solves on one mesh (local-global's
// global steps, direct's levels, qc/iso frames) orders the same graph again and again, and
// METIS is a sixth of such a step's time at 20k elements. The orderings are deterministic
// functions of the graph (METIS's generator is seeded on every call), so a remembered answer
// is the one a new call would give: results stay bitwise the same.
class OrderingMemo {
 public:
  // kind: which function (bisection, ordering with its threshold).
  bool find(int kind, const std::vector<int>& offset, const std::vector<int>& adj, std::vector<int>& out) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const Entry& e : entries_)
      if (e.kind == kind && e.offset == offset && e.adj == adj) {
        out = e.result;
        return true;
      }
    return false;
  }
  void keep(int kind, const std::vector<int>& offset, const std::vector<int>& adj, const std::vector<int>& result) {
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.push_front(Entry{kind, offset, adj, result});
    if (entries_.size() > kEntries) entries_.pop_back();
  }

 private:
  struct Entry {
    int kind;
    std::vector<int> offset, adj, result;
  };
  static constexpr size_t kEntries = 6;  // a bisection and its two halves, for two meshes
  std::mutex mutex_;
  std::deque<Entry> entries_;
};

OrderingMemo& memo() {
  static OrderingMemo m;
  return m;
}

// METIS's random generator is the C library's, global to the process, and METIS seeds it at
// the start of every call. One call at a time, then, and each returns what it would alone:
// solves that order their graphs on several threads at once stay reproducible.
std::mutex& metis_lock() {
  static std::mutex m;
  return m;
}

constexpr int kBisection = -1;  // the memo's kind for vertex_bisection (orderings: their threshold)

}  // namespace

std::vector<int> vertex_bisection(const std::vector<int>& offset, const std::vector<int>& adj) {
  const int n = static_cast<int>(offset.size()) - 1;
  if (n < 3) return {};
  std::vector<int> remembered;
  if (memo().find(kBisection, offset, adj, remembered)) return remembered;
  std::vector<int> part = compute_bisection(offset, adj);
  memo().keep(kBisection, offset, adj, part);
  return part;
}

std::vector<int> compute_bisection(const std::vector<int>& offset, const std::vector<int>& adj) {
  const int n = static_cast<int>(offset.size()) - 1;
  LowerGraph g(offset, adj);
  cholmod_common common;
  cholmod_start(&common);
  common.print = 0;
  std::vector<int> part(n, 0);
  long sep;
  {
    std::lock_guard<std::mutex> one_at_a_time(metis_lock());
    sep = cholmod_bisect(&g.A, nullptr, 0, 1, part.data(), &common);
  }
  const bool ok = common.status == CHOLMOD_OK && sep >= 0;
  cholmod_finish(&common);
  if (!ok) return {};
  int count[3] = {0, 0, 0};
  for (int v : part) {
    if (v < 0 || v > 2) return {};
    ++count[v];
  }
  if (count[0] == 0 || count[1] == 0) return {};
  return part;
}

std::vector<int> bisected_ordering(const std::vector<int>& offset, const std::vector<int>& adj,
                                   const std::vector<int>& part, int sizes[3]) {
  const int n = static_cast<int>(offset.size()) - 1;
  std::vector<int> local(n, -1);
  std::vector<int> vertices[3];
  for (int v = 0; v < n; ++v) {
    local[v] = static_cast<int>(vertices[part[v]].size());
    vertices[part[v]].push_back(v);
  }
  // The halves' nested dissections (one after the other: METIS runs one call at a time, see
  // metis_lock); the separator's Schur complement is dense: any order.
  std::vector<int> half_order[2];
  auto order_half = [&](int p) {
    std::vector<int> sub_offset(1, 0), sub_adj;
    for (int v : vertices[p]) {
      for (int e = offset[v]; e < offset[v + 1]; ++e)
        if (part[adj[e]] == p) sub_adj.push_back(local[adj[e]]);
      sub_offset.push_back(static_cast<int>(sub_adj.size()));
    }
    for (int i : vertex_ordering(sub_offset, sub_adj)) half_order[p].push_back(vertices[p][i]);
  };
  order_half(0);
  order_half(1);
  std::vector<int> order;
  order.reserve(n);
  for (int p = 0; p < 2; ++p) order.insert(order.end(), half_order[p].begin(), half_order[p].end());
  order.insert(order.end(), vertices[2].begin(), vertices[2].end());
  for (int p = 0; p < 3; ++p) sizes[p] = static_cast<int>(vertices[p].size());
  return order;
}

std::vector<int> vertex_ordering(const std::vector<int>& offset, const std::vector<int>& adj, int metis_threshold) {
  const int n = static_cast<int>(offset.size()) - 1;
  if (n < 3) return compute_ordering(offset, adj, metis_threshold);
  std::vector<int> remembered;
  if (memo().find(metis_threshold, offset, adj, remembered)) return remembered;
  std::vector<int> order = compute_ordering(offset, adj, metis_threshold);
  memo().keep(metis_threshold, offset, adj, order);
  return order;
}

std::vector<int> compute_ordering(const std::vector<int>& offset, const std::vector<int>& adj, int metis_threshold) {
  const int n = static_cast<int>(offset.size()) - 1;
  std::vector<int> order(std::max(n, 0));
  std::iota(order.begin(), order.end(), 0);
  if (n < 3) return order;
  LowerGraph g(offset, adj);
  cholmod_common common;
  cholmod_start(&common);
  common.print = 0;
  cholmod_sparse& A = g.A;
  std::vector<int> perm(n);
  bool ok = false;
  if (n >= metis_threshold) {
    std::lock_guard<std::mutex> one_at_a_time(metis_lock());
    ok = cholmod_metis(&A, nullptr, 0, 1, perm.data(), &common);
  }
  if (!ok) ok = cholmod_amd(&A, nullptr, 0, perm.data(), &common);
  cholmod_finish(&common);
  return ok ? perm : order;
}

}  // namespace strictmin::socp
