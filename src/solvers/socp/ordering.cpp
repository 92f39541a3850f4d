#include "strictmin/solvers/socp/ordering.h"

#include <Eigen/SparseCore>
#include <cholmod.h>
#include <algorithm>
#include <numeric>

namespace strictmin::socp {

std::vector<int> vertex_ordering(const std::vector<int>& offset, const std::vector<int>& adj, int metis_threshold) {
  const int n = static_cast<int>(offset.size()) - 1;
  std::vector<int> order(std::max(n, 0));
  std::iota(order.begin(), order.end(), 0);
  if (n < 3) return order;
  std::vector<Eigen::Triplet<double>> pattern;
  pattern.reserve(adj.size() / 2 + n);
  for (int v = 0; v < n; ++v) {
    pattern.emplace_back(v, v, 1.0);
    for (int e = offset[v]; e < offset[v + 1]; ++e)
      if (adj[e] > v) pattern.emplace_back(adj[e], v, 1.0);
  }
  Eigen::SparseMatrix<double> lower(n, n);
  lower.setFromTriplets(pattern.begin(), pattern.end());
  lower.makeCompressed();
  cholmod_common common;
  cholmod_start(&common);
  common.print = 0;
  cholmod_sparse A;
  A.nrow = A.ncol = n;
  A.nzmax = lower.nonZeros();
  A.p = lower.outerIndexPtr();
  A.i = lower.innerIndexPtr();
  A.nz = nullptr;
  A.x = lower.valuePtr();
  A.z = nullptr;
  A.stype = -1;
  A.itype = CHOLMOD_INT;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  std::vector<int> perm(n);
  bool ok = false;
  if (n >= metis_threshold) ok = cholmod_metis(&A, nullptr, 0, 1, perm.data(), &common);
  if (!ok) ok = cholmod_amd(&A, nullptr, 0, perm.data(), &common);
  cholmod_finish(&common);
  return ok ? perm : order;
}

}  // namespace strictmin::socp
