#pragma once
// L-infinity and strict minimizers of the quasiconformal distortion sigma1/sigma2 and the
// isometric distortion max(sigma1, 1/sigma2) of 2D triangle maps (paper Section 7), by
// bisection over convex second-order cones with per-triangle frames (solvers/qc/qc_program.h):
//
//   for frame iterations f = 1, 2, ...:
//     r_T = a_T / |a_T| of the current map (the frames);
//     qc: bisection on the level k = (K-1)/(K+1), each step a slack feasibility program
//     solved by the interior-point method of solvers/qc/sparse_socp.h, warm-started from the
//     last feasible map; the map of the lowest feasible level becomes current;
//     iso: the least level S in one cone program (minimize S, solvers/qc/iso_level.h);
//   stop when a frame iteration lowers the maximum by less than frame_tolerance.
//
// Guarantees: every map returned is orientation-preserving (det J > 0 on every triangle with
// a free vertex); the maximum never increases over frame iterations (the current map stays
// feasible under frames taken from it; asserted). Not guaranteed: the global optimum of the
// non-convex problem (the frames fix a convex subset of the feasible maps).
//
// direct: Algorithm 2 (strict.h: solve_direct) with each level this bisection, the fixed
// elements' bounds as cone levels of their own; levels after the first bisect to the
// larger of bisection_tolerance and DirectOptions::level_gap.
#include <Eigen/Core>
#include <functional>

#include "strictmin/measures/measures.h"
#include "strictmin/problem/problem.h"
#include "strictmin/solvers/result.h"
#include "strictmin/solvers/strict.h"

namespace strictmin {

struct ConformalOptions {
  Measure measure = Measure::Quasiconformal;  // Quasiconformal or Isometric
  // Bisection stops when the bracket [certified infeasible, feasible] of the level is below
  // bisection_tolerance * max(1, level) (in measure units: K or S). A last bracket closed
  // only through levels the feasibility test could not decide gives almost-solved
  // (docs/measures.md, "When is a bracket closed").
  double bisection_tolerance = 1e-7;
  int max_bisection_steps = 60;
  // Frame iterations stop when one lowers the maximum by less than frame_tolerance * max
  // (with the bracket at bisection_tolerance: earlier iterations bisect more coarsely, to a
  // tenth of the last improvement).
  double frame_tolerance = 1e-5;
  int max_frame_iterations = 50;
  // Per-element fixed bounds in measure units (direct's levels; empty or negative: free;
  // NaN, inf and values above 1e100 are refused).
  Eigen::VectorXd element_bounds;
  int max_ipm_iterations = 100;  // each feasibility program's cap (LinfOptions::max_iterations's default)
  // iso: each frame iteration's least level by one cone program (minimize S with the rotated
  // cone v_T S >= 1, docs/measures.md "iso in one program") instead of a bisection; false:
  // bisect as qc does (the two agree to the tolerance; kept for comparison).
  bool iso_one_program = true;
  std::function<void(const IterationRecord&)> progress;  // after every frame iteration

  // Ranges: bisection_tolerance and frame_tolerance > 0, max_bisection_steps,
  // max_frame_iterations and max_ipm_iterations >= 1. False with the reason in *why otherwise
  // (the solvers below throw InputError with it).
  bool is_valid(std::string* why = nullptr) const;
};

struct ConformalStats {
  int bisection_steps = 0;   // feasibility programs solved
  int frame_iterations = 0;
  int ipm_iterations = 0;
  // The largest level certified infeasible by the last bisection (measure units; NaN: none).
  // It bounds the frame-relative measure (qc: |b|/<a, r> as K) of every map, for that
  // bisection's frames only: not the measure itself, which is not convex.
  double frames_lower_bound = std::numeric_limits<double>::quiet_NaN();
  double bisection_time_s = 0, frame_time_s = 0;  // totals
};

// L-infinity minimizer from the map `start` (#V by 2; must be orientation-preserving on the
// active elements for the monotone guarantee: otherwise a first bisection from the level
// K = 1e6 (iso: S = 1e6) looks for an orientation-preserving map, and ends Infeasible when
// the convexified problem has none). Result.distortion = the measure per element;
// Result.lower_bound = NaN (no certified bound for the non-convex problem).
Result solve_conformal_linf(const Problem& problem, const Eigen::MatrixXd& start, const ConformalOptions& options,
                            ConformalStats* stats = nullptr);

// Direct strict minimizer (Algorithm 2) over solve_conformal_linf levels. direct.linf's
// element bounds are ignored; direct.delta_k and k_min are in measure units.
Result solve_conformal_direct(const Problem& problem, const Eigen::MatrixXd& start, const ConformalOptions& options,
                              const DirectOptions& direct, ConformalStats* stats = nullptr);

// The measure (qc or iso) of every element of the map X (+inf where det J <= 0). Throws
// InputError for a problem that fails check_problem or an X of another size.
Eigen::VectorXd conformal_distortion(const Problem& problem, Measure m, const Eigen::MatrixXd& X);

}  // namespace strictmin
