#pragma once
// A triangle surface in 3D deformed in 3D (libigl's ARAP tutorial set-up): image_dim 3,
// domain_dim 2. Each triangle's Jacobian is 3 by 2, from barycentric gradients in the
// triangle's own isometric frame (local_frame_coordinates); its target is the rest pose's
// Jacobian, the frame's two axes in 3D (orthonormal columns), so field deviation
// ||J_T - R_T|| is 0 at rest and the ARAP local step's family is {3 by 2 matrices with
// orthonormal columns} (closest_rotation).
#include "strictmin/mesh/mesh.h"
#include "strictmin/problem/problem.h"

namespace strictmin {

// mesh: triangles with 3D vertex positions. Positions start at the rest pose; nothing fixed
// but vertices used by no triangle.
Problem make_surface_deformation_problem(const Mesh& mesh);

}  // namespace strictmin
