#include "strictmin/tasks/method.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "strictmin/io/input_error.h"
#include "strictmin/solvers/l2.h"
#include "../solvers/option_check.h"
#include "tasks/no_new_flips.h"

namespace strictmin {
namespace {

constexpr Method kMethods[] = {Method::L2,    Method::Linf,   Method::Lp,   Method::Irls,
                               Method::Relax, Method::Direct, Method::Exact};

}  // namespace

std::string method_name(Method m) {
  switch (m) {
    case Method::L2: return "l2";
    case Method::Linf: return "linf";
    case Method::Lp: return "lp";
    case Method::Irls: return "irls";
    case Method::Relax: return "relax";
    case Method::Direct: return "direct";
    case Method::Exact: return "exact";
  }
  return "?";
}

std::optional<Method> parse_method(const std::string& name) {
  for (Method m : kMethods)
    if (method_name(m) == name) return m;
  return std::nullopt;
}

std::string method_list() {
  std::string out;
  for (Method m : kMethods) out += (out.empty() ? "" : ", ") + method_name(m);
  return out;
}

std::string option_not_read(const std::string& key, Method method, Method relax_init) {
  static const std::vector<std::pair<std::vector<std::string>, std::vector<Method>>> owners{
      {{"linf_min_l2"}, {Method::Linf}},
      {{"p"}, {Method::Lp}},
      {{"irls_iterations"}, {Method::Irls}},
      {{"sweeps", "move_tolerance", "accept_tolerance"}, {Method::Relax}},
      {{"delta_k", "k_min", "level_gap", "max_levels", "warm_levels", "pin_threshold", "moving_rings"}, {Method::Direct}},
      {{"pin_essential"}, {Method::Direct, Method::Exact}},
      {{"exact_max_elements"}, {Method::Exact}},
  };
  for (const auto& [keys, methods] : owners) {
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) continue;
    const auto reads = [&](Method m) { return std::find(methods.begin(), methods.end(), m) != methods.end(); };
    if (reads(method) || (method == Method::Relax && reads(relax_init))) return "";
    std::string phrase;
    for (size_t i = 0; i < methods.size(); ++i) phrase += (i ? " or " : "") + method_name(methods[i]);
    const bool a_start = methods.size() == 1 && (methods[0] == Method::L2 || methods[0] == Method::Linf ||
                                                 methods[0] == Method::Lp || methods[0] == Method::Irls);
    if (a_start) phrase += " (or relax starting from " + method_name(methods[0]) + ")";
    return phrase;
  }
  return "";
}

bool SolverOptions::is_valid(std::string* why) const {
  return OptionCheck(why)
      .nested("linf", linf)
      .nested("lp", lp)
      .nested("irls", irls)
      .nested("relax", relax)
      .that(relax_init != Method::Relax && relax_init != Method::Direct && relax_init != Method::Exact,
            "relax_init must be l2, lp, irls or linf (got " + method_name(relax_init) + ")")
      .nested("direct", direct)
      .nested("exact", exact)
      .that(frame_iterations >= 1, "frame_iterations must be >= 1 (got " + std::to_string(frame_iterations) + ")")
      .ok();
}

Result run_method(const Problem& p, const SolverOptions& o) {
  std::string why;
  if (!o.is_valid(&why)) throw InputError("invalid solver options: " + why);
  switch (o.method) {
    case Method::L2: return solve_l2(p);
    case Method::Linf: return solve_linf(p, o.linf);
    case Method::Lp: return solve_lp(p, o.lp);
    case Method::Irls: return solve_irls(p, o.irls);
    case Method::Direct: return solve_direct(p, o.direct, o.linf);
    case Method::Exact: return solve_exact(p, o.exact, o.linf);
    case Method::Relax: {
      if (o.relax_init == Method::Relax) throw InputError("relax cannot start from relax (--init l2|lp|irls|linf)");
      SolverOptions init = o;
      init.method = o.relax_init;
      return relax_after(p, o, run_method(p, init));
    }
  }
  return solve_l2(p);
}

}  // namespace strictmin
