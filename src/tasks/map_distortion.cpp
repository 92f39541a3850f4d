#include "strictmin/tasks/map_distortion.h"

#include <Eigen/Dense>
#include <algorithm>
#include <vector>

#include "strictmin/io/input_error.h"
#include "strictmin/mesh/validate.h"
#include "strictmin/problem/check_problem.h"
#include "strictmin/problem/problem.h"
#include "mesh/image_sizes.h"
#include "problem/frame_axes.h"

namespace strictmin {
namespace {

// Whether `b` lists the vertices of `a` (distinct) in an even permutation of a's order: for
// a triangle, the same cyclic order from another corner.
bool same_orientation(const Eigen::RowVectorXi& a, const Eigen::RowVectorXi& b) {
  std::vector<int> position(a.size());
  for (Eigen::Index i = 0; i < a.size(); ++i)
    for (Eigen::Index j = 0; j < b.size(); ++j)
      if (b(j) == a(i)) position[i] = static_cast<int>(j);
  int inversions = 0;
  for (size_t i = 0; i < position.size(); ++i)
    for (size_t j = i + 1; j < position.size(); ++j) inversions += position[i] > position[j] ? 1 : 0;
  return inversions % 2 == 0;
}

}  // namespace

Eigen::MatrixXd corner_images(const Eigen::MatrixXi& F, const Eigen::MatrixXd& X) {
  for (Eigen::Index e = 0; e < F.rows(); ++e)
    for (Eigen::Index j = 0; j < F.cols(); ++j)
      if (F(e, j) < 0 || F(e, j) >= X.rows())
        throw InputError("corner_images: element " + std::to_string(e) + " has vertex " + std::to_string(F(e, j)) +
                         ", the map has " + std::to_string(X.rows()) + " rows");
  Eigen::MatrixXd C(F.rows() * F.cols(), X.cols());
  for (Eigen::Index e = 0; e < F.rows(); ++e)
    for (Eigen::Index j = 0; j < F.cols(); ++j) C.row(e * F.cols() + j) = X.row(F(e, j));
  return C;
}

MapDistortion map_distortion(const Mesh& rest, const Eigen::MatrixXd& images, Measure measure,
                             const std::string& images_name) {
  check_values_within_sizes(images, images_name, "corner image");  // beyond 1e150 the distortions overflow
  const Problem p = make_problem(rest);
  const int c = p.corners(), E = p.num_elements();
  const bool surface_to_3d = p.domain_dim == 2 && images.cols() == 3 && !rest.is_planar();
  // A parametrization of a surface in 3D: each triangle's J is taken in the triangle's own
  // frame, whose turn in its plane is arbitrary, so J - I depends on it. The field deviation
  // of a parametrization is against its target frames (gparam's field, param's starting map),
  // which a map alone does not carry.
  const bool parametrization = p.domain_dim == 2 && images.cols() == 2 && !rest.is_planar();
  if (parametrization && measure == Measure::FieldDeviation)
    throw InputError("fd of a parametrization needs its target frames (gparam's field, param's starting map), which a "
                     "map alone does not carry; evaluate it with arap, asap, qc or iso");
  if (!surface_to_3d && images.cols() != p.image_dim)
    throw InputError("the map has " + std::to_string(images.cols()) + " coordinates per vertex, the rest mesh needs " +
                     std::to_string(p.image_dim));
  if (images.rows() != static_cast<Eigen::Index>(E) * c)
    throw InputError("the map has " + std::to_string(images.rows()) + " corner images, the rest mesh's " +
                     std::to_string(E) + " elements have " + std::to_string(static_cast<Eigen::Index>(E) * c) +
                     " corners (one image per element corner)");
  MapDistortion out;
  out.distortion.resize(E);
  out.flipped = Eigen::VectorXi::Zero(E);
  out.weights = p.weights;
  for (int e = 0; e < E; ++e) {
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(images.cols(), p.domain_dim);
    for (int j = 0; j < c; ++j) J.noalias() += images.row(e * c + j).transpose() * p.gradients.row(e * c + j);
    Eigen::MatrixXd R = p.target(e);
    if (surface_to_3d) {
      // The identity of the surface in 3D: the element's frame axes (local_frame_coordinates).
      const Eigen::Vector3d p0 = rest.V.row(rest.F(e, 0)), p1 = rest.V.row(rest.F(e, 1)), p2 = rest.V.row(rest.F(e, 2));
      R = frame_axes(p0, p1, p2);
    }
    out.distortion(e) = distortion(measure, J, R);
    out.flipped(e) = is_flipped(J) ? 1 : 0;
  }
  out.stats = distortion_stats(out.distortion, out.weights);
  out.stats.flipped = surface_to_3d ? -1 : out.flipped.sum();  // a 3x2 Jacobian has no determinant
  return out;
}

MapDistortion map_distortion(const Mesh& rest, const Mesh& mapped, Measure measure, const std::string& rest_name,
                             const std::string& mapped_name) {
  check_mesh_structure(rest, rest_name);
  check_mesh_structure(mapped, mapped_name, false);  // its UVs are read by index; a map may hold anything
  check_image_sizes(mapped, mapped_name);            // beyond 1e150 the distortions overflow
  if (rest.num_elements() != mapped.num_elements() || rest.F.cols() != mapped.F.cols())
    throw InputError(mapped_name + " has " + std::to_string(mapped.num_elements()) + " elements of " +
                     std::to_string(mapped.F.cols()) + " corners, " + rest_name + " has " +
                     std::to_string(rest.num_elements()) + " of " + std::to_string(rest.F.cols()) +
                     ": a map needs the same connectivity");
  // The same elements on the same vertices, a UV-mapped OBJ too (its f v/vt: shuffled faces
  // would pair each rest triangle with another's texture coordinates).
  if (rest.num_vertices() != mapped.num_vertices())
    throw InputError(mapped_name + " has " + std::to_string(mapped.num_vertices()) + " vertices, " + rest_name +
                     " has " + std::to_string(rest.num_vertices()) + ": a map needs the same connectivity");
  for (int e = 0; e < rest.num_elements(); ++e)
    for (int j = 0; j < rest.F.cols(); ++j)
      if (rest.F(e, j) != mapped.F(e, j)) {
        Eigen::VectorXi a = rest.F.row(e).transpose(), b = mapped.F.row(e).transpose();
        std::sort(a.data(), a.data() + a.size());
        std::sort(b.data(), b.data() + b.size());
        const std::string what = a != b ? " has different vertices in "
                                 : same_orientation(rest.F.row(e), mapped.F.row(e))
                                     ? " lists its vertices from another corner (the same orientation) in "
                                     : " has its vertices in the reverse order (another orientation) in ";
        throw InputError("element " + std::to_string(e) + " (0-based)" + what + rest_name + " and " + mapped_name +
                         ": a map needs the same connectivity, element by element and corner by corner");
      }
  if (mapped.has_uv()) return map_distortion(rest, corner_images(mapped.FUV, mapped.UV), measure);
  if (rest.element_type() == ElementType::Triangle && rest.is_planar() && mapped.V.cols() == 3 && !mapped.is_planar())
    throw InputError(mapped_name + " is not planar, while " + rest_name +
                     " is: a planar rest is evaluated against a planar map (a flat sheet bent into 3D is not supported)");
  Eigen::MatrixXd X = mapped.V;
  const bool rest_planar = rest.element_type() == ElementType::Triangle && rest.is_planar();
  if (rest_planar && mapped.V.cols() == 3 && mapped.is_planar()) X = to_planar(mapped).V;
  return map_distortion(rest, corner_images(rest.F, X), measure);
}

MapDistortion frame_distortion(const Problem& p, const Eigen::MatrixXd& X, Measure measure) {
  check_problem(p, "frame_distortion");
  check_map(p, X, "frame_distortion");
  MapDistortion d;
  const int E = p.num_elements();
  d.distortion.resize(E);
  d.flipped = Eigen::VectorXi::Zero(E);
  d.weights = p.weights;
  for (int e = 0; e < E; ++e) {
    const Eigen::MatrixXd J = p.jacobian(e, X);
    d.distortion(e) = measure == Measure::FieldDeviation ? (J - p.target(e)).norm() : distortion(measure, J, p.target(e));
    d.flipped(e) = is_flipped(J) ? 1 : 0;
  }
  d.stats = distortion_stats(d.distortion, d.weights);
  d.stats.flipped = d.flipped.sum();
  return d;
}

}  // namespace strictmin
