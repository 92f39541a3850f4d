// strictmin interp SOURCE TARGET --t 0.25,0.5,0.75 -o PREFIX [--method l2|linf|...]
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include "commands.h"
#include "common.h"
#include "report_output.h"
#include "solver_options.h"
#include "strictmin/io/input_error.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/tasks/interp.h"
#include "io/text_parse.h"

namespace strictmin::cli {
namespace {

struct InterpArgs {
  std::string source, target, output, pin = "centroid", rotation_blend = "auto";
  std::vector<std::string> times{"0.5"};  // as given: comma-separated lists (parse_times)
  int lg_iterations = 100;
  double lg_tolerance = 1e-4;
  LocalGlobalArgs lg_steps;  // --lg-acceleration, --lg-extrapolation, --lg-cold-start (docs/interp.md)
  SolverArgs solver;
  OutputOptions out;
  ReportArgs report;
};

// "PREFIX_0.25.obj": t in its shortest exact text, the extension taken from SOURCE.
std::string frame_path(const std::string& prefix, double t, const std::string& source) {
  std::string ext = std::filesystem::path(source).extension().string();
  if (ext.empty()) ext = ".obj";
  return prefix + "_" + io_detail::exact_text(t) + ext;
}

// interp --report DIR: one section, the source pose then every frame side by side in one
// frame of reference, each coloured by its distortion from the blended shapes.
std::string write_interp_report(const ReportArgs& a, const nlohmann::json& summary, const InterpArgs& args,
                                const Mesh& source, const std::vector<InterpFrame>& frames) {
  const std::string method = summary.value("method", std::string("l2"));
  SectionInput in;
  in.title = method_label(method) + " interpolation from " + input_title(args.source) + " to " +
             input_title(args.target);
  in.description = "Task interp, " + summary.value("kind", std::string("planar")) + ", " +
                   std::to_string(source.num_elements()) + " elements, " + std::to_string(frames.size()) +
                   " frame(s). Each frame is coloured by its distortion: the distance of each element's differential "
                   "from its blended shape and rotation (0 at t = 0 and t = 1).";
  in.measure = "distance ‖J − Q(t) Y(t)‖ from the blended element";
  in.rest = &source;
  in.alternatives = false;  // frames of one sequence, not rival maps
  for (const InterpFrame& f : frames) {
    const std::string t = shown_number(f.t);
    MethodRun run = method_run(method, f);
    run.label = "t = " + t;
    run.view_name = "t" + t;
    run.links.emplace_back("summary.json", "summary.json");
    in.runs.push_back(std::move(run));
  }
  // Automatic scale from the largest frame maximum (frames at t = 0 or 1 have maximum 0).
  ReportArgs scaled = a;
  if (!(scaled.scale > 0)) {
    double largest = 0;
    for (const InterpFrame& f : frames)
      if (std::isfinite(f.stats.max)) largest = std::max(largest, f.stats.max);
    scaled.scale = largest > 0 ? auto_colour_scale(largest) : kDefaultColourScale;
  }
  return write_report_folder(scaled, summary, in.title, {in});
}

int parse_pin(const std::string& pin) {
  if (pin == "centroid") return -1;
  try {
    size_t used = 0;
    const int v = std::stoi(pin, &used);
    if (used == pin.size() && v >= 0) return v;
  } catch (const std::exception&) {
  }
  throw InputError("--pin takes 'centroid' or a vertex index (0-based), not '" + pin + "'");
}

// --t's values, each a comma-separated list. Split here, not by the option parser, which
// dropped empty items ("0.5,,1" ran two frames, "0.5," one) where a time was meant.
std::vector<double> parse_times(const std::vector<std::string>& args) {
  std::vector<double> times;
  for (const std::string& arg : args) {
    for (size_t start = 0;;) {
      const size_t comma = arg.find(',', start);
      std::string item = arg.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      item.erase(0, item.find_first_not_of(" \t"));
      item.erase(item.find_last_not_of(" \t") + 1);
      double t = 0;
      if (item.empty())
        throw InputError("--t " + io_detail::quote_token(arg) + ": an empty time (each comma separates two times)");
      if (!io_detail::parse_double(item, t)) throw InputError("--t: " + io_detail::quote_token(item) + " is not a number");
      times.push_back(t);
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  }
  return times;
}

int run_interp(const InterpArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto threads = limit_threads(a.out.threads);
  refuse_frame_iterations(a.solver, std::nullopt, "interp");
  refuse_other_methods_flags(a.solver);
  InterpOptions options;
  options.solver = make_solver_options(a.solver, a.out);
  options.local_global.max_iterations = a.lg_iterations;
  options.local_global.relative_change = a.lg_tolerance;
  apply_local_global_step_options(a.lg_steps, options.local_global);
  options.pin_vertex = parse_pin(a.pin);
  std::vector<double> times = parse_times(a.times);
  if (times.empty()) throw InputError("--t needs at least one time in [0, 1]");
  for (double& t : times) t += 0.0;  // -0 is 0 (it wrote PREFIX_-0 beside PREFIX_0, the same frame)
  for (size_t i = 0; i < times.size(); ++i) {
    const double t = times[i];
    const std::string shown = io_detail::exact_text(t);  // also the frame's file name: never alike for two times
    if (!(t >= 0.0 && t <= 1.0)) throw InputError("--t: " + shown + " is outside [0, 1]");
    for (size_t j = 0; j < i; ++j)
      if (times[j] == t) throw InputError("--t: " + shown + " is given twice (each time writes its own file)");
  }
  if (!a.out.distortion.empty() && times.size() != 1)
    throw InputError("--distortion writes one frame: give a single --t value with it");
  // Every frame's file with the other outputs, and none of them a pose (-o lion with
  // t = 1 writes lion_1.obj, which may be the target).
  std::vector<std::pair<std::string, std::string>> frame_outputs;
  if (!a.output.empty())
    for (double t : times) frame_outputs.push_back({"--output", frame_path(a.output, t, a.source)});
  check_run_outputs(a.out, frame_outputs, a.report.dir, {{"the source pose", a.source}, {"the target pose", a.target}});
  if (!a.out.quiet)
    options.local_global.progress = [](const IterationRecord& r) {
      print_local_global_progress(r, "  ");
    };

  std::vector<std::string> warnings;
  const Mesh source = read_mesh(a.source, &warnings);
  MeshReadOptions loose;
  loose.check_geometry = false;  // a target pose may have inverted or flat elements
  const Mesh target = read_mesh(a.target, &warnings, loose);
  for (const auto& w : warnings) progress(a.out, "warning: " + w);
  const Interpolator interp(source, target, a.source, a.target, parse_rotation_blend(a.rotation_blend, "--rotation-blend"));
  if (options.pin_vertex >= source.num_vertices())
    throw InputError("--pin " + a.pin + ": " + a.source + " has " + std::to_string(source.num_vertices()) +
                     " vertices (0-based indices)");
  progress(a.out, "interp: " + std::to_string(source.num_elements()) + " elements (" + interp_kind_name(interp.kind()) +
                      "), method " + a.solver.method + ", " + std::to_string(times.size()) + " frame(s)");

  if (!interp.warning().empty()) progress(a.out, "interp: warning: " + interp.warning());
  nlohmann::json s = interp_summary(source, interp, options, a.source, a.target);
  nlohmann::json frames = nlohmann::json::array();
  SolveStatus worst = SolveStatus::Solved;
  Eigen::VectorXd last_distortion;
  std::vector<InterpFrame> kept;  // for the report
  for (double t : times) {
    const auto tf = std::chrono::steady_clock::now();
    progress(a.out, "interp: t = " + std::to_string(t));
    const InterpFrame f = interp.at(t, options);
    const std::string frame_file = a.output.empty() ? "" : frame_path(a.output, t, a.source);
    const std::string path = write_map(frame_file, f.mesh, f.result.status);  // "" when not written
    if (!f.result.ok()) {
      worst = worse_status(worst, f.result.status);
      progress(a.out, "warning: t = " + std::to_string(t) + ": " + status_name(f.result.status) + ": " + f.result.message);
    }
    nlohmann::json j = interp_frame_summary(f, options, path);
    j["time_s"] = seconds_since(tf);
    frames.push_back(j);
    last_distortion = f.result.distortion;
    if (!a.report.dir.empty()) kept.push_back(f);
    progress(a.out, "interp: t = " + std::to_string(t) + ": max distortion " + std::to_string(f.stats.max) +
                        ", " + flipped_phrase(f.stats.flipped) +
                        (path.empty() ? "" : ", wrote " + path));
  }
  s["frames"] = frames;
  s["time_s"] = seconds_since(t0);
  write_outputs(a.out, s, last_distortion);
  if (!a.report.dir.empty())
    progress(a.out, "report: " + file_url(write_interp_report(a.report, s, a, source, kept)));
  return exit_code_for(worst);
}

}  // namespace

void add_interp_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<InterpArgs>();
  CLI::App* cmd = app.add_subcommand(
      "interp",
      "Interpolate between two poses of one mesh (same elements): at each time t every element's shape is blended "
      "linearly and its rotation along a turn consistent with its neighbours' (--rotation-blend), then the map closest to these is found with "
      "the chosen method (local-global). Writes PREFIX_<t><ext of SOURCE> per t.");
  cmd->add_option("source", args->source, "Source pose (.obj/.off triangles, planar or a 3D surface; .mesh tets)")
      ->required();
  cmd->add_option("target", args->target, "Target pose: same vertices and elements as SOURCE")->required();
  cmd->add_option("--t", args->times, "Times in [0, 1], comma-separated (0 = source, 1 = target), each once")
      ->type_name("LIST")
      ->capture_default_str();
  cmd->add_option("-o,--output", args->output,
                  "Output prefix: frame t goes to PREFIX_<t>.<ext>, t in its shortest exact text (0.25, 0.5, 1), ext from SOURCE")
      ->type_name("PREFIX");
  cmd->add_option("--pin", args->pin,
                  "What moves linearly from source to target: 'centroid' (vertex mean) or a vertex index (0-based)")
      ->capture_default_str();
  cmd->add_option("--rotation-blend", args->rotation_blend,
                  "3D poses: how rotations are blended: 'logarithms' (each element's own, scaled by t), 'tree' "
                  "(relative to the neighbours' along a spanning tree: follows twists of a full turn or more) or "
                  "'auto' (logarithms unless they jump somewhere, then tree)")
      ->type_name("WORD")
      ->capture_default_str();
  cmd->add_option("--lg-iterations", args->lg_iterations,
                  "Local-global iteration cap (0: one solve with the interpolated rotations, no local steps)")
      ->capture_default_str()
      ->check(at_least(0));
  cmd->add_option("--lg-tolerance", args->lg_tolerance,
                  "Stop when the maximum (l2: its energy) changes by less than this (relative)")
      ->capture_default_str()
      ->check(at_least(0));
  add_local_global_step_options(*cmd, args->lg_steps);
  args->solver.k_min = kInterpKMin;  // interp's own default (interp.h), shown in --help
  add_solver_options(*cmd, args->solver);
  add_output_options(*cmd, args->out);
  // Frames are close to their blended shapes: an automatic colour scale by default (a fixed
  // 0.6 would show them all dark blue).
  args->report.scale = 0;
  add_report_options(*cmd, args->report);
  cmd->get_option("--report-scale")
      ->description("Report: the distortion shown red (dark blue is 0); 0: automatic, 1.5 times the largest frame "
                    "maximum rounded up to 1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6 or 8 times a power of ten");
  // Interpolation's targets are the blended shapes' rotations: local-global does not
  // extrapolate them (a value here would be ignored).
  CLI::Option* extrapolation = cmd->get_option("--lg-extrapolation");
  extrapolation->description("Refused by interp (its targets are the blended shapes' rotations, which local-global "
                             "does not extrapolate)");
  extrapolation->default_str("");
  cmd->callback([args, &exit_code, extrapolation] {
    if (extrapolation->count() > 0)
      throw InputError("--lg-extrapolation does not apply to interp: its targets are the blended shapes' rotations, "
                       "which local-global does not extrapolate");
    exit_code = run_interp(*args);
  });
}

}  // namespace strictmin::cli
