#pragma once
// Edges, edge-face incidences and ordered vertex fans of a connected, oriented manifold
// triangle mesh, closed or (when asked) with boundary: what the cross field, its
// singularities and the cut graph walk on (docs/gparam.md).
//
// Conventions: side i of face f is the edge from F(f, i) to F(f, (i + 1) % 3). An interior
// edge e joins edges(e, 0) < edges(e, 1); edge_faces(e, 0) is the face in which it runs from
// edges(e, 0) to edges(e, 1), edge_faces(e, 1) the face in which it runs back. A boundary
// edge has edge_faces(e, 1) = edge_sides(e, 1) = -1, and edges(e, 0) -> edges(e, 1) is the
// way it runs in its one face edge_faces(e, 0) (so its ends need not be in order).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "strictmin/mesh/mesh.h"

namespace strictmin {

struct SurfaceGraph {
  int num_vertices = 0;
  int num_faces = 0;
  Eigen::MatrixXi edges;       // #E by 2
  Eigen::MatrixXi face_edges;  // #F by 3: edge of side i
  Eigen::MatrixXi edge_faces;  // #E by 2
  Eigen::MatrixXi edge_sides;  // #E by 2: the side index of e in edge_faces(e, k)
  // Faces around each vertex in counter-clockwise order (about the outward normal):
  // fan_faces[fan_start[v] .. fan_start[v+1]) with the corner index of v in each face. A
  // boundary vertex's fan is open: it starts at the face whose side leaving v is a boundary
  // edge and ends at the face whose side reaching v is one.
  std::vector<int> fan_start, fan_faces, fan_corners;
  std::vector<char> boundary_vertex;  // #V
  int num_boundary_loops = 0;

  int num_edges() const { return static_cast<int>(edges.rows()); }
  bool is_boundary_edge(int e) const { return edge_faces(e, 1) < 0; }
  bool has_boundary() const { return num_boundary_loops > 0; }
  // The face across side i of face f, -1 across a boundary edge.
  int neighbour(int f, int i) const;
  // The edge crossed from fan face k of v to fan face k + 1 (the side of fan face k that
  // reaches v); for the last face of a boundary vertex's fan, the boundary edge ending its fan.
  int fan_edge(int k) const { return face_edges(fan_faces[k], (fan_corners[k] + 2) % 3); }
  int euler_characteristic() const { return num_vertices - num_edges() + num_faces; }
};

// A breadth-first spanning tree of the dual graph from face 0 (across interior edges): the
// faces in visiting order, and in parent_edge each face's edge to its parent (-1 for face 0).
std::vector<int> dual_spanning_tree(const SurfaceGraph& graph, std::vector<int>& parent_edge);

// Throws InputError (naming `source`) unless the mesh is a connected, consistently oriented
// 2-manifold triangle mesh in 3D, closed unless allow_boundary: several components, a
// boundary (when not allowed), non-manifold edges or vertices and tetrahedra are refused with
// the offending element.
SurfaceGraph surface_graph(const Mesh& mesh, const std::string& source = "", bool allow_boundary = false);

}  // namespace strictmin
