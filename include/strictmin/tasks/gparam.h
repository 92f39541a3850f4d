#pragma once
// Global seamless parametrization of a surface guided by a cross field (the paper's
// Appendix A; docs/gparam.md): field -> singularities -> cut and matchings -> seamless
// Problem (seams as linear equalities) -> any method -> per-corner UV.
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "strictmin/field/cone_field.h"
#include "strictmin/field/cross_field.h"
#include "strictmin/field/cut_graph.h"
#include "strictmin/field/singularities.h"
#include "strictmin/field/surface_graph.h"
#include "strictmin/measures/measures.h"
#include "strictmin/mesh/mesh.h"
#include "strictmin/problem/problem.h"
#include "strictmin/solvers/local_global.h"
#include "strictmin/solvers/result.h"
#include "strictmin/tasks/integer_grid.h"
#include "strictmin/tasks/map_distortion.h"
#include "strictmin/tasks/method.h"

namespace strictmin {

struct GParamOptions {
  Measure measure = Measure::FieldDeviation;  // fd (against the field) or arap (local-global)
  // Target edge length h (surface units); when <= 0, h = sqrt(area / quads).
  double edge_length = 0;
  int quads = 1000;
  std::optional<Eigen::MatrixXd> field;  // #F by 3 given directions (--field FILE)
  bool curvature_field = false;          // --field curvature (when no field is given)
  double curvature_alignment = 0.01;  // --curvature-alignment
  std::string field_source;              // names the field (or the cone file) in messages
  std::vector<long> field_lines;         // each face's line in the field file (read_field_file; empty: an array)
  // --cones FILE: the field with exactly these cones (#V indices in quarters, cone_field.h).
  std::optional<std::vector<int>> cones;
  // --parallel: keep the field's singularities and replace the field by the parallel one with
  // exactly those cones (cone_cross_field): smoother, and a lower maximum distortion
  // (docs/gparam.md, "Fields from cones"). Implied by `cones`.
  bool parallel_field = false;
  // --integer-grid: the singular vertices and the seam translations rounded to the grid of
  // the edge length before the method's solve (tasks/integer_grid.h).
  bool integer_grid = false;
  IntegerGridOptions integer_grid_options;  // the rounding's (its exact check)
  // --grid-guide: the map whose values the rounding follows. L2: the seamless L2 map (as
  // MIQ does). Linf: the free L-infinity map (fd), one solve more: the rounding's L2 solves
  // then take its Jacobians as their targets, so that as the grid shrinks the rounded map
  // tends to the L-infinity optimum rather than to the L2 map held at its singular vertices
  // (docs/gparam.md, "The rounding's guide").
  enum class GridGuide { L2, Linf };
  GridGuide grid_guide = GridGuide::L2;
  CrossFieldOptions field_options;
  SolverOptions solver;
  LocalGlobalOptions local_global;
  std::function<void(const std::string&)> progress;  // one line per phase

  // Whether the field used is parallel between its singularities (cones or parallel_field).
  bool field_is_parallel() const { return parallel_field || cones.has_value(); }
  // Whether a computed field is replaced by the parallel one (a cone field is parallel already).
  bool makes_field_parallel() const { return parallel_field && !cones; }

  // Which field the run computes or takes: "given" (field set), "cones" (cones set),
  // "curvature", "unit" (field_options.unit) or "smoothest".
  const char* field_kind() const {
    return field             ? "given"
           : cones           ? "cones"
           : curvature_field ? "curvature"
           : field_options.unit ? "unit"
                                : "smoothest";
  }
};

struct GParamOutcome {
  SurfaceGraph graph;
  FaceFrames frames;
  CrossField field;
  double field_energy_before_parallel = 0;  // parallel_field: the computed field's E before it
  int spread_singularities = 0;     // computed fields: fans changed to spread index >= +1 singularities
  int full_turn_singularities = 0;  // interior vertices left with index >= +1 (no map can be injective there)
  int cones_missed = 0;  // cones or parallel_field: vertices whose index differs from the one asked for
  // What the result's status does not say: full-turn singularities left (the map folds or
  // collapses around them whatever the method), cones missed. Each a sentence.
  std::vector<std::string> warnings;
  std::vector<int> quarters;  // every vertex's index in quarters
  std::vector<Singularity> singular;
  CutGraph cut;
  Problem problem;            // on the cut mesh, h = 1 (see seamless_problem.h)
  double edge_length = 0;     // h
  Result result;              // positions: #wedges by 2 at h = 1
  Mesh mapped;                // input V and F, UV = result / h, FUV = corner wedges
  MapDistortion measured;     // fd against the field's frames, or arap (dimensionless)
  double seam_error = 0;      // largest transition violation, in UV units
  IntegerGridRounding rounding;  // integer_grid: what was rounded
  // integer_grid: the guide the rounding followed (L2 when the L-infinity guide's solve was
  // not usable, whatever grid_guide asked for).
  GParamOptions::GridGuide grid_guide = GParamOptions::GridGuide::L2;
  double integer_error = 0;      // integer_grid: the map's distance to the grid (integer_grid_error)
  double graph_time_s = 0;  // the surface graph (edges, fans) and the manifold checks
  double field_time_s = 0, cut_time_s = 0, solve_time_s = 0;
};

// Takes closed surfaces and surfaces with boundary (the field then follows the boundary,
// which stays free in the map; docs/gparam.md, "Surfaces with boundary"); a planar mesh
// (#V by 2) is the surface z = 0.
// Throws InputError (naming `source`) for a mesh that is not one manifold surface, a bad
// field, a non-positive edge length or quad count, a measure other than fd/arap, or, on a
// surface with boundary, the options that take closed surfaces only (integer grid, cones,
// parallel, unit field).
GParamOutcome global_parametrize(const Mesh& mesh, const GParamOptions& options, const std::string& source = "");

}  // namespace strictmin
