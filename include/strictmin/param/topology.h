#pragma once
// Is a triangle mesh a topological disk (the input free-boundary parametrization can take)?
// Counts components, boundary loops and the genus from the Euler characteristic
// chi = V - E + F = 2 - 2g - b, and finds non-manifold edges and vertices.
#include <string>
#include <vector>

#include "strictmin/mesh/mesh.h"

namespace strictmin {

struct SurfaceTopology {
  int vertices = 0;  // used by some face
  int edges = 0;
  int faces = 0;
  int components = 0;                            // connected through shared vertices
  std::vector<std::vector<int>> boundary_loops;  // each in the faces' orientation (interior on the left)
  int non_manifold_edge = -1;                    // first face of an edge in more than two faces, or -1
  int non_manifold_vertex = -1;                  // first vertex whose faces form more than one fan, or -1
  int euler_characteristic() const { return vertices - edges + faces; }
  // g from chi = 2 - 2g - b (meaningful for a connected, manifold, orientable surface).
  int genus() const { return (2 - euler_characteristic() - static_cast<int>(boundary_loops.size())) / 2; }
};

SurfaceTopology surface_topology(const Mesh& mesh);

// The boundary loop of a disk, oriented like the faces. Throws InputError naming what was
// found and what to do (cut it to a disk first) for tets, several components, non-manifold
// edges or vertices, a closed surface (with its genus), several boundary loops, or one loop
// with handles (genus > 0). `source` names the file in messages.
std::vector<int> disk_boundary(const Mesh& mesh, const std::string& source);

}  // namespace strictmin
