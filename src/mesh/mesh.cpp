#include "strictmin/mesh/mesh.h"

#include <cmath>

namespace strictmin {

bool Mesh::is_planar(double relative_tolerance) const {
  if (element_type() != ElementType::Triangle) return false;
  if (dim() == 2) return true;
  if (dim() != 3 || V.rows() == 0) return false;
  // Constant z up to a tolerance relative to the bounding-box diagonal.
  // Half extents: hi - lo overflows for coordinates near the largest double.
  const Eigen::RowVector3d lo = V.colwise().minCoeff();
  const Eigen::RowVector3d hi = V.colwise().maxCoeff();
  const Eigen::RowVector3d half_extent = 0.5 * hi - 0.5 * lo;
  const double half_diagonal = half_extent.stableNorm();
  if (!std::isfinite(half_diagonal)) return false;
  return half_extent(2) <= relative_tolerance * half_diagonal;
}

Mesh to_planar(const Mesh& mesh) {
  if (mesh.dim() != 3 || !mesh.is_planar()) return mesh;
  Mesh planar = mesh;
  planar.V = mesh.V.leftCols(2);
  return planar;
}

}  // namespace strictmin
