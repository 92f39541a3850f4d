#include "strictmin/problem/parts.h"

#include "mesh/union_find.h"

namespace strictmin {

ElementParts element_parts(const Problem& p, const std::vector<char>* elements) {
  const int V = p.num_vertices, c = p.corners();
  UnionFind sets(V);
  std::vector<char> used(V, 0);
  for (int e = 0; e < p.num_elements(); ++e) {
    if (elements && !(*elements)[e]) continue;
    for (int j = 0; j < c; ++j) {
      used[p.elements(e, j)] = 1;
      sets.unite(p.elements(e, j), p.elements(e, 0));
    }
  }
  ElementParts out;
  out.part.assign(V, -1);
  std::vector<int> id(V, -1);
  for (int v = 0; v < V; ++v) {
    if (!used[v]) continue;
    const int r = sets.find(v);
    if (id[r] < 0) id[r] = out.count++;
    out.part[v] = id[r];
  }
  return out;
}

std::vector<int> unanchored_parts(const ElementParts& parts, const std::vector<char>& anchor) {
  std::vector<char> anchored(parts.count, 0), seen(parts.count, 0);
  for (size_t v = 0; v < parts.part.size(); ++v)
    if (parts.part[v] >= 0 && anchor[v]) anchored[parts.part[v]] = 1;
  std::vector<int> out;
  for (size_t v = 0; v < parts.part.size(); ++v) {
    const int q = parts.part[v];
    if (q >= 0 && !anchored[q] && !seen[q]) {
      seen[q] = 1;
      out.push_back(static_cast<int>(v));
    }
  }
  return out;
}

std::vector<int> unanchored_components(const Problem& p) {
  return unanchored_parts(element_parts(p), p.fixed);
}

}  // namespace strictmin
