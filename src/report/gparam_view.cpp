#include "strictmin/report/gparam_view.h"

#include <algorithm>
#include <cmath>

#include "strictmin/report/colour_map.h"

namespace strictmin {
namespace {

constexpr Rgb kSeam{150, 20, 20}, kPositive{220, 30, 30}, kNegative{30, 60, 220};

// The base colour overdrawn with the seams and singularities near barycentric (b0, b1, b2).
Rgb marked(const GParamMarks& m, int f, const double b[3], Rgb base) {
  for (int i = 0; i < 3; ++i) {
    const int q = m.corner_index[f * 3 + i];
    if (q != 0 && b[i] > 1.0 - m.dot_radius) return q > 0 ? kPositive : kNegative;
  }
  for (int i = 0; i < 3; ++i)  // side i is opposite corner (i + 2) % 3
    if (m.seam_side[f * 3 + i] && b[(i + 2) % 3] < m.line_width) return kSeam;
  return base;
}

}  // namespace

Image render_gparam_distortion(const Mesh& mesh, const Eigen::VectorXd& d, const GParamMarks& m, double scale,
                               const RasterOptions& options) {
  return rasterize(
      mesh.V, mesh.F,
      [&](int f, double b0, double b1, double b2) {
        const double b[3] = {b0, b1, b2};
        return marked(m, f, b, distortion_colour(d(f), scale));
      },
      options);
}

Image render_gparam_grid(const Mesh& mesh, const GParamMarks& m, const RasterOptions& options) {
  RasterOptions r = options;
  r.edge_width = 0;
  const Rgb light{240, 240, 240}, dark{70, 90, 160};
  return rasterize(
      mesh.V, mesh.F,
      [&](int f, double b0, double b1, double b2) {
        const Eigen::Vector2d uv = b0 * mesh.UV.row(mesh.FUV(f, 0)) + b1 * mesh.UV.row(mesh.FUV(f, 1)) +
                                   b2 * mesh.UV.row(mesh.FUV(f, 2));
        const long i = static_cast<long>(std::floor(uv.x())), j = static_cast<long>(std::floor(uv.y()));
        const double b[3] = {b0, b1, b2};
        return marked(m, f, b, ((i + j) & 1) ? dark : light);
      },
      r);
}

}  // namespace strictmin
