#include "strictmin/report/checkerboard.h"

#include <cmath>

#include "strictmin/io/input_error.h"

namespace strictmin {

Image render_checkerboard(const Mesh& mesh, const CheckerboardOptions& o) {
  if (mesh.element_type() != ElementType::Triangle || !mesh.has_uv())
    throw InputError("checkerboard view: the mesh has no UV coordinates (a parametrization is needed)");
  const Eigen::Vector2d lo = mesh.UV.colwise().minCoeff().transpose(), hi = mesh.UV.colwise().maxCoeff().transpose();
  const double side = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-12});
  const double k = o.period > 0 ? 1 / o.period : o.checks / side;
  const Eigen::Vector2d origin = o.period > 0 ? Eigen::Vector2d::Zero() : lo;
  RasterOptions r = o.raster;
  if (mesh.is_planar()) {
    r.camera = top_camera();
    r.shading = false;
  }
  r.edge_width = 0;  // the checks are the picture
  const Eigen::MatrixXi& FUV = mesh.FUV;
  return rasterize(
      mesh.V, mesh.F,
      [&](int f, double b0, double b1, double b2) {
        const Eigen::Vector2d uv = b0 * mesh.UV.row(FUV(f, 0)) + b1 * mesh.UV.row(FUV(f, 1)) + b2 * mesh.UV.row(FUV(f, 2));
        const long i = static_cast<long>(std::floor((uv.x() - origin.x()) * k));
        const long j = static_cast<long>(std::floor((uv.y() - origin.y()) * k));
        return ((i + j) & 1) ? o.dark : o.light;
      },
      r);
}

}  // namespace strictmin
