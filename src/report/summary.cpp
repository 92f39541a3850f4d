#include "summary.h"

#include <algorithm>
#include <cmath>

#include "runtime/blas_kernels.h"
#include "strictmin/solvers/strict.h"
#include "strictmin/tasks/conformal_method.h"
#include "strictmin/version.h"

namespace strictmin {

nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

void add_provenance_summary(nlohmann::json& s) {
  s["version"] = std::string(version());
  const std::string core = runtime::openblas_core();
  if (!core.empty()) s["blas_kernels"] = "OpenBLAS " + core;
}

void add_distortion_summary(nlohmann::json& s, const DistortionStats& stats) {
  s["max_distortion"] = number_or_null(stats.max);
  s["max_element"] = stats.max_element;
  s["l2_distortion"] = number_or_null(stats.l2);
  s["mean_distortion"] = number_or_null(stats.mean);
  s["flipped"] = stats.flipped < 0 ? nlohmann::json(nullptr) : nlohmann::json(stats.flipped);  // null: not defined
}

void add_status_summary(nlohmann::json& s, const Result& r) {
  s["status"] = status_name(r.status);
  s["usable"] = r.usable();
  // Always a reason (docs/formats.md); a solver that leaves none is named by its status.
  s["stop_reason"] = !r.message.empty()                ? r.message
                     : r.status == SolveStatus::Solved ? "solved: the method's own criterion was met"
                                                       : status_name(r.status) + " (no further reason given)";
  if (!r.message.empty()) s["message"] = r.message;
}

void add_solver_summary(nlohmann::json& s, const SolverOptions& o, const Result& r) {
  s["iterations"] = r.iterations;
  if (o.method == Method::Linf || o.method == Method::Direct || o.method == Method::Exact ||
      (o.method == Method::Relax && o.relax_init == Method::Linf))
    s["lower_bound"] = number_or_null(r.lower_bound);
  if (o.method == Method::Direct || o.method == Method::Exact) s["levels"] = r.iterations;
  // Below delta-k / 4 every level's band of fixed elements is where Algorithm 2 puts it;
  // null when a level has no certified bound.
  if (o.method == Method::Direct) {
    s["worst_level_gap"] = number_or_null(worst_level_gap(r));
    s["delta_k"] = o.direct.delta_k;  // report compares direct with the others at it
    s["k_min"] = o.direct.k_min;
  }
  if (o.method == Method::Relax) {
    s["sweeps"] = r.iterations;
    s["init"] = method_name(o.relax_init);
    s["accept_tolerance"] = o.relax.accept_tolerance;
  }
  if (o.method == Method::Lp) s["p"] = o.lp.p;
}

void add_local_global_summary(nlohmann::json& s, const Result& r) {
  s["local_global_iterations"] = r.iterations;
  // direct: its levels' local-global steps together (r.iterations counts the levels).
  if (s.contains("levels")) {
    int steps = 0;
    for (const auto& h : r.history) steps += std::max(0, h.inner_iterations);
    s["local_global_iterations"] = steps;
  }
  // relax: its start's global steps come first; the sweeps are the records with a move.
  if (s.contains("sweeps")) {
    int sweeps = 0;
    for (const auto& h : r.history) sweeps += !std::isnan(h.largest_move);
    s["sweeps"] = sweeps;
  }
  // The global steps' certified bound is for field deviation with their rotations fixed, not
  // for the ARAP / ASAP measure reported: it moves to its own key, lower_bound is null.
  if (s.contains("lower_bound")) {
    s["fd_step_lower_bound"] = s["lower_bound"];
    s["lower_bound"] = nullptr;
  }
  nlohmann::json history = nlohmann::json::array();
  for (const auto& h : r.history) history.push_back({{"iteration", h.iteration}, {"max", h.max_distortion}});
  s["history"] = history;
}

void add_conformal_summary(nlohmann::json& s, const SolverOptions& o, const ConformalStats& stats) {
  if (o.method == Method::L2) s["start_only"] = true;  // l2 with qc / iso: the starting map
  s["bisection_steps"] = stats.bisection_steps;
  s["frame_iterations"] = stats.frame_iterations;
  s["ipm_iterations"] = stats.ipm_iterations;
  s["lower_bound"] = nullptr;
  s["frames_lower_bound"] = number_or_null(stats.frames_lower_bound);
  s["bisection_time_s"] = stats.bisection_time_s;
}

namespace {

// The keys every task with a mesh in and a map out starts with.
nlohmann::json task_header(const char* task, const SummaryFiles& files) {
  nlohmann::json s;
  s["task"] = task;
  s["input"] = files.input;
  s["output"] = files.output;
  s["distortion_file"] = files.distortion_file;
  return s;
}

}  // namespace

nlohmann::json deform_summary(const Mesh& mesh, size_t handles, const DeformOptions& options,
                              const DeformOutcome& d, const SummaryFiles& files) {
  nlohmann::json s = task_header("deform", files);
  s["method"] = method_name(options.solver.method);
  s["measure"] = measure_name(options.measure);
  s["elements"] = mesh.num_elements();
  s["vertices"] = mesh.num_vertices();
  s["handles"] = handles;
  s["dimension"] = d.problem.image_dim;
  add_distortion_summary(s, d.measured.stats);
  s["flips_added"] = d.flips_added;
  s["no_flips"] = options.no_flips;
  add_status_summary(s, d.result);
  add_solver_summary(s, options.solver, d.result);
  if (options.measure == Measure::Arap || options.measure == Measure::Asap) add_local_global_summary(s, d.result);
  if (is_conformal_measure(options.measure)) add_conformal_summary(s, options.solver, d.conformal);
  s["solver_time_s"] = d.result.time_s;
  return s;
}

nlohmann::json param_summary(const Mesh& mesh, const ParamOptions& options, const ParamOutcome& p,
                             const SummaryFiles& files) {
  nlohmann::json s = task_header("param", files);
  s["method"] = options.init_only ? init_name(options.init) : method_name(options.solver.method);
  s["measure"] = measure_name(options.measure);
  s["init"] = init_name(options.init);
  s["elements"] = mesh.num_elements();
  s["vertices"] = mesh.num_vertices();
  s["boundary_vertices"] = p.boundary.size();
  add_distortion_summary(s, p.measured.stats);
  s["flips"] = p.flips;
  s["flips_added"] = p.flips_added;
  s["no_flips"] = options.no_flips;
  s["boundary_overlap"] = p.boundary_overlap;
  s["warnings"] = p.warnings;
  add_status_summary(s, p.result);
  if (!options.init_only) {
    add_solver_summary(s, options.solver, p.result);
    // relax's own `init` (the method it starts from) would overwrite the starting map's: here
    // `init` stays the starting map (tutte / lscm) and relax's goes to `relax_init`.
    if (options.solver.method == Method::Relax) s["relax_init"] = method_name(options.solver.relax_init);
    s["init"] = init_name(options.init);
    if (is_conformal_measure(options.measure))
      add_conformal_summary(s, options.solver, p.conformal);
    else if (options.measure != Measure::FieldDeviation)
      add_local_global_summary(s, p.result);
  }
  s["init_time_s"] = p.init_time_s;
  s["solver_time_s"] = p.result.time_s;
  return s;
}

namespace {

// Each singular vertex and its index in quarters; "boundary": true on a boundary vertex (a
// corner of the boundary, where the index is the boundary's turn in quarters, signed).
nlohmann::json singularity_list(const std::vector<Singularity>& s, const SurfaceGraph& g) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& x : s) {
    nlohmann::json item = {{"vertex", x.vertex}, {"index", x.quarters}};
    if (g.boundary_vertex[static_cast<size_t>(x.vertex)]) item["boundary"] = true;
    list.push_back(item);
  }
  return list;
}

}  // namespace

