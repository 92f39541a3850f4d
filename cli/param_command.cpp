// strictmin param MESH -o OUT.obj [--measure arap|asap|fd|qc|iso] [--method ...] [--init tutte|lscm]
#include <cstdio>
#include <filesystem>
#include <memory>

#include "commands.h"
#include "common.h"
#include "report_output.h"
#include "solver_options.h"
#include "strictmin/io/atomic_file.h"
#include "strictmin/io/input_error.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/report/html_report.h"
#include "strictmin/tasks/conformal_method.h"
#include "strictmin/tasks/param.h"

namespace strictmin::cli {
namespace {

struct ParamArgs {
  std::string mesh, output, measure = "arap";
  LocalGlobalArgs lg;
  SolverArgs solver;
  OutputOptions out;
  ReportArgs report;
};

// param --report DIR: summary.json, the map's surface view, UV layout and checkerboard
// (report/comparison.h draws maps with UVs that way), histogram.svg and index.html.
std::string write_param_report(const ReportArgs& a, const nlohmann::json& summary, const std::string& input,
                               const Mesh& mesh, const ParamOutcome& p) {
  const std::string method = summary.value("method", std::string("l2"));
  SectionInput in;
  in.title = method_label(method) + " parametrization of " + input_title(input);
  in.description = "Task param, measure " + summary.value("measure", std::string("arap")) + ", start " +
                   summary.value("init", std::string("tutte")) + ", " + std::to_string(mesh.num_elements()) +
                   " triangles, " + std::to_string(p.flips) + " flipped, boundary " +
                   (p.boundary_overlap ? "overlaps itself." : "does not overlap.");
  describe_measure(in, summary.value("measure", std::string("arap")), "param");
  in.rest = &mesh;
  MethodRun run = method_run(method, p, *parse_measure(summary.value("measure", std::string("arap"))));
  run.view_name = "view";
  run.links.emplace_back("summary.json", "summary.json");
  in.runs.push_back(std::move(run));
  return write_report_folder(a, summary, in.title, {in});
}

// --method tutte|lscm is that starting map itself: an --init naming the other one contradicts it.
void check_init_agrees_with_start_method(const std::string& method, const std::string& init) {
  const auto is_start = [](const std::string& name) { return name == "tutte" || name == "lscm"; };
  if (is_start(method) && is_start(init) && init != method)
    throw InputError("--init " + init + " contradicts --method " + method + ": that method is the " + method +
                     " starting map itself (give --method " + init + ", or --init " + method + ")");
}

int run_param(ParamArgs a) {
  const auto t0 = std::chrono::steady_clock::now();
  check_run_outputs(a.out, {{"--output", a.output}}, a.report.dir, {{"the input mesh", a.mesh}});
  const auto threads = limit_threads(a.out.threads);
  ParamOptions options;
  const auto measure = parse_measure(a.measure);
  if (!measure) throw InputError("--measure: unknown measure '" + a.measure + "' (use arap, asap, fd, qc or iso)");
  options.measure = *measure;
  refuse_local_global_flags(a.lg, options.measure);
  refuse_frame_iterations(a.solver, options.measure, "param");
  refuse_other_methods_flags(a.solver);
  check_init_agrees_with_start_method(a.solver.method, a.solver.init);
  // --init names the starting map (tutte, lscm); a method name there is relax's start.
  if (a.solver.init == "tutte" || a.solver.init == "lscm") {
    options.init = a.solver.init == "tutte" ? ParamInit::Tutte : ParamInit::Lscm;
    a.solver.init = "linf";
  }
  if (a.solver.method == "tutte" || a.solver.method == "lscm") {
    options.init = a.solver.method == "tutte" ? ParamInit::Tutte : ParamInit::Lscm;
    options.init_only = true;
    a.solver.method = "l2";
  }
  options.solver = make_solver_options(a.solver, a.out, "tutte, lscm");
  apply_local_global_options(a.lg, options.local_global);
  options.no_flips = a.lg.no_flips;
  if (!a.out.quiet)
    options.local_global.progress = [](const IterationRecord& r) {
      print_local_global_progress(r, "");
    };
  if (a.mesh.empty()) throw InputError("param needs a mesh file (a triangle surface with one boundary loop)");
  std::vector<std::string> warnings;
  const Mesh mesh = read_mesh(a.mesh, &warnings);
  for (const auto& w : warnings) progress(a.out, "warning: " + w);
  const std::string method = options.init_only ? init_name(options.init) : method_name(options.solver.method);
  progress(a.out, "param: " + std::to_string(mesh.num_elements()) + " triangles, method " + method + ", measure " +
                      a.measure + ", start " + init_name(options.init));

  const ParamOutcome p = parametrize(mesh, options, a.mesh);
  if (!p.result.ok()) progress(a.out, "warning: " + status_name(p.result.status) + ": " + p.result.message);
  for (const std::string& w : p.warnings) progress(a.out, "param: warning: " + w);
  const std::string written = write_map(a.output, p.mapped, p.result.status);
  nlohmann::json s = param_summary(mesh, options, p, {a.mesh, written, a.out.distortion});
  s["time_s"] = seconds_since(t0);
  write_outputs(a.out, s, p.measured.distortion);
  if (!a.report.dir.empty()) progress(a.out, "report: " + file_url(write_param_report(a.report, s, a.mesh, mesh, p)));
  progress(a.out, "param: max distortion " + std::to_string(p.measured.stats.max) + ", L2 " +
                      std::to_string(p.measured.stats.l2) + ", " + std::to_string(p.flips) + " flipped, boundary " +
                      (p.boundary_overlap ? "overlaps" : "ok") + ", " + status_name(p.result.status));
  return exit_code_for(p.result.status);
}

}  // namespace

void add_param_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ParamArgs>();
  CLI::App* cmd = app.add_subcommand(
      "param",
      "Parametrize a disk-topology surface (one boundary loop) in the plane with a free boundary: the least "
      "ARAP / ASAP distortion in the chosen norm, written as the OBJ's vt coordinates.");
  cmd->add_option("mesh", args->mesh, "Input surface (.obj/.off triangles, one boundary loop)");
  cmd->add_option("-o,--output", args->output, "Output .obj: the input's vertices and faces, the map as vt, f v/vt");
  cmd->add_option("--measure", args->measure,
                  "arap or asap (local-global iterations around the method), fd (frames from the starting map), qc "
                  "(sigma1/sigma2) or iso (max(sigma1, 1/sigma2)) with methods l2 (the Tutte/LSCM start), linf, "
                  "direct: convex cones around per-triangle frames (qc by bisection, iso one program per frame set), never a flipped triangle")
      ->capture_default_str();
  add_local_global_options(*cmd, args->lg);
  add_solver_options(*cmd, args->solver);
  cmd->get_option("--method")
      ->description("tutte or lscm (the starting map itself), l2 (Liu et al. 2008 ARAP), linf (least maximum), "
                    "relax / direct (strict minimizer), exact (fd only, small meshes), lp / irls (baselines)");
  cmd->get_option("--init")
      ->description(
          "the starting map: tutte (default; bijective) or lscm; l2, lp, irls or linf: relax's start (default linf)")
      ->default_str("tutte");
  add_output_options(*cmd, args->out);
  add_report_options(*cmd, args->report);
  cmd->callback([args, &exit_code] { exit_code = run_param(*args); });
}

}  // namespace strictmin::cli
