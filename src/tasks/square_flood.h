#pragma once
// One unit square of an integer-grid map's UV, followed over the surface (quad extraction,
// include/strictmin/tasks/quad_extraction.h): from a triangle holding its centre, across
// every edge that meets it (through it or along a side), each seam's transition applied.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "strictmin/field/surface_graph.h"
#include "strictmin/mesh/mesh.h"
#include "tasks/uv_transitions.h"

namespace strictmin {

// A grid point on the surface, the same from every square that has it as a corner: a mesh
// vertex, an integer point on an edge (in the chart of the edge's face 0) or inside a face
// (in its chart).
struct SurfacePointKey {
  enum Kind : int { Vertex, Edge, Face };
  int kind = Vertex;
  int element = -1;
  std::int64_t u = 0, v = 0;
  bool operator==(const SurfacePointKey& o) const {
    return kind == o.kind && element == o.element && u == o.u && v == o.v;
  }
};

struct SurfacePointKeyHash {
  size_t operator()(const SurfacePointKey& k) const {
    size_t h = static_cast<size_t>(k.kind) * 1000003u + static_cast<size_t>(k.element);
    h = h * 0x9E3779B97F4A7C15ull + static_cast<size_t>(k.u);
    return h * 0x9E3779B97F4A7C15ull + static_cast<size_t>(k.v);
  }
};

struct SquareCorner {
  SurfacePointKey key;
  int face = -1;                      // a triangle holding it
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();  // in that triangle
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();           // in the square's starting chart
};

struct SquareFlood {
  enum class Outcome { Quad, TouchesFlip, Wraps, NotCoveredOnce };
  Outcome outcome = Outcome::Quad;
  std::array<SquareCorner, 4> corners;  // counter-clockwise from (i, j)
  double covered = 0;                   // the UV area of the triangles inside the square
  // Every (face, centre in its chart) with the centre in the closed face: the other starts of
  // the same square.
  std::vector<std::pair<int, Eigen::Vector2d>> centres;
};

class SquareFlooder {
 public:
  SquareFlooder(const Mesh& map, const SurfaceGraph& graph, const std::vector<UvTransition>& transitions,
                double tolerance);
  // The square of centre `centre` (half-integers, in face's chart), face holding the centre.
  SquareFlood flood(int face, const Eigen::Vector2d& centre);

 private:
  struct Visit {
    std::uint32_t stamp = 0;
    Eigen::Vector2d centre;
    Eigen::Matrix2d frame;
  };
  bool cross_to_neighbour(int face, int side, const std::array<Eigen::Vector2d, 3>& t, const Visit& here,
                          std::vector<int>& queue);
  bool is_face0_side(int face, int side) const;
  Eigen::Vector2d across(int face, int side, const Eigen::Vector2d& p) const;
  Visit carried_across(int face, int side, const Visit& here) const;
  SquareFlood::Outcome outcome_of(bool flips, bool all_corners_found, const SquareFlood& s) const;
  static Eigen::Vector2d corner_point(const Visit& here, int k);
  void find_corner_nearby(int k, const std::vector<int>& square_faces, const Eigen::Vector2d& start_centre,
                          std::array<bool, 4>& found, SquareFlood& out);
  void find_corners(int face, const Visit& here, const Eigen::Vector2d& start_centre, std::array<bool, 4>& found,
                    SquareFlood& out) const;
  std::pair<int, Eigen::Vector2d> holding_face(int face, Eigen::Vector2d p) const;
  void key_corner(int face, const Eigen::Vector2d& p, SquareCorner& c) const;

  const Mesh& map_;
  const SurfaceGraph& graph_;
  const std::vector<UvTransition>& transitions_;
  const double tolerance_;
  std::vector<Visit> visits_;
  std::uint32_t stamp_ = 0;
  bool wraps_ = false;  // this flood reached a face a second time in another chart
};

// Whether p lies in the closed UV triangle of face f (within `tolerance`, UV units).
bool uv_face_contains(const Mesh& map, int f, const Eigen::Vector2d& p, double tolerance);

}  // namespace strictmin
