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

Mesh without_elements(const Mesh& mesh, const std::vector<char>& drop) {
  std::vector<int> kept;
  for (int f = 0; f < mesh.num_elements(); ++f)
    if (!drop[static_cast<std::size_t>(f)]) kept.push_back(f);
  std::vector<int> index(static_cast<std::size_t>(mesh.num_vertices()), -1);
  for (int f : kept)
    for (int i = 0; i < mesh.F.cols(); ++i) index[static_cast<std::size_t>(mesh.F(f, i))] = 0;
  int next = 0;
  for (int& v : index)
    if (v == 0) v = next++;
  Mesh out;
  out.V.resize(next, mesh.V.cols());
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (index[static_cast<std::size_t>(v)] >= 0) out.V.row(index[static_cast<std::size_t>(v)]) = mesh.V.row(v);
  out.F.resize(static_cast<Eigen::Index>(kept.size()), mesh.F.cols());
  for (std::size_t k = 0; k < kept.size(); ++k)
    for (int i = 0; i < mesh.F.cols(); ++i)
      out.F(static_cast<Eigen::Index>(k), i) = index[static_cast<std::size_t>(mesh.F(kept[k], i))];
  return out;
}

}  // namespace strictmin