nlohmann::json gparam_summary(const Mesh& mesh, const GParamOptions& o, const GParamOutcome& g,
                              const std::string& field, const SummaryFiles& files) {
  nlohmann::json s = task_header("gparam", files);
  s["method"] = method_name(o.solver.method);
  s["measure"] = measure_name(o.measure);
  s["field"] = o.cones ? std::string("cones") : field;
  s["field_parallel"] = o.field_is_parallel();
  if (o.field_is_parallel()) s["cones_missed"] = g.cones_missed;
  if (o.makes_field_parallel()) s["field_energy_before_parallel"] = g.field_energy_before_parallel;
  s["field_energy"] = g.field.energy;
  s["elements"] = mesh.num_elements();
  s["vertices"] = mesh.num_vertices();
  s["euler_characteristic"] = g.graph.euler_characteristic();
  s["singularities"] = g.singular.size();
  s["singularity_indices"] = singularity_list(g.singular, g.graph);
  s["boundary_loops"] = g.graph.num_boundary_loops;
  s["spread_singularities"] = g.spread_singularities;
  s["full_turn_singularities"] = g.full_turn_singularities;
  s["warnings"] = g.warnings;
  s["seam_edges"] = g.cut.num_cut_edges;
  s["seam_branches"] = g.cut.branches.size();
  s["cut_mesh_vertices"] = g.cut.num_wedges();
  s["edge_length"] = g.edge_length;
  s["seam_error"] = g.seam_error;  // UV units: grows as 1/h with the map's size
  const double uv_size = g.mapped.UV.size() > 0 ? (g.mapped.UV.colwise().maxCoeff() - g.mapped.UV.colwise().minCoeff()).norm() : 0;
  s["seam_error_relative"] = g.seam_error / std::max(1.0, uv_size);  // against the UV bounding box's diagonal
  s["integer_grid"] = o.integer_grid;
  if (o.integer_grid) {
    s["grid_guide"] = g.grid_guide == GParamOptions::GridGuide::Linf ? "linf" : "l2";  // the one followed
    s["integer_error"] = g.integer_error;
    s["rounded_singularities"] = g.rounding.singularities;
    s["rounded_translations"] = g.rounding.translations;
    s["off_grid_singularities"] = g.rounding.singularities_off_grid;
    s["off_grid_translations"] = g.rounding.translations_off_grid;
    s["rounding_largest_move"] = g.rounding.largest_rounding;
    s["rounding_solves"] = g.rounding.solves;
    s["rounding_time_s"] = g.rounding.time_s;
  }
  add_distortion_summary(s, g.measured.stats);
  add_status_summary(s, g.result);
  add_solver_summary(s, o.solver, g.result);
  if (o.measure != Measure::FieldDeviation) add_local_global_summary(s, g.result);
  s["graph_time_s"] = g.graph_time_s;
  s["field_time_s"] = g.field_time_s;
  s["field_iterations"] = g.field.iterations;
  if (std::string(o.field_kind()) == "unit") {
    s["field_unit_steps"] = g.field.unit_steps;
    s["field_eigen_energy"] = g.field.eigen_energy;
  }
  s["cut_time_s"] = g.cut_time_s;
  s["solver_time_s"] = g.solve_time_s;
  return s;
}

