#include "options.h"

#include <climits>
#include <cmath>

#include "convert.h"
#include "strictmin/io/input_error.h"
#include "strictmin/tasks/interp.h"
#include "io/text_parse.h"

namespace py = pybind11;

namespace strictmin::python {
namespace {

// "int", "str", ... for messages.
std::string type_name(py::handle v) { return py::str(v.get_type().attr("__name__")); }

double real(const std::string& key, py::handle v) {
  if (py::isinstance<py::bool_>(v) || py::isinstance<py::str>(v))
    throw py::type_error(key + " must be a number, not " + type_name(v));
  try {
    return v.cast<double>();
  } catch (const py::cast_error&) {
    throw py::type_error(key + " must be a number, not " + type_name(v));
  }
}

int integer(const std::string& key, py::handle v) {
  if (py::isinstance<py::bool_>(v) || py::isinstance<py::float_>(v) || py::isinstance<py::str>(v))
    throw py::type_error(key + " must be an integer, not " + type_name(v));
  long long x = 0;
  try {
    x = v.cast<long long>();
  } catch (const py::cast_error&) {
    // An int that does not fit (2**63) is out of range; anything else is not an integer.
    if (py::isinstance<py::int_>(v)) throw InputError(key + ": " + std::string(py::str(v)) + " is out of range");
    throw py::type_error(key + " must be an integer, not " + type_name(v));
  }
  if (x < INT_MIN || x > INT_MAX) throw InputError(key + ": " + std::to_string(x) + " is out of range");
  return static_cast<int>(x);
}

bool flag(const std::string& key, py::handle v) {
  if (!py::isinstance<py::bool_>(v)) throw py::type_error(key + " must be True or False, not " + type_name(v));
  return v.cast<bool>();
}

std::string text(const std::string& key, py::handle v) {
  if (!py::isinstance<py::str>(v)) throw py::type_error(key + " must be a string, not " + type_name(v));
  return v.cast<std::string>();
}

// One keyword onto the options; false when the task doesn't take it.
bool apply(TaskOptions& o, Task task, const std::string& key, py::handle v) {
  SolverOptions& s = o.solver;
  if (key == "gap") s.linf.gap_tolerance = real(key, v);
  else if (key == "max_iterations") s.linf.max_iterations = integer(key, v);
  else if (key == "linf_min_l2") s.linf.minimize_l2_among_optimal = flag(key, v);
  else if (key == "p") s.lp.p = real(key, v);
  else if (key == "irls_iterations") s.irls.iterations = integer(key, v);
  else if (key == "sweeps") s.relax.sweeps = integer(key, v);
  else if (key == "move_tolerance") s.relax.move_tolerance = real(key, v);
  else if (key == "accept_tolerance") s.relax.accept_tolerance = real(key, v);
  else if (key == "init") o.init = text(key, v);
  else if (key == "relax_init") o.relax_init = text(key, v);
  else if (key == "no_flips" && (task == Task::Deform || task == Task::Param)) o.no_flips = flag(key, v);
  else if (key == "max_levels") s.direct.max_steps = integer(key, v);
  else if (key == "delta_k") s.direct.delta_k = real(key, v);
  else if (key == "k_min") s.direct.k_min = real(key, v);
  else if (key == "level_gap") s.direct.level_gap = real(key, v);
  else if (key == "moving_rings") s.direct.moving_rings = integer(key, v);
  else if (key == "pin_essential") s.direct.pin_essential = s.exact.pin_essential = flag(key, v);
  else if (key == "pin_threshold") s.direct.pin_threshold = real(key, v);
  else if (key == "warm_levels") s.direct.warm_levels = flag(key, v);
  else if (key == "exact_max_elements") s.exact.max_elements = integer(key, v);
  else if (key == "frame_iterations") {
    s.frame_iterations = integer(key, v);
    o.frame_iterations_given = true;
  }
  else if (key == "threads") o.threads = integer(key, v);
  else if (key == "lg_iterations") o.local_global.max_iterations = integer(key, v);
  else if (key == "lg_tolerance") o.local_global.relative_change = real(key, v);
  else if (key == "lg_acceleration") o.local_global.acceleration_window = integer(key, v);
  else if (key == "lg_extrapolation" && task != Task::Interp)  // interp's targets are its blended shapes
    o.local_global.target_extrapolation = real(key, v);
  else if (key == "lg_warm_start") o.local_global.warm_start = flag(key, v);
  else if (key == "lg_cold_start") o.local_global.warm_start = !flag(key, v);  // the flag's own name
  else if (key == "start" && task == Task::Deform) {
    o.start = text(key, v);
    o.start_given = true;
  }
  else if (key == "rotation_blend" && task == Task::Interp) o.rotation_blend = text(key, v);
  else if (key == "pin" && task == Task::Interp) {
    if (py::isinstance<py::str>(v)) {
      if (text(key, v) != "centroid")
        throw InputError("pin takes 'centroid' or a vertex index (0-based), not '" + text(key, v) + "'");
      o.pin = -1;
    } else {
      o.pin = integer(key, v);
      if (o.pin < 0) throw InputError("pin takes 'centroid' or a vertex index (0-based), not " + std::to_string(o.pin));
    }
  } else
    return false;
  return true;
}

// The checks the command line makes beyond the options' own is_valid.
void check_task_ranges(const TaskOptions& o, Task task, const std::string& key) {
  if (key == "threads" && o.threads < 0) throw InputError("threads must be >= 0 (got " + std::to_string(o.threads) + ")");
  if (key == "lg_iterations" && task != Task::Interp && o.local_global.max_iterations < 1)
    throw InputError("lg_iterations must be >= 1 (got " + std::to_string(o.local_global.max_iterations) + ")");
  if (key == "lg_tolerance" && !(o.local_global.relative_change >= 0))
    throw InputError("lg_tolerance must be >= 0 (got " + io_detail::number_text(o.local_global.relative_change) + ")");
}

}  // namespace

void refuse_local_global_keys(const TaskOptions& o, Measure measure) {
  if (o.local_global_key.empty() || measure == Measure::Arap || measure == Measure::Asap) return;
  throw InputError(o.local_global_key +
                   (o.task == Task::GParam ? " applies to measure 'arap' (its local-global iterations), not '"
                                           : " applies to measure 'arap' or 'asap' (their local-global iterations), not '") +
                   measure_name(measure) + "', which takes no local steps");
}

void refuse_measure_keys(const TaskOptions& o, std::optional<Measure> measure) {
  if (o.frame_iterations_given && !(measure && (*measure == Measure::Quasiconformal || *measure == Measure::Isometric)))
    throw InputError("frame_iterations applies to measure 'qc' or 'iso' (their frame iterations), not " +
                     (measure ? "'" + measure_name(*measure) + "', which has none" : std::string("interp")));
  if (o.frame_iterations_given && o.solver.method == Method::L2)
    throw InputError("frame_iterations applies to method 'linf' or 'direct' with measure '" + measure_name(*measure) +
                     "'; method 'l2' is their starting map, with no frame iterations");
  if (o.start_given && !(measure && (*measure == Measure::Arap || *measure == Measure::Asap)))
    throw InputError("start applies to measure 'arap' or 'asap' (the start of their local-global iterations), not '" +
                     (measure ? measure_name(*measure) : std::string("?")) + "'");
}

TaskOptions parse_options(Task task, const std::string& function, const std::string& method,
                          const py::dict& options) {
  TaskOptions o;
  o.task = task;
  if (task == Task::Interp) o.solver.direct.k_min = kInterpKMin;  // interp's own default (interp.h)
  for (const auto& [k, v] : options) {
    const std::string key = py::str(k);
    if (key.rfind("lg_", 0) == 0 && o.local_global_key.empty()) o.local_global_key = key;
    if (!apply(o, task, key, v))
      throw py::type_error(function + "() got an unexpected keyword argument '" + key + "'");
    std::string why;
    if (!o.solver.is_valid(&why) || !o.local_global.is_valid(&why)) throw InputError(key + ": " + why);
    check_task_ranges(o, task, key);
  }
  std::string m = method;
  if (task == Task::Param && (m == "tutte" || m == "lscm")) m = "l2";  // the starting map itself
  const auto parsed = parse_method(m);
  if (!parsed) throw InputError("unknown method '" + method + "' (use one of: " + method_list() + ")");
  o.solver.method = *parsed;
  // relax's start: relax_init, else init when it names a method (param's init may name the
  // starting map instead), else linf.
  std::string relax_init = !o.relax_init.empty() ? o.relax_init : o.init.empty() ? "linf" : o.init;
  if (task == Task::Param && o.relax_init.empty() && (relax_init == "tutte" || relax_init == "lscm"))
    relax_init = "linf";
  const auto init = parse_method(relax_init);
  if (!init || *init == Method::Relax || *init == Method::Direct || *init == Method::Exact) {
    if (!o.relax_init.empty())
      throw InputError("unknown relax_init '" + o.relax_init + "' (use l2, lp, irls or linf)");
    throw InputError("unknown init '" + o.init + "' (use " + (task == Task::Param ? "tutte, lscm, " : "") +
                     "l2, lp, irls or linf)");
  }
  if (task == Task::Param && !o.init.empty() && o.init != "tutte" && o.init != "lscm" && !o.relax_init.empty())
    throw InputError("init names the starting map (tutte or lscm) when relax_init is given, not '" + o.init + "'");
  o.solver.relax_init = *init;
  if (o.start != "l2" && o.start != "rest") throw InputError("unknown start '" + o.start + "' (use l2 or rest)");
  // A method's own keyword given with another method would be ignored (as the command line
  // refuses its flag).
  for (const auto& item : options) {
    const std::string key = py::str(item.first);
    const std::string readers = option_not_read(key, o.solver.method, o.solver.relax_init);
    if (!readers.empty())
      throw InputError(key + " applies to method " + readers + "; method '" + method + "' does not read it");
  }
  return o;
}

void wire_progress(TaskOptions& o, PyObject* callback) {
  if (!callback) return;
  auto records = [callback](const char* stage) {
    return [callback, stage](const IterationRecord& r) {
      py::gil_scoped_acquire gil;
      const py::handle function(callback);
      function(record_dict(r, stage));
    };
  };
  // (With l2 its only cone programs are no_flips's steps inside the orientation cones.)
  o.solver.linf.progress = records(o.solver.method == Method::L2 ? "l2-no-flip-steps" : "linf");
  o.solver.lp.progress = records("lp");
  o.solver.irls.progress = records("irls");
  o.solver.relax.progress = records("relax");
  o.local_global.progress = records("local-global");
  auto steps = [callback](const StrictStep& s) {
    py::gil_scoped_acquire gil;
    const py::handle function(callback);
    function(step_dict(s));
  };
  o.solver.direct.progress = steps;
  o.solver.exact.progress = steps;
}

}  // namespace strictmin::python
