#include "strictmin/report/quad_view.h"

#include <algorithm>
#include <vector>

namespace strictmin {
namespace {

constexpr Rgb kFill{226, 232, 244}, kSide{40, 50, 90}, kWhite{255, 255, 255}, kBlack{0, 0, 0};
constexpr double kSideWidth = 0.05;  // barycentric units of a half-quad

// Each quad as two triangles, (0, 1, 2) and (0, 2, 3): triangle 2i + h is half h of quad i.
Eigen::MatrixXi halves(const Eigen::MatrixXi& Q) {
  Eigen::MatrixXi T(2 * Q.rows(), 3);
  for (int i = 0; i < Q.rows(); ++i) {
    T.row(2 * i) << Q(i, 0), Q(i, 1), Q(i, 2);
    T.row(2 * i + 1) << Q(i, 0), Q(i, 2), Q(i, 3);
  }
  return T;
}

}  // namespace

Image render_quad_mesh(const QuadMesh& q, const RasterOptions& options, double dot_pixels) {
  RasterOptions r = options;
  r.edge_width = 0;  // the quads' sides are drawn below, not the halves' diagonals
  if (r.frame_points.rows() == 0) r.frame_points = q.V;
  const Eigen::MatrixXi T = halves(q.Q);
  std::vector<int> valence(q.num_vertices(), 0);
  for (int i = 0; i < q.Q.rows(); ++i)
    for (int k = 0; k < 4; ++k) ++valence[q.Q(i, k)];
  const double extent = (r.frame_points.colwise().maxCoeff() - r.frame_points.colwise().minCoeff()).norm();
  const double pixels = std::min(r.width, r.height) * (1 - 2 * r.margin);
  const double radius = pixels > 0 ? dot_pixels * extent / pixels : 0.0;
  return rasterize(
      q.V, T,
      [&](int t, double b0, double b1, double b2) -> Rgb {
        const double b[3] = {b0, b1, b2};
        const Eigen::Vector3d at = b0 * q.V.row(T(t, 0)) + b1 * q.V.row(T(t, 1)) + b2 * q.V.row(T(t, 2));
        for (int i = 0; i < 3; ++i) {
          const int v = T(t, i);
          if (valence[v] == 4) continue;
          const double d = (at - q.V.row(v).transpose()).norm();
          if (d < radius) return (d < 0.65 * radius) == (valence[v] < 4) ? kWhite : kBlack;
        }
        // Half 0 has the quad's sides 0-1 and 1-2 (opposite its corners 2 and 0), half 1 the
        // sides 2-3 and 3-0 (opposite its corners 0 and 1).
        const bool side = t % 2 == 0 ? (b[2] < kSideWidth || b[0] < kSideWidth) : (b[0] < kSideWidth || b[1] < kSideWidth);
        return side ? kSide : kFill;
      },
      r);
}

}  // namespace strictmin
