// strictmin gparam MESH -o OUT.obj [--field smoothest|unit|curvature|FILE] [--cones FILE]
//   [--field-out FILE] [--cones-out FILE]
//   [--edge-length L | --quads N] [--measure fd|arap] [--method ...] (docs/gparam.md)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "commands.h"
#include "common.h"
#include "gparam_report.h"
#include "quad_output.h"
#include "report_output.h"
#include "solver_options.h"
#include "strictmin/io/input_error.h"
#include "strictmin/field/surface_graph.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/validate.h"
#include "strictmin/tasks/gparam.h"

namespace strictmin::cli {
namespace {

struct GParamArgs {
  std::string mesh, output, field = "smoothest", field_out, measure = "fd", cones, cones_out, grid_guide, quad_mesh;
  double edge_length = 0, curvature_alignment = 0.01;
  int quads = 0;
  bool edge_length_given = false, quads_given = false, curvature_alignment_given = false, parallel = false, integer_grid = false,
       fill_holes = false;
  int lg_iterations = 100;
  double lg_tolerance = 1e-4;
  LocalGlobalArgs lg_steps;  // --lg-acceleration, --lg-extrapolation, --lg-cold-start
  SolverArgs solver;
  OutputOptions out;
  ReportArgs report;
};

// --field's built-in fields; anything else is a field file.
bool is_field_name(const std::string& field) { return field == "smoothest" || field == "curvature" || field == "unit"; }

GParamOptions make_options(const GParamArgs& a, const Mesh& mesh) {
  GParamOptions o;
  const auto measure = parse_measure(a.measure);
  if (!measure || (*measure != Measure::FieldDeviation && *measure != Measure::Arap))
    throw InputError("--measure: unknown or unavailable measure '" + a.measure + "' for gparam (use fd or arap)");
  o.measure = *measure;
  refuse_local_global_flags(a.lg_steps, o.measure, /*task_has_asap=*/false);
  refuse_frame_iterations(a.solver, o.measure, "gparam");
  refuse_other_methods_flags(a.solver);
  if (a.edge_length_given && a.quads_given) throw InputError("give --edge-length or --quads, not both");
  if (a.edge_length_given && !(a.edge_length > 0 && std::isfinite(a.edge_length)))
    throw InputError("--edge-length must be a positive finite number, got " + shown_number(a.edge_length));
  if (a.quads_given && a.quads <= 0) throw InputError("--quads must be positive, got " + std::to_string(a.quads));
  if (a.edge_length_given) o.edge_length = a.edge_length;
  if (a.quads_given) o.quads = a.quads;
  o.curvature_field = a.field == "curvature";
  if (a.curvature_alignment_given && !o.curvature_field)
    throw InputError("--curvature-alignment applies to --field curvature only (the field is " +
                     (a.cones.empty() ? a.field : std::string("from --cones")) + ")");
  o.field_options.unit = a.field == "unit";
  if (!(a.curvature_alignment > 0 && std::isfinite(a.curvature_alignment)))
    throw InputError("--curvature-alignment must be a positive number, got " + shown_number(a.curvature_alignment));
  o.curvature_alignment = a.curvature_alignment;
  o.parallel_field = a.parallel;
  o.integer_grid = a.integer_grid;
  if (!a.grid_guide.empty()) {
    if (!a.integer_grid) throw InputError("--grid-guide applies to --integer-grid only");
    if (a.grid_guide != "l2" && a.grid_guide != "linf")
      throw InputError("--grid-guide takes l2 or linf, not '" + a.grid_guide + "'");
    o.grid_guide = a.grid_guide == "linf" ? GParamOptions::GridGuide::Linf : GParamOptions::GridGuide::L2;
  }
  if (!a.quad_mesh.empty() && !a.integer_grid)
    throw InputError("--quad-mesh needs --integer-grid: quads come from an integer-grid map");
  if (a.fill_holes && a.quad_mesh.empty()) throw InputError("--fill-holes applies to --quad-mesh only");
  if (!a.cones.empty()) {
    if (a.field != "smoothest") throw InputError("give --cones or --field " + a.field + ", not both");
    o.cones = read_cone_file(a.cones, mesh.num_vertices());
    o.field_source = a.cones;
  }
  if (!is_field_name(a.field)) {
    std::error_code ec;
    if (!std::filesystem::exists(a.field, ec))
      throw InputError("--field " + a.field + ": not smoothest, unit or curvature, and no such file");
    o.field = read_field_file(a.field, mesh.num_elements(), &o.field_lines);
    o.field_source = a.field;
  }
  o.solver = make_solver_options(a.solver, a.out);
  o.local_global.max_iterations = a.lg_iterations;
  o.local_global.relative_change = a.lg_tolerance;
  apply_local_global_step_options(a.lg_steps, o.local_global);
  if (!a.out.quiet) {
    o.progress = [](const std::string& line) { std::fprintf(stderr, "gparam %s\n", line.c_str()); };
    o.local_global.progress = [](const IterationRecord& r) { print_local_global_progress(r, ""); };
  }
  return o;
}

QuadExtractionOptions quad_options(const GParamArgs& a) {
  QuadExtractionOptions o;
  o.fill_holes = a.fill_holes;
  return o;
}

// The quad mesh of gparam's map, or why not. A map finer than the extraction takes is said in
// gparam's terms (the extraction's own message asks whether the UVs are in grid units).
QuadOutput extract_quad_mesh(const GParamArgs& a, const GParamOutcome& g) {
  QuadOutput quads;
  const bool usable = status_usable(g.result.status);
  const double squares = usable ? positive_uv_area(g.mapped) : 0;
  if (!usable)
    quads.summary = {{"status", "not-extracted"}, {"reason", "the map is not usable"}, {"file", ""}};
  else if (squares > kMaxQuadExtractionSquares)
    quads.summary = {{"status", "not-extracted"},
                     {"reason", "the map has about " + std::to_string(std::llround(squares)) +
                                    " unit squares (--quads / --edge-length), more than quad extraction takes (1e7, "
                                    "about 5.5 GB)"},
                     {"file", ""}};
  else
    quads = write_quad_mesh(g.mapped, a.quad_mesh, a.mesh, quad_options(a));
  if (quads.summary.value("status", std::string()) == "not-extracted") {
    // A quad mesh left at the path by an earlier run would pass for this run's.
    std::error_code ec;
    if (std::filesystem::remove(a.quad_mesh, ec)) quads.summary["removed_earlier_file"] = a.quad_mesh;
  }
  return quads;
}

int run_gparam(const GParamArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  check_run_outputs(a.out,
                    {{"--output", a.output},
                     {"--field-out", a.field_out},
                     {"--cones-out", a.cones_out},
                     {"--quad-mesh", a.quad_mesh}},
                    a.report.dir,
                    {{"the input mesh", a.mesh}, {"the --field file", is_field_name(a.field) ? "" : a.field},
                     {"the --cones file", a.cones}});
  check_uv_output_path(a.output);
  if (!a.quad_mesh.empty() && lowercase_extension(a.quad_mesh) != ".obj")
    throw InputError("--quad-mesh " + a.quad_mesh + ": the quad mesh is written as .obj only");
  const auto threads = limit_threads(a.out.threads);
  if (a.mesh.empty()) throw InputError("gparam needs a mesh file (a triangle surface, closed or with boundary)");
  std::vector<std::string> warnings;
  const Mesh mesh = read_mesh(a.mesh, &warnings);
  // Unused vertices, which the other tasks ignore with a warning, are refused here (the
  // surface graph's message): their warning would say the opposite of the error that follows.
  if (!unreferenced_vertices(mesh).empty()) surface_graph(mesh, a.mesh, true);  // throws, naming the vertex
  for (const auto& w : warnings) progress(a.out, "warning: " + w);
  const GParamOptions o = make_options(a, mesh);
  progress(a.out, "gparam: " + std::to_string(mesh.num_elements()) + " triangles, method " +
                      method_name(o.solver.method) + ", measure " + a.measure);
  const GParamOutcome g = global_parametrize(mesh, o, a.mesh);
  if (!g.result.ok()) progress(a.out, "warning: " + status_name(g.result.status) + ": " + g.result.message);
  if (!a.field_out.empty()) write_field_file(a.field_out, field_directions(g.field, g.frames));
  if (!a.cones_out.empty()) write_cone_file(a.cones_out, g.quarters);
  const std::string written = write_map(a.output, g.mapped, g.result.status);
  nlohmann::json s = gparam_summary(mesh, o, g, a.field, {a.mesh, written, a.out.distortion});
  bool quads_complete = true;
  QuadOutput quads;
  if (!a.quad_mesh.empty()) {
    progress(a.out, "gparam: quad extraction");
    quads = extract_quad_mesh(a, g);
    s["quad_mesh"] = quads.summary;
    quads_complete = quads.complete;
    progress(a.out, "gparam: quad mesh " + s["quad_mesh"].value("status", std::string()) + ", " +
                        std::to_string(s["quad_mesh"].value("quads", 0)) + " quads" +
                        (s["quad_mesh"].contains("reason") ? ": " + s["quad_mesh"]["reason"].get<std::string>() : ""));
  }
  s["time_s"] = seconds_since(t0);
  write_outputs(a.out, s, g.measured.distortion);
  if (!a.report.dir.empty())
    progress(a.out, "report: " + file_url(write_gparam_report(a.report, s, a.mesh, mesh, g, quads.mesh ? &*quads.mesh : nullptr)));
  progress(a.out, "gparam: max distortion " + std::to_string(g.measured.stats.max) + ", L2 " +
                      std::to_string(g.measured.stats.l2) + ", " + std::to_string(g.measured.stats.flipped) +
                      " flipped, seam error " + shown_number(g.seam_error) +
                      (o.integer_grid ? ", integer-grid error " + shown_number(g.integer_error) : std::string()) + ", " +
                      status_name(g.result.status));
  for (const std::string& w : g.warnings) progress(a.out, "gparam: warning: " + w);
  const int code = exit_code_for(g.result.status);
  return code == kExitSuccess && !quads_complete ? kExitNotConverged : code;
}

}  // namespace

void add_gparam_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<GParamArgs>();
  CLI::App* cmd = app.add_subcommand(
      "gparam",
      "Global seamless parametrization of a surface guided by a cross field (the paper's Appendix A): "
      "field, singularities, cut, seams as linear equalities, then the chosen method; per-corner vt in the OBJ. "
      "Surfaces with boundary: the field follows the boundary, the map's boundary is free.");
  cmd->add_option("mesh", args->mesh,
                  "Input surface (.obj/.off triangles, one component, any genus; closed or with boundary loops)");
  cmd->add_option("-o,--output", args->output, "Output .obj: the input's vertices and faces, vt per cut-mesh vertex, f v/vt");
  cmd->add_option("--field", args->field,
                  "smoothest (default: Knoeppel et al. 2013), unit (the smoothest field lowered among unit fields: "
                  "smoother, fewer singularities, lower distortion; slower), curvature (principal directions, smoothed) or a "
                  "file with one 3D direction per face per line")
      ->capture_default_str();
  cmd->add_option("--curvature-alignment", args->curvature_alignment,
                  "--field curvature: how closely the field follows the principal directions (smaller: smoother; > 0)")
      ->capture_default_str();
  cmd->add_option("--field-out", args->field_out, "Write the field used, one direction per face per line");
  cmd->add_option("--cones", args->cones,
                  "The field with exactly these cones: a file with one total angle (radians) per vertex per line, 2 pi "
                  "where there is none, 2 pi - k pi/2 for an index-k/4 cone (the smoothest such field, docs/gparam.md)");
  cmd->add_flag("--parallel", args->parallel,
                 "Keep the field's singularities and make it parallel between them (the smoothest field with exactly "
                 "those cones): lower smoothness energy and maximum distortion, a few Laplacian solves more");
  cmd->add_option("--cones-out", args->cones_out, "Write the field's singularities as a cone file (the --cones format)");

