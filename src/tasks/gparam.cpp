// Global seamless parametrization: the phases, each a named step (docs/gparam.md).
#include "strictmin/tasks/gparam.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "strictmin/field/cone_field.h"
#include "strictmin/io/input_error.h"
#include "strictmin/mesh/validate.h"
#include "strictmin/report/stats.h"
#include "strictmin/solvers/interrupt.h"
#include "strictmin/solvers/l2.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/solvers/timing.h"
#include "strictmin/tasks/seamless_problem.h"
#include "tasks/unit_size.h"
#include "io/text_parse.h"

namespace strictmin {
namespace {

void check_options(const GParamOptions& o) {
  if (o.measure != Measure::FieldDeviation && o.measure != Measure::Arap)
    throw InputError("gparam minimizes fd or arap; '" + measure_name(o.measure) + "' is not available");
  if (!(o.edge_length > 0) && o.edge_length != 0)
    throw InputError("--edge-length must be a positive number, got " + io_detail::number_text(o.edge_length));
  if (!std::isfinite(o.edge_length)) throw InputError("--edge-length must be finite");
  if (o.edge_length == 0 && o.quads <= 0)
    throw InputError("--quads must be a positive number, got " + std::to_string(o.quads));
  if (o.curvature_field && !(o.curvature_alignment > 0 && std::isfinite(o.curvature_alignment)))
    throw InputError("--curvature-alignment must be a positive number");
  if (o.cones) check_cone_indices(*o.cones, o.field_source.empty() ? "cones" : o.field_source);
}

// The texture coordinates are the map divided by the edge length: an edge length far out of
// the surface's scale (sqrt of its area) makes them overflow or lose every digit. Refused
// before the solve, naming the flag and the scale.
void check_edge_length_scale(const GParamOptions& o, double area) {
  if (!(o.edge_length > 0)) return;  // --quads: sqrt(area / quads), in scale by construction
  const double scale = std::sqrt(area);
  if (o.edge_length >= 1e-9 * scale && o.edge_length <= 1e9 * scale) return;
  char why[200];
  std::snprintf(why, sizeof why,
                "--edge-length %g is out of scale for this surface (the square root of its area is %g): use a value "
                "within 1e-9 to 1e9 times that",
                o.edge_length, scale);
  throw InputError(why);
}

// What takes closed surfaces only (docs/gparam.md, "Surfaces with boundary"): the rounding to
// the integer grid (the boundary would have to lie on grid lines), the fields made from cones
// or made parallel (their holonomy solve), and the unit field.
void check_boundary_options(const GParamOptions& o, const SurfaceGraph& g, const std::string& source) {
  if (!g.has_boundary()) return;
  const char* flag = o.integer_grid         ? "--integer-grid"
                     : o.cones              ? "--cones"
                     : o.parallel_field     ? "--parallel"
                     : !o.field && !o.curvature_field && o.field_options.unit ? "--field unit"
                                                                              : nullptr;
  if (!flag) return;
  throw InputError((source.empty() ? std::string("gparam") : source) + ": the surface has " +
                   std::to_string(g.num_boundary_loops) + " boundary loop(s); " + flag +
                   " takes closed surfaces only (the smoothest, curvature and given fields and every method take "
                   "surfaces with boundary)");
}

void say(const GParamOptions& o, const std::string& line) {
  if (o.progress) o.progress(line);
}

std::string fixed(double seconds) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3f", seconds);
  return buffer;
}


// GParamOptions::parallel_field: the computed field replaced by the parallel field with its
// singularities (out.quarters); the computed field's counters and timings are kept.
void make_parallel(const Mesh& mesh, const GParamOptions& o, GParamOutcome& out) {
  const auto t0 = std::chrono::steady_clock::now();
  CrossField parallel = cone_cross_field(mesh, out.graph, out.frames, out.quarters, o.field_options);
  out.field_energy_before_parallel = out.field.energy;
  out.field.u = std::move(parallel.u);
  out.field.energy = parallel.energy;
  out.field.timing.parallel_s = seconds_since(t0);
}

void compute_field(const Mesh& mesh, const GParamOptions& o, GParamOutcome& out) {
  const auto t0 = std::chrono::steady_clock::now();
  out.frames = face_frames(mesh, out.graph);
  if (o.field) {
    out.field = cross_field_from_directions(*o.field, out.frames, o.field_source, o.field_lines);
    out.field.energy = field_energy(out.field.u, mesh, out.graph, out.frames);
  } else if (o.cones) {
    out.field = cone_cross_field(mesh, out.graph, out.frames, *o.cones, o.field_options, o.field_source);
  } else if (o.curvature_field) {
    out.field = curvature_cross_field(mesh, out.graph, out.frames, o.curvature_alignment);
  } else {
    out.field = smoothest_cross_field(mesh, out.graph, out.frames, o.field_options);
  }
  out.quarters = vertex_indices(mesh, out.graph, out.frames, out.field.u);
  if (!o.field && !o.cones) {  // a computed field: no cone of angle 0 (singularities.h)
    out.spread_singularities = spread_full_turn_singularities(mesh, out.graph, out.frames, out.field.u, out.quarters);
    if (out.spread_singularities > 0) out.field.energy = field_energy(out.field.u, mesh, out.graph, out.frames);
  }
  std::vector<int> wanted = o.cones ? *o.cones : std::vector<int>();
  if (o.makes_field_parallel()) {
    wanted = out.quarters;
    make_parallel(mesh, o, out);
    out.quarters = vertex_indices(mesh, out.graph, out.frames, out.field.u);
  }
  // The cones asked for that the parallel field does not have (cone_field.h).
  for (size_t v = 0; v < wanted.size(); ++v) out.cones_missed += wanted[v] != out.quarters[v];
  out.singular = singularities(out.quarters);
  for (const Singularity& s : out.singular) out.full_turn_singularities += s.quarters >= 4 && !out.graph.boundary_vertex[s.vertex];
  out.field_time_s = seconds_since(t0);
  const CrossFieldTiming& t = out.field.timing;
  std::string split;
  const std::string kind = o.field_kind();
  if (!o.field && !o.cones)
    split = " (assemble " + fixed(t.assemble_s) + ", analyse " + fixed(t.analyze_s) + ", factorize " + fixed(t.factorize_s) +
            (o.curvature_field ? std::string()
             : out.graph.has_boundary()
                 ? ", one solve with the boundary faces fixed " + fixed(t.iterate_s)
                 : ", " + std::to_string(out.field.iterations) + " Lanczos steps " + fixed(t.iterate_s)) +
            (kind == "unit" ? ", " + std::to_string(out.field.unit_steps) + " unit steps " + fixed(t.unit_s) + " from energy " +
                        std::to_string(out.field.eigen_energy)
                  : std::string()) +
            ")";
  if (o.makes_field_parallel())
    split += ", made parallel in " + fixed(t.parallel_s) + " s from energy " + std::to_string(out.field_energy_before_parallel);
  if (out.spread_singularities > 0)
    split += "; " + std::to_string(out.spread_singularities) +
             " singularities of index +1 or more spread over their neighbours (cones of angle 0 cannot be mapped)";
  if (out.full_turn_singularities > 0)
    out.warnings.push_back(std::to_string(out.full_turn_singularities) +
                           " interior vertices have index +1 or more (cones of angle 0 or less): every map folds or "
                           "collapses around them (only a given field or cones can leave them; docs/gparam.md)");
  if (out.cones_missed > 0)
    out.warnings.push_back(std::to_string(out.cones_missed) +
                           " vertices' indices differ from the cones asked for (the field would turn by more than pi/4 "
                           "between two faces: near cones of index -1/2 or beyond, or vertices of few faces; "
                           "docs/gparam.md)");
  for (const std::string& w : out.warnings) split += "; warning: " + w;
  say(o, "field: " + kind + ", energy " + std::to_string(out.field.energy) +
             ", " + std::to_string(out.singular.size()) + " singularities, " + fixed(out.field_time_s) + " s" + split);
}

void compute_cut(const Mesh& mesh, const GParamOptions& o, GParamOutcome& out) {
  const auto t0 = std::chrono::steady_clock::now();
  out.cut = cut_graph(mesh, out.graph, out.frames, out.field.u, out.quarters);
  const double cut_s = seconds_since(t0);
  out.problem = seamless_problem(mesh, out.graph, out.cut);
  out.cut_time_s = seconds_since(t0);
  say(o, "cut: " + std::to_string(out.cut.num_cut_edges) + " seam edges in " + std::to_string(out.cut.branches.size()) +
             " branches, " + std::to_string(out.cut.num_wedges()) + " cut-mesh vertices, " + fixed(out.cut_time_s) +
             " s (cut graph " + fixed(cut_s) + ", seamless problem " + fixed(out.cut_time_s - cut_s) + ")");
}


// The surface at a size of order 1. The seamless problem is homogeneous (the seams'
// right-hand sides are 0, wedge 0 sits at the origin) and the field depends on angles and
// area ratios only, so a surface far from unit size is computed scaled and its map scaled
// back: the file's units then change nothing (a torus with coordinates about 1e8 ended
// numerical-error under linf, about 1e-70 stopped on non-finite gradients, about 1e80 failed
// to factor its field's Laplacian).
struct UnitSize {
  double scale = 1;                  // the surface's lengths are these times scale
  const Mesh* mesh = nullptr;        // the surface at that size (the input when scale is 1)
  const Problem* problem = nullptr;  // its seamless problem
};

// The map and the lengths of a solve at unit size, in surface units.
void scale_lengths(Result& r, double scale) {
  r.positions *= scale;
  for (IterationRecord& record : r.history) record.largest_move *= scale;
}

Result solve_unit_size(const GParamOptions& o, const UnitSize& unit) {
  const Problem& problem = *unit.problem;
  SolverOptions solver = o.solver;
  solver.relax.move_tolerance /= unit.scale;  // a length: surface units
  if (o.measure == Measure::FieldDeviation) return run_method(problem, solver);
  LocalGlobalOptions lg = o.local_global;
  lg.local = LocalStep::Rotation;
  const Result start = solve_l2(problem);  // the field-guided map starts local-global
  return start.ok() ? local_global(problem, start.positions, solver, lg) : start;
}

// The problem the rounding's L2 solves are made on: the seamless problem itself (the L2
// guide), or the same with each element's target replaced by the free L-infinity map's
// Jacobian (the Linf guide), whose L2 map is that map: the steps then move the guide's
// values by the L2 response to the rounding. Null when the guide's solve is not usable (the
// L2 guide is used, and progress says so).
std::optional<Problem> guided_rounding_problem(const GParamOptions& o, const Problem& solved) {
  if (o.grid_guide != GParamOptions::GridGuide::Linf) return std::nullopt;
  const Result guide = solve_linf(solved);
  if (!guide.usable()) {
    say(o, "integer grid: the L-infinity guide ended " + status_name(guide.status) + "; the rounding follows the L2 map");
    return std::nullopt;
  }
  say(o, "integer grid: the rounding follows the L-infinity map (max " + std::to_string(guide.distortion.maxCoeff()) +
             ", " + fixed(guide.time_s) + " s)");
  Problem guided = solved;
  const int n = solved.image_dim;
  for (int e = 0; e < solved.num_elements(); ++e)
    guided.targets.middleRows(e * n, n) = solved.jacobian(e, guide.positions);
  return guided;
}

// --integer-grid: the problem that is solved (the surface at unit size) is rounded to the grid
// of the edge length at that size; out.problem, in surface units, takes the same constraints
// scaled back when the two differ.
void round_unit_problem(const GParamOptions& o, const UnitSize& unit, Problem& solved, GParamOutcome& out) {
  std::optional<Problem> guided = guided_rounding_problem(o, solved);
  out.grid_guide = guided ? GParamOptions::GridGuide::Linf : GParamOptions::GridGuide::L2;
  Problem& rounded = guided ? *guided : solved;
  out.rounding = round_to_integer_grid(*unit.mesh, out.graph, out.cut, out.singular, out.edge_length / unit.scale,
                                       rounded, o.progress, o.integer_grid_options);
  if (guided) {  // the rounding's holds, on the problem with the surface's own targets
    solved.eq_matrix = guided->eq_matrix;
    solved.eq_rhs = guided->eq_rhs;
    solved.fixed = guided->fixed;
    solved.positions = guided->positions;
  }
  if (&solved == &out.problem) return;
  out.problem.eq_matrix = solved.eq_matrix;
  out.problem.eq_rhs = solved.eq_rhs * unit.scale;
  out.problem.fixed = solved.fixed;
  out.problem.positions = solved.positions * unit.scale;
}

void solve(const GParamOptions& o, const UnitSize& unit, GParamOutcome& out) {
  const auto t0 = std::chrono::steady_clock::now();
  say(o, "solve: " + method_name(o.solver.method) + ", measure " + measure_name(o.measure));
  out.result = solve_unit_size(o, unit);
  scale_lengths(out.result, unit.scale);
  out.solve_time_s = seconds_since(t0);
  say(o, "solve: " + status_name(out.result.status) + ", " + std::to_string(out.solve_time_s) + " s");
}

// The integer-grid map's own criterion: every value rounded. Values the rounding left to
// the others off the grid (integer_grid.h) make the outcome stalled, whatever the method's.
void note_values_off_the_grid(GParamOutcome& out) {
  const int off = out.rounding.singularities_off_grid + out.rounding.translations_off_grid;
  if (off == 0 || !out.result.usable()) return;
  out.result.status = worse_status(out.result.status, SolveStatus::Stalled);
  char why[400];
  std::snprintf(why, sizeof why,
                "integer grid: %d singular vertices and %d seam translations could not be rounded (every try "
                "fixed a value off the grid: the parity of a handle's loops, docs/gparam.md, \"Integer-grid "
                "maps\"); the map is seamless but %.3g grid units off an integer-grid map; ",
                out.rounding.singularities_off_grid, out.rounding.translations_off_grid, out.integer_error);
  out.result.message = why + out.result.message;
}

// fd against the field's frames or ARAP, in the faces' own frames (a flat surface too),
// measured at unit size (a uniform scale of the surface and the map leaves every Jacobian as
// it is), weighted by the surface's areas.
MapDistortion distortion_in_surface_units(const GParamOptions& o, const UnitSize& unit, const Eigen::MatrixXd& X) {
  MapDistortion d = frame_distortion(*unit.problem, X / unit.scale, o.measure);
  d.weights *= unit.scale * unit.scale;
  return d;
}

void measure(const Mesh& mesh, const GParamOptions& o, const UnitSize& unit, GParamOutcome& out) {
  const Eigen::MatrixXd& X = out.result.positions;
  out.measured = distortion_in_surface_units(o, unit, X);
  out.mapped = mesh;
  out.mapped.UV = X / out.edge_length;
  out.mapped.FUV = out.cut.corner_wedge;
  branch_translations(mesh, out.graph, out.cut, out.mapped.UV, &out.seam_error);
  if (o.integer_grid) {
    out.integer_error = integer_grid_error(mesh, out.graph, out.cut, out.singular, out.edge_length, X);
    note_values_off_the_grid(out);
  }
  if (out.result.usable() && !out.mapped.UV.allFinite()) {  // a safety net: the scale check should prevent it
    out.result.status = SolveStatus::NumericalError;
    out.result.message = "the texture coordinates (the map / the edge length " + std::to_string(out.edge_length) +
                         ") are not finite; " + out.result.message;
  }
}

}  // namespace

