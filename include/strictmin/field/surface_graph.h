#pragma once
// Edges, edge-face incidences and ordered vertex fans of a closed, connected, oriented
// manifold triangle mesh: what the cross field, its singularities and the cut graph walk on
// (docs/gparam.md).
//
// Conventions: side i of face f is the edge from F(f, i) to F(f, (i + 1) % 3). Edge e joins
// edges(e, 0) < edges(e, 1); edge_faces(e, 0) is the face in which it runs from edges(e, 0)
// to edges(e, 1), edge_faces(e, 1) the face in which it runs back.
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
  // fan_faces[fan_start[v] .. fan_start[v+1]) with the corner index of v in each face.
  std::vector<int> fan_start, fan_faces, fan_corners;

  int num_edges() const { return static_cast<int>(edges.rows()); }
  // The face across side i of face f.
  int neighbour(int f, int i) const;
  int euler_characteristic() const { return num_vertices - num_edges() + num_faces; }
};

// A breadth-first spanning tree of the dual graph from face 0: the faces in visiting order,
// and in parent_edge each face's edge to its parent (-1 for face 0).
std::vector<int> dual_spanning_tree(const SurfaceGraph& graph, std::vector<int>& parent_edge);

// Throws InputError (naming `source`) unless the mesh is a closed, connected, consistently
// oriented 2-manifold triangle mesh in 3D: several components, a boundary, non-manifold
// edges or vertices and tetrahedra are refused with the offending element.
SurfaceGraph surface_graph(const Mesh& mesh, const std::string& source = "");

}  // namespace strictmin
