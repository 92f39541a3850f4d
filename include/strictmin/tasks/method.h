#pragma once
// The optimization methods every task can run, their options, and one dispatch.
#include <optional>
#include <string>

#include "strictmin/problem/problem.h"
#include "strictmin/solvers/irls.h"
#include "strictmin/solvers/linf.h"
#include "strictmin/solvers/lp.h"
#include "strictmin/solvers/relax.h"
#include "strictmin/solvers/result.h"
#include "strictmin/solvers/strict.h"

namespace strictmin {

enum class Method { L2, Linf, Lp, Irls, Relax, Direct, Exact };

std::string method_name(Method m);  // "l2", "linf", "lp", "irls", "relax", "direct", "exact"
std::optional<Method> parse_method(const std::string& name);
std::string method_list();  // for help and error messages

// A method's own option, which the other methods ignore: empty when `key` (the Python keyword
// spelling: "p", "sweeps", "delta_k", "pin_essential", ...) is read by every method or is no
// method's own. Otherwise, "" when `method` reads it (relax also reads the options of the
// method it starts from, relax_init), else a phrase naming the methods that do, "lp (or
// relax starting from lp)", for the message refusing it.
std::string option_not_read(const std::string& key, Method method, Method relax_init);

struct SolverOptions {
  Method method = Method::L2;
  LinfOptions linf;
  LpOptions lp;
  IrlsOptions irls;
  RelaxOptions relax;
  Method relax_init = Method::Linf;  // relax starts from this method's result (not relax itself)
  DirectOptions direct;  // with linf's tolerances for every level
  ExactOptions exact;    // with linf's tolerances for every level
  // --measure qc / iso (conformal.h): the cap on frame iterations (>= 1); their bracket is
  // linf.gap_tolerance (relative).
  int frame_iterations = 50;

  // Every nested options struct valid and relax_init one of l2, lp, irls, linf; otherwise
  // false with the reason (prefixed by the struct: "direct.delta_k must be > 0 (got 0)").
  bool is_valid(std::string* why = nullptr) const;
};

// Runs options.method on the problem, from problem.positions. For relax, the result's
// iterations are the sweeps and time_s includes the initial solve. Throws InputError when
// the options are not valid.
Result run_method(const Problem& problem, const SolverOptions& options);

}  // namespace strictmin
