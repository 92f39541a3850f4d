#pragma once
// Where ARAP / ASAP deformation starts local-global (its local step converges slowly from a
// start whose rotations are far from the answer's: an L2 field-deviation map with identity
// targets when the handles are turned by a large rotation).
#include <Eigen/Core>
#include <vector>

#include "strictmin/mesh/handle.h"
#include "strictmin/problem/problem.h"
#include "strictmin/solvers/local_global.h"

namespace strictmin {

// The rotation (image_dim square, det +1) of the handles' best rigid motion from their rest
// positions (rest, #V by image_dim) to their targets, least squares (Kabsch); the identity
// with fewer than two handles.
Eigen::MatrixXd handles_best_rotation(const Eigen::MatrixXd& rest, const std::vector<Handle>& handles);

// Of the L2 field-deviation maps with the problem's targets and with every target turned by
// handles_best_rotation, the one with the lower maximum local distortion (options.local).
// Rigid handles: the second is the rigid map itself, so local-global starts converged.
Eigen::MatrixXd deform_start(const Problem& problem, const Eigen::MatrixXd& rest, const std::vector<Handle>& handles,
                             const LocalGlobalOptions& options);

}  // namespace strictmin
