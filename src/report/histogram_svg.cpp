#include "strictmin/report/histogram_svg.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "markup.h"
#include "strictmin/io/atomic_file.h"
#include "strictmin/report/colour_map.h"
#include "strictmin/report/histogram.h"

namespace strictmin {
namespace {

using markup::coord;
using markup::escape;

// Tick step for [0, hi] with about `target` ticks: 1, 2, 2.5 or 5 times a power of ten.
double tick_step(double hi, int target) {
  const double raw = hi / target;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 2.5, 5.0})
    if (m * p >= raw * (1 - 1e-9)) return m * p;
  return 10 * p;
}

void check(const std::vector<HistogramSeries>& series) {
  for (const auto& s : series) {
    if (s.distortion.size() != s.weights.size())
      throw std::invalid_argument("histogram_svg: series '" + s.name + "' has distortion and weights of different sizes");
    if (s.distortion.size() == 0) throw std::invalid_argument("histogram_svg: series '" + s.name + "' is empty");
  }
}

double upper_of(const std::vector<HistogramSeries>& series) {
  std::vector<const Eigen::VectorXd*> all;
  for (const auto& s : series) all.push_back(&s.distortion);
  return histogram_upper(all);
}

// A decade at or below the smallest positive share, between 1e-4 % and 0.1 %.
double min_exponent_of(const std::vector<Histogram>& hists) {
  double smallest = 100;
  for (const auto& h : hists)
    for (double p : h.percent)
      if (p > 0) smallest = std::min(smallest, p);
  return std::clamp(std::floor(std::log10(smallest) + 1e-9), -4.0, -1.0);
}

}  // namespace

std::string series_colour(int i) {
  static const char* palette[] = {"#303030", "#e6550d", "#1a9850", "#7b3294", "#1f78b4", "#8c510a", "#d01c8b"};
  return palette[static_cast<std::size_t>(i) % std::size(palette)];
}

HistogramAxes histogram_axes(const std::vector<HistogramSeries>& series, int bins) {
  check(series);
  HistogramAxes a;
  if (series.empty()) return a;
  a.upper = upper_of(series);
  std::vector<Histogram> hists;
  for (const auto& s : series) hists.push_back(distortion_histogram(s.distortion, s.weights, a.upper, bins));
  a.min_exponent = min_exponent_of(hists);
  return a;
}

