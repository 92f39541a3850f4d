#pragma once
// Strict minimizers (paper Section 4-5): the lexicographically smallest area-weighted
// distortion distribution, approximated level by level with L-infinity solves.
//
// direct (Algorithm 2): solve (1) with the bounds fixed so far; fix every free element
//   within delta_k of the optimum k at k; repeat until all are fixed or k <= k_min. The
//   elements below k_min keep the last solution's values.
// exact (Algorithm 1): at each level, find the essential set exactly (the elements that no
//   optimal solution lowers), one extra L-infinity solve per undecided candidate; the
//   reference the others are compared with, for small meshes only.
#include <Eigen/Core>
#include <functional>
#include <string>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/solvers/result.h"

namespace strictmin {

struct StrictStep {
  int step = 0;          // 1-based
  double k = 0;          // optimal value of this level
  int fixed_now = 0;     // elements fixed at this step
  int fixed_total = 0;   // elements fixed so far
  int solves = 0;        // L-infinity solves so far
  double time_s = 0;
  int level_iterations = 0;      // iterations of this step's solve (direct), counted in level_iteration_unit
  // What level_iterations counts: "interior-point iterations" (the field deviation's levels),
  // "local-global steps" (ARAP/ASAP levels), "frame iterations" (qc/iso levels).
  std::string level_iteration_unit = "interior-point iterations";
  int level_free_vertices = -1;  // vertices this step's solve moved (-1: not reported)
  int pinned_total = 0;          // elements pinned so far (DirectOptions::pin_essential)
};

// Solves one level of the direct algorithm: problem (1) with the bounds in
// linf.element_bounds, from the previous level's map X. Default: solve_linf. A usable result
// must have the problem's sizes (positions #V by image_dim, distortion #E: solve_direct
// throws InputError otherwise); a usable status with a map that is not finite ends the run
// numerical-error.
using LevelSolver = std::function<Result(const Problem&, const LinfOptions&, const Eigen::MatrixXd& X)>;

struct DirectOptions {
  double delta_k = 1e-3;
  double k_min = 0.1;
  int max_steps = 100000;
  // Relative gap at which the levels after the first stop: elements are fixed within
  // delta_k of a level, so its value is needed to a small fraction of delta_k only.
  // Negative: delta_k / 100 (never finer than linf.gap_tolerance). The first level (the
  // L-infinity optimum and its certified bound) always uses linf.gap_tolerance.
  double level_gap = -1;
  // Levels after the first move only the vertices within this many rings of the elements
  // still free (1: the free elements' own vertices; 2: and their neighbours; ...); the rest
  // of the mesh stays where the previous level left it, and the level's problem shrinks to
  // the region that can still change (problem/subproblem.h). 0: every vertex moves at every
  // level (the paper's Algorithm 2 as stated). See docs/strict.md for what it costs.
  int moving_rings = 2;
  // Pin the essential elements (certificate multiplier >= pin_threshold) after each level:
  // they leave the later levels' programs and their Jacobians are held (docs/strict.md,
  // "Pinned elements"). Only with the field deviation through solve_linf (no level_solver),
  // on problems with equalities (gparam's seams) too; elsewhere ignored.
  bool pin_essential = true;
  double pin_threshold = 1e-4;
  // Start each level's interior-point method from the previous level's last dual iterate,
  // element by element (docs/strict.md, "Warm levels"): a tenth to a third fewer iterations
  // (homer 11%, cow 19%, horse's levels 2-8 37%).
  // Only through solve_linf (no level_solver). false: every level from a centred dual.
  bool warm_levels = true;
  std::function<void(const StrictStep&)> progress;
  LevelSolver level_solver;  // ARAP/ASAP: local-global iterations per level (local_global.h)
  // Whether the level solver's Result.lower_bound bounds the level's own measure (so that a
  // level that stopped short within delta_k / 4 of it still places its band). false for
  // local-global levels: their bound is the last field-deviation step's, with the rotations
  // held, and says nothing of a loop that did not converge; such a level counts with its
  // status whatever its gap.
  bool level_bound_certifies = true;
  // What the level solver's Result.iterations counts (StrictStep::level_iteration_unit).
  std::string level_iteration_unit = "interior-point iterations";

  // Ranges: delta_k > 0, k_min >= 0, max_steps >= 1, level_gap < 1 (negative: the default),
  // moving_rings >= 0, pin_threshold in (0, 1]. False with the reason in *why otherwise.
  bool is_valid(std::string* why = nullptr) const;
};

struct ExactOptions {
  // An element is a candidate when within tolerance of the level, lowered when it ends
  // below k - tolerance (see strict_exact.cpp for why not smaller).
  double tolerance = 1e-3;
  int max_elements = 3000;  // refuse larger meshes (see docs/strict.md)
  // Pin the essential elements (their Jacobians held, out of the later programs; docs/strict.md,
  // "Pinned elements"); on problems without equalities, else ignored.
  bool pin_essential = true;
  std::function<void(const StrictStep&)> progress;

  // Ranges: tolerance > 0, max_elements >= 1.
  bool is_valid(std::string* why = nullptr) const;
};

// Both start from problem.positions and solve every level with the tolerances of `linf`
// (its element_bounds and progress are the algorithms' own and ignored).
// Result.iterations = steps (levels); history has one record per step (k in
// max_distortion, the level's relative certified gap in certified_gap); Result.lower_bound =
// the first level's certified bound. Throws InputError for invalid options.
Result solve_direct(const Problem& problem, const DirectOptions& options = {}, const LinfOptions& linf = {});
// The largest certified gap of a level of solve_direct's result (relative, as --gap; its
// history's gaps), +inf when a level has no certified bound (its accuracy is unknown).
double worst_level_gap(const Result& direct);
// Throws InputError when the problem has more than options.max_elements elements.
Result solve_exact(const Problem& problem, const ExactOptions& options = {}, const LinfOptions& linf = {});

}  // namespace strictmin
