#include "tasks/no_new_flips.h"

#include "solvers/no_flips_linf.h"
#include "strictmin/io/input_error.h"
#include "strictmin/solvers/no_flips.h"
#include "strictmin/solvers/relax.h"

namespace strictmin {

Result relax_after(const Problem& p, const SolverOptions& o, const Result& start) {
  if (!start.usable()) return start;
  Result r = relax(p, start.positions, o.relax);
  r.time_s += start.time_s;
  r.lower_bound = start.lower_bound;
  if (!start.ok()) {  // the start's shortfall stays visible
    r.status = worse_status(r.status, start.status);
    r.message = "initial " + method_name(o.relax_init) + ": " + start.message + "; " + r.message;
  }
  return r;
}

Result relax_without_new_flips(const Problem& p, const Eigen::MatrixXd& start_map, const SolverOptions& o) {
  if (o.relax_init == Method::Relax) throw InputError("relax cannot start from relax (--init l2|lp|irls|linf)");
  SolverOptions init = o;
  init.method = o.relax_init;
  Result start = run_method(p, init);
  if (!start.usable()) return start;
  SolverOptions sweeps = o;
  sweeps.relax.no_flips = true;
  // First the sweeps from the start method's own map, inside the kernels of its positive
  // elements: its flipped ones are free to turn back, and when none is left flipped (against
  // start_map) that map is the answer. It can be the better one: the steps below stay near
  // flip-free maps all the way (a squeezed, turned tet bar: 2.000 here, 2.457 there).
  if (flips_added(p, start_map, start.positions) > 0) {
    Result swept = relax_after(p, sweeps, start);
    if (swept.usable() && flips_added(p, start_map, swept.positions) == 0) {
      swept.message = "no flip left by the sweeps from the start method's map; " + swept.message;
      return swept;
    }
  }
  remove_added_flips(p, start_map, init.method, init.linf, start);
  Result r = relax_after(p, sweeps, start);
  // How the start was made flip-free (relax_after says it only for a start that fell short).
  if (start.ok()) r.message = "initial " + method_name(init.method) + ": " + start.message + "; " + r.message;
  return r;
}

Result run_method_without_new_flips(const Problem& p, const Eigen::MatrixXd& start_map, const SolverOptions& o) {
  if (o.method == Method::Relax) return relax_without_new_flips(p, start_map, o);
  Result r = run_method(p, o);
  remove_added_flips(p, start_map, o.method, o.linf, r);
  return r;
}

}  // namespace strictmin
