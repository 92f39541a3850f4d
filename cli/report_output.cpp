#include "report_output.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "common.h"
#include "strictmin/io/atomic_file.h"
#include "strictmin/io/input_error.h"
#include "strictmin/report/html_report.h"

namespace strictmin::cli {

void add_report_options(CLI::App& cmd, ReportArgs& a) {
  CLI::Option* report = cmd.add_option("--report", a.dir,
                 "Write a report to folder DIR: summary.json, a colour-coded view, histogram.svg and index.html "
                 "(open it in a browser)")
      ->type_name("DIR");
  cmd.add_option("--report-scale", a.scale,
                 "Report: the distortion shown red (dark blue is 0); 0: automatic, 1.5 times the least maximum "
                 "rounded up to 1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6 or 8 times a power of ten")
      ->capture_default_str()
      ->check(at_least(0))
      ->needs(report);  // alone it would be ignored
}

namespace {
constexpr double kNoBound = std::numeric_limits<double>::quiet_NaN();

// qc, iso >= 1: reports show their excess over 1 (the pictures' scale starts at 1, blue =
// undistorted), and their cards say so (describe_measure).
bool shown_as_excess(Measure measure) { return measure == Measure::Quasiconformal || measure == Measure::Isometric; }
}  // namespace

Eigen::VectorXd report_values(Measure measure, const Eigen::VectorXd& distortion) {
  if (!shown_as_excess(measure)) return distortion;
  return distortion.array() - 1.0;
}

MethodRun method_run(const std::string& method, const DeformOutcome& d, Measure measure) {
  MethodRun r;
  r.method = method;
  r.mapped = d.deformed;
  r.distortion = report_values(measure, d.measured.distortion);
  r.weights = d.measured.weights;
  r.flipped = d.measured.stats.flipped;
  r.lower_bound = measure == Measure::FieldDeviation ? d.result.lower_bound : kNoBound;
  r.time_s = d.result.time_s;
  r.status = status_name(d.result.status);
  r.message = d.result.message;
  return r;
}

MethodRun method_run(const std::string& method, const ParamOutcome& p, Measure measure) {
  MethodRun r;
  r.method = method;
  r.mapped = p.mapped;
  r.distortion = report_values(measure, p.measured.distortion);
  r.weights = p.measured.weights;
  r.flipped = p.flips;
  r.lower_bound = measure == Measure::FieldDeviation ? p.result.lower_bound : kNoBound;
  r.time_s = p.result.time_s;
  r.status = status_name(p.result.status);
  r.message = p.result.message;
  return r;
}

double order_tolerance(const SolverOptions& options) {
  return options.method == Method::Direct ? options.direct.delta_k : 0.0;
}

MethodRun method_run(const std::string& method, const InterpFrame& f) {
  MethodRun r;
  r.method = method;
  r.mapped = f.mesh;
  r.distortion = f.result.distortion;
  r.weights = f.weights;
  r.flipped = f.stats.flipped;  // -1 on a surface: no orientation in 3D
  r.time_s = f.result.time_s;
  r.status = status_name(f.result.status);
  r.message = f.result.message;
  return r;
}

std::string write_report_folder(const ReportArgs& a, const nlohmann::json& summary, const std::string& title,
                                const std::vector<SectionInput>& sections) {
  namespace fs = std::filesystem;
  open_report_folder(a.dir);
  nlohmann::json with_provenance = summary;
  add_provenance_summary(with_provenance);  // as --summary writes it (the same file when both name it)
  write_file_atomically((fs::path(a.dir) / "summary.json").string(),
                        [&](std::ostream& os) { os << with_provenance.dump(2) << '\n'; });
  ComparisonOptions o;
  o.scale = a.scale;
  o.picture_width = 520;
  o.png_height = 380;
  HtmlReport report;
  report.title = "strictmin: " + title;
  report.scale = a.scale;
  for (const SectionInput& in : sections) {
    report.sections.push_back(write_section(a.dir, in, o));
    if (in.id.empty()) report.sections.back().id = "result";
  }
  if (!(a.scale > 0) && !report.sections.empty()) report.scale = report.sections.front().scale;  // automatic
  const std::string index = (fs::path(a.dir) / "index.html").string();
  write_index_html(index, report);
  return index;
}

std::string write_task_report(const ReportArgs& a, const nlohmann::json& summary, const std::string& input_name,
                              const Mesh& rest, const std::vector<Handle>& handles, const DeformOutcome& d) {
  const std::string method = summary.value("method", std::string("given"));
  SectionInput in;
  in.title = method_label(method) + " on " + input_title(input_name);
  in.description = std::string("Task ") + summary.value("task", std::string("deform")) + ", measure " +
                   summary.value("measure", std::string("fd")) + ", " + std::to_string(rest.num_elements()) +
                   " elements.";
  describe_measure(in, summary.value("measure", std::string("fd")), summary.value("task", std::string("deform")));
  in.rest = &rest;
  in.handles = handles;
  const std::string measure = summary.value("measure", std::string("fd"));
  MethodRun run = method_run(method, d, parse_measure(measure).value_or(Measure::Arap));
  run.view_name = "view";
  run.links.emplace_back("summary.json", "summary.json");
  in.runs.push_back(std::move(run));
  return write_report_folder(a, summary, in.title, {in});
}

std::string file_url(const std::string& path) {
  std::error_code ec;
  const auto abs = std::filesystem::absolute(path, ec);
  const std::string plain = ec ? path : abs.lexically_normal().string();
  // Percent-encoded (RFC 3986): a '#', '%', '?' or space in a folder name would otherwise cut
  // the address short or change it in a browser.
  std::string url = "file://";
  for (const unsigned char ch : plain) {
    if (std::isalnum(ch) || ch == '/' || ch == '-' || ch == '_' || ch == '.' || ch == '~') {
      url += static_cast<char>(ch);
    } else {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", ch);
      url += hex;
    }
  }
  return url;
}

std::string measure_description(const std::string& m, const std::string& task) {
  // Field deviation is from the identity in deformations only: a parametrization's targets
  // are rotations (gparam: the cross field's, param: the starting map's), docs/gparam.md.
  if (m == "fd" && task == "gparam") return "field deviation \u2016J \u2212 R\u2016 from the cross field's frames";
  if (m == "fd" && task == "param") return "field deviation \u2016J \u2212 R\u2016 from the starting map's rotations";
  if (m == "fd") return "field deviation \u2016J \u2212 I\u2016";
  if (m == "arap") return "ARAP distortion";
  if (m == "asap") return "ASAP distortion";
  // qc and iso are >= 1 (1: conformal / isometric): reports show their excess over 1.
  if (m == "qc") return "quasiconformal distortion \u03c3\u2081/\u03c3\u2082 \u2212 1";
  if (m == "iso") return "isometric distortion max(\u03c3\u2081, 1/\u03c3\u2082) \u2212 1";
  return m;
}

void describe_measure(SectionInput& in, const std::string& measure, const std::string& task) {
  in.measure = measure_description(measure, task);
  const auto m = parse_measure(measure);
  in.value_name = m && shown_as_excess(*m) ? "distortion \u2212 1" : "distortion";
}

std::string input_title(const std::string& input) {
  if (input.rfind("example:", 0) == 0) return input.substr(8);
  return std::filesystem::path(input).filename().string();
}

}  // namespace strictmin::cli
