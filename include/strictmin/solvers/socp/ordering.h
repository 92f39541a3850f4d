#pragma once
// Fill-reducing ordering of the free vertices for the normal equations. The normal matrix
// has one n by n block per pair of adjacent vertices, so the ordering is computed on the
// vertex graph (n^2 times fewer nonzeros than the dof graph, hence that much cheaper) and
// expanded to the dofs: METIS nested dissection (through CHOLMOD) for large meshes, where it
// saves about 40% of the factorisation flops of every iteration against minimum degree,
// approximate minimum degree (AMD) for small ones.
#include <vector>

namespace strictmin::socp {

// adjacency in CSR form (adj[offset[v] .. offset[v+1]]), symmetric, without self loops.
// Returns order: order[i] is the vertex eliminated i-th.
std::vector<int> vertex_ordering(const std::vector<int>& offset, const std::vector<int>& adj,
                                 int metis_threshold = 5000);

}  // namespace strictmin::socp
