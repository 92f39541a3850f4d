#pragma once
// Tutte's embedding of a disk: the boundary loop on the unit circle at arc-length spacing,
// every interior vertex at the average of its neighbours (uniform weights). With uniform
// weights and a convex boundary the map is a bijection (Tutte 1963, Floater 2003): no flips.
// Cotangent weights are not used because they can be negative and then flip triangles.
#include <Eigen/Core>
#include <vector>

#include "strictmin/mesh/mesh.h"

namespace strictmin {

// boundary: the disk's boundary loop (param/topology.h disk_boundary). Returns #V by 2;
// vertices used by no face are put at the origin. Throws std::runtime_error if the sparse
// factorization fails (it cannot for a connected disk).
Eigen::MatrixXd tutte_embedding(const Mesh& mesh, const std::vector<int>& boundary);

}  // namespace strictmin
