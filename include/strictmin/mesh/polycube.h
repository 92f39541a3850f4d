#pragma once
// Polycubes made in code (closed surfaces with a known, exactly axis-aligned cross field):
// the boundary of a union of unit cubes, each boundary square split into an n by n grid
// whose inner points are moved in the square's plane and whose cells take pseudo-random
// diagonals (an irregular triangulation of a flat square). Consistently oriented, outward.
#include <array>
#include <vector>

#include "strictmin/mesh/mesh.h"

namespace strictmin {

// cubes: integer positions of the unit cubes; n >= 1 cells per square side; scale
// multiplies every coordinate. The surface must be a manifold (no two cubes meeting only
// at an edge or a corner).
Mesh make_polycube(const std::vector<std::array<int, 3>>& cubes, int n, double scale = 1.0, unsigned seed = 1);

// A cube of side `side` (one unit cube scaled) and the genus-1 frame (3 by 3 by 1 cubes
// without the centre one).
Mesh make_cube_surface(int n, double side = 5.0, unsigned seed = 1);
Mesh make_frame_surface(int n, unsigned seed = 1);

// The frame with its flat top and bottom bulged outward by a smooth bump (0.25 high): the
// field can no longer be parallel, so every seamless map distorts somewhere (the gparam
// demo's and the tests' closed mesh of genus 1 with a non-trivial optimum).
Mesh make_bulged_frame_surface(int n, unsigned seed = 1);

// A frame (either of the two above) less the faces of one outer side square (x = 0,
// 1 <= y <= 2): genus 1 with one boundary loop, a square window (the gparam demo's and the
// tests' surface of genus 1 with boundary).
Mesh frame_with_a_window(const Mesh& frame);

}  // namespace strictmin
