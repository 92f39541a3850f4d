#pragma once
// Keyword arguments -> the library's options, with the command-line tool's names and
// defaults (docs/python.md lists them per function).
#include <pybind11/pybind11.h>

#include <optional>
#include <string>

#include "strictmin/measures/measures.h"
#include "strictmin/solvers/local_global.h"
#include "strictmin/tasks/method.h"

namespace strictmin::python {

enum class Task { Deform, Param, Interp, GParam };

struct TaskOptions {
  Task task = Task::Deform;
  SolverOptions solver;
  LocalGlobalOptions local_global;
  std::string init;           // param: tutte (default) or lscm; relax: l2, lp, irls, linf
  std::string relax_init;     // relax's start (l2, lp, irls, linf) beside param's init
  bool no_flips = false;      // deform, param: as --no-flips
  std::string start = "l2";   // deform arap / asap: l2 or rest
  int pin = -1;               // interp: -1 the centroid, else a vertex
  std::string rotation_blend = "auto";  // interp: auto, logarithms or tree
  int threads = 0;            // 0: all cores
  std::string local_global_key;  // the first lg_* keyword given (refuse_local_global_keys)
  bool frame_iterations_given = false, start_given = false;  // refuse_measure_keys
};

// ValueError naming the first lg_* keyword given when the measure takes no local steps (fd,
// qc, iso): it would be ignored (as the command line refuses its --lg-* flags).
void refuse_local_global_keys(const TaskOptions& options, Measure measure);

// ValueError when frame_iterations is given without qc or iso (no measure: interp), or start
// (deform) without arap or asap: either would be ignored (as the command line refuses
// --frame-iterations and --start there).
void refuse_measure_keys(const TaskOptions& options, std::optional<Measure> measure);

// method: the CLI's --method; options: the other keywords. Unknown keywords raise
// TypeError, wrong types TypeError, values out of range ValueError naming the keyword and
// the library's reason (Options::is_valid), unknown method names ValueError.
TaskOptions parse_options(Task task, const std::string& function, const std::string& method,
                          const pybind11::dict& options);

// Sends every solver's iteration records (and the strict levels) to `callback` (a Python
// callable, borrowed: the caller keeps it alive during the solve), taking the GIL for each.
void wire_progress(TaskOptions& o, PyObject* callback);

}  // namespace strictmin::python