nlohmann::json interp_summary(const Mesh& source, const Interpolator& interp, const InterpOptions& options,
                              const std::string& source_name, const std::string& target_name) {
  nlohmann::json s;
  s["task"] = "interp";
  s["source"] = source_name;
  s["target"] = target_name;
  s["kind"] = interp_kind_name(interp.kind());
  s["rotation_jumps"] = interp.rotation_jumps();
  s["rotation_blend"] = interp.rotation_blend();
  s["rotation_disagreements"] = interp.rotation_disagreements();
  s["warnings"] = interp.warning().empty() ? nlohmann::json::array() : nlohmann::json::array({interp.warning()});
  s["method"] = method_name(options.solver.method);
  s["elements"] = source.num_elements();
  s["vertices"] = source.num_vertices();
  s["pin"] = options.pin_vertex < 0 ? nlohmann::json("centroid") : nlohmann::json(options.pin_vertex);
  s["lg_iterations_cap"] = options.local_global.max_iterations;
  s["lg_tolerance"] = options.local_global.relative_change;
  return s;
}

nlohmann::json interp_frame_summary(const InterpFrame& f, const InterpOptions& options,
                                    const std::string& output) {
  nlohmann::json j;
  j["t"] = f.t;
  j["output"] = output;
  add_distortion_summary(j, f.stats);  // flipped null on a surface (stats.flipped -1)
  add_status_summary(j, f.result);
  add_solver_summary(j, options.solver, f.result);
  add_local_global_summary(j, f.result);
  j["solver_time_s"] = f.result.time_s;  // the solve alone (the report's "time"); time_s adds the frame's writing
  // --lg-iterations 0: one global solve, no local-global iteration (iterations and history
  // are that solve's).
  if (options.local_global.max_iterations == 0) j["local_global_iterations"] = 0;
  // direct's levels bound field deviation against the interpolated rotations held fixed, not
  // the distance reported (the best rotation's): null, as lower_bound (docs/interp.md). With
  // --lg-iterations 0 the single direct solve's own gap was reported.
  if (j.contains("worst_level_gap")) j["worst_level_gap"] = nullptr;
  return j;
}

