#include "strictmin/report/gparam_view.h"

#include <algorithm>
#include <cmath>

#include "strictmin/report/colour_map.h"

namespace strictmin {
namespace {

constexpr Rgb kSeam{150, 20, 20}, kWhite{255, 255, 255}, kBlack{0, 0, 0};

// The dots' radius in the mesh's units: dot_pixels at the scale the rasterizer frames the mesh
// (its bounding box across the picture, less the margins).
double dot_radius(const Eigen::MatrixXd& V, const GParamMarks& m, const RasterOptions& o) {
  const double extent = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  const double pixels = std::min(o.width, o.height) * (1 - 2 * o.margin);
  return extent > 0 && pixels > 0 ? m.dot_pixels * extent / pixels : 0.0;
}

// The base colour overdrawn with the seams and singularities at barycentric (b0, b1, b2).
Rgb marked(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const GParamMarks& m, double radius, int f,
           const double b[3], Rgb base) {
  for (int i = 0; i < 3; ++i) {
    const int q = m.corner_index[f * 3 + i];
    if (q == 0) continue;
    const Eigen::VectorXd at = b[0] * V.row(F(f, 0)) + b[1] * V.row(F(f, 1)) + b[2] * V.row(F(f, 2));
    const double r = (at - V.row(F(f, i)).transpose()).norm();
    if (r < radius) return (r < 0.65 * radius) == (q > 0) ? kWhite : kBlack;  // the fill, then the rim
  }
  for (int i = 0; i < 3; ++i)  // side i is opposite corner (i + 2) % 3
    if (m.seam_side[f * 3 + i] && b[(i + 2) % 3] < m.line_width) return kSeam;
  return base;
}

}  // namespace

Image render_gparam_distortion(const Mesh& mesh, const Eigen::VectorXd& d, const GParamMarks& m, double scale,
                               const RasterOptions& options) {
  const double radius = dot_radius(mesh.V, m, options);
  return rasterize(
      mesh.V, mesh.F,
      [&](int f, double b0, double b1, double b2) {
        const double b[3] = {b0, b1, b2};
        return marked(mesh.V, mesh.F, m, radius, f, b, distortion_colour(d(f), scale));
      },
      options);
}

Image render_gparam_grid(const Mesh& mesh, const GParamMarks& m, const RasterOptions& options) {
  RasterOptions r = options;
  r.edge_width = 0;
  const Rgb light{240, 240, 240}, dark{70, 90, 160};
  const double radius = dot_radius(mesh.V, m, options);
  return rasterize(
      mesh.V, mesh.F,
      [&](int f, double b0, double b1, double b2) {
        const Eigen::Vector2d uv = b0 * mesh.UV.row(mesh.FUV(f, 0)) + b1 * mesh.UV.row(mesh.FUV(f, 1)) +
                                   b2 * mesh.UV.row(mesh.FUV(f, 2));
        const long i = static_cast<long>(std::floor(uv.x())), j = static_cast<long>(std::floor(uv.y()));
        const double b[3] = {b0, b1, b2};
        return marked(mesh.V, mesh.F, m, radius, f, b, ((i + j) & 1) ? dark : light);
      },
      r);
}

}  // namespace strictmin
