#include "strictmin/field/surface_graph.h"

#include <algorithm>
#include <array>
#include <unordered_map>

#include "strictmin/io/input_error.h"
#include "strictmin/param/topology.h"

namespace strictmin {
namespace {

std::string prefix(const std::string& source) { return source.empty() ? std::string("gparam: ") : source + ": "; }

void check_closed_manifold(const Mesh& mesh, const std::string& source) {
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
                     " connected components; global parametrization takes one closed surface");
  if (!t.boundary_loops.empty())
    throw InputError(prefix(source) + "the surface has " + std::to_string(t.boundary_loops.size()) +
                     " boundary loop(s) (first at vertex " + std::to_string(t.boundary_loops.front().front()) +
                     "); gparam takes closed surfaces only (use 'strictmin param' for a disk)");
}

}  // namespace

int SurfaceGraph::neighbour(int f, int i) const {
  const int e = face_edges(f, i);
  return edge_faces(e, 0) == f && edge_sides(e, 0) == i ? edge_faces(e, 1) : edge_faces(e, 0);
}

SurfaceGraph surface_graph(const Mesh& mesh, const std::string& source) {
  check_closed_manifold(mesh, source);
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
  for (int e = 0; e < E; ++e)
    for (int k = 0; k < 2; ++k) {
      g.edges(e, k) = ends[e][k];
      g.edge_faces(e, k) = faces[e][k];
      g.edge_sides(e, k) = sides[e][k];
    }
  // Fans: from any face of v, the next face counter-clockwise lies across the side that
  // ends at v (side (i + 2) % 3 for the corner i of v).
  std::vector<int> first_face(g.num_vertices, -1), first_corner(g.num_vertices, -1), degree(g.num_vertices, 0);
  for (int f = 0; f < F; ++f)
    for (int i = 0; i < 3; ++i) {
      const int v = mesh.F(f, i);
      ++degree[v];
      if (first_face[v] < 0) {
        first_face[v] = f;
        first_corner[v] = i;
      }
    }
  g.fan_start.assign(g.num_vertices + 1, 0);
  for (int v = 0; v < g.num_vertices; ++v) {
    if (degree[v] == 0)
      throw InputError(prefix(source) + "vertex " + std::to_string(v) + " belongs to no face");
    g.fan_start[v + 1] = g.fan_start[v] + degree[v];
  }
  g.fan_faces.resize(g.fan_start.back());
  g.fan_corners.resize(g.fan_start.back());
  for (int v = 0; v < g.num_vertices; ++v) {
    int f = first_face[v], i = first_corner[v];
    for (int k = g.fan_start[v]; k < g.fan_start[v + 1]; ++k) {
      g.fan_faces[k] = f;
      g.fan_corners[k] = i;
      f = g.neighbour(f, (i + 2) % 3);
      i = mesh.F(f, 0) == v ? 0 : mesh.F(f, 1) == v ? 1 : 2;
    }
  }
  return g;
}

}  // namespace strictmin
