#include "strictmin/report/html_report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include "markup.h"
#include "strictmin/io/atomic_file.h"
#include "strictmin/io/input_error.h"
#include "strictmin/report/histogram.h"
#include "strictmin/report/report_manifest.h"
#include "strictmin/report/strict_order.h"

namespace strictmin {
namespace {

using markup::escape;
using markup::number;

constexpr const char* kStyle = R"(
body { font-family: "Helvetica Neue", Helvetica, Arial, sans-serif; color: #222; margin: 0; background: #fafafa; }
main { max-width: 1400px; margin: 0 auto; padding: 18px 28px 40px; }
h1 { font-size: 26px; margin: 6px 0 10px; }
h2 { font-size: 21px; margin: 34px 0 6px; padding-top: 10px; border-top: 2px solid #ddd; }
h3 { font-size: 15px; margin: 0 0 8px; }
p { line-height: 1.45; max-width: 1100px; }
.story { background: #fff; border: 1px solid #dde; border-radius: 6px; padding: 4px 18px; }
.legend { display: flex; align-items: center; gap: 14px; flex-wrap: wrap; margin: 10px 0; font-size: 14px; }
.cards { display: grid; grid-template-columns: repeat(auto-fit, minmax(215px, 1fr)); gap: 12px; }
.card { background: #fff; border: 1px solid #ddd; border-radius: 6px; padding: 10px 10px; max-width: 420px; }
.card h3 { border-left: 6px solid #888; padding-left: 8px; }
.card img { width: 100%; height: auto; display: block; margin: 0 auto 6px; }
.card img.hist { margin-top: 4px; }
.card.input { background: #f3f3f3; }
.caption { font-size: 12.5px; color: #555; margin: 2px 0 6px; }
table.numbers { border-collapse: collapse; font-size: 13px; width: 100%; }
table.numbers td { padding: 2px 4px; border-bottom: 1px solid #eee; vertical-align: top; }
table.numbers td.v { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
tr.key td { font-weight: bold; }
.ok { color: #1a7f37; } .warn { color: #b35900; font-weight: bold; }
.links { font-size: 12.5px; margin-top: 6px; }
.below { display: flex; flex-wrap: wrap; gap: 22px; margin-top: 16px; align-items: flex-start; }
.below figure { margin: 0; background: #fff; border: 1px solid #ddd; border-radius: 6px; padding: 6px; }
.below figure img { display: block; width: 560px; max-width: 100%; height: auto; }
.below figcaption { font-size: 12.5px; color: #555; max-width: 560px; padding: 4px; }
.notes { flex: 1 1 380px; font-size: 14px; }
.notes li { margin-bottom: 6px; line-height: 1.4; }
footer { margin-top: 40px; font-size: 12px; color: #777; }
)";

std::string colour_bar_svg(double scale, const std::string& id) {
  std::ostringstream s;
  const int w = 320, h = 16, x0 = 10;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w + 50 << "\" height=\"40\" viewBox=\"0 0 " << w + 50
    << " 40\" role=\"img\" aria-label=\"colour scale\">";
  s << "<defs>" << "<linearGradient id=\"ramp-" << escape(id) << "\" x1=\"0\" x2=\"1\" y1=\"0\" y2=\"0\">";
  for (int i = 0; i <= 28; ++i) {
    const double t = i / 28.0;
    s << "<stop offset=\"" << markup::coord(t, 4) << "\" stop-color=\"" << hex(colour_ramp(t)) << "\"/>";
  }
  s << "</linearGradient></defs>";
  s << "<rect x=\"" << x0 << "\" y=\"2\" width=\"" << w << "\" height=\"" << h
    << "\" fill=\"url(#ramp-" << escape(id) << ")\" stroke=\"#888\"/>";
  for (int i = 0; i <= 4; ++i) {
    const double x = x0 + w * i / 4.0;
    s << "<line x1=\"" << x << "\" y1=\"" << 2 + h << "\" x2=\"" << x << "\" y2=\"" << 6 + h
      << "\" stroke=\"#444\"/><text x=\"" << x << "\" y=\"36\" font-size=\"12\" text-anchor=\"middle\" "
      << "font-family=\"Helvetica, Arial, sans-serif\">" << (i == 4 ? "\u2265 " : "") << number(scale * i / 4.0, 3)
      << "</text>";
  }
  s << "</svg>";
  return s.str();
}

std::string seconds(double t) {
  if (!std::isfinite(t)) return "n/a";
  if (t < 0.01) return number(t * 1000, 2) + " ms";
  return number(t, 3) + " s";
}

// The heading a method's map goes by in cards, notes and verdicts: its label, and when its
// solve did not meet its own criterion, that it did not (a capped L-infinity "losing" to
// relax read as L-infinity losing on its own criterion).
std::string shown_name(const MethodEntry& m) {
  std::string name = m.label.empty() ? method_label(m.name) : m.label;
  if (!m.status.empty() && m.status != "solved") name += " (not solved: " + m.status + ")";
  return name;
}

bool comparable(const MethodEntry& a, const MethodEntry& b) {
  return a.distortion.size() > 0 && a.distortion.size() == b.distortion.size() &&
         a.weights.size() == a.distortion.size();
}

// The strict order of a against b, values closer than either run's own tolerance tied:
// direct fixes each level's elements within delta-k of it, so finer differences say nothing.
constexpr double kFinestOrderTolerance = 1e-6;
double order_tolerance(const MethodEntry& a, const MethodEntry& b) {
  return std::max({kFinestOrderTolerance, a.order_tolerance, b.order_tolerance});
}
StrictComparison strict_order(const MethodEntry& a, const MethodEntry& b) {
  return compare_strict(a.distortion, b.distortion, a.weights, order_tolerance(a, b));
}

// The smallest finite maximum among the methods (the least maximum shown).
double least_maximum(const ReportSection& s) {
  double k = std::numeric_limits<double>::infinity();
  for (const auto& m : s.methods)
    if (std::isfinite(m.stats.max)) k = std::min(k, m.stats.max);
  return k;
}

void write_card(std::ostream& h, const MethodEntry& m, double kstar, const std::string& value_name) {
  const std::string label = shown_name(m);
  h << "<div class=\"card\"><h3 style=\"border-left-color:" << escape(m.colour.empty() ? "#888888" : m.colour)
    << "\">" << escape(label) << "</h3>\n";
  if (!m.picture.empty())
    h << "<img src=\"" << escape(m.picture) << "\" alt=\"" << escape(label) << ": elements coloured by distortion\">\n";
  if (!m.histogram.empty())
    h << "<img class=\"hist\" src=\"" << escape(m.histogram) << "\" alt=\"" << escape(label)
      << ": distortion histogram\">\n";
  for (const auto& [caption, path] : m.extra_pictures)
    h << "<div class=\"caption\">" << escape(caption) << "</div><img src=\"" << escape(path) << "\" alt=\""
      << escape(label + ": " + caption) << "\">\n";
  h << "<table class=\"numbers\">\n";
  h << "<tr class=\"key\"><td>max " << escape(value_name) << "</td><td class=\"v\">" << number(m.stats.max, 5)
    << "</td></tr>\n";
  if (std::isfinite(m.lower_bound))
    h << "<tr><td>certified lower bound (no map does better)</td><td class=\"v\">" << number(m.lower_bound, 5)
      << "</td></tr>\n";
  const std::string l2_name = value_name == "distortion" ? "L2 distortion" : "L2 of " + value_name;
  h << "<tr><td>" << escape(l2_name) << " (area-weighted RMS)</td><td class=\"v\">" << number(m.stats.l2, 4)
    << "</td></tr>\n";
  if (std::isfinite(kstar) && kstar > kZeroDistortionShown && m.distortion.size() == m.weights.size() &&
      m.distortion.size() > 0)
    h << "<tr><td>area with distortion \u2265 " << number(0.9 * kstar, 3) << " (90% of the least max)</td><td class=\"v\">"
      << number(area_percent_at_or_above(m.distortion, m.weights, 0.9 * kstar), 3) << "%</td></tr>\n";
  if (m.stats.flipped < 0)  // a surface in 3D: its 3 by 2 Jacobians have no orientation
    h << "<tr><td>flipped elements</td><td class=\"v\">not defined (surface)</td></tr>\n";
  else
    h << "<tr><td>flipped elements</td><td class=\"v\">" << m.stats.flipped << " of " << m.stats.elements
      << "</td></tr>\n";
  h << "<tr><td>time</td><td class=\"v\">" << seconds(m.time_s) << "</td></tr>\n";
  const bool ok = m.status == "solved";
  // A given map (strictmin eval) was measured, not solved for: its summary's "solved" means usable.
  const std::string status = m.name == "given" && ok ? "evaluated (no solve)" : m.status;
  h << "<tr><td>status</td><td class=\"v " << (ok ? "ok" : "warn") << "\">" << escape(status) << "</td></tr>\n";
  h << "</table>\n";
  if (!m.message.empty())
    h << "<div class=\"caption" << (ok ? "" : " warn") << "\">" << escape(m.message) << "</div>\n";
  if (!m.links.empty()) {
    h << "<div class=\"links\">";
    for (std::size_t i = 0; i < m.links.size(); ++i)
      h << (i ? " \u00b7 " : "") << "<a href=\"" << escape(m.links[i].second) << "\">" << escape(m.links[i].first)
        << "</a>";
    h << "</div>\n";
  }
  h << "</div>\n";
}

void write_notes(std::ostream& h, const ReportSection& s, double kstar) {
  h << "<div class=\"notes\">\n";
  if (std::isfinite(kstar) && s.methods.size() > 1) {
    h << "<h3>What the numbers say</h3><ul>\n";
    double bound = -std::numeric_limits<double>::infinity();
    for (const auto& m : s.methods)
      if (std::isfinite(m.lower_bound)) bound = std::max(bound, m.lower_bound);
    if (std::isfinite(bound))
      h << "<li>No map of this problem has a maximum distortion below " << number(bound, 5)
        << " (the certified lower bound of the L\u221e solve).</li>\n";
    for (const auto& m : s.methods) {
      const std::string label = shown_name(m);
      const bool have = m.distortion.size() > 0 && m.distortion.size() == m.weights.size();
      if (m.stats.max <= kZeroDistortionShown) {
        // An exact map (zero distortion to rounding): no ratio to the least maximum, no share.
        h << "<li><b>" << escape(label) << "</b>: no distortion (maximum " << number(m.stats.max, 3)
          << ", zero to rounding).</li>\n";
      } else if (kstar <= kZeroDistortionShown) {
        h << "<li><b>" << escape(label) << "</b>: maximum " << number(m.stats.max, 4)
          << ", where another map shown has no distortion.</li>\n";
      } else if (!std::isfinite(m.stats.max)) {
        h << "<li><b>" << escape(label) << "</b>: some elements are infinitely distorted (flipped).</li>\n";
      } else if (m.stats.max > kstar * (1 + 1e-3)) {
        h << "<li><b>" << escape(label) << "</b>: maximum " << number(m.stats.max, 4) << ", "
          << number(m.stats.max / kstar, 3) << "\u00d7 the least maximum " << number(kstar, 4);
        if (have)
          h << "; only " << number(area_percent_at_or_above(m.distortion, m.weights, kstar), 3)
            << "% of the area is above " << number(kstar, 4) << ": its distortion is concentrated";
        h << ".</li>\n";
      } else {
        h << "<li><b>" << escape(label) << "</b>: maximum " << number(m.stats.max, 5);
        if (have)
          h << "; " << number(area_percent_at_or_above(m.distortion, m.weights, 0.9 * kstar), 3)
            << "% of the area is within 10% of it, L2 distortion " << number(m.stats.l2, 4);
        h << ".</li>\n";
      }
    }
    h << "</ul>\n";
  }
  std::vector<std::string> verdicts;
  std::vector<const MethodEntry*> ranked;  // the comparable ones
  bool all_equivalent = true;
  for (std::size_t i = 1; i < s.methods.size(); ++i) {
    const MethodEntry &a = s.methods[i - 1], &b = s.methods[i];
    if (!comparable(a, b)) continue;
    const StrictComparison c = strict_order(a, b);
    all_equivalent = all_equivalent && c.order == StrictOrder::Equivalent;
    std::string verdict = verdict_text(c, shown_name(a), shown_name(b), a.weights.sum());
    if (order_tolerance(a, b) > kFinestOrderTolerance)
      verdict += " (values within " + number(order_tolerance(a, b), 3) + ", direct's delta-k, count as equal)";
    verdicts.push_back(verdict);
  }
  if (!verdicts.empty()) {
    h << "<h3>Strict order (paper, Section 4)</h3>\n<p class=\"caption\">Two maps compared from the top down: the "
         "lower maximum wins; at equal maxima, less area at that level wins; and so on down the levels. The strict "
         "minimizer is the least map in this order.</p>\n<ul>\n";
    for (const auto& v : verdicts) h << "<li>" << escape(v) << ".</li>\n";
    if (all_equivalent && s.methods.size() > 1) {
      // (Not an explanation of why: the maps may simply be the same one, e.g. relax with no sweep.)
      h << "<li>All these maps have the same distortion distribution: none is less distorting than another in "
           "the strict order.</li>\n";
    } else {
      // The least of all the methods shown (when all are comparable with the first).
      std::size_t best = 0;
      bool all_comparable = true;
      for (std::size_t i = 1; i < s.methods.size(); ++i) {
        if (!comparable(s.methods[i], s.methods[best])) {
          all_comparable = false;
          break;
        }
        if (strict_order(s.methods[i], s.methods[best]).order == StrictOrder::Less)
          best = i;
      }
      if (all_comparable && s.methods.size() > 2)
        h << "<li><b>Least distorting of the maps shown: " << escape(shown_name(s.methods[best])) << ".</b></li>\n";
    }
    h << "</ul>\n";
  }
  h << "</div>\n";
}

}  // namespace

std::string verdict_text(const StrictComparison& c, const std::string& name_a, const std::string& name_b,
                         double total_area) {
  if (c.order == StrictOrder::Equivalent) return name_a + " and " + name_b + " have the same distortion distribution";
  const bool less = c.order == StrictOrder::Less;
  const std::string& win = less ? name_a : name_b;
  const std::string& lose = less ? name_b : name_a;
  const double vw = less ? c.value_a : c.value_b, vl = less ? c.value_b : c.value_a;
  const double aw = less ? c.area_a : c.area_b, al = less ? c.area_b : c.area_a;
  std::string s = win + " is less distorting than " + lose + ": ";
  const std::string agree = "they agree on the " + std::to_string(c.level) + " highest distortion level" +
                            (c.level == 1 ? "" : "s") + "; ";
  // Enough digits to tell the two numbers apart.
  auto pair = [](double x, double y, const char* unit) {
    int digits = 3;
    while (digits < 10 && number(x, digits) == number(y, digits)) ++digits;
    return std::make_pair(number(x, digits) + unit, number(y, digits) + unit);
  };
  if (c.by_value) {  // the comparison's own decision (its value tolerance), not a second test
    const auto [w, l] = pair(vw, vl, "");
    if (c.level == 0) return s + "its maximum is " + w + " against " + l;
    return s + agree + "below them, its highest distortion is " + w + " against " + l;
  }
  const double scale = total_area > 0 ? 100.0 / total_area : 1.0;
  const auto [w, l] = pair(aw * scale, al * scale, total_area > 0 ? "%" : "");
  if (c.level == 0) return s + "both reach the maximum " + number(vw, 5) + ", but " + win + " on " + w + " of the area against " + l;
  return s + agree + "at distortion " + number(vw, 5) + ", " + win + " has " + w + " of the area against " + l;
}

std::string method_label(const std::string& m) {
  if (m == "l2") return "L2 (least squares)";
  if (m == "linf") return "L\u221e (least maximum)";
  if (m == "relax") return "strict minimizer (relaxation)";
  if (m == "direct") return "strict minimizer (direct)";
  if (m == "exact") return "strict minimizer (exact)";
  if (m == "lp") return "Lp (Polya)";
  if (m == "irls") return "IRLS (Lawson)";
  if (m == "given") return "given map";
  return m;
}

double area_percent_at_or_above(const Eigen::VectorXd& d, const Eigen::VectorXd& w, double level) {
  double above = 0, total = 0;
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    total += w(i);
    if (d(i) >= level || std::isnan(d(i))) above += w(i);
  }
  return total > 0 ? 100.0 * above / total : 0.0;
}

std::string index_html(const HtmlReport& r) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
    << "<title>" << escape(r.title) << "</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n<main>\n";
  h << "<h1>" << escape(r.title) << "</h1>\n";
  if (!r.intro.empty()) {
    h << "<div class=\"story\">\n";
    for (const auto& p : r.intro) h << "<p>" << escape(p) << "</p>\n";
    h << "</div>\n";
  }
  bool one_scale = true;
  for (const auto& sec : r.sections) one_scale = one_scale && (std::isnan(sec.scale) || sec.scale == r.scale);
  if (one_scale)
    h << "<div class=\"legend\"><span>Every element is coloured by its distortion:</span>"
      << colour_bar_svg(r.scale, "report") << "<span>dark blue = 0 (undistorted), red = " << number(r.scale, 3)
      << " and above.</span></div>\n";
  if (r.sections.size() > 1) {
    h << "<p>Examples: ";
    for (std::size_t i = 0; i < r.sections.size(); ++i)
      h << (i ? " \u00b7 " : "") << "<a href=\"#" << escape(r.sections[i].id) << "\">" << escape(r.sections[i].title)
        << "</a>";
    h << "</p>\n";
  }
  for (const auto& s : r.sections) {
    // The least maximum shown is a reference only among rival maps of one problem.
    const double kstar = s.alternatives ? least_maximum(s) : std::numeric_limits<double>::quiet_NaN();
    h << "<section id=\"" << escape(s.id) << "\">\n<h2>" << escape(s.title) << "</h2>\n";
    if (!s.description.empty()) h << "<p>" << escape(s.description) << "</p>\n";
    if (!one_scale) {
      const double sc = std::isnan(s.scale) ? r.scale : s.scale;
      h << "<div class=\"legend\"><span>Colours:</span>" << colour_bar_svg(sc, s.id)
        << "<span>dark blue = 0 (undistorted), red = " << number(sc, 3) << " and above.</span></div>\n";
    }
    h << "<div class=\"cards\">\n";
    if (!s.input_picture.empty()) {
      h << "<div class=\"card input\"><h3>input</h3><img src=\"" << escape(s.input_picture)
        << "\" alt=\"the input mesh\">\n";
      if (!s.input_caption.empty()) h << "<div class=\"caption\">" << escape(s.input_caption) << "</div>\n";
      h << "</div>\n";
    }
    for (const auto& m : s.methods) write_card(h, m, kstar, s.value_name);
    h << "</div>\n<div class=\"below\">\n";
    if (!s.histogram.empty())
      h << "<figure><img src=\"" << escape(s.histogram) << "\" alt=\"distortion histogram\"><figcaption>Distortion "
        << "(" << escape(s.measure) << ") on the vertical axis, with the colour scale beside it; the share of the "
        << "area in each distortion bin on the horizontal axis, on a log scale (each grid line is ten times the "
        << "previous). " << (s.methods.size() == 1 ? "Bars in the colours of the picture" : "One outline per map")
        << "; a dashed line marks " << (s.methods.size() == 1 ? "the" : "each map's") << " maximum.</figcaption></figure>\n";
    if (s.alternatives) write_notes(h, s, kstar);
    h << "</div>\n</section>\n";
  }
  if (!r.footer.empty()) h << "<footer>" << escape(r.footer) << "</footer>\n";
  h << "</main>\n</body>\n</html>\n";
  return h.str();
}

void open_report_folder(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError("cannot create the report folder " + dir + ": " + ec.message());
  const std::filesystem::path index = std::filesystem::path(dir) / "index.html";
  if (std::filesystem::is_regular_file(index, ec) && !std::filesystem::remove(index, ec))
    throw InputError("cannot replace " + index.string() + ": " + ec.message());
}

void write_index_html(const std::string& path, const HtmlReport& report) {
  const std::string text = index_html(report);
  write_file_atomically(path, [&](std::ostream& os) { os << text; });
  const std::filesystem::path index(path);
  const std::filesystem::path folder = index.has_parent_path() ? index.parent_path() : ".";
  update_report_manifest(folder.string(), report_files(report, index.filename().string()));
}

}  // namespace strictmin
