#pragma once
// The paper's log-scale distortion histogram as SVG: distortion on the vertical axis (with
// the colour scale beside it), the share of the mesh's area per distortion bin on a
// logarithmic horizontal axis; several methods overlaid as outlined step curves (or one
// method as bars in the colours of the pictures), each with a dashed line at its maximum,
// a legend and axis labels.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace strictmin {

struct HistogramSeries {
  std::string name;            // legend text, e.g. "L2"
  Eigen::VectorXd distortion;  // #E
  Eigen::VectorXd weights;     // #E (rest areas / volumes)
  std::string colour;          // "#rrggbb"; empty: a default per series index
};

struct HistogramSvgOptions {
  int bins = 40;
  double upper = 0;            // top of the distortion axis; 0: histogram_upper of the series
  double min_exponent = 0;     // the share axis starts at 10^min_exponent %; 0: from the smallest share
  double colour_scale = 0.6;   // red end of the colour bar beside the distortion axis
  int width = 560, height = 380;
  std::string title;           // drawn above the plot when not empty
  std::string value_label = "distortion";
  bool colour_bars = false;    // fill each bin with its distortion's colour (for a single method)
  bool legend = true;          // the methods' names and maxima, below the plot
};

// Axes shared by several histograms (so that they compare at a glance): the top of the
// distortion axis and the start of the share axis, as histogram_svg would pick them for all
// the series together.
struct HistogramAxes {
  double upper = 1;
  double min_exponent = -2;
};
HistogramAxes histogram_axes(const std::vector<HistogramSeries>& series, int bins = 40);

// Default colour of series i (distinct from the blue-to-red distortion ramp's use).
std::string series_colour(int i);

// The SVG document. Throws std::invalid_argument when a series' sizes differ or it is empty.
std::string histogram_svg(const std::vector<HistogramSeries>& series, const HistogramSvgOptions& options = {});

// Writes histogram_svg(...) to `path` atomically (throws InputError when it cannot).
void write_histogram_svg(const std::string& path, const std::vector<HistogramSeries>& series,
                         const HistogramSvgOptions& options = {});

}  // namespace strictmin
