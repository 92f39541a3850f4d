#pragma once
// The image of a map (eval's MAPPED mesh, an interpolation target) and UVs: held to the
// solvers' largest size (kLargestSize, mesh/validate.h). validate_mesh checks this too: with
// check_geometry = false for the vertices (an image may be flipped or collapsed, but not
// beyond 1e150, where its distortions overflow), and always for UVs.
#include <string>

#include "strictmin/mesh/mesh.h"

namespace strictmin {

// Every coordinate and UV at most kLargestSize in magnitude (no lower limit: a collapsed
// image is a result). Throws InputError naming `source`, the vertex and the value.
void check_image_sizes(const Mesh& mesh, const std::string& source);

// The same for a matrix of image points (one per row, named `row_name` i in the message), and
// non-finite entries refused alike (check_image_sizes leaves those to check_mesh_structure).
void check_values_within_sizes(const Eigen::MatrixXd& values, const std::string& source, const std::string& row_name);

}  // namespace strictmin
