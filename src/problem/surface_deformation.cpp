#include "strictmin/problem/surface_deformation.h"

#include <Eigen/Dense>

#include "strictmin/io/input_error.h"

namespace strictmin {

Problem make_surface_deformation_problem(const Mesh& mesh) {
  if (mesh.element_type() != ElementType::Triangle || mesh.dim() != 3)
    throw InputError("surface deformation needs a triangle mesh with 3D vertex positions");
  // make_problem already builds each triangle's frame, gradients and area for a surface
  // (as for a parametrization); the image becomes 3D and the targets the rest Jacobians.
  Problem p = make_problem(mesh);
  p.image_dim = 3;
  p.positions = mesh.V;
  const int E = p.num_elements();
  p.targets.resize(static_cast<Eigen::Index>(E) * 3, 2);
  for (int e = 0; e < E; ++e) p.set_target(e, p.jacobian(e, p.positions));
  return p;
}

}  // namespace strictmin
