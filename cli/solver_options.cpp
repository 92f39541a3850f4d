#include "solver_options.h"

#include <cstdio>

#include "strictmin/io/input_error.h"

namespace strictmin::cli {
void add_solver_options(CLI::App& cmd, SolverArgs& a) {
  cmd.add_option("--method", a.method,
                 "l2 (least squares: fast, concentrates distortion), linf (least maximum, certified), "
                 "relax / direct / exact (strict minimizer: least maximum, then least area at each lower level), "
                 "lp / irls (the baselines)")
      ->capture_default_str();
  auto* g = cmd.add_option_group("Method options");
  g->add_option("--gap", a.gap, "linf: stop at this certified relative gap, in (0, 1)")
      ->capture_default_str()
      ->check(open_range(0, 1));
  g->add_option("--max-iterations", a.max_iterations, "linf: interior-point iteration cap (>= 1)")
      ->capture_default_str()
      ->check(at_least(1));
  a.method_specific.push_back({g->add_flag("--linf-min-l2", a.linf_min_l2,
              "linf: among the L-infinity optima, return the one with the least L2 distortion (a second solve)"), "linf_min_l2"});
  a.method_specific.push_back({g->add_option("--p", a.p, "lp: the exponent p (>= 2)")->capture_default_str()->check(at_least(2)), "p"});
  a.method_specific.push_back({g->add_option("--irls-iterations", a.irls_iterations, "irls: number of reweighted solves (>= 1)")
      ->capture_default_str()
      ->check(at_least(1)), "irls_iterations"});
  a.method_specific.push_back({g->add_option("--sweeps", a.sweeps, "relax: number of sweeps over the vertices (>= 0)")
      ->capture_default_str()
      ->check(at_least(0)), "sweeps"});
  a.method_specific.push_back({g->add_option("--move-tolerance", a.move_tolerance,
                "relax: stop when no vertex moves more than this (>= 0; 0: run every sweep)")
      ->capture_default_str()
      ->check(at_least(0)), "move_tolerance"});
  a.method_specific.push_back({g->add_option("--accept-tolerance", a.accept_tolerance,
                "relax: a move must improve its ring in the strict order with values within this fraction of "
                "the ring maximum counted as equal (0: any decrease of the ring maximum)")
      ->capture_default_str()
      ->check(half_open_range(0, 1)), "accept_tolerance"});
  g->add_option("--init", a.init, "relax: start from l2, lp, irls or linf")->capture_default_str();
  a.method_specific.push_back({g->add_option("--delta-k", a.delta_k, "direct: fix elements within this of each level's optimum (> 0)")
      ->capture_default_str()
      ->check(greater_than(0)), "delta_k"});
  a.method_specific.push_back({g->add_option("--k-min", a.k_min, "direct: stop when the level falls below this (>= 0)")
      ->capture_default_str()
      ->check(at_least(0)), "k_min"});
  a.method_specific.push_back({g->add_option("--level-gap", a.level_gap,
                "direct: relative gap at which the levels after the first stop (negative, the default -1: delta-k / 100; the "
                "first level uses --gap; below 1)")
      ->capture_default_str()
      ->check(less_than(1)), "level_gap"});
  a.method_specific.push_back({g->add_option("--max-levels", a.max_levels,
                "direct: stop after this many levels (status max-iterations if elements are still free above "
                "k-min; >= 1)")
      ->capture_default_str()
      ->check(at_least(1)), "max_levels"});
  a.method_specific.push_back({g->add_flag("--no-pin", a.no_pin,
             "direct/exact: keep essential elements as cones at their bounds instead of pinning their Jacobians "
             "(the behaviour before pinning; the later levels then depend on the bounds' slack)"), "pin_essential"});
  a.method_specific.push_back({g->add_flag("--level-cold-start", a.level_cold_start,
              "direct: start every level's interior-point method afresh (default: from the previous level's dual, "
              "element by element)"), "warm_levels"});
  a.method_specific.push_back({g->add_option("--pin-threshold", a.pin_threshold,
                "direct: pin an element when its certificate multiplier is at least this (multipliers sum to 1; "
                "in (0, 1])")
      ->capture_default_str()
      ->check(greater_than(0))
      ->check(CLI::Range(0.0, 1.0)), "pin_threshold"});
  a.method_specific.push_back({g->add_option("--moving-rings", a.moving_rings,
                "direct: levels after the first move only the vertices within this many rings of the elements "
                "still free, the rest stays (0: every vertex at every level, the paper's Algorithm 2 as stated)")
      ->capture_default_str()
      ->check(at_least(0)), "moving_rings"});
  a.frame_iterations_option = g->add_option("--frame-iterations", a.frame_iterations,
                "qc/iso: cap on frame iterations (each a level program or bisection for the current frames; >= 1)")
      ->capture_default_str()
      ->check(at_least(1));
  a.method_specific.push_back({g->add_option("--exact-max-elements", a.exact_max_elements, "exact: refuse meshes larger than this (>= 1)")
      ->capture_default_str()
      ->check(at_least(1)), "exact_max_elements"});
}

void refuse_frame_iterations(const SolverArgs& a, const std::optional<Measure>& measure, const std::string& task) {
  if (!given(a.frame_iterations_option)) return;
  if (measure && (*measure == Measure::Quasiconformal || *measure == Measure::Isometric)) {
    if (a.method != "l2") return;
    throw InputError("--frame-iterations applies to --method linf or direct with --measure " + measure_name(*measure) +
                     "; --method l2 is their starting map, with no frame iterations");
  }
  throw InputError("--frame-iterations applies to --measure qc or iso (their frame iterations), not " +
                   (measure ? measure_name(*measure) + ", which has none" : task + ", which has no such measure"));
}

void add_local_global_step_options(CLI::App& cmd, LocalGlobalArgs& a) {
  a.options.push_back(cmd.add_option("--lg-acceleration", a.lg_acceleration,
                  "arap/asap: Anderson acceleration window of local-global (0: off); an accelerated step is "
                  "taken only when it does not raise the maximum (l2: the energy)")
      ->capture_default_str()
      ->check(CLI::Range(0, 50)));
  a.options.push_back(cmd.add_option("--lg-extrapolation", a.lg_extrapolation,
                  "arap/asap: extrapolate each target along its last change by this factor before a global step "
                  "(a momentum on the rotations, 0: off); a step that raises the maximum is repeated without")
      ->capture_default_str()
      ->check(at_least(0))  // 0: off; at_least also refuses nan
      ->check(CLI::Range(0.0, 1.0)));
  a.options.push_back(cmd.add_flag("--lg-cold-start", a.lg_cold_start,
                "arap/asap with linf/direct: start every global step's interior-point method afresh (default: from "
                "the previous step's dual)"));
}

void add_local_global_options(CLI::App& cmd, LocalGlobalArgs& a) {
  a.options.push_back(cmd.add_option("--lg-iterations", a.lg_iterations, "arap/asap: local-global iteration cap (>= 1)")
      ->capture_default_str()
      ->check(at_least(1)));
  a.options.push_back(cmd.add_option("--lg-tolerance", a.lg_tolerance,
                  "arap/asap: stop when the maximum (l2: its energy) changes by less than this (relative, >= 0)")
      ->capture_default_str()
      ->check(at_least(0)));
  add_local_global_step_options(cmd, a);
  cmd.add_flag("--no-flips", a.no_flips,
                "planar/disk and tet maps: add no flipped element to the start (linf steps inside orientation-preserving "
                "cones on planar maps, other steps cut back, relax moves "
                "kept in their rings' kernels); the summary's flips_added counts them. Refused on a triangle surface "
                "in 3D (a 3x2 Jacobian has no orientation)");
}

void apply_local_global_step_options(const LocalGlobalArgs& a, LocalGlobalOptions& o) {
  o.acceleration_window = a.lg_acceleration;
  o.target_extrapolation = a.lg_extrapolation;
  o.warm_start = !a.lg_cold_start;
}

void apply_local_global_options(const LocalGlobalArgs& a, LocalGlobalOptions& o) {
  o.max_iterations = a.lg_iterations;
  o.relative_change = a.lg_tolerance;
  apply_local_global_step_options(a, o);
}

void refuse_local_global_flags(const LocalGlobalArgs& a, Measure measure, bool task_has_asap) {
  if (measure == Measure::Arap || measure == Measure::Asap) return;
  for (const CLI::Option* option : a.options)
    if (given(option))
      throw InputError(option->get_name() +
                       (task_has_asap ? " applies to --measure arap or asap (their local-global iterations), not "
                                      : " applies to --measure arap (its local-global iterations), not ") +
                       measure_name(measure) + ", which takes no local steps");
}

void refuse_other_methods_flags(const SolverArgs& a) {
  const auto parsed = parse_method(a.method), init = parse_method(a.init);
  const bool starting_map = a.method == "tutte" || a.method == "lscm";  // param's: they read none of these
  if (!parsed && !starting_map) return;  // an unknown method: said by make_solver_options
  const Method method = parsed ? *parsed : Method::L2;  // l2 reads none of them either
  for (const auto& [option, key] : a.method_specific) {
    if (!given(option)) continue;
    const std::string readers = option_not_read(key, method, init ? *init : Method::Linf);
    if (!readers.empty())
      throw InputError(option->get_name() + " applies to --method " + readers + "; --method " + a.method +
                       " does not read it");
  }
}

SolverOptions make_solver_options(const SolverArgs& a, const OutputOptions& out, const std::string& extra_names) {
  SolverOptions o;
  const std::string extra = extra_names.empty() ? "" : extra_names + ", ";
  const auto method = parse_method(a.method);
  if (!method)
    throw InputError("--method: unknown method '" + a.method + "' (use " + extra + (extra.empty() ? "" : "or ") +
                     "one of: " + method_list() + ")");
  const auto init = parse_method(a.init);
  if (!init || *init == Method::Relax || *init == Method::Direct || *init == Method::Exact)
    throw InputError("unknown --init '" + a.init + "' (use " + extra + "l2, lp, irls or linf)");
  o.method = *method;
  o.relax_init = *init;
  o.linf.gap_tolerance = a.gap;
  o.linf.max_iterations = a.max_iterations;
  o.linf.minimize_l2_among_optimal = a.linf_min_l2;
  o.lp.p = a.p;
  o.irls.iterations = a.irls_iterations;
  o.relax.sweeps = a.sweeps;
  o.relax.move_tolerance = a.move_tolerance;
  o.relax.accept_tolerance = a.accept_tolerance;
  o.direct.delta_k = a.delta_k;
  o.direct.k_min = a.k_min;
  o.direct.level_gap = a.level_gap;
  o.direct.moving_rings = a.moving_rings;
  o.direct.max_steps = a.max_levels;
  o.direct.pin_essential = !a.no_pin;
  o.direct.warm_levels = !a.level_cold_start;
  o.direct.pin_threshold = a.pin_threshold;
  o.exact.pin_essential = !a.no_pin;
  o.exact.max_elements = a.exact_max_elements;
  o.frame_iterations = a.frame_iterations;
  if (!out.quiet) {
    // (With l2 its only cone programs are --no-flips's steps inside the orientation cones.)
    if (o.method == Method::L2)
      o.linf.progress = [](const IterationRecord& r) { print_iteration("  l2 no-flip step", r); };
    else
      o.linf.progress = [](const IterationRecord& r) { print_iteration("  linf  iter", r); };
    o.lp.progress = [](const IterationRecord& r) { print_iteration("  lp    iter", r); };
    o.irls.progress = [](const IterationRecord& r) { print_iteration("  irls  iter", r); };
    o.relax.progress = [](const IterationRecord& r) { print_iteration("  relax sweep", r); };
    auto strict_progress = [](const StrictStep& s) {
      std::fprintf(stderr, "  strict step %3d  k %.8g  fixed %d (total %d)  solves %d", s.step, s.k, s.fixed_now,
                   s.fixed_total, s.solves);
      if (s.level_free_vertices >= 0) std::fprintf(stderr, "  moving vertices %d", s.level_free_vertices);
      if (s.pinned_total > 0) std::fprintf(stderr, "  pinned %d", s.pinned_total);
      if (s.level_iterations > 0) std::fprintf(stderr, "  %d %s", s.level_iterations, s.level_iteration_unit.c_str());
      std::fprintf(stderr, "  %.2f s\n", s.time_s);
    };
    o.direct.progress = strict_progress;
    o.exact.progress = strict_progress;
  }
  return o;
}

}  // namespace strictmin::cli
