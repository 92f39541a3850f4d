#pragma once
// Internal: the exact scale at which a task computes a surface far from unit size. A task
// whose problem is homogeneous in the surface's size (gparam, param) computes the surface
// divided by it and scales its map back, so that the file's units change nothing. Not a
// public header.
#include <cmath>

#include "strictmin/mesh/mesh.h"

namespace strictmin {

// A power of two near the largest side of the bounding box (the size the reader checks), so
// that the scaling is exact, for a surface far from unit size; 1 (the surface as given, bit
// for bit) when that side is within 2^-10 .. 2^10.
inline double unit_size_scale(const Mesh& mesh) {
  if (mesh.V.rows() == 0) return 1;
  const double side = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).maxCoeff();
  if (!(side > 0) || !std::isfinite(side) || (side >= 0x1p-10 && side <= 0x1p10)) return 1;
  return std::exp2(std::round(std::log2(side)));
}

// The mesh divided by `scale` (a power of two: exact).
inline Mesh scaled_down(const Mesh& mesh, double scale) {
  Mesh scaled = mesh;
  scaled.V /= scale;
  return scaled;
}

}  // namespace strictmin
