#include "strictmin/report/rasterizer.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace strictmin {

Camera oblique_camera() {
  Camera c;
  c.direction = -Eigen::Vector3d(0.45, 0.55, 1.0).normalized();
  c.up = Eigen::Vector3d(0, 1, 0);
  return c;
}

Camera top_camera() { return Camera{}; }

namespace {

// The pixels [first, last] whose centres can lie in [lo, hi], clipped to 0..size-1 (none
// when first > last). Clamped before the conversion: a huge coordinate is no int.
std::pair<int, int> pixel_span(double lo, double hi, int size) {
  const int first = static_cast<int>(std::floor(std::clamp(lo, 0.0, static_cast<double>(size))));
  const int last = static_cast<int>(std::ceil(std::clamp(hi, -1.0, static_cast<double>(size - 1))));
  return {first, last};
}

}  // namespace

Image rasterize(const Eigen::MatrixXd& V_in, const Eigen::MatrixXi& F, const FaceShader& shader,
                const RasterOptions& o) {
  if (V_in.cols() != 2 && V_in.cols() != 3) throw std::invalid_argument("rasterize: V must be #V by 2 or 3");
  if (F.rows() > 0 && F.cols() != 3) throw std::invalid_argument("rasterize: F must be #F by 3");
  if (o.width < 1 || o.height < 1 || o.supersample < 1) throw std::invalid_argument("rasterize: empty picture");
  Eigen::MatrixXd V = Eigen::MatrixXd::Zero(V_in.rows(), 3);
  V.leftCols(V_in.cols()) = V_in;

  // Camera frame: screen x = right, screen y = up, depth along the viewing direction.
  const Eigen::Vector3d d = o.camera.direction.normalized();
  Eigen::Vector3d right = d.cross(o.camera.up);
  if (right.norm() < 1e-12) right = d.cross(Eigen::Vector3d(1, 0, 0));
  right.normalize();
  const Eigen::Vector3d up = right.cross(d).normalized();
  const Eigen::Vector3d light = (-d + 0.45 * up + 0.3 * right).normalized();

  // Fit the frame (box corners or the vertices used) into the picture.
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  auto extend = [&](const Eigen::Vector3d& p) {
    x0 = std::min(x0, p.dot(right)), x1 = std::max(x1, p.dot(right));
    y0 = std::min(y0, p.dot(up)), y1 = std::max(y1, p.dot(up));
  };
  if (o.frame_points.rows() > 0 && o.frame_points.cols() == 3) {
    for (Eigen::Index i = 0; i < o.frame_points.rows(); ++i) extend(o.frame_points.row(i).transpose());
  } else if (o.fit_box) {
    for (int c = 0; c < 8; ++c)
      extend(Eigen::Vector3d(c & 1 ? o.box_max.x() : o.box_min.x(), c & 2 ? o.box_max.y() : o.box_min.y(),
                             c & 4 ? o.box_max.z() : o.box_min.z()));
  } else {
    for (int f = 0; f < F.rows(); ++f)
      for (int j = 0; j < 3; ++j) extend(V.row(F(f, j)).transpose());
  }
  const int ss = o.supersample;
  const int W = o.width * ss, H = o.height * ss;
  if (F.rows() == 0 || !(x1 >= x0)) return Image(o.width, o.height, o.background);
  Image big(W, H, o.background);
  const double span_x = std::max(x1 - x0, 1e-12), span_y = std::max(y1 - y0, 1e-12);
  const double s = std::min(W * (1 - 2 * o.margin) / span_x, H * (1 - 2 * o.margin) / span_y);
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);

  const Eigen::Index nv = V.rows();
  Eigen::MatrixXd P(nv, 3);  // pixel x, pixel y (down), depth
  for (Eigen::Index v = 0; v < nv; ++v) {
    const Eigen::Vector3d p = V.row(v).transpose();
    P(v, 0) = 0.5 * W + (p.dot(right) - cx) * s;
    P(v, 1) = 0.5 * H - (p.dot(up) - cy) * s;
    P(v, 2) = p.dot(d);
  }

  // Edges only when triangles are big enough on screen to show them.
  double edge_px = o.edge_width * ss;
  if (edge_px > 0) {
    double total = 0;
    for (int f = 0; f < F.rows(); ++f)
      total += (P.row(F(f, 1)).head<2>() - P.row(F(f, 0)).head<2>()).norm();
    if (total / F.rows() < 5.0 * ss) edge_px = 0;
  }

  std::vector<float> zbuf(static_cast<std::size_t>(W) * H, std::numeric_limits<float>::infinity());
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = P.row(F(f, 0)).transpose(), b = P.row(F(f, 1)).transpose(),
                          c = P.row(F(f, 2)).transpose();
    const double area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    if (!(std::abs(area) >= 1e-12) || !std::isfinite(area)) continue;  // degenerate, or a corner not finite
    double shade = 1.0;
    if (o.shading) {
      const Eigen::Vector3d e1 = (V.row(F(f, 1)) - V.row(F(f, 0))).transpose();
      const Eigen::Vector3d e2 = (V.row(F(f, 2)) - V.row(F(f, 0))).transpose();
      const Eigen::Vector3d n = e1.cross(e2);
      const double nn = n.norm();
      shade = nn > 0 ? 0.3 + 0.7 * std::abs(n.dot(light)) / nn : 0.3;
    }
    const double len[3] = {(c - b).head<2>().norm(), (a - c).head<2>().norm(), (b - a).head<2>().norm()};
    const auto [px0, px1] = pixel_span(std::min({a.x(), b.x(), c.x()}), std::max({a.x(), b.x(), c.x()}), W);
    const auto [py0, py1] = pixel_span(std::min({a.y(), b.y(), c.y()}), std::max({a.y(), b.y(), c.y()}), H);
    for (int y = py0; y <= py1; ++y) {
      for (int x = px0; x <= px1; ++x) {
        const double qx = x + 0.5, qy = y + 0.5;
        // Edge functions (twice the signed areas of the sub-triangles), normalized by the area.
        const double w0 = ((c.x() - b.x()) * (qy - b.y()) - (c.y() - b.y()) * (qx - b.x())) / area;
        const double w1 = ((a.x() - c.x()) * (qy - c.y()) - (a.y() - c.y()) * (qx - c.x())) / area;
        const double w2 = 1.0 - w0 - w1;
        const double eps = -1e-9;
        if (w0 < eps || w1 < eps || w2 < eps) continue;
        const float z = static_cast<float>(w0 * a.z() + w1 * b.z() + w2 * c.z());
        float& zb = zbuf[static_cast<std::size_t>(y) * W + x];
        if (z >= zb) continue;
        zb = z;
        Rgb colour = scaled(shader(f, w0, w1, w2), shade);
        if (edge_px > 0) {
          // Distance to edge i in pixels: w_i * |area| / |edge i|.
          const double dist = std::min({w0 * std::abs(area) / len[0], w1 * std::abs(area) / len[1],
                                        w2 * std::abs(area) / len[2]});
          if (dist < edge_px) colour = scaled(colour, 1.0 - o.edge_darkening);
        }
        big.set(x, y, colour);
      }
    }
  }
  if (ss == 1) return big;
  Image out(o.width, o.height, o.background);
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x) {
      int r = 0, g = 0, bl = 0;
      for (int j = 0; j < ss; ++j)
        for (int i = 0; i < ss; ++i) {
          const Rgb p = big.at(x * ss + i, y * ss + j);
          r += p.r, g += p.g, bl += p.b;
        }
      const int n = ss * ss;
      out.set(x, y, Rgb{static_cast<std::uint8_t>((r + n / 2) / n), static_cast<std::uint8_t>((g + n / 2) / n),
                        static_cast<std::uint8_t>((bl + n / 2) / n)});
    }
  return out;
}

}  // namespace strictmin
