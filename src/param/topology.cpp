#include "strictmin/param/topology.h"

#include <algorithm>
#include <tuple>

#include "mesh/union_find.h"
#include "strictmin/io/input_error.h"

namespace strictmin {
namespace {

// A vertex is manifold when the edges (a, b) opposite to it in its faces link into one
// path or cycle: one component of that link graph.
bool single_fan(const std::vector<int>& faces, int v, const Eigen::MatrixXi& F) {
  std::vector<int> link;
  for (int f : faces)
    for (int j = 0; j < 3; ++j)
      if (F(f, j) != v) link.push_back(F(f, j));
  std::sort(link.begin(), link.end());
  link.erase(std::unique(link.begin(), link.end()), link.end());
  UnionFind uf(static_cast<int>(link.size()));
  const auto local = [&](int x) { return static_cast<int>(std::lower_bound(link.begin(), link.end(), x) - link.begin()); };
  for (int f : faces) {
    int other[2], k = 0;
    for (int j = 0; j < 3; ++j)
      if (F(f, j) != v && k < 2) other[k++] = F(f, j);
    uf.unite(local(other[0]), local(other[1]));
  }
  int roots = 0;
  for (int i = 0; i < static_cast<int>(link.size()); ++i) roots += uf.find(i) == i ? 1 : 0;
  return roots == 1;
}

}  // namespace

SurfaceTopology surface_topology(const Mesh& mesh) {
  SurfaceTopology t;
  const Eigen::MatrixXi& F = mesh.F;
  const int nv = mesh.num_vertices(), nf = mesh.num_elements();
  t.faces = nf;
  // Half-edges keyed by their undirected edge.
  std::vector<std::tuple<int, int, int, int, int>> half;  // (min, max, from, to, face)
  half.reserve(static_cast<size_t>(nf) * 3);
  for (int f = 0; f < nf; ++f)
    for (int j = 0; j < 3; ++j) {
      const int a = F(f, j), b = F(f, (j + 1) % 3);
      half.emplace_back(std::min(a, b), std::max(a, b), a, b, f);
    }
  std::sort(half.begin(), half.end());
  std::vector<int> next(nv, -1);
  for (size_t i = 0; i < half.size();) {
    size_t j = i;
    while (j < half.size() && std::get<0>(half[j]) == std::get<0>(half[i]) && std::get<1>(half[j]) == std::get<1>(half[i])) ++j;
    ++t.edges;
    if (j - i > 2 && (t.non_manifold_edge < 0 || std::get<4>(half[i]) < t.non_manifold_edge))
      t.non_manifold_edge = std::get<4>(half[i]);
    if (j - i == 1) {
      const int from = std::get<2>(half[i]), to = std::get<3>(half[i]);
      if (next[from] >= 0 && (t.non_manifold_vertex < 0 || from < t.non_manifold_vertex)) t.non_manifold_vertex = from;
      next[from] = to;
    }
    i = j;
  }
  // Vertex -> faces, used vertices, components.
  std::vector<std::vector<int>> faces_of(nv);
  UnionFind uf(nv);
  for (int f = 0; f < nf; ++f)
    for (int j = 0; j < 3; ++j) {
      faces_of[F(f, j)].push_back(f);
      uf.unite(F(f, j), F(f, (j + 1) % 3));
    }
  for (int v = 0; v < nv; ++v) {
    if (faces_of[v].empty()) continue;
    ++t.vertices;
    if (uf.find(v) == v) ++t.components;
    if (t.non_manifold_vertex < 0 && !single_fan(faces_of[v], v, F)) t.non_manifold_vertex = v;
  }
  // Boundary loops (only where every boundary vertex has one outgoing boundary edge).
  if (t.non_manifold_vertex < 0 && t.non_manifold_edge < 0) {
    std::vector<char> seen(nv, 0);
    for (int v = 0; v < nv; ++v) {
      if (next[v] < 0 || seen[v]) continue;
      std::vector<int> loop;
      for (int w = v; w >= 0 && !seen[w]; w = next[w]) {
        seen[w] = 1;
        loop.push_back(w);
      }
      t.boundary_loops.push_back(std::move(loop));
    }
  }
  return t;
}

std::vector<int> disk_boundary(const Mesh& mesh, const std::string& source) {
  const std::string what = source.empty() ? "the mesh" : source;
  const std::string cut = "; cut it to a disk first (one piece, one boundary loop, no handles)";
  if (mesh.element_type() != ElementType::Triangle)
    throw InputError(what + ": parametrization needs a triangle surface mesh, this is a tet mesh");
  if (mesh.num_elements() == 0) throw InputError(what + ": the mesh has no faces");
  const SurfaceTopology t = surface_topology(mesh);
  if (t.components > 1)
    throw InputError(what + ": the mesh has " + std::to_string(t.components) +
                     " connected components, a disk has one; split it and parametrize each piece separately");
  if (t.non_manifold_edge >= 0)
    throw InputError(what + ": face " + std::to_string(t.non_manifold_edge) +
                     " (0-based) has an edge shared by more than two faces (non-manifold)" + cut);
  if (t.non_manifold_vertex >= 0)
    throw InputError(what + ": vertex " + std::to_string(t.non_manifold_vertex) +
                     " (0-based) is non-manifold (its faces form more than one fan)" + cut);
  const int loops = static_cast<int>(t.boundary_loops.size());
  if (loops == 0)
    throw InputError(what + ": the surface is closed (no boundary, genus " + std::to_string(t.genus()) +
                     ", Euler characteristic " + std::to_string(t.euler_characteristic()) + ")" + cut);
  if (loops > 1)
    throw InputError(what + ": the surface has " + std::to_string(loops) + " boundary loops (genus " +
                     std::to_string(t.genus()) + "), a disk has one; fill the holes or cut between them" + cut);
  if (t.genus() != 0)
    throw InputError(what + ": one boundary loop but genus " + std::to_string(t.genus()) +
                     " (Euler characteristic " + std::to_string(t.euler_characteristic()) + ")" + cut);
  return t.boundary_loops.front();
}

}  // namespace strictmin
