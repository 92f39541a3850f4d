#pragma once
// Meshes made in code: the built-in examples and the tests' small meshes.
#include "strictmin/mesh/mesh.h"

namespace strictmin {

// Planar grid of nx by ny cells over [x0, x0+width] x [y0, y0+height], each cell split
// into two triangles along alternating diagonals (so the grid has no preferred direction).
// V is #V by 2, vertex (i, j) has index j * (nx + 1) + i; triangles counter-clockwise.
Mesh make_grid(int nx, int ny, double width = 1.0, double height = 1.0, double x0 = 0.0, double y0 = 0.0);

// Tet box of nx by ny by nz cubes over [0,width]x[0,height]x[0,depth], each cube split
// into 6 tets (Kuhn subdivision: conforming across cubes), all positively oriented.
// Vertex (i, j, k) has index (k * (ny + 1) + j) * (nx + 1) + i.
Mesh make_tet_box(int nx, int ny, int nz, double width = 1.0, double height = 1.0, double depth = 1.0);

}  // namespace strictmin
