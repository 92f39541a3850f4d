#pragma once
// What the report-writing subcommands share: the --report option of tasks, a report
// section from a task's outcome, and the "open this" line.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "strictmin/report/colour_map.h"
#include "strictmin/report/comparison.h"
#include "strictmin/tasks/deform.h"
#include "strictmin/tasks/interp.h"
#include "strictmin/tasks/param.h"

namespace strictmin::cli {

struct ReportArgs {
  std::string dir;                     // --report DIR
  double scale = kDefaultColourScale;  // --report-scale S
};

// Adds --report DIR and --report-scale S to a task's command.
void add_report_options(CLI::App& cmd, ReportArgs& args);

// One method's run for a report section, from a task's outcome. The lower bound is shown
// only for the convex measure (fd): under arap / asap (and in interpolation) the solver's
// bound holds for the last local-global step's fixed rotations, not for the measure.
MethodRun method_run(const std::string& method, const DeformOutcome& d, Measure measure);
MethodRun method_run(const std::string& method, const ParamOutcome& p, Measure measure);
MethodRun method_run(const std::string& method, const InterpFrame& f);

// MethodRun::order_tolerance of a run made with these options: direct's delta-k, else 0.
double order_tolerance(const SolverOptions& options);

// The values a report shows for a measure: qc and iso (>= 1, 1 undistorted) as their excess
// over 1, so that the colour scale starts at 1 (blue) like the others' at 0; the rest as is.
Eigen::VectorXd report_values(Measure measure, const Eigen::VectorXd& distortion);

// A task's --report DIR: DIR/summary.json (the summary), then each section's pictures and
// histogram (report/comparison.h; a section with id "" writes into DIR itself) and
// DIR/index.html titled "strictmin: TITLE". Returns the path of index.html.
std::string write_report_folder(const ReportArgs& args, const nlohmann::json& summary, const std::string& title,
                                const std::vector<SectionInput>& sections);

// deform --report DIR: DIR/summary.json (the summary), DIR/view.svg (planar) or
// DIR/view.png (tets), DIR/input.svg|png, DIR/histogram.svg and DIR/index.html.
// Returns the path of index.html.
std::string write_task_report(const ReportArgs& args, const nlohmann::json& summary, const std::string& input_name,
                              const Mesh& rest, const std::vector<Handle>& handles, const DeformOutcome& d);

// "file:///absolute/path" of a local file, for the line telling where to open a report.
std::string file_url(const std::string& path);

// "field deviation ||J - I||" etc. for a measure's short name and the task that measured it (fd
// of gparam and param is from rotations, not from I; the name itself when unknown).
std::string measure_description(const std::string& measure, const std::string& task);
// The section's measure and what its cards' numbers are (qc and iso: their excess over 1).
void describe_measure(SectionInput& in, const std::string& measure, const std::string& task);

// A plain title for an input: "example:square" -> "square", "dir/gecko.obj" -> "gecko.obj".
std::string input_title(const std::string& input);

}  // namespace strictmin::cli
