#pragma once
// Least squares conformal maps (Levy et al. 2002): minimize sum_T A_T |J_T - conformal part|^2
// = sum_T A_T ((u_x - v_y)^2 + (u_y + v_x)^2) over the map, each triangle in its own
// isometric frame, with two boundary vertices pinned (far apart, so the map does not
// collapse). Free boundary; not guaranteed flip-free.
#include <Eigen/Core>
#include <vector>

#include "strictmin/mesh/mesh.h"

namespace strictmin {

// boundary: the disk's boundary loop. Returns #V by 2 (unused vertices at the origin), the
// pinned pair at distance equal to their 3D distance. Throws std::runtime_error if the
// sparse factorization fails.
Eigen::MatrixXd lscm(const Mesh& mesh, const std::vector<int>& boundary);

}  // namespace strictmin
