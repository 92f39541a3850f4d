#pragma once
// The seams of a per-corner UV map read back from the UVs alone (what quad extraction
// needs, docs/gparam.md "Quad meshes"): across every edge, the two sides' UVs are related by
//   uv(edge_faces(e, 0) side) = R uv(edge_faces(e, 1) side) + t,
// R a quarter turn and t a translation, integer on an integer-grid map. An edge whose two
// sides share their corners has R = I and t = 0.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "strictmin/field/surface_graph.h"
#include "strictmin/mesh/mesh.h"

namespace strictmin {

struct UvTransition {
  bool known = true;    // false: the edge is degenerate in UV (zero length), so R is undetermined
  int quarter_turns = 0;
  Eigen::Vector2d translation = Eigen::Vector2d::Zero();  // integer values, exactly
  // From the chart of edge_faces(e, 0) to that of edge_faces(e, 1) and back.
  Eigen::Vector2d to_face1(const Eigen::Vector2d& x) const;
  Eigen::Vector2d to_face0(const Eigen::Vector2d& x) const;
  Eigen::Matrix2d rotation() const;
};

// The UV of corner `corner` of face f.
inline Eigen::Vector2d corner_uv(const Mesh& map, int f, int corner) {
  return map.UV.row(map.FUV(f, corner)).transpose();
}

// Every edge's transition. Throws InputError (naming `source` and the edge's vertices,
// 0-based) when the two sides of an edge are not related by a quarter turn (the map is not
// seamless) or the translation is not integer within `tolerance` (not an integer-grid map).
std::vector<UvTransition> integer_uv_transitions(const Mesh& map, const SurfaceGraph& graph, double tolerance,
                                                 const std::string& source);

// Each vertex's cone index in quarters from the UV angles around it (4 - total angle / (pi/2));
// 0 for regular vertices. Vertices next to a face of zero or negative UV area get 0 (their
// angles are not those of a cone). Throws InputError when a cone is not at an integer point
// within `tolerance`.
std::vector<int> cones_on_the_grid(const Mesh& map, const SurfaceGraph& graph, double tolerance,
                                   const std::string& source);

// Twice the signed UV area of face f (positive: counter-clockwise, as the surface).
double doubled_uv_area(const Mesh& map, int f);

}  // namespace strictmin
