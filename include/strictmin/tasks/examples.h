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

namespace strictmin {

struct Example {
  std::string name;
  Mesh mesh;
  std::vector<Handle> handles;
};

std::vector<std::string> example_names();
// Throws InputError for an unknown name (listing the known ones).
Example make_example(const std::string& name);

}  // namespace strictmin
