#pragma once
// Fill-reducing ordering of the free vertices for the normal equations. The normal matrix
// has one n by n block per pair of adjacent vertices, so the ordering is computed on the
// vertex graph (n^2 times fewer nonzeros than the dof graph, hence that much cheaper) and
// expanded to the dofs: METIS nested dissection (through CHOLMOD) for large meshes, where it
// saves about 40% of the factorisation flops of every iteration against minimum degree,
// approximate minimum degree (AMD) for small ones.
#include <vector>

namespace strictmin::socp {

// Graphs of fewer vertices are ordered by AMD, larger ones by METIS. METIS's random
// generator is the C library's, global to the process, and it seeds it at the start of each
// call: its calls here take turns (a lock), so each gives what it would alone and solves on
// several threads stay reproducible.
constexpr int kMetisMinVertices = 5000;

// adjacency in CSR form (adj[offset[v] .. offset[v+1]]), symmetric, without self loops.
// Returns order: order[i] is the vertex eliminated i-th.
std::vector<int> vertex_ordering(const std::vector<int>& offset, const std::vector<int>& adj,
                                 int metis_threshold = kMetisMinVertices);

// Top-level vertex separator (METIS, through CHOLMOD): part[v] is 0 or 1 for the two halves,
// 2 for the separator. Empty when METIS fails or a half is empty.
std::vector<int> vertex_bisection(const std::vector<int>& offset, const std::vector<int>& adj);

// An elimination order for a bisected graph: part 0 (nested dissection of its subgraph),
// part 1 (likewise), then the separator. sizes[p] receives the number of vertices of part p.
std::vector<int> bisected_ordering(const std::vector<int>& offset, const std::vector<int>& adj,
                                   const std::vector<int>& part, int sizes[3]);

// vertex_ordering and vertex_bisection remember their last few graphs and answers (the same
// graph is ordered again by every solve of a sequence); these compute without the memo.
std::vector<int> compute_ordering(const std::vector<int>& offset, const std::vector<int>& adj, int metis_threshold);
std::vector<int> compute_bisection(const std::vector<int>& offset, const std::vector<int>& adj);

}  // namespace strictmin::socp
