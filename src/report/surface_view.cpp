#include "strictmin/report/surface_view.h"

#include <stdexcept>

#include "strictmin/io/mesh_io.h"

namespace strictmin {
namespace {

// Triangles to draw and, for each, the element it shows.
void drawn_faces(const Mesh& mesh, Eigen::MatrixXi* faces, Eigen::VectorXi* element) {
  if (mesh.element_type() == ElementType::Tetrahedron) {
    *faces = tet_boundary_faces(mesh.F, element);
  } else {
    *faces = mesh.F;
    *element = Eigen::VectorXi::LinSpaced(mesh.F.rows(), 0, static_cast<int>(mesh.F.rows()) - 1);
  }
}

RasterOptions adapted(const Mesh& mesh, RasterOptions r) {
  if (mesh.element_type() == ElementType::Triangle && mesh.is_planar()) {
    r.camera = top_camera();
    r.shading = false;
  }
  return r;
}

}  // namespace

Image render_distortion(const Mesh& mesh, const Eigen::VectorXd& distortion, const SurfaceViewOptions& o) {
  if (distortion.size() != mesh.num_elements())
    throw std::invalid_argument("render_distortion: one distortion value per element");
  Eigen::MatrixXi faces;
  Eigen::VectorXi element;
  drawn_faces(mesh, &faces, &element);
  std::vector<Rgb> colour(faces.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f) colour[f] = distortion_colour(distortion(element(f)), o.scale);
  return rasterize(mesh.V, faces, [&](int f, double, double, double) { return colour[f]; }, adapted(mesh, o.raster));
}

Image render_plain(const Mesh& mesh, Rgb colour, const SurfaceViewOptions& o) {
  Eigen::MatrixXi faces;
  Eigen::VectorXi element;
  drawn_faces(mesh, &faces, &element);
  return rasterize(mesh.V, faces, [&](int, double, double, double) { return colour; }, adapted(mesh, o.raster));
}

}  // namespace strictmin
