#pragma once
// Validation of a mesh read from a file: rejects what the maths can't take, naming the
// element and the reason (InputError); warns about what it can ignore.
#include <string>
#include <vector>

#include "strictmin/mesh/mesh.h"

namespace strictmin {

// Checks, in this order: empty mesh; non-finite coordinates (vertex index); indices out of
// range or repeated in an element; zero-area triangles / zero-volume tets (relative to the
// mesh size); non-manifold edges (triangles: an edge in more than two faces) or faces
// (tets: a face in more than two tets); inconsistent orientation (triangles: an interior
// edge traversed the same way by both faces; planar triangles and tets: signed areas /
// volumes of both signs). Unreferenced vertices are kept (their indices stay valid) and
// reported in `warnings`. `source` names the file in messages.
// Also rejected (after the zero-measure check): two elements over the same vertex set.
// Orientation: an all-clockwise planar mesh is accepted silently; all-negative tets are
// rejected ("all tets are inverted ... swap two corners"). Degenerate means area <=
// 1e-14 d^2 or volume <= 1e-14 d^3, d the bounding-box diagonal of the used vertices.
// With the geometry checks, a mesh whose bounding box (used vertices) has its largest side
// outside [1e-150, 1e150] is rejected as too large or too small for the solvers.
// check_geometry = false skips the zero-area/volume and orientation checks: for the image of
// a map (eval's MAPPED mesh), where flipped or collapsed elements are results to report.
void validate_mesh(const Mesh& mesh, const std::string& source, std::vector<std::string>* warnings = nullptr,
                   bool check_geometry = true);

// Sizes (the largest side of the used vertices' bounding box; handle targets' coordinates)
// the solvers take: beyond them squared and cubed lengths overflow or underflow and a solve
// ends in numerical-error (measured: 1e-150 and 1e150 solve, 1e-170 and 1e170 do not).
constexpr double kSmallestSize = 1e-150, kLargestSize = 1e150;

// The part of validate_mesh that every function taking a Mesh relies on, for meshes built in
// code: 3 or 4 corners per element, 2 or 3 coordinates per vertex (3 for tets), with UVs two
// per texture coordinate and as many texture corners per element as corners, finite
// coordinates and UVs (unless `require_finite` is false: a map written whatever it holds),
// every index (and UV index) in range, no vertex twice in an element. An empty mesh passes. Throws InputError naming `source`, the element or vertex and the reason (an index
// out of range read and wrote out of bounds before).
void check_mesh_structure(const Mesh& mesh, const std::string& source, bool require_finite = true);

// check_mesh_structure, then validate_mesh's zero-area / zero-volume test and its size range
// (1e-150 to 1e150): for library entries that take a mesh built in code and divide by its
// areas (global_parametrize). Throws InputError naming `source` and the element.
void check_element_measures(const Mesh& mesh, const std::string& source);

// True when every vertex coordinate and texture coordinate is finite (check_mesh_structure
// with require_finite names the first one that is not).
bool coordinates_are_finite(const Mesh& mesh);

// Vertices used by no element.
std::vector<int> unreferenced_vertices(const Mesh& mesh);

}  // namespace strictmin
