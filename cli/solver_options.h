#pragma once
// The --method option and every method's options, shared by all tasks.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "common.h"
#include "strictmin/measures/measures.h"
#include "strictmin/solvers/local_global.h"
#include "strictmin/tasks/method.h"

namespace strictmin::cli {

struct SolverArgs {
  std::string method = "l2";
  // linf
  double gap = 1e-8;
  int max_iterations = 100;
  bool linf_min_l2 = false;
  // lp, irls
  double p = 16;
  int irls_iterations = 50;
  // relax
  int sweeps = 50;
  double move_tolerance = 0;
  double accept_tolerance = 1e-4;
  std::string init = "linf";
  // direct, exact
  double delta_k = 1e-3;
  double k_min = 0.1;
  double level_gap = -1;  // direct: relative gap of the levels after the first (-1: delta_k / 100)
  bool no_pin = false;          // direct/exact: cones at the bounds instead of pinned elements
  bool level_cold_start = false;  // direct: every level's interior-point method from a centred dual
  double pin_threshold = 1e-4;  // direct: DirectOptions::pin_threshold
  int max_levels = 100000;  // direct: cap on the levels (DirectOptions::max_steps)
  int moving_rings = 2;   // direct: vertices within this many rings of the free elements move (0: all)
  int exact_max_elements = 3000;
  // qc, iso
  int frame_iterations = 50;
  const CLI::Option* frame_iterations_option = nullptr;  // set by add_solver_options
  // One method's own flags and their keys for option_not_read (set by add_solver_options).
  std::vector<std::pair<const CLI::Option*, std::string>> method_specific;
};

void add_solver_options(CLI::App& cmd, SolverArgs& args);
// Throws InputError when --frame-iterations was given but the run has no frame iterations
// (a measure other than qc or iso; no measure: a task without them, named `task`): it
// would be ignored.
void refuse_frame_iterations(const SolverArgs& args, const std::optional<Measure>& measure, const std::string& task);
// Throws InputError when a flag of one method (--p, --sweeps, --delta-k, ...) was given with
// another --method, which would ignore it. relax also reads the flags of its --init method.
void refuse_other_methods_flags(const SolverArgs& args);

// arap / asap local-global flags of deform and param, and --no-flips.
struct LocalGlobalArgs {
  int lg_iterations = 100;
  double lg_tolerance = 1e-4;
  int lg_acceleration = LocalGlobalOptions{}.acceleration_window;
  double lg_extrapolation = LocalGlobalOptions{}.target_extrapolation;
  bool lg_cold_start = false;
  bool no_flips = false;
  std::vector<const CLI::Option*> options;  // the local-global flags, set by the add_ functions (refuse_local_global_flags)
};
void add_local_global_options(CLI::App& cmd, LocalGlobalArgs& args);
// Only the steps' flags (--lg-acceleration, --lg-extrapolation, --lg-cold-start): gparam's arap.
void add_local_global_step_options(CLI::App& cmd, LocalGlobalArgs& args);
void apply_local_global_step_options(const LocalGlobalArgs& args, LocalGlobalOptions& options);
// Sets the local-global options from the flags (the caller sets no_flips on its task).
void apply_local_global_options(const LocalGlobalArgs& args, LocalGlobalOptions& options);
// Throws InputError naming the first local-global flag given when the measure takes no
// local steps (fd, qc, iso): it would be ignored.
// task_has_asap: false for gparam (no asap measure there: the message names arap alone).
void refuse_local_global_flags(const LocalGlobalArgs& args, Measure measure, bool task_has_asap = true);

// Parses the method names and wires progress reporting (stderr unless --quiet).
// Throws InputError for an unknown method.
// extra_names: a task's own names for --method / --init, listed first in the messages for
// unknown ones (param: "tutte, lscm").
SolverOptions make_solver_options(const SolverArgs& args, const OutputOptions& out, const std::string& extra_names = "");

}  // namespace strictmin::cli
