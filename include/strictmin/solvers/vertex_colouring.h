#pragma once
// Greedy colouring of the free vertices such that no two vertices of one colour share an
// element: their 1-rings are disjoint, so all vertices of one colour can move at once in a
// relaxation sweep (relax.h; paper Section 5.3, "red-black" relaxation).
#include <Eigen/Core>
#include <vector>

namespace strictmin {

struct VertexColouring {
  std::vector<int> colour;   // #V: colour of each free vertex that is in some element, else -1
  int num_colours = 0;
  std::vector<int> offsets;  // num_colours + 1: colour c's vertices are order[offsets[c]..offsets[c+1])
  std::vector<int> order;    // the coloured vertices, colour by colour, increasing index within one
};

// elements: #E by corners (vertex indices); fixed: #V flags (1 = not coloured).
// Vertices are coloured in index order, each with the smallest colour none of the vertices
// it shares an element with has.
VertexColouring colour_free_vertices(const Eigen::MatrixXi& elements, const std::vector<char>& fixed);

}  // namespace strictmin