GParamOutcome global_parametrize(const Mesh& mesh, const GParamOptions& o, const std::string& source) {
  if (mesh.dim() == 2 && mesh.element_type() == ElementType::Triangle) {  // a planar domain: the plane z = 0
    Mesh lifted = mesh;
    lifted.V.conservativeResize(Eigen::NoChange, 3);
    lifted.V.col(2).setZero();
    return global_parametrize(lifted, o, source);
  }
  check_options(o);
  GParamOutcome out;
  const auto t0 = std::chrono::steady_clock::now();
  check_element_measures(mesh, source.empty() ? "gparam" : source);  // read_mesh's check, for meshes built in code
  out.graph = surface_graph(mesh, source, /*allow_boundary=*/true);
  check_boundary_options(o, out.graph, source);
  out.graph_time_s = seconds_since(t0);
  say(o, "surface graph: " + std::to_string(out.graph.num_edges()) + " edges" +
             (out.graph.has_boundary() ? ", " + std::to_string(out.graph.num_boundary_loops) + " boundary loop(s)"
                                       : std::string()) +
             ", " + fixed(out.graph_time_s) + " s");
  UnitSize unit;
  unit.scale = unit_size_scale(mesh);
  const Mesh scaled = unit.scale != 1 ? scaled_down(mesh, unit.scale) : Mesh();
  unit.mesh = unit.scale != 1 ? &scaled : &mesh;
  compute_field(*unit.mesh, o, out);
  check_interrupt();  // solvers/interrupt.h: between the phases (the field's loops check too)
  compute_cut(*unit.mesh, o, out);
  check_interrupt();
  Problem unit_problem;  // out.problem stays the surface's own (h = 1, surface units)
  if (unit.scale != 1) {
    out.frames.area *= unit.scale * unit.scale;
    unit_problem = std::move(out.problem);
    out.problem = seamless_problem(mesh, out.graph, out.cut);
  }
  unit.problem = unit.scale != 1 ? &unit_problem : &out.problem;
  const double area = out.frames.area.sum();
  check_edge_length_scale(o, area);
  out.edge_length = o.edge_length > 0 ? o.edge_length : std::sqrt(area / o.quads);
  if (o.integer_grid) round_unit_problem(o, unit, unit.scale != 1 ? unit_problem : out.problem, out);
  check_interrupt();
  solve(o, unit, out);
  measure(mesh, o, unit, out);
  return out;
}

}  // namespace strictmin
