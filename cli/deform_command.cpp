// strictmin deform MESH --handles FILE [--measure fd] [--method l2|linf] -o OUT
#include <cstdio>
#include <memory>

#include "commands.h"
#include "common.h"
#include "report_output.h"
#include "solver_options.h"
#include "strictmin/io/handles_io.h"
#include "strictmin/io/input_error.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/tasks/conformal_method.h"
#include "strictmin/tasks/deform.h"
#include "strictmin/tasks/examples.h"

namespace strictmin::cli {
namespace {

struct DeformArgs {
  std::string mesh, handles, example, output, measure = "fd", start = "l2";
  const CLI::Option* start_option = nullptr;  // --start, to refuse it where it does not apply
  LocalGlobalArgs lg;
  SolverArgs solver;
  OutputOptions out;
  ReportArgs report;
};

int run_deform(const DeformArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  check_run_outputs(a.out, {{"--output", a.output}}, a.report.dir,
                    {{"the input mesh", a.mesh}, {"the --handles file", a.handles}});
  const auto threads = limit_threads(a.out.threads);
  DeformOptions options;
  options.solver = make_solver_options(a.solver, a.out);
  const auto measure = parse_measure(a.measure);
  if (!measure) throw InputError("--measure: unknown measure '" + a.measure + "' (use fd, arap, asap, qc or iso)");
  options.measure = *measure;
  refuse_local_global_flags(a.lg, options.measure);
  refuse_frame_iterations(a.solver, options.measure, "deform");
  refuse_other_methods_flags(a.solver);
  if (a.start != "l2" && a.start != "rest") throw InputError("unknown --start '" + a.start + "' (use l2 or rest)");
  // The start of local-global; fd, qc and iso start from the rest pose and the L2 map whatever
  // --start said.
  if (given(a.start_option) && options.measure != Measure::Arap && options.measure != Measure::Asap)
    throw InputError("--start applies to --measure arap or asap (the start of their local-global iterations), not " +
                     measure_name(options.measure));
  options.start = a.start == "l2" ? DeformStart::L2 : DeformStart::Rest;
  apply_local_global_options(a.lg, options.local_global);
  options.no_flips = a.lg.no_flips;
  if (!a.out.quiet)
    options.local_global.progress = [](const IterationRecord& r) {
      print_local_global_progress(r, "");
    };

  Mesh mesh;
  std::vector<Handle> handles;
  std::string input;
  if (!a.example.empty()) {
    if (!a.mesh.empty()) throw InputError("give either a mesh file or --example, not both");
    Example ex = make_example(a.example);
    mesh = std::move(ex.mesh);
    handles = a.handles.empty() ? std::move(ex.handles) : read_handles(a.handles, mesh.num_vertices(), mesh.dim());
    input = "example:" + a.example;
  } else {
    if (a.mesh.empty()) throw InputError("deform needs a mesh file or --example NAME");
    if (a.handles.empty()) throw InputError("deform needs --handles FILE (positional constraints)");
    std::vector<std::string> warnings;
    mesh = read_mesh(a.mesh, &warnings);
    for (const auto& w : warnings) progress(a.out, "warning: " + w);
    // Tets and triangle surfaces in 3D move in 3D; planar triangles in 2D.
    const int dim = mesh.element_type() == ElementType::Tetrahedron || !mesh.is_planar() ? 3 : 2;
    handles = read_handles(a.handles, mesh.num_vertices(), dim);
    input = a.mesh;
  }
  progress(a.out, "deform: " + std::to_string(mesh.num_elements()) + " elements, " + std::to_string(handles.size()) +
                      " handles, method " + a.solver.method + ", measure " + a.measure);

  const DeformOutcome d = deform(mesh, handles, options);
  if (!d.result.ok()) progress(a.out, "warning: " + status_name(d.result.status) + ": " + d.result.message);
  MeshWriteOptions w;
  w.element_quality = &d.measured.distortion;
  const std::string written = write_map(a.output, d.deformed, d.result.status, w);
  nlohmann::json s = deform_summary(mesh, handles.size(), options, d, {input, written, a.out.distortion});
  s["time_s"] = seconds_since(t0);
  write_outputs(a.out, s, d.measured.distortion);
  if (!a.report.dir.empty()) progress(a.out, "report: " + file_url(write_task_report(a.report, s, input, mesh, handles, d)));
  progress(a.out, "deform: max distortion " + std::to_string(d.measured.stats.max) + ", L2 " +
                      std::to_string(d.measured.stats.l2) + ", " + flipped_phrase(d.measured.stats.flipped) + ", " +
                      status_name(d.result.status));
  return exit_code_for(d.result.status);
}

}  // namespace

void add_deform_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<DeformArgs>();
  CLI::App* cmd = app.add_subcommand(
      "deform",
      "Deform a planar triangle mesh, a triangle surface in 3D or a tet mesh so that the handle vertices reach their targets, with the least "
      "distortion ||J - I|| (field deviation) in the chosen norm. Every method works on all three (a 3D surface: each "
      "triangle in its own frame, 3x2 Jacobians); --no-flips is for planar and tet meshes, qc and iso for planar meshes.");
  cmd->add_option("mesh", args->mesh, "Input mesh (.obj/.off triangles, planar or a 3D surface; .mesh tetrahedra)");
  cmd->add_option("--example", args->example, "Use a built-in example instead of a mesh: square, bar, tetbar");
  cmd->add_option("--handles", args->handles,
                  "Positional constraints: JSON {\"handles\":[{\"vertex\":i,\"position\":[x,y]}]} or text lines "
                  "'vertex x y [z]' (0-based vertex indices)")
      ->type_name("FILE");
  cmd->add_option("--measure", args->measure,
                  "fd (field deviation ||J - I||), arap or asap (local-global iterations around the method), qc "
                  "(sigma1/sigma2) or iso (max(sigma1, 1/sigma2)): planar meshes, methods l2 (the L2 fd start map), "
                  "linf, direct; convex cones around per-triangle frames (qc by bisection, iso one program per frame set), never a flipped triangle")
      ->capture_default_str();
  args->start_option = cmd->add_option("--start", args->start, "arap/asap: start from the l2 fd map or the rest pose")->capture_default_str();
  add_local_global_options(*cmd, args->lg);
  cmd->add_option("-o,--output", args->output, "Output mesh (.obj, .off, .mesh, .ply with per-face distortion)");
  add_solver_options(*cmd, args->solver);
  add_output_options(*cmd, args->out);
  add_report_options(*cmd, args->report);
  cmd->callback([args, &exit_code] { exit_code = run_deform(*args); });
}

}  // namespace strictmin::cli
