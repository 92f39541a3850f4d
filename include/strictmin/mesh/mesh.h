#pragma once
// A triangle or tetrahedral mesh: V is #V by 2 or 3, F is #F by 3 (triangles) or #F by 4
// (tets), 0-based. A parametrized surface also carries UV (#UV by 2) and FUV (#F by 3).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace strictmin {

enum class ElementType { Triangle, Tetrahedron };

struct Mesh {
  Eigen::MatrixXd V;    // #V by dim
  Eigen::MatrixXi F;    // #F by 3 or 4
  Eigen::MatrixXd UV;   // #UV by 2, optional (OBJ vt)
  Eigen::MatrixXi FUV;  // #F by 3, optional (OBJ f v/vt)

  ElementType element_type() const {
    return F.cols() == 4 ? ElementType::Tetrahedron : ElementType::Triangle;
  }
  int dim() const { return static_cast<int>(V.cols()); }
  int num_vertices() const { return static_cast<int>(V.rows()); }
  int num_elements() const { return static_cast<int>(F.rows()); }
  bool has_uv() const { return UV.rows() > 0 && FUV.rows() == F.rows(); }
  // A triangle mesh whose every vertex lies in the plane z = const (or that has 2D
  // coordinates): deformed in 2D.
  bool is_planar(double relative_tolerance = 1e-12) const;
};

// A planar triangle mesh as #V by 2 (drops a constant z); other meshes unchanged.
Mesh to_planar(const Mesh& mesh);

// The mesh less the elements `drop` marks (#F entries, non-zero: dropped), without the
// vertices no element uses any more (the others keep their order). UV is not kept.
Mesh without_elements(const Mesh& mesh, const std::vector<char>& drop);

}  // namespace strictmin
