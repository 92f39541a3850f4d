#pragma once
// The cut that turns a surface into a disk through every singularity, the field combed
// across the uncut edges, the matchings across the cut, and the cut mesh's vertices (wedges)
// (docs/gparam.md, "The cut").
//
// - A spanning tree of the dual graph (breadth first from face 0); the interior primal edges
//   it does not cross form, with the boundary, a graph with 2g + b - 1 independent loops (b
//   boundary loops); edges ending at a non-singular interior vertex of degree 1 are pruned
//   until none is left. The rest is the cut: seams only (boundary edges are never cut).
// - Combing walks the same tree: each face takes the one of its four directions closest to
//   its parent's transported direction, so the matching is the identity across every tree
//   edge (and across the pruned ones: the field's turn around a regular vertex is a whole
//   number of turns).
// - matching(e) = k in 0..3: the combed direction of edge_faces(e,1) is its transported
//   neighbour's turned by k quarter turns. Then a map whose differential sends the combed
//   direction to the u axis has, across e, uv(face 0 side) = rot(k pi/2) uv(face 1 side) + t.
#include <Eigen/Core>
#include <vector>

#include "strictmin/field/cross_field.h"
#include "strictmin/field/surface_graph.h"

namespace strictmin {

// A maximal path of the cut between nodes (singularities, vertices of cut degree != 2):
// vertices[k] -> vertices[k+1] along edges[k]. `left` faces: the faces in which each edge runs
// in the branch's direction. Its transition: uv(left side) = rotation * uv(right side) + t,
// with one t for the whole branch.
struct SeamBranch {
  std::vector<int> vertices;  // edges.size() + 1
  std::vector<int> edges;
  int quarter_turns = 0;      // the rotation, in quarter turns (0..3)
};

struct CutGraph {
  std::vector<char> tree;       // #E: crossed by the dual spanning tree
  std::vector<char> cut;        // #E
  int num_cut_edges = 0;
  Eigen::VectorXd combed;       // #F: angle of the combed direction in each face's frame
  std::vector<int> matching;    // #E: see above
  Eigen::MatrixXi corner_wedge; // #F by 3: the cut-mesh vertex of each corner
  std::vector<int> wedge_vertex;  // #W: the surface vertex of each wedge
  std::vector<SeamBranch> branches;
  int num_wedges() const { return static_cast<int>(wedge_vertex.size()); }
};

// quarters: every vertex's index in quarters (singularities.h).
CutGraph cut_graph(const Mesh& mesh, const SurfaceGraph& graph, const FaceFrames& frames, const Eigen::VectorXcd& u,
                   const std::vector<int>& quarters);

// The cut mesh: one vertex per wedge (at its surface vertex's position), the faces' corners
// renumbered to wedges.
Mesh cut_mesh(const Mesh& mesh, const CutGraph& cut);

// The rotation by k quarter turns.
Eigen::Matrix2d quarter_rotation(int k);

}  // namespace strictmin
