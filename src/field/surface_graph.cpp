#include "strictmin/field/surface_graph.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "strictmin/io/input_error.h"
#include "strictmin/mesh/validate.h"
#include "strictmin/param/topology.h"

namespace strictmin {

std::vector<int> dual_spanning_tree(const SurfaceGraph& g, std::vector<int>& parent_edge) {
  parent_edge.assign(g.num_faces, -1);
  std::vector<char> seen(g.num_faces, 0);
  std::vector<int> order{0};
  seen[0] = 1;
  for (size_t k = 0; k < order.size(); ++k)
    for (int i = 0; i < 3; ++i) {
      const int f = order[k], h = g.neighbour(f, i);
      if (h < 0 || seen[h]) continue;
      seen[h] = 1;
      parent_edge[h] = g.face_edges(f, i);
      order.push_back(h);
    }
  return order;
}

int SurfaceGraph::neighbour(int f, int i) const {
  const int e = face_edges(f, i);
  return edge_faces(e, 0) == f && edge_sides(e, 0) == i ? edge_faces(e, 1) : edge_faces(e, 0);
}

namespace {

std::string prefix(const std::string& source) { return source.empty() ? std::string("gparam: ") : source + ": "; }

void check_manifold(const Mesh& mesh, const std::string& source, bool allow_boundary) {
  if (mesh.element_type() != ElementType::Triangle || mesh.dim() != 3)
    throw InputError(prefix(source) + "global parametrization needs a triangle surface in 3D");
  const SurfaceTopology t = surface_topology(mesh);
  if (t.non_manifold_edge >= 0)
    throw InputError(prefix(source) + "face " + std::to_string(t.non_manifold_edge) +
                     " has an edge shared by more than two faces (non-manifold mesh)");
  if (t.non_manifold_vertex >= 0)
    throw InputError(prefix(source) + "vertex " + std::to_string(t.non_manifold_vertex) +
                     " is non-manifold (its faces form more than one fan)");
  if (t.components != 1)
    throw InputError(prefix(source) + "the mesh has " + std::to_string(t.components) +
                     " connected components; global parametrization takes one surface");
  if (!allow_boundary && !t.boundary_loops.empty())
    throw InputError(prefix(source) + "the surface has " + std::to_string(t.boundary_loops.size()) +
                     " boundary loop(s) (first at vertex " + std::to_string(t.boundary_loops.front().front()) +
                     "); this takes closed surfaces only");
}

// Fans from face_edges / edge_faces: from any face of v, the next face counter-clockwise
// lies across the side that ends at v (side (i + 2) % 3 for the corner i of v); a boundary
// vertex's walk starts at the face whose side leaving v (side i) is a boundary edge. False
// when a vertex is in no face, or a walk ends or closes before it has seen every face of v
// (several fans: a non-manifold vertex). Also marks the boundary vertices and counts the
// boundary loops.
bool build_fans(const Mesh& mesh, SurfaceGraph& g) {
  const int V = g.num_vertices, F = g.num_faces;
  std::vector<int> first_face(V, -1), first_corner(V, -1);
  g.boundary_vertex.assign(V, 0);
  g.fan_start.assign(V + 1, 0);
  for (int f = F - 1; f >= 0; --f)
    for (int i = 2; i >= 0; --i) {
      const int v = mesh.F(f, i);
      ++g.fan_start[v + 1];
      if (g.boundary_vertex[v]) continue;  // keep the open fan's start
      first_face[v] = f;
      first_corner[v] = i;
      if (g.is_boundary_edge(g.face_edges(f, i))) g.boundary_vertex[v] = 1;
    }
  for (int v = 0; v < V; ++v) {
    if (g.fan_start[v + 1] == 0) return false;
    g.fan_start[v + 1] += g.fan_start[v];
  }
  g.fan_faces.resize(g.fan_start.back());
  g.fan_corners.resize(g.fan_start.back());
  for (int v = 0; v < V; ++v) {
    int f = first_face[v], i = first_corner[v];
    for (int k = g.fan_start[v]; k < g.fan_start[v + 1]; ++k) {
      if (f < 0 || (k > g.fan_start[v] && f == first_face[v])) return false;
      g.fan_faces[k] = f;
      g.fan_corners[k] = i;
      f = g.neighbour(f, (i + 2) % 3);
      if (f >= 0) i = mesh.F(f, 0) == v ? 0 : mesh.F(f, 1) == v ? 1 : 2;
    }
    if (f != (g.boundary_vertex[v] ? -1 : first_face[v])) return false;
  }
  // Boundary loops: each boundary vertex starts exactly one boundary edge (manifold).
  std::vector<int> next(V, -1);
  for (int e = 0; e < g.num_edges(); ++e)
    if (g.is_boundary_edge(e)) next[g.edges(e, 0)] = g.edges(e, 1);
  std::vector<char> seen(V, 0);
  g.num_boundary_loops = 0;
  for (int v = 0; v < V; ++v) {
    if (next[v] < 0 || seen[v]) continue;
    ++g.num_boundary_loops;
    for (int w = v; w >= 0 && !seen[w]; w = next[w]) seen[w] = 1;
  }
  return true;
}

// The checked construction: every defect is reported with its element, in the order the
// checks run (used when the fast construction below meets any defect).
SurfaceGraph checked_surface_graph(const Mesh& mesh, const std::string& source, bool allow_boundary) {
  check_manifold(mesh, source, allow_boundary);
  SurfaceGraph g;
  g.num_vertices = mesh.num_vertices();
  g.num_faces = mesh.num_elements();
  const int F = g.num_faces;
  g.face_edges.resize(F, 3);
  std::unordered_map<long long, int> index;
  index.reserve(static_cast<size_t>(F) * 2);
  std::vector<std::array<int, 2>> ends, faces, sides;
  for (int f = 0; f < F; ++f)
    for (int i = 0; i < 3; ++i) {
      const int a = mesh.F(f, i), b = mesh.F(f, (i + 1) % 3);
      const long long key = static_cast<long long>(std::min(a, b)) * g.num_vertices + std::max(a, b);
      auto [it, added] = index.try_emplace(key, static_cast<int>(ends.size()));
      if (added) {
        ends.push_back({std::min(a, b), std::max(a, b)});
        faces.push_back({-1, -1});
        sides.push_back({-1, -1});
      }
      const int e = it->second, k = a < b ? 0 : 1;
      if (faces[e][k] >= 0)
        throw InputError(prefix(source) + "faces " + std::to_string(faces[e][k]) + " and " + std::to_string(f) +
                         " run through edge (" + std::to_string(a) + ", " + std::to_string(b) +
                         ") the same way: inconsistent orientation");
      faces[e][k] = f;
      sides[e][k] = i;
      g.face_edges(f, i) = e;
    }
  const int E = static_cast<int>(ends.size());
  g.edges.resize(E, 2);
  g.edge_faces.resize(E, 2);
  g.edge_sides.resize(E, 2);
  for (int e = 0; e < E; ++e) {
    if (faces[e][0] < 0) {  // a boundary edge run from its larger end: its one face goes first
      std::swap(ends[e][0], ends[e][1]);
      std::swap(faces[e][0], faces[e][1]);
      std::swap(sides[e][0], sides[e][1]);
    }
    for (int k = 0; k < 2; ++k) {
      g.edges(e, k) = ends[e][k];
      g.edge_faces(e, k) = faces[e][k];
      g.edge_sides(e, k) = sides[e][k];
    }
  }
  std::vector<char> used(g.num_vertices, 0);
  for (int f = 0; f < F; ++f)
    for (int i = 0; i < 3; ++i) used[mesh.F(f, i)] = 1;
  for (int v = 0; v < g.num_vertices; ++v)
    if (!used[v])
      throw InputError(prefix(source) + "vertex " + std::to_string(v) +
                       " (0-based) belongs to no face: remove the unused vertices (a cross field's singularities, cone "
                       "files and seams are per vertex of the surface, so every vertex must lie on it)");
  if (!build_fans(mesh, g))  // surface_topology has reported every non-manifold vertex above
    throw InputError(prefix(source) + "a vertex's faces do not form one fan (non-manifold mesh)");
  return g;
}

// One component: every face reached from face 0 across edges.
bool connected(const SurfaceGraph& g) {
  std::vector<char> seen(g.num_faces, 0);
  std::vector<int> stack{0};
  seen[0] = 1;
  int count = 1;
  while (!stack.empty()) {
    const int f = stack.back();
    stack.pop_back();
    for (int i = 0; i < 3; ++i)
      if (const int h = g.neighbour(f, i); h >= 0 && !seen[h]) {
        seen[h] = 1;
        ++count;
        stack.push_back(h);
      }
  }
  return count == g.num_faces;
}

// The fast construction: half-edges sorted by their undirected edge; every edge must have
// exactly two, one each way (or, with allow_boundary, one: a boundary edge). Edges are
// numbered in order of first appearance (face by face, side by side), as the checked
// construction numbers them. Null at the first defect.
std::optional<SurfaceGraph> sorted_surface_graph(const Mesh& mesh, bool allow_boundary) {
  if (mesh.element_type() != ElementType::Triangle || mesh.dim() != 3 || mesh.num_elements() == 0) return std::nullopt;
  SurfaceGraph g;
  g.num_vertices = mesh.num_vertices();
  g.num_faces = mesh.num_elements();
  const int F = g.num_faces, H = 3 * F;
  std::vector<std::pair<uint64_t, int>> half(H);  // (undirected key, half-edge 3 f + i)
  for (int f = 0; f < F; ++f)
    for (int i = 0; i < 3; ++i) {
      const uint64_t a = static_cast<uint32_t>(mesh.F(f, i)), b = static_cast<uint32_t>(mesh.F(f, (i + 1) % 3));
      half[3 * f + i] = {std::min(a, b) << 32 | std::max(a, b), 3 * f + i};
    }
  std::sort(half.begin(), half.end());
  std::vector<int> twin(H, -1);
  for (int k = 0; k < H;) {
    const int n = k + 1 < H && half[k + 1].first == half[k].first ? 2 : 1;
    if (k + n < H && half[k + n].first == half[k].first) return std::nullopt;  // three faces on an edge
    if (n == 1 && !allow_boundary) return std::nullopt;
    if (n == 2) {
      twin[half[k].second] = half[k + 1].second;
      twin[half[k + 1].second] = half[k].second;
    }
    k += n;
  }
  g.face_edges.resize(F, 3);
  std::vector<std::array<int, 6>> rows;  // per edge: ends, faces, sides
  rows.reserve(static_cast<size_t>(H) / 2 + 1);
  for (int h = 0; h < H; ++h) {
    const int t = twin[h];
    if (t >= 0 && t < h) {
      g.face_edges(h / 3, h % 3) = g.face_edges(t / 3, t % 3);
      continue;
    }
    const int e = static_cast<int>(rows.size()), f = h / 3, i = h % 3;
    const int a = mesh.F(f, i), b = mesh.F(f, (i + 1) % 3);
    g.face_edges(f, i) = e;
    if (t < 0) {  // a boundary edge: its face first, its ends as the face runs it
      rows.push_back({a, b, f, -1, i, -1});
      continue;
    }
    if (mesh.F(t / 3, t % 3) == a) return std::nullopt;  // both faces run through the edge the same way
    // edge_faces(e, 0) runs from the smaller end to the larger
    if (a < b) rows.push_back({a, b, f, t / 3, i, t % 3});
    else rows.push_back({b, a, t / 3, f, t % 3, i});
  }
  const int E = static_cast<int>(rows.size());
  g.edges.resize(E, 2);
  g.edge_faces.resize(E, 2);
  g.edge_sides.resize(E, 2);
  for (int e = 0; e < E; ++e)
    for (int k = 0; k < 2; ++k) {
      g.edges(e, k) = rows[e][k];
      g.edge_faces(e, k) = rows[e][2 + k];
      g.edge_sides(e, k) = rows[e][4 + k];
    }
  if (!build_fans(mesh, g) || !connected(g)) return std::nullopt;
  return g;
}

}  // namespace

SurfaceGraph surface_graph(const Mesh& mesh, const std::string& source, bool allow_boundary) {
  check_mesh_structure(mesh, source);
  if (std::optional<SurfaceGraph> g = sorted_surface_graph(mesh, allow_boundary)) return std::move(*g);
  SurfaceGraph checked = checked_surface_graph(mesh, source, allow_boundary);  // throws, naming the defect
  return checked;
}

}  // namespace strictmin
