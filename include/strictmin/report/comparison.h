#pragma once
// Writes the files of one report section — each method's colour-coded view, the input
// picture, the overlaid histogram — and returns the section for index.html
// (report/html_report.h). Planar maps are drawn as SVG, 3D surfaces and tet meshes as PNG
// (their boundary); maps with UVs (parametrizations) also get a UV layout and a
// checkerboard view. All pictures of a section share one frame, so they compare at a glance.
#include <Eigen/Core>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "strictmin/mesh/handle.h"
#include "strictmin/mesh/mesh.h"
#include "strictmin/report/colour_map.h"
#include "strictmin/report/html_report.h"

namespace strictmin {

struct MethodRun {
  std::string method;          // "l2", "linf", ...
  std::string label;           // heading; empty: method_label(method)
  Mesh mapped;                 // the rest mesh's elements at the map's positions (a deformation), or a surface with UVs
  Eigen::VectorXd distortion;  // #E
  Eigen::VectorXd weights;     // #E rest areas / volumes
  int flipped = 0;             // -1: not defined (a 3 by 2 Jacobian, a surface in 3D, has no orientation)
  double lower_bound = std::numeric_limits<double>::quiet_NaN();
  double time_s = std::numeric_limits<double>::quiet_NaN();
  std::string status = "solved";
  std::string message;
  // Values closer than this count as equal in the strict-order verdicts (at least 1e-6):
  // direct's delta-k, the band it fixes each level's elements in (docs/strict.md).
  double order_tolerance = 0;
  std::string view_name;       // file stem of its pictures; empty: the method name (made unique)
  std::vector<std::pair<std::string, std::string>> links;  // (text, path relative to the report folder)
};

struct SectionInput {
  std::string id;              // sub-folder of the report for its files ("" = the report folder) and HTML anchor
  std::string title, description;
  const Mesh* rest = nullptr;  // the input, drawn as "input" when given
  std::vector<Handle> handles; // drawn on the input picture (2D): fixed as dots, moved as arrows
  std::string measure = "field deviation \u2016J \u2212 I\u2016";
  std::string value_name = "distortion";  // what the cards' numbers are ("distortion \u2212 1": qc, iso)
  std::vector<MethodRun> runs;
  bool alternatives = true;    // the runs are rival maps of one problem (notes and strict-order verdicts
                               // compare them); false for a sequence such as interpolation frames
};

struct ComparisonOptions {
  double scale = kDefaultColourScale;  // red end of the colour scale; 0: auto_colour_scale of the section
  int picture_width = 420;             // pixels
  int png_height = 300;
  std::string histogram_name = "histogram.svg";
};

// A colour scale for results whose least maximum distortion is k: 1.5 k rounded up to 1,
// 1.2, 1.5, 2, 2.5, 3, 4, 5, 6 or 8 times a power of ten, so that the least maximum is
// green-yellow, what only worse maps reach is orange to red, and low distortion is blue.
double auto_colour_scale(double least_maximum);
// The colour scale of a section with these runs: `requested` when positive, else
// auto_colour_scale of their least maximum (what write_section uses; pictures drawn beside a
// section take it too, so that one colour means one distortion on the page).
double section_colour_scale(const std::vector<MethodRun>& runs, double requested);

// Writes into report_dir/section.id/ (created when missing): the input picture, per run
// <stem>.svg|png (its view) and, with several runs, <stem>-histogram.svg (its histogram in
// the pictures' colours), and the section's histogram (the runs overlaid). Throws InputError when a file
// cannot be written, std::invalid_argument when a run's sizes do not match its mesh.
ReportSection write_section(const std::string& report_dir, const SectionInput& section,
                            const ComparisonOptions& options = {});

}  // namespace strictmin
