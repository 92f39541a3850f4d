#include "report_output.h"

#include <filesystem>

#include "strictmin/io/atomic_file.h"
#include "strictmin/io/input_error.h"
#include "strictmin/report/html_report.h"

namespace strictmin::cli {

void add_report_options(CLI::App& cmd, ReportArgs& a) {
  cmd.add_option("--report", a.dir,
                 "Write a report to folder DIR: summary.json, a colour-coded view, histogram.svg and index.html "
                 "(open it in a browser)")
      ->type_name("DIR");
  cmd.add_option("--report-scale", a.scale, "Report: the distortion shown red (dark blue is 0)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
}

MethodRun method_run(const std::string& method, const DeformOutcome& d) {
  MethodRun r;
  r.method = method;
  r.mapped = d.deformed;
  r.distortion = d.measured.distortion;
  r.weights = d.measured.weights;
  r.flipped = d.measured.stats.flipped;
  r.lower_bound = d.result.lower_bound;
  r.time_s = d.result.time_s;
  r.status = status_name(d.result.status);
  r.message = d.result.message;
  return r;
}

std::string write_task_report(const ReportArgs& a, const nlohmann::json& summary, const std::string& input_name,
                              const Mesh& rest, const std::vector<Handle>& handles, const DeformOutcome& d) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(a.dir, ec);
  if (ec) throw InputError("cannot create " + a.dir + ": " + ec.message());
  const std::string method = summary.value("method", std::string("given"));
  write_file_atomically((fs::path(a.dir) / "summary.json").string(),
                        [&](std::ostream& os) { os << summary.dump(2) << '\n'; });
  SectionInput in;
  in.id = "";
  in.title = method_label(method) + " on " + input_title(input_name);
  in.description = std::string("Task ") + summary.value("task", std::string("deform")) + ", measure " +
                   summary.value("measure", std::string("fd")) + ", " + std::to_string(rest.num_elements()) +
                   " elements.";
  in.measure = measure_description(summary.value("measure", std::string("fd")));
  in.rest = &rest;
  in.handles = handles;
  MethodRun run = method_run(method, d);
  run.view_name = "view";
  run.links.emplace_back("summary.json", "summary.json");
  in.runs.push_back(std::move(run));
  ComparisonOptions o;
  o.scale = a.scale;
  o.picture_width = 520;
  o.png_height = 380;
  HtmlReport report;
  report.title = "strictmin: " + in.title;
  report.scale = a.scale;
  report.sections.push_back(write_section(a.dir, in, o));
  report.sections.back().id = "result";
  const std::string index = (fs::path(a.dir) / "index.html").string();
  write_index_html(index, report);
  return index;
}

std::string file_url(const std::string& path) {
  std::error_code ec;
  const auto abs = std::filesystem::absolute(path, ec);
  return "file://" + (ec ? path : abs.lexically_normal().string());
}

std::string measure_description(const std::string& m) {
  if (m == "fd") return "field deviation \u2016J \u2212 I\u2016";
  if (m == "arap") return "ARAP distortion";
  if (m == "asap") return "ASAP distortion";
  if (m == "qc") return "quasiconformal distortion \u03c3\u2081/\u03c3\u2082";
  if (m == "iso") return "isometric distortion max(\u03c3\u2081, 1/\u03c3\u2082)";
  return m;
}

std::string input_title(const std::string& input) {
  if (input.rfind("example:", 0) == 0) return input.substr(8);
  return std::filesystem::path(input).filename().string();
}

}  // namespace strictmin::cli
