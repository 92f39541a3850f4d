#pragma once
// Filling the holes of an extracted quad mesh with the grid's own squares (quad extraction's
// fill_holes; docs/gparam.md, "Filling the holes"). A hole's boundary loop is unfolded into the
// plane by the angles of its corners on the hole's side (a vertex of valence 4 - k when
// complete, k its cone index, with `fan` kept quads has 4 - k - fan quarter turns left for the
// hole). When the loop closes up after one full turn (no cone inside) as a simple
// counter-clockwise polygon, the unit squares inside it are the hole's quads: their corners on
// the loop are the loop's vertices, the grid points inside are new vertices placed by averaging
// their grid neighbours (the loop held), off the surface.
#include <cstdint>
#include <vector>

#include "strictmin/tasks/quad_extraction.h"

namespace strictmin {

struct HoleFilling {
  int filled_holes = 0, filled_squares = 0;
};

// A directed edge a -> b of a quad mesh as one key.
inline std::uint64_t directed_edge(int a, int b) {
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

// cone_quarters: per vertex of q, its cone index in quarters (0 when regular). Adds the filled
// quads, vertices (vertex_face -1, barycentric NaN) and UVs (in each hole's own frame) to q.
HoleFilling fill_quad_holes(QuadMesh& q, const std::vector<int>& cone_quarters);

}  // namespace strictmin
