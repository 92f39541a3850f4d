#pragma once
// Disjoint sets over 0 .. n-1 (path halving; no ranks: the sets here are mesh parts, built
// once): the connected parts of a mesh, of a vertex's link, of rows coupling parts.
#include <numeric>
#include <vector>

namespace strictmin {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(int a, int b) { parent[find(a)] = find(b); }
};

}  // namespace strictmin
