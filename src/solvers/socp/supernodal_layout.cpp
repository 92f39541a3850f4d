#include "solvers/socp/supernodal_layout.h"

#include <algorithm>

namespace strictmin::socp {

bool SupernodalEntryMap::locate(const cholmod_factor& L, const std::vector<int>& row, const std::vector<int>& col) {
  if (row.size() != col.size()) return false;
  const int n = static_cast<int>(L.n), nsuper = static_cast<int>(L.nsuper);
  const int* super = static_cast<const int*>(L.super);
  const int* pi = static_cast<const int*>(L.pi);
  const int* px = static_cast<const int*>(L.px);
  const int* ls = static_cast<const int*>(L.s);
  super_of_column.assign(n, 0);
  for (int s = 0; s < nsuper; ++s)
    for (int j = super[s]; j < super[s + 1]; ++j) super_of_column[j] = s;
  // Entries bucketed by supernode, then located through the supernode's row map.
  std::vector<int> start(nsuper + 1, 0);
  source.clear();
  for (size_t e = 0; e < row.size(); ++e) {
    if (row[e] < 0) continue;
    if (col[e] < 0 || col[e] >= n || row[e] < col[e] || row[e] >= n) return false;
    ++start[super_of_column[col[e]] + 1];
    source.push_back(static_cast<int>(e));
  }
  for (int s = 0; s < nsuper; ++s) start[s + 1] += start[s];
  std::vector<int> order(source.size());
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int e : source) order[fill[super_of_column[col[e]]]++] = e;
  }
  std::vector<long> target_of(row.size(), -1);
  std::vector<int> map(n, -1);
  for (int s = 0; s < nsuper; ++s) {
    const int nsrow = pi[s + 1] - pi[s];
    for (int k = 0; k < nsrow; ++k) map[ls[pi[s] + k]] = k;
    for (int q = start[s]; q < start[s + 1]; ++q) {
      const int e = order[q];
      const int k = map[row[e]];
      if (k < 0 || ls[pi[s] + k] != row[e]) return false;  // outside the pattern
      target_of[e] = px[s] + static_cast<long>(col[e] - super[s]) * nsrow + k;
    }
    for (int k = 0; k < nsrow; ++k) map[ls[pi[s] + k]] = -1;
  }
  target.resize(source.size());
  for (size_t q = 0; q < source.size(); ++q) target[q] = target_of[source[q]];
  return true;
}

void LeftLookingWorkspace::reserve(const cholmod_factor& L) {
  const int nsuper = static_cast<int>(L.nsuper);
  const int* pi = static_cast<const int*>(L.pi);
  head.assign(nsuper, -1);
  next.assign(nsuper, -1);
  position.assign(nsuper, 0);
  map.assign(L.n, -1);
  int widest_rows = 0;
  for (int s = 0; s < nsuper; ++s) widest_rows = std::max(widest_rows, pi[s + 1] - pi[s]);
  relative.assign(widest_rows, 0);
}

}  // namespace strictmin::socp
