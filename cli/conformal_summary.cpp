#include "conformal_summary.h"

#include "common.h"

namespace strictmin::cli {

void add_conformal_summary(nlohmann::json& s, const SolverOptions& o, const ConformalStats& stats) {
  if (o.method == Method::L2) s["start_only"] = true;  // l2 with qc / iso: the starting map
  s["bisection_steps"] = stats.bisection_steps;
  s["frame_iterations"] = stats.frame_iterations;
  s["ipm_iterations"] = stats.ipm_iterations;
  s["lower_bound"] = nullptr;
  s["frames_lower_bound"] = number_or_null(stats.frames_lower_bound);
  s["bisection_time_s"] = stats.bisection_time_s;
}

}  // namespace strictmin::cli
