#pragma once
// Built-in examples: a mesh and its handles, made in code.
//   square  the paper's Figure 2: a 20 x 20 square grid with its boundary fixed and the
//           centre vertex moved sideways by 0.15 (a fifth of the way to the boundary)
//   bar     a planar 8 x 1 bar (64 x 8 cells), left end fixed, right end lifted by 2 and
//           turned by 45 degrees about its midpoint (a bend)
//   tetbar  a 4 x 1 x 1 tet bar (16 x 4 x 4 cubes), one end fixed, the other end moved
//           up by 1 and turned 45 degrees about the bar's axis
#include <string>
#include <vector>

#include "strictmin/mesh/handle.h"
#include "strictmin/mesh/mesh.h"
#include "strictmin/problem/problem.h"

namespace strictmin {

struct Example {
  std::string name;
  Mesh mesh;
  std::vector<Handle> handles;
};

std::vector<std::string> example_names();
// Throws InputError for an unknown name (listing the known ones).
Example make_example(const std::string& name);

// The paper's Figure 2 at any size: a cells x cells grid of the unit square (2 cells^2
// triangles), boundary fixed, the centre vertex (the middle one for odd cells: the one just
// below-left of the middle) moved by `shift` in x.
// make_example("square") is make_square_example(20, 0.15).
Example make_square_example(int cells, double shift = 0.15);

// The example's Problem: make_problem(mesh) with its handles fixed.
Problem example_problem(const Example& example);

// A disk mesh's parametrization problem (make_problem: per-triangle frames, identity targets)
// with three boundary vertices held, a third of the boundary apart (in vertex order), where
// an L2 map with one pinned vertex puts them: the surface problem of the L-infinity
// benchmark and tests. A mesh with fewer than three boundary vertices is returned unpinned.
Problem three_pin_disk_problem(const Mesh& disk);

}  // namespace strictmin