std::string histogram_svg(const std::vector<HistogramSeries>& series, const HistogramSvgOptions& o) {
  check(series);
  const double hi = o.upper > 0 ? o.upper : upper_of(series);
  std::vector<Histogram> hists;
  for (const auto& s : series) hists.push_back(distortion_histogram(s.distortion, s.weights, hi, o.bins));
  const double lo_exp = o.min_exponent < 0 ? o.min_exponent : min_exponent_of(hists);
  const double hi_exp = 2.0;
  auto colour_of = [&](std::size_t k) {
    return series[k].colour.empty() ? series_colour(static_cast<int>(k)) : series[k].colour;
  };

  const double W = o.width, H = o.height;
  const double legend_h = o.legend ? 8 + 18.0 * series.size() : 0;
  const double step = tick_step(hi, 5);
  // Room on the left for the longest tick label (4e+06 ran into the axis title) and on the
  // right for half of the last decade's label (100% was cut).
  std::size_t tick_chars = 1;
  for (double v = 0; v <= hi * (1 + 1e-9); v += step) tick_chars = std::max(tick_chars, markup::number(v, 3).size());
  const double top = o.title.empty() ? 12 : 34, right = W - 20;
  const double left = std::max(W < 400 ? 58.0 : 74.0, 40 + 6.5 * static_cast<double>(tick_chars));
  const double bottom = H - 46 - legend_h;
  auto X = [&](double percent) {
    const double e = std::clamp(std::log10(std::max(percent, 1e-300)), lo_exp, hi_exp);
    return left + (e - lo_exp) / (hi_exp - lo_exp) * (right - left);
  };
  auto Y = [&](double value) { return bottom - std::clamp(value / hi, 0.0, 1.0) * (bottom - top); };

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << o.width << "\" height=\"" << o.height
      << "\" viewBox=\"0 0 " << o.width << ' ' << o.height << "\" font-family=\"Helvetica, Arial, sans-serif\">\n";
  svg << "<rect x=\"0\" y=\"0\" width=\"" << o.width << "\" height=\"" << o.height << "\" fill=\"#ffffff\"/>\n";
  if (!o.title.empty())
    svg << "<text x=\"" << coord(0.5 * (left + right)) << "\" y=\"21\" text-anchor=\"middle\" font-size=\"14\" "
        << "font-weight=\"bold\">" << escape(o.title) << "</text>\n";

  // Grid: decades (vertical lines) and distortion ticks (horizontal lines).
  svg << "<g stroke=\"#e3e3e3\" stroke-width=\"1\">\n";
  for (double e = lo_exp; e <= hi_exp + 1e-9; e += 1)
    svg << "<line x1=\"" << coord(X(std::pow(10.0, e))) << "\" y1=\"" << coord(top) << "\" x2=\""
        << coord(X(std::pow(10.0, e))) << "\" y2=\"" << coord(bottom) << "\"/>\n";
  for (double v = step; v <= hi * (1 + 1e-9); v += step)
    svg << "<line x1=\"" << coord(left) << "\" y1=\"" << coord(Y(v)) << "\" x2=\"" << coord(right) << "\" y2=\""
        << coord(Y(v)) << "\"/>\n";
  svg << "</g>\n";

  // The colour scale beside the distortion axis (red from colour_scale up).
  const int strips = 64;
  svg << "<g stroke=\"none\">\n";
  for (int i = 0; i < strips; ++i) {
    const double v0 = hi * i / strips, v1 = hi * (i + 1) / strips;
    svg << "<rect x=\"" << coord(left - 11) << "\" y=\"" << coord(Y(v1)) << "\" width=\"8\" height=\""
        << coord(Y(v0) - Y(v1) + 0.5) << "\" fill=\"" << hex(distortion_colour(0.5 * (v0 + v1), o.colour_scale))
        << "\"/>\n";
  }
  svg << "</g>\n";

  // One step curve per series (bars in the pictures' colours when asked), and a dashed line at its maximum.
  for (std::size_t k = 0; k < series.size(); ++k) {
    const std::string colour = colour_of(k);
    const Histogram& h = hists[k];
    if (o.colour_bars) {
      svg << "<g stroke=\"none\">\n";
      for (int b = 0; b < h.bins(); ++b) {
        if (h.percent[b] <= 0) continue;
        const double x = X(h.percent[b]);
        svg << "<rect x=\"" << coord(left) << "\" y=\"" << coord(Y(h.edge(b + 1))) << "\" width=\""
            << coord(std::max(x - left, 1.0)) << "\" height=\"" << coord(Y(h.edge(b)) - Y(h.edge(b + 1))) << "\" fill=\""
            << hex(distortion_colour(h.edge(b) + 0.5 * h.bin_width(), o.colour_scale)) << "\"/>\n";
      }
      svg << "</g>\n";
    }
    svg << "<path fill=\"" << (o.colour_bars ? "none" : colour) << "\" fill-opacity=\"0.08\" stroke=\"" << colour
        << "\" stroke-width=\"" << (o.colour_bars ? "1.2" : "2") << "\" stroke-linejoin=\"miter\" d=\"M" << coord(left)
        << ',' << coord(Y(0));
    for (int b = 0; b < h.bins(); ++b) {
      const double x = h.percent[b] > 0 ? std::max(X(h.percent[b]), left + 1) : left;
      svg << " L" << coord(x) << ',' << coord(Y(h.edge(b))) << " L" << coord(x) << ',' << coord(Y(h.edge(b + 1)));
    }
    svg << " L" << coord(left) << ',' << coord(Y(hi)) << " Z\"/>\n";
    const double mx = series[k].distortion.maxCoeff();
    svg << "<line x1=\"" << coord(left) << "\" y1=\"" << coord(Y(mx)) << "\" x2=\"" << coord(right) << "\" y2=\""
        << coord(Y(mx)) << "\" stroke=\"" << colour << "\" stroke-width=\"1\" stroke-dasharray=\"6 4\"/>\n";
  }

  // Axes, ticks and labels.
  svg << "<polyline fill=\"none\" stroke=\"#000000\" stroke-width=\"1\" points=\"" << coord(left) << ',' << coord(top)
      << ' ' << coord(left) << ',' << coord(bottom) << ' ' << coord(right) << ',' << coord(bottom) << "\"/>\n";
  svg << "<g font-size=\"11\" fill=\"#000000\">\n";
  // Every decade's label where they fit (about 40 px each), else every other one from the top.
  const double decade_px = (right - left) / std::max(1.0, hi_exp - lo_exp);
  const int label_every = decade_px >= 40 ? 1 : 2;
  for (double e = lo_exp; e <= hi_exp + 1e-9; e += 1) {
    if (static_cast<int>(std::lround(hi_exp - e)) % label_every != 0) continue;
    svg << "<text x=\"" << coord(X(std::pow(10.0, e))) << "\" y=\"" << coord(bottom + 14)
        << "\" text-anchor=\"middle\">" << markup::number(std::pow(10.0, e), 3) << "%</text>\n";
  }
  for (double v = 0; v <= hi * (1 + 1e-9); v += step)
    svg << "<text x=\"" << coord(left - 15) << "\" y=\"" << coord(Y(v) + 4) << "\" text-anchor=\"end\">"
        << markup::number(v, 3) << "</text>\n";
  svg << "</g>\n";
  // Axis titles sized to their room (a 290 px card cut "(log scale)"; interp's long distortion
  // label ran past both ends of its axis): about 0.55 em a character.
  const std::string x_title =
      right - left >= 0.55 * 12 * 48 ? "share of the area per distortion bin (log scale)" : "share of the area per bin (log)";
  auto fitting_size = [](double room, std::size_t chars) {
    return std::clamp(room / (0.55 * static_cast<double>(std::max<std::size_t>(chars, 1))), 7.0, 12.0);
  };
  svg << "<text x=\"" << coord(0.5 * (left + right)) << "\" y=\"" << coord(bottom + 32)
      << "\" text-anchor=\"middle\" font-size=\"" << coord(fitting_size(right - left + 20, x_title.size())) << "\">"
      << x_title << "</text>\n";
  svg << "<text transform=\"translate(15," << coord(0.5 * (top + bottom)) << ") rotate(-90)\" text-anchor=\"middle\" "
         "font-size=\""
      << coord(fitting_size(bottom - top + 24, o.value_label.size())) << "\">" << escape(o.value_label) << "</text>\n";

  // Legend (below the plot).
  if (o.legend) {
    for (std::size_t k = 0; k < series.size(); ++k) {
      const double y = bottom + 56 + 18.0 * k;
      svg << "<line x1=\"" << coord(left) << "\" y1=\"" << coord(y - 4) << "\" x2=\"" << coord(left + 24) << "\" y2=\""
          << coord(y - 4) << "\" stroke=\"" << colour_of(k) << "\" stroke-width=\"3\"/>\n";
      svg << "<text x=\"" << coord(left + 32) << "\" y=\"" << coord(y) << "\" font-size=\"12\">"
          << escape(series[k].name) << " (max " << markup::number(series[k].distortion.maxCoeff(), 4) << ")</text>\n";
    }
  }
  svg << "</svg>\n";
  return svg.str();
}

void write_histogram_svg(const std::string& path, const std::vector<HistogramSeries>& series,
                         const HistogramSvgOptions& options) {
  const std::string text = histogram_svg(series, options);
  write_file_atomically(path, [&](std::ostream& os) { os << text; });
}

}  // namespace strictmin
