#include "strictmin/report/comparison.h"

#include <cmath>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "strictmin/io/input_error.h"
#include "strictmin/report/checkerboard.h"
#include "strictmin/report/histogram_svg.h"
#include "strictmin/report/stats.h"
#include "strictmin/report/surface_view.h"
#include "strictmin/report/svg_view.h"

namespace strictmin {
namespace {

namespace fs = std::filesystem;

bool drawn_as_svg(const Mesh& m) { return m.element_type() == ElementType::Triangle && m.is_planar(); }

// Whether a handle moves its vertex: beyond a millionth of the mesh's size (a handle file's
// full digits against an OBJ's six decimals differ by ~1e-7 and hold the vertex still), over
// the coordinates both have (a planar OBJ's z = 0 against 'vertex x y' handles).
bool handle_moves(const Mesh& rest, const Handle& h, double mesh_size) {
  const Eigen::Index n = std::min<Eigen::Index>(h.position.size(), rest.V.cols());
  const Eigen::VectorXd from = rest.V.row(h.vertex).head(n).transpose();
  return (h.position.head(n) - from).norm() > 1e-6 * mesh_size;
}

// The length of the mesh's bounding-box diagonal.
double mesh_size(const Mesh& m) {
  if (m.V.rows() == 0) return 0;
  return (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm();
}

// Bounding box of all the meshes' vertices (used by their elements), as 3D.
void frame(const std::vector<const Mesh*>& meshes, Eigen::Vector3d* lo, Eigen::Vector3d* hi) {
  lo->setConstant(std::numeric_limits<double>::infinity());
  hi->setConstant(-std::numeric_limits<double>::infinity());
  for (const Mesh* m : meshes)
    for (Eigen::Index v = 0; v < m->V.rows(); ++v) {
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      p.head(std::min<Eigen::Index>(3, m->V.cols())) = m->V.row(v).head(std::min<Eigen::Index>(3, m->V.cols()));
      *lo = lo->cwiseMin(p);
      *hi = hi->cwiseMax(p);
    }
}

std::string joined(const std::string& dir, const std::string& name) { return dir.empty() ? name : dir + "/" + name; }

}  // namespace

double auto_colour_scale(double k) {
  if (!(k > 0) || !std::isfinite(k)) return kDefaultColourScale;
  const double target = 1.5 * k * (1 - 1e-6);
  const double p = std::pow(10.0, std::floor(std::log10(target)));
  for (double m : {1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0})
    if (m * p >= target) return m * p;
  return 10 * p;
}

double section_colour_scale(const std::vector<MethodRun>& runs, double requested) {
  if (requested > 0) return requested;
  double k = std::numeric_limits<double>::infinity();
  for (const auto& r : runs)
    if (r.distortion.size() > 0 && std::isfinite(r.distortion.maxCoeff())) k = std::min(k, r.distortion.maxCoeff());
  return auto_colour_scale(k);
}

ReportSection write_section(const std::string& report_dir, const SectionInput& in, const ComparisonOptions& o) {
  const fs::path folder = in.id.empty() ? fs::path(report_dir) : fs::path(report_dir) / in.id;
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw InputError("cannot create " + folder.string() + ": " + ec.message());

  ReportSection out;
  out.id = in.id.empty() ? "report" : in.id;
  out.title = in.title;
  out.description = in.description;
  out.measure = in.measure;
  out.value_name = in.value_name;
  out.alternatives = in.alternatives;

  const double scale = section_colour_scale(in.runs, o.scale);
  out.scale = scale;

  std::vector<const Mesh*> meshes;
  if (in.rest) meshes.push_back(in.rest);
  for (const auto& r : in.runs) meshes.push_back(&r.mapped);
  Eigen::Vector3d lo, hi;
  frame(meshes, &lo, &hi);

  SvgViewOptions svg;
  svg.scale = scale;
  svg.width = o.picture_width;
  svg.max_height = o.picture_width;
  svg.fit_box = true;
  svg.box_min = lo.head<2>();
  svg.box_max = hi.head<2>();
  SurfaceViewOptions png;
  png.scale = scale;
  png.raster.width = o.picture_width;
  png.raster.height = o.png_height;
  png.raster.fit_box = true;
  png.raster.box_min = lo;
  png.raster.box_max = hi;
  if (!meshes.empty() && !drawn_as_svg(*meshes.front())) {  // frame what all the 3D pictures show
    Eigen::Index n = 0;
    for (const Mesh* m : meshes) n += m->V.rows();
    png.raster.frame_points.setZero(n, 3);
    n = 0;
    for (const Mesh* m : meshes) {
      const Eigen::Index c = std::min<Eigen::Index>(3, m->V.cols());
      png.raster.frame_points.block(n, 0, m->V.rows(), c) = m->V.leftCols(c);
      n += m->V.rows();
    }
  }

  if (in.rest) {
    const Mesh& rest = *in.rest;
    if (drawn_as_svg(rest)) {
      SvgViewOptions s = svg;
      const double size = mesh_size(rest);
      for (const Handle& h : in.handles) {
        if (h.vertex < 0 || h.vertex >= rest.num_vertices() || h.position.size() < 2) continue;
        const Eigen::Vector2d from = rest.V.row(h.vertex).head<2>().transpose(), to = h.position.head<2>();
        if (handle_moves(rest, h, size)) s.arrows.emplace_back(from, to);
        else s.markers.push_back(from);
      }
      const std::vector<Rgb> grey(rest.num_elements(), Rgb{214, 220, 228});
      Eigen::MatrixXd corners(rest.num_elements() * 3, 2);
      for (int f = 0; f < rest.num_elements(); ++f)
        for (int j = 0; j < 3; ++j) corners.row(3 * f + j) = rest.V.row(rest.F(f, j)).head<2>();
      write_text_file((folder / "input.svg").string(), triangles_svg(corners, grey, s));
      out.input_picture = joined(in.id, "input.svg");
    } else {
      write_png((folder / "input.png").string(), render_plain(rest, Rgb{205, 210, 218}, png));
      out.input_picture = joined(in.id, "input.png");
    }
    if (!in.handles.empty()) {
      int moved = 0;
      const double size = mesh_size(rest);
      for (const Handle& h : in.handles)
        if (h.vertex >= 0 && h.vertex < rest.num_vertices() && handle_moves(rest, h, size)) ++moved;
      const bool one = rest.num_elements() == 1;
      out.input_caption = std::to_string(rest.num_elements()) +
                          (rest.element_type() == ElementType::Tetrahedron ? (one ? " tetrahedron, " : " tetrahedra, ")
                                                                           : (one ? " triangle, " : " triangles, ")) +
                          std::to_string(in.handles.size() - moved) + " fixed and " + std::to_string(moved) +
                          " moved handle vertices" + (drawn_as_svg(rest) ? " (dots: fixed; arrows: moved)." : ".");
    }
  }

  std::vector<HistogramSeries> series;
  for (std::size_t i = 0; i < in.runs.size(); ++i) {
    const MethodRun& r = in.runs[i];
    if (r.distortion.size() != r.mapped.num_elements() || r.weights.size() != r.distortion.size())
      throw std::invalid_argument("write_section: run '" + r.method + "' has " + std::to_string(r.distortion.size()) +
                                  " distortion values and " + std::to_string(r.weights.size()) + " weights for " +
                                  std::to_string(r.mapped.num_elements()) + " elements");
    series.push_back({r.label.empty() ? method_label(r.method) : r.label, r.distortion, r.weights,
                      series_colour(static_cast<int>(i))});
  }
  HistogramSvgOptions hist;
  hist.colour_scale = scale;
  hist.value_label = "distortion (" + in.measure + ")";
  if (!series.empty()) {
    const HistogramAxes axes = histogram_axes(series, hist.bins);
    hist.upper = axes.upper;
    hist.min_exponent = axes.min_exponent;
  }

  std::set<std::string> used{"input", "histogram"};
  for (std::size_t i = 0; i < in.runs.size(); ++i) {
    const MethodRun& r = in.runs[i];
    std::string stem = r.view_name.empty() ? r.method : r.view_name;
    for (int k = 2; used.count(stem); ++k) stem = (r.view_name.empty() ? r.method : r.view_name) + "-" + std::to_string(k);
    used.insert(stem);

    MethodEntry e;
    e.name = r.method;
    e.label = r.label;
    e.colour = series[i].colour;
    e.stats = distortion_stats(r.distortion, r.weights);
    e.stats.flipped = r.flipped;
    e.lower_bound = r.lower_bound;
    e.time_s = r.time_s;
    e.status = r.status;
    e.message = r.message;
    e.order_tolerance = r.order_tolerance;
    e.distortion = r.distortion;
    e.weights = r.weights;
    e.links = r.links;
    if (drawn_as_svg(r.mapped)) {
      write_text_file((folder / (stem + ".svg")).string(), planar_map_svg(r.mapped.V, r.mapped.F, r.distortion, svg));
      e.picture = joined(in.id, stem + ".svg");
    } else {
      write_png((folder / (stem + ".png")).string(), render_distortion(r.mapped, r.distortion, png));
      e.picture = joined(in.id, stem + ".png");
    }
    if (r.mapped.element_type() == ElementType::Triangle && r.mapped.has_uv()) {
      SvgViewOptions uv = svg;
      uv.fit_box = false;
      write_text_file((folder / (stem + "-uv.svg")).string(), uv_layout_svg(r.mapped, r.distortion, uv));
      e.extra_pictures.emplace_back("UV layout", joined(in.id, stem + "-uv.svg"));
      CheckerboardOptions c;
      c.raster = png.raster;
      // A seamed (global) parametrization, UV per corner: its unit squares, the grid it is for
      // (the checks still jump across seams by the translations' fractional parts: not rounded).
      if (r.mapped.UV.rows() != r.mapped.V.rows()) c.period = 1;
      write_png((folder / (stem + "-checker.png")).string(), render_checkerboard(r.mapped, c));
      e.extra_pictures.emplace_back("checkerboard texture", joined(in.id, stem + "-checker.png"));
    }
    if (in.runs.size() > 1) {  // (one run: the section's histogram is its own)
      HistogramSvgOptions mini = hist;
      mini.colour_bars = true;
      mini.legend = false;
      mini.width = 290;
      mini.height = 210;
      mini.value_label = "distortion";
      write_histogram_svg((folder / (stem + "-histogram.svg")).string(), {series[i]}, mini);
      e.histogram = joined(in.id, stem + "-histogram.svg");
    }
    out.methods.push_back(std::move(e));
  }
  if (!series.empty()) {
    hist.colour_bars = series.size() == 1;
    write_histogram_svg((folder / o.histogram_name).string(), series, hist);
    out.histogram = joined(in.id, o.histogram_name);
  }
  return out;
}

}  // namespace strictmin
