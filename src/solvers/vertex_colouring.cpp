#include "strictmin/solvers/vertex_colouring.h"

#include <algorithm>

namespace strictmin {

VertexColouring colour_free_vertices(const Eigen::MatrixXi& elements, const std::vector<char>& fixed) {
  const int nv = static_cast<int>(fixed.size());
  const int ne = static_cast<int>(elements.rows()), nc = static_cast<int>(elements.cols());

  // Vertex -> elements (CSR).
  std::vector<int> start(nv + 1, 0);
  for (int e = 0; e < ne; ++e)
    for (int j = 0; j < nc; ++j) ++start[elements(e, j) + 1];
  for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<int> incident(start[nv]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int e = 0; e < ne; ++e)
    for (int j = 0; j < nc; ++j) incident[fill[elements(e, j)]++] = e;

  VertexColouring out;
  out.colour.assign(nv, -1);
  std::vector<int> seen;  // seen[c] == v + 1: colour c is taken by a neighbour of v
  for (int v = 0; v < nv; ++v) {
    if (fixed[v] || start[v] == start[v + 1]) continue;
    for (int k = start[v]; k < start[v + 1]; ++k)
      for (int j = 0; j < nc; ++j) {
        const int c = out.colour[elements(incident[k], j)];
        if (c >= 0) seen[c] = v + 1;
      }
    int c = 0;
    while (c < out.num_colours && seen[c] == v + 1) ++c;
    if (c == out.num_colours) {
      ++out.num_colours;
      seen.push_back(0);
    }
    out.colour[v] = c;
  }

  out.offsets.assign(out.num_colours + 1, 0);
  for (int v = 0; v < nv; ++v)
    if (out.colour[v] >= 0) ++out.offsets[out.colour[v] + 1];
  for (int c = 0; c < out.num_colours; ++c) out.offsets[c + 1] += out.offsets[c];
  out.order.resize(out.offsets[out.num_colours]);
  std::vector<int> next(out.offsets.begin(), out.offsets.end() - 1);
  for (int v = 0; v < nv; ++v)
    if (out.colour[v] >= 0) out.order[next[out.colour[v]]++] = v;
  return out;
}

}  // namespace strictmin
