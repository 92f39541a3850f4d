#pragma once
// The summary of a task's run as JSON: the keys of `strictmin ... --summary` (docs/formats.md),
// built in one place for the command-line tool and the Python module. Keys that depend on
// the caller's clock (time_s) are added by the caller. A private header (src/): it is not
// part of the installed API, whose headers need Eigen only.
#include <nlohmann/json.hpp>
#include <string>

#include "strictmin/report/stats.h"
#include "strictmin/solvers/result.h"
#include "strictmin/tasks/deform.h"
#include "strictmin/tasks/gparam.h"
#include "strictmin/tasks/interp.h"
#include "strictmin/tasks/method.h"
#include "strictmin/tasks/param.h"
#include "strictmin/tasks/quad_extraction.h"
#include "strictmin/solvers/conformal.h"

namespace strictmin {

// A JSON number, or null for a non-finite value (an infinite distortion, no bound).
nlohmann::json number_or_null(double x);

// The keys that say what wrote a summary: version (strictmin::version()) and, when the BLAS is
// OpenBLAS, blas_kernels (e.g. "OpenBLAS SkylakeX": the dense kernels the run's factorizations used).
void add_provenance_summary(nlohmann::json& s);

// The distortion keys of every summary: max_distortion, max_element, l2_distortion,
// mean_distortion, flipped.
void add_distortion_summary(nlohmann::json& s, const DistortionStats& stats);

// status, usable, stop_reason, and message when there is one.
void add_status_summary(nlohmann::json& s, const Result& r);

// Keys that depend on the method (iterations, lower_bound, levels, worst_level_gap, sweeps, ...).
void add_solver_summary(nlohmann::json& s, const SolverOptions& options, const Result& r);

// arap / asap: local_global_iterations, fd_step_lower_bound (lower_bound becomes null) and
// history (the maximum per iteration).
void add_local_global_summary(nlohmann::json& s, const Result& r);

// qc / iso (deform, param): bisection_steps, frame_iterations, ipm_iterations,
// frames_lower_bound (the frame-relative bound of the last frames: not a bound on the
// measure), lower_bound = null (none is certified for the non-convex measure), and
// start_only for l2 (the starting map).
void add_conformal_summary(nlohmann::json& s, const SolverOptions& o, const ConformalStats& stats);

// What names the run's files in a summary: "" when there is none.
struct SummaryFiles {
  std::string input;            // the mesh file (deform: "example:NAME" for a built-in example)
  std::string output;           // -o
  std::string distortion_file;  // --distortion
};

// deform: every key but time_s.
nlohmann::json deform_summary(const Mesh& mesh, size_t handles, const DeformOptions& options,
                              const DeformOutcome& outcome, const SummaryFiles& files);

// param: every key but time_s. The method is the initial map's name when options.init_only.
nlohmann::json param_summary(const Mesh& mesh, const ParamOptions& options, const ParamOutcome& outcome,
                             const SummaryFiles& files);

// gparam: every key but time_s. `field`: what the field was ("smoothest", "curvature", or
// the file or array that gave it).
nlohmann::json gparam_summary(const Mesh& mesh, const GParamOptions& options, const GParamOutcome& outcome,
                              const std::string& field, const SummaryFiles& files);

// A quad extraction (strictmin quads, gparam --quad-mesh): status ("complete" or "holes"),
// quads, vertices, edges, uv_area, flipped_triangles, cones, dropped_squares and why,
// boundary_edges, holes, non_manifold_edges, euler_characteristic,
// surface_euler_characteristic, tolerance, fill_holes, valences ({"3": count, ...}), irregular_vertices, the quads'
// quality (min_angle_deg, max_angle_deg, min_scaled_jacobian, min_side, max_side, mean_side),
// time_s.
nlohmann::json quad_extraction_summary(const QuadExtraction& x, const QuadExtractionOptions& options);
// "N quads, M vertices, Euler characteristic X, complete", or the holes and why, or (closed but
// incomplete: no squares, or a part missing) the surface's Euler characteristic and UV area.
// The summary's `reason` when the quad mesh is not complete.
std::string quad_extraction_phrase(const QuadExtraction& x);

// interp: the keys around the frames (source, target, kind, rotation_jumps, warnings, method,
// elements, vertices, pin, lg_iterations_cap, lg_tolerance); the caller adds frames and time_s.
nlohmann::json interp_summary(const Mesh& source, const Interpolator& interp, const InterpOptions& options,
                              const std::string& source_name, const std::string& target_name);

// One entry of interp's frames: every key but time_s. `output` is the frame's file ("" for none).
nlohmann::json interp_frame_summary(const InterpFrame& frame, const InterpOptions& options,
                                    const std::string& output);

}  // namespace strictmin
