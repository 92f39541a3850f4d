#pragma once
// Distortion of a given map of a mesh, in any measure: the map is given by the image of
// every element corner, so seamed UV layouts (an OBJ whose vt differ across a seam) work too.
#include <Eigen/Core>
#include <string>

#include "strictmin/measures/measures.h"
#include "strictmin/mesh/mesh.h"
#include "strictmin/report/stats.h"

namespace strictmin {

struct MapDistortion {
  Eigen::VectorXd distortion;  // #E, in the measure asked for
  Eigen::VectorXd weights;     // #E rest areas / volumes
  Eigen::VectorXi flipped;     // #E, 1 where det J <= 0 (0 for a 3x2 Jacobian: no orientation)
  DistortionStats stats;       // stats.flipped -1 for a surface mapped in 3D (not defined)
};

// Map of `rest` that sends corner j of element e to corner_images.row(e * corners + j).
// Rest planar triangles (2D or constant z) or tets: images of the same dimension.
// Rest 3D surface triangles: images 2D (a parametrization, each triangle in its own
// isometric frame) or 3D (a deformed surface; fd then compares J with the rest frame).
// Throws InputError for a rest mesh that fails check_mesh_structure, or images that are not
// #E*corners rows of that dimension, or not finite, or beyond 1e150 (their distortions
// overflow); the message names them `images_name`.
MapDistortion map_distortion(const Mesh& rest, const Eigen::MatrixXd& corner_images, Measure measure,
                             const std::string& images_name = "the map");

// The map from rest to mapped: same number of elements required. Uses mapped's UVs when it
// has them (a UV-mapped OBJ is the map of its surface), else mapped's vertex positions
// (same number of vertices and the same elements required). Throws InputError naming
// what differs, or a mesh that fails check_mesh_structure (mapped's coordinates may be
// non-finite).
MapDistortion map_distortion(const Mesh& rest, const Mesh& mapped, Measure measure,
                             const std::string& rest_name = "rest", const std::string& mapped_name = "mapped");

// Corner images of vertex positions X (#V by k) through the elements F. Throws InputError
// for an index of F outside X's rows.
Eigen::MatrixXd corner_images(const Eigen::MatrixXi& F, const Eigen::MatrixXd& X);

// Field deviation against a problem's own targets (parametrization frames, the cross field):
// D_T = ||J_T - R_T||_F of the map X (#V by n), flips from the Jacobians' signs; another
// measure (arap, ...) of the same Jacobians, taken in the problem's element frames. Throws
// InputError for a problem that fails check_problem or an X of another size.
struct Problem;
MapDistortion frame_distortion(const Problem& problem, const Eigen::MatrixXd& X,
                               Measure measure = Measure::FieldDeviation);

}  // namespace strictmin
