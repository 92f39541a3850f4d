#include "strictmin/report/svg_view.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "markup.h"
#include "strictmin/io/atomic_file.h"
#include "strictmin/io/input_error.h"

namespace strictmin {

using markup::coord;

std::string triangles_svg(const Eigen::MatrixXd& corners, const std::vector<Rgb>& colours, const SvgViewOptions& o) {
  if (corners.rows() % 3 != 0 || corners.cols() < 2) throw std::invalid_argument("triangles_svg: corners must be #F*3 by 2");
  const Eigen::Index nf = corners.rows() / 3;
  if (static_cast<Eigen::Index>(colours.size()) != nf) throw std::invalid_argument("triangles_svg: one colour per triangle");
  Eigen::Vector2d lo, hi;
  if (o.fit_box) {
    lo = o.box_min, hi = o.box_max;
  } else if (nf > 0) {
    lo = corners.leftCols<2>().colwise().minCoeff().transpose();
    hi = corners.leftCols<2>().colwise().maxCoeff().transpose();
  } else {
    lo.setZero(), hi.setOnes();
  }
  const double sx = std::max(hi.x() - lo.x(), 1e-12), sy = std::max(hi.y() - lo.y(), 1e-12);
  double inner_w = o.width - 2 * o.margin;
  double s = inner_w / sx;
  if (sy * s > o.max_height - 2 * o.margin) s = (o.max_height - 2 * o.margin) / sy;
  const double W = std::ceil(sx * s + 2 * o.margin), H = std::ceil(sy * s + 2 * o.margin);
  const double ox = 0.5 * (W - sx * s), oy = 0.5 * (H - sy * s);
  auto px = [&](double x) { return ox + (x - lo.x()) * s; };
  auto py = [&](double y) { return H - oy - (y - lo.y()) * s; };
  const int digits = s * sx > 2000 ? 2 : 1;

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << coord(W) << "\" height=\"" << coord(H)
      << "\" viewBox=\"0 0 " << coord(W) << ' ' << coord(H) << "\">\n";
  svg << "<rect x=\"0\" y=\"0\" width=\"" << coord(W) << "\" height=\"" << coord(H) << "\" fill=\"#ffffff\"/>\n";
  const bool outline = nf < o.outline_below;
  // Outlines in a darker shade of each face's own colour; without outlines, a hairline
  // stroke of the same colour hides the seams anti-aliasing leaves between polygons.
  svg << "<g stroke-width=\"" << (outline ? "0.6" : "0.35") << "\" stroke-linejoin=\"round\">\n";
  for (Eigen::Index f = 0; f < nf; ++f) {
    const std::string fill = hex(colours[f]);
    svg << "<polygon points=\"";
    for (int j = 0; j < 3; ++j) {
      if (j) svg << ' ';
      svg << coord(px(corners(3 * f + j, 0)), digits) << ',' << coord(py(corners(3 * f + j, 1)), digits);
    }
    svg << "\" fill=\"" << fill << "\" stroke=\"" << (outline ? hex(scaled(colours[f], 0.6)) : fill) << "\"/>\n";
  }
  svg << "</g>\n";
  if (!o.markers.empty()) {
    svg << "<g fill=\"#000000\" stroke=\"#ffffff\" stroke-width=\"0.8\">\n";
    const double r = std::clamp(0.012 * std::max(W, H), 2.0, 4.0);
    for (const auto& m : o.markers)
      svg << "<circle cx=\"" << coord(px(m.x()), 1) << "\" cy=\"" << coord(py(m.y()), 1) << "\" r=\"" << coord(r, 1)
          << "\"/>\n";
    svg << "</g>\n";
  }
  if (!o.arrows.empty()) {
    svg << "<g stroke=\"#d00000\" fill=\"#d00000\" stroke-width=\"2\">\n";
    for (const auto& [from, to] : o.arrows) {
      const Eigen::Vector2d a(px(from.x()), py(from.y())), b(px(to.x()), py(to.y()));
      const Eigen::Vector2d d = b - a;
      const double len = d.norm();
      svg << "<circle cx=\"" << coord(a.x(), 1) << "\" cy=\"" << coord(a.y(), 1) << "\" r=\"3\" stroke=\"none\"/>\n";
      if (len < 1e-9) continue;
      const Eigen::Vector2d u = d / len, n(-u.y(), u.x());
      const double head = std::min(9.0, 0.6 * len);
      const Eigen::Vector2d base = b - head * u;
      svg << "<line x1=\"" << coord(a.x(), 1) << "\" y1=\"" << coord(a.y(), 1) << "\" x2=\"" << coord(base.x(), 1)
          << "\" y2=\"" << coord(base.y(), 1) << "\"/>\n";
      const Eigen::Vector2d l = base + 0.45 * head * n, r = base - 0.45 * head * n;
      svg << "<path stroke=\"none\" d=\"M" << coord(b.x(), 1) << ',' << coord(b.y(), 1) << " L" << coord(l.x(), 1)
          << ',' << coord(l.y(), 1) << " L" << coord(r.x(), 1) << ',' << coord(r.y(), 1) << " Z\"/>\n";
    }
    svg << "</g>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

std::string planar_map_svg(const Eigen::MatrixXd& X, const Eigen::MatrixXi& F, const Eigen::VectorXd& distortion,
                           const SvgViewOptions& o) {
  if (F.cols() != 3) throw std::invalid_argument("planar_map_svg: F must be #F by 3 (triangles)");
  if (distortion.size() != F.rows()) throw std::invalid_argument("planar_map_svg: one distortion value per triangle");
  Eigen::MatrixXd corners(F.rows() * 3, 2);
  std::vector<Rgb> colours(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int j = 0; j < 3; ++j) corners.row(3 * f + j) = X.row(F(f, j)).leftCols<2>();
    colours[f] = distortion_colour(distortion(f), o.scale);
  }
  return triangles_svg(corners, colours, o);
}

std::string uv_layout_svg(const Mesh& mesh, const Eigen::VectorXd& distortion, const SvgViewOptions& o) {
  if (!mesh.has_uv()) throw InputError("uv_layout_svg: the mesh has no UV coordinates");
  return planar_map_svg(mesh.UV, mesh.FUV, distortion, o);
}

void write_text_file(const std::string& path, const std::string& text) {
  write_file_atomically(path, [&](std::ostream& os) { os << text; });
}

}  // namespace strictmin
