#pragma once
// index.html: methods side by side, per method its picture and numbers (max and L2
// distortion, area near the top, flips, time, status), the overlaid histogram and the
// strict-order verdicts between consecutive methods. One static page with inline CSS and
// inline SVG (the colour bar), no scripts, no external URLs; pictures are relative links.
#include <Eigen/Core>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "strictmin/report/colour_map.h"
#include "strictmin/report/stats.h"
#include "strictmin/report/strict_order.h"

namespace strictmin {

struct MethodEntry {
  std::string name;          // method name: "l2", "linf", "relax", ...
  std::string label;         // heading; empty: method_label(name)
  std::string colour;        // its colour in the histogram ("#rrggbb")
  std::string picture;       // relative path of its colour-coded view; empty: none
  std::string histogram;     // relative path of its own histogram; empty: none
  std::vector<std::pair<std::string, std::string>> extra_pictures;  // (caption, relative path)
  std::vector<std::pair<std::string, std::string>> links;           // (text, relative path): summary JSON, ...
  DistortionStats stats;     // max, l2, flipped, elements
  double lower_bound = std::numeric_limits<double>::quiet_NaN();  // certified (linf and strict methods)
  double time_s = std::numeric_limits<double>::quiet_NaN();
  std::string status = "solved";
  std::string message;
  double order_tolerance = 0;  // values closer tie in the verdicts (MethodRun::order_tolerance)
  Eigen::VectorXd distortion, weights;  // #E: for the verdicts and the area near the top
};

struct ReportSection {
  std::string id;            // HTML anchor
  std::string title;
  std::string description;   // plain text (escaped), a paragraph
  std::string input_picture; // relative path of the undeformed input; empty: none
  std::string input_caption;
  std::string histogram;     // relative path of the overlaid histogram
  double scale = std::numeric_limits<double>::quiet_NaN();  // its colour scale; NaN: the report's
  std::string measure = "field deviation \u2016J \u2212 I\u2016";
  std::string value_name = "distortion";  // what the cards' numbers are ("distortion \u2212 1": qc, iso)
  std::vector<MethodEntry> methods;
  bool alternatives = true;  // rival maps of one problem: compare them (notes, verdicts); false: a sequence
};

struct HtmlReport {
  std::string title = "strictmin report";
  std::vector<std::string> intro;  // paragraphs of plain text shown first (escaped)
  double scale = kDefaultColourScale;
  std::vector<ReportSection> sections;
  std::string footer;              // plain text, e.g. the command that made the report
};

// "L2 (least squares)", "L\u221e (least maximum)", "strict minimizer (relaxation)", ...; the name itself
// for unknown methods.
std::string method_label(const std::string& method);

// The share of the total weight (percent) with distortion >= level.
double area_percent_at_or_above(const Eigen::VectorXd& distortion, const Eigen::VectorXd& weights, double level);

// The strict-order verdict of a against b in words, areas as shares of total_area
// ("A is less distorting than B: both reach 0.3, but A has 10% of the area at or above it
// against 79%").
std::string verdict_text(const StrictComparison& c, const std::string& name_a, const std::string& name_b,
                         double total_area);

std::string index_html(const HtmlReport& report);
// Creates the report folder dir (and its parents) for a new report and removes the previous
// report's index.html there. The index is written last (write_index_html), so a folder whose
// writing was cut short (a second Ctrl-C) has none, where an older run's index would point at
// a mix of both runs' files. Throws InputError naming the folder when it cannot be created.
void open_report_folder(const std::string& dir);

// Writes index_html(report) to path atomically, then the folder's manifest of the files the
// report refers to, removing the previous report's files it no longer refers to
// (report/report_manifest.h).
void write_index_html(const std::string& path, const HtmlReport& report);

}  // namespace strictmin