std::string quad_extraction_phrase(const QuadExtraction& x) {
  std::string line = std::to_string(x.mesh.num_quads()) + " quads, " + std::to_string(x.mesh.num_vertices()) +
                     " vertices, Euler characteristic " + std::to_string(x.euler_characteristic);
  if (x.complete && x.filled_squares > 0)
    return line + ", complete after filling " + std::to_string(x.filled_holes) + " hole(s) with " +
           std::to_string(x.filled_squares) + " squares";
  if (x.complete) return line + ", complete";
  if (x.filled_squares > 0)
    line += ", " + std::to_string(x.filled_holes) + " hole(s) filled with " + std::to_string(x.filled_squares) +
            " squares";
  if (x.holes == 0)  // closed, yet not the surface: no squares at all, or a part of it missing
    return line + ", incomplete: the surface's Euler characteristic is " + std::to_string(x.surface_euler_characteristic) +
           ", the map's UV area " + std::to_string(std::llround(x.uv_area)) + ", " + std::to_string(x.flipped_triangles) +
           " flipped triangles, " + std::to_string(x.dropped_squares) + " unit squares left out";
  return line + ", " + std::to_string(x.holes) + " hole(s): " + std::to_string(x.dropped_squares) +
         " unit squares left out (" + std::to_string(x.squares_touching_flips) + " touch the map's " +
         std::to_string(x.flipped_triangles) + " flipped triangles, " + std::to_string(x.squares_wrapped) +
         " wrap onto themselves, " + std::to_string(x.squares_not_covered_once) + " are not covered once, " +
         std::to_string(x.squares_overlapping) + " overlap others, " + std::to_string(x.squares_inverted) +
         " face against the surface)" +
         (x.non_manifold_vertices > 0 ? ", " + std::to_string(x.non_manifold_vertices) + " non-manifold vertices"
                                      : std::string());
}

nlohmann::json quad_extraction_summary(const QuadExtraction& x, const QuadExtractionOptions& options) {
  nlohmann::json s;
  s["tolerance"] = options.tolerance;
  s["fill_holes"] = options.fill_holes;
  s["status"] = !x.complete ? "holes" : x.filled_squares > 0 ? "filled" : "complete";
  if (!x.complete) s["reason"] = quad_extraction_phrase(x);  // "holes" with holes 0: no square, or a part missing
  s["filled_holes"] = x.filled_holes;
  s["filled_squares"] = x.filled_squares;
  s["quads"] = x.mesh.num_quads();
  s["vertices"] = x.mesh.num_vertices();
  s["edges"] = x.edges;
  s["uv_area"] = x.uv_area;
  s["flipped_triangles"] = x.flipped_triangles;
  s["cones"] = x.cones;
  s["dropped_squares"] = x.dropped_squares;
  s["squares_touching_flips"] = x.squares_touching_flips;
  s["squares_wrapped"] = x.squares_wrapped;
  s["squares_not_covered_once"] = x.squares_not_covered_once;
  s["squares_overlapping"] = x.squares_overlapping;
  s["squares_inverted"] = x.squares_inverted;
  s["boundary_edges"] = x.boundary_edges;
  s["holes"] = x.holes;
  s["non_manifold_edges"] = x.non_manifold_edges;
  s["non_manifold_vertices"] = x.non_manifold_vertices;
  s["split_vertices"] = x.split_vertices;
  s["euler_characteristic"] = x.euler_characteristic;
  s["surface_euler_characteristic"] = x.surface_euler_characteristic;
  nlohmann::json valences = nlohmann::json::object();
  int irregular = 0;
  for (const auto& [valence, count] : x.valences) {
    valences[std::to_string(valence)] = count;
    if (valence != 4) irregular += count;
  }
  s["valences"] = valences;
  s["irregular_vertices"] = irregular;
  s["min_angle_deg"] = number_or_null(x.quality.min_angle_deg);
  s["max_angle_deg"] = number_or_null(x.quality.max_angle_deg);
  s["min_scaled_jacobian"] = number_or_null(x.quality.min_scaled_jacobian);
  s["min_side"] = number_or_null(x.quality.min_side);
  s["max_side"] = number_or_null(x.quality.max_side);
  s["mean_side"] = number_or_null(x.quality.mean_side);
  s["time_s"] = x.time_s;
  return s;
}

}  // namespace strictmin
