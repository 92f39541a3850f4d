#pragma once
// Quad meshes from integer-grid maps (docs/gparam.md, "Quad meshes"). On an integer-grid map
// (a seamless per-corner UV map whose seam translations are integers and whose cones lie at
// integer points; gparam --integer-grid) the integer lines close up across the seams, and
// every unit square [i, i+1] x [j, j+1] of UV is one quad of the surface.
//
// Each square is found from a triangle containing its centre and flooded across the edges
// that meet it (through it or along its sides), carried through each seam's transition: the faces it
// covers, their UV areas inside it (which must add up to 1) and the triangles holding its
// four corners. A corner is a surface point: a vertex, a point on an edge or inside a face,
// so corners found from different squares are one vertex of the quad mesh.
//
// A square that touches a flipped (or zero-area) triangle, wraps onto itself, is not covered
// exactly once, faces against the surface, or overlaps another square (shares one of its
// edges run the same way, three of its corners or a diagonal) is left out: the quad mesh then
// has holes, and the extraction says so (complete = false). A map without flips whose squares are all covered gives a closed
// quad mesh with the surface's Euler characteristic, one quad per unit of UV area, and a
// vertex of valence 4 - k at each cone of index k/4.
#include <Eigen/Core>
#include <cmath>
#include <map>
#include <string>

#include "strictmin/mesh/mesh.h"

namespace strictmin {

// The most unit squares extract_quads takes (UV area of the triangles of positive area).
inline constexpr double kMaxQuadExtractionSquares = 1e7;

// The UV area of the map's triangles of positive area: about the unit squares it has (what
// kMaxQuadExtractionSquares bounds). The map must have per-corner UVs.
double positive_uv_area(const Mesh& map);

struct QuadExtractionOptions {
  // UV units: how far a seam translation or a cone may be from the grid, and how close to a
  // vertex or an edge a grid point counts as on it.
  double tolerance = 1e-6;
  // Fill each hole whose boundary unfolds into a simple loop with no cone on or inside it with
  // the grid's squares inside the loop; their inner vertices are placed by averaging their grid
  // neighbours, off the surface (vertex_face -1). Holes that do not qualify stay.
  bool fill_holes = false;
  // Empty when the options are usable, else why not.
  std::string invalid_reason() const;
};

struct QuadMesh {
  Eigen::MatrixXd V;    // #vertices by 3, on the input surface
  Eigen::MatrixXi Q;    // #quads by 4, counter-clockwise about the surface's outward normal
  Eigen::MatrixXd UV;   // integer UVs of the quads' corners, each quad in its own chart
  Eigen::MatrixXi QUV;  // #quads by 4 rows of UV
  // Where each vertex lies: a triangle of the input and barycentric coordinates in it (-1 and
  // NaN for the inner vertices of filled holes).
  Eigen::VectorXi vertex_face;
  Eigen::MatrixXd vertex_barycentric;  // #vertices by 3

  int num_vertices() const { return static_cast<int>(V.rows()); }
  int num_quads() const { return static_cast<int>(Q.rows()); }
};

// The quads' shapes in 3D (none: every figure NaN). At a corner with sides a and b (to the
// next and the previous corner) and the quad's normal n (the cross product of its diagonals),
// the angle is that between a and b, and the scaled Jacobian (a x b) . n / (|a| |b| |n|):
// 1 for a right angle, 0 for a degenerate corner, negative for a corner folded over.
struct QuadQuality {
  double min_angle_deg = NAN, max_angle_deg = NAN;
  double min_scaled_jacobian = NAN;
  double min_side = NAN, max_side = NAN, mean_side = NAN;  // surface units
};

// The quality figures of a quad mesh.
QuadQuality quad_quality(const QuadMesh& quads);

struct QuadExtraction {
  QuadMesh mesh;
  // Closed, manifold (edges and vertices), the surface's Euler characteristic, one quad per unit of UV area, and
  // either no square left out and no fold, or the holes filled (fill_holes).
  bool complete = false;
  int filled_holes = 0, filled_squares = 0;  // fill_holes: the holes filled and their squares
  double uv_area = 0;          // the map's signed UV area: the number of squares when complete
  int flipped_triangles = 0;   // of the map: UV area <= 0
  int cones = 0;               // vertices of the map with a non-zero index (none of their triangles flipped)
  int dropped_squares = 0;     // squares left out (the reasons below, each square counted once)
  int squares_touching_flips = 0, squares_wrapped = 0, squares_not_covered_once = 0;
  int squares_overlapping = 0;  // sharing a quad edge with another square, run the same way, or more than a
                                // side's corners (three, or a diagonal): folded onto it (next to a fold)
  int squares_inverted = 0;     // facing against the surface (a corner from another layer of a fold)
  int edges = 0;               // of the quad mesh
  int boundary_edges = 0;      // quad edges with one quad (around the holes)
  int holes = 0;               // connected groups of boundary edges
  int non_manifold_edges = 0;  // a directed quad edge used twice
  // Vertices whose quads form several fans (touching at the vertex alone, as across a pinched
  // hole): each fan after the first gets its own copy of the vertex (split_vertices: the copies
  // added), so non_manifold_vertices counts what is left, 0.
  int split_vertices = 0;
  int non_manifold_vertices = 0;
  int euler_characteristic = 0;          // of the quad mesh
  int surface_euler_characteristic = 0;  // of the input surface
  std::map<int, int> valences;           // valence -> how many vertices
  QuadQuality quality;
  double time_s = 0;
};

// Throws InputError (naming `source`) when the map has no per-corner UVs, is not one closed
// manifold triangle surface, is not seamless, or is not an integer-grid map (a seam
// translation or a cone off the grid), when its UVs are far from grid units (more than 1e7
// squares under its triangles, 4e8 grid cells under their UV bounding boxes, or a UV beyond
// 1e9), or when the options are invalid.
QuadExtraction extract_quads(const Mesh& map, const QuadExtractionOptions& options = {},
                             const std::string& source = "");

// Writes the quad mesh as OBJ: v, vt (each quad's integer corners) and f v/vt with four
// corners. Atomic (io/atomic_file.h); throws InputError when the path cannot be written.
void write_quad_obj(const std::string& path, const QuadMesh& quads);

}  // namespace strictmin