  cmd->add_option("--edge-length", args->edge_length,
                  "Target edge length h: a surface length h maps to 1 in UV (> 0, within 1e-9 to 1e9 times the square "
                  "root of the surface's area)");
  cmd->add_flag("--integer-grid", args->integer_grid,
                "Round the singular vertices and the seam translations to the grid of the edge length first (greedy, "
                "with L2 solves between the steps), so that the map's integer lines close up into a quad mesh");
  cmd->add_option("--grid-guide", args->grid_guide,
                  "--integer-grid: the map whose values the rounding follows: l2 (default, the seamless L2 map) or linf "
                  "(the free L-infinity map, one solve more: as the grid shrinks the map tends to the L-infinity "
                  "optimum; often fewer flips, docs/gparam.md)");
  cmd->add_option("--quad-mesh", args->quad_mesh,
                  "--integer-grid: also write the map's quad mesh (.obj), one quad per unit square (as 'strictmin "
                  "quads'); squares next to flipped triangles are left out as holes, and the exit code is then 2");
  cmd->add_flag("--fill-holes", args->fill_holes,
                "--quad-mesh: fill the holes the map's folds leave with the grid's squares where their boundary allows "
                "(as 'strictmin quads --fill-holes')");
  cmd->add_option("--quads", args->quads, "Choose h so that the surface has about N unit squares (default 1000; >= 1)");
  cmd->add_option("--measure", args->measure, "fd (against the field, default) or arap (local-global on top)")
      ->capture_default_str();
  // gparam's own --lg-iterations and --lg-tolerance (arap only), refused with fd as the steps' flags.
  args->lg_steps.options.push_back(
      cmd->add_option("--lg-iterations", args->lg_iterations, "arap: local-global iteration cap (>= 1)")
          ->capture_default_str()
          ->check(at_least(1)));
  args->lg_steps.options.push_back(
      cmd->add_option("--lg-tolerance", args->lg_tolerance, "arap: stop when the maximum changes by less (relative, >= 0)")
          ->capture_default_str()
          ->check(at_least(0)));
  add_local_global_step_options(*cmd, args->lg_steps);
  add_solver_options(*cmd, args->solver);
  add_output_options(*cmd, args->out);
  add_report_options(*cmd, args->report);
  cmd->callback([args, cmd, &exit_code] {
    args->edge_length_given = cmd->count("--edge-length") > 0;
    args->quads_given = cmd->count("--quads") > 0;
    args->curvature_alignment_given = cmd->count("--curvature-alignment") > 0;
    exit_code = run_gparam(*args);
  });
}

}  // namespace strictmin::cli
