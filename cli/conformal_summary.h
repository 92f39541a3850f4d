#pragma once
// Summary keys of the Section 7 measures (qc, iso) for deform and param.
#include <nlohmann/json.hpp>

#include "strictmin/solvers/conformal.h"
#include "strictmin/tasks/method.h"

namespace strictmin::cli {

// bisection_steps, frame_iterations, ipm_iterations, frames_lower_bound (the frame-relative
// bound of the last frames: not a bound on the measure), lower_bound = null (none is
// certified for the non-convex measure).
void add_conformal_summary(nlohmann::json& s, const SolverOptions& o, const ConformalStats& stats);

}  // namespace strictmin::cli
