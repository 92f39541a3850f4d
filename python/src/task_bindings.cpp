// deform, param, interp, gparam: options from keywords, the solve on a worker thread without the
// GIL (run_released.h), the result as a dict with the command line's summary.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include "strictmin/version.h"
#include "bindings.h"
#include "convert.h"
#include "options.h"
#include "run_released.h"
#include "strictmin/io/input_error.h"
#include "report/summary.h"  // private (src/): the CLI and the Python module
#include "strictmin/solvers/timing.h"
#include "strictmin/tasks/deform.h"
#include "strictmin/tasks/gparam.h"
#include "strictmin/tasks/interp.h"
#include "strictmin/tasks/param.h"
#include "io/text_parse.h"

// OpenBLAS's thread control, when CHOLMOD runs on OpenBLAS (weak: absent with other BLAS).
extern "C" void openblas_set_num_threads(int) __attribute__((weak));

namespace py = pybind11;

namespace strictmin::python {
namespace {

using Clock = std::chrono::steady_clock;

// Limits TBB (and OpenBLAS) to `threads` while alive; 0 leaves the defaults.
std::unique_ptr<tbb::global_control> limit_threads(int threads) {
  if (threads <= 0) return nullptr;
  if (openblas_set_num_threads) openblas_set_num_threads(threads);
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               static_cast<size_t>(threads));
}

PyObject* callback_or_null(const py::object& progress) { return progress.is_none() ? nullptr : progress.ptr(); }

// What every task's result shares. `map_key`: "positions" or "uv".
py::dict result_dict(const Result& r, const char* map_key, const Eigen::MatrixXd& map, const Eigen::VectorXd& distortion,
                     const Eigen::VectorXd& weights, const char* stage, const nlohmann::json& summary) {
  py::dict out;
  out[map_key] = RowMatrixXd(map);
  out["distortion"] = distortion;
  out["weights"] = weights;
  out["status"] = status_name(r.status);
  out["usable"] = r.usable();
  out["message"] = r.message;
  out["iterations"] = r.iterations;
  // As in the summary: under arap / asap the global steps' certified bound is for field
  // deviation with their rotations fixed, not a bound on the measure reported.
  const bool local_global = std::string(stage) == "local-global";
  out["lower_bound"] = local_global ? kNotApplicable : r.lower_bound;
  out["fd_step_lower_bound"] = local_global ? r.lower_bound : kNotApplicable;
  py::list history;
  for (const IterationRecord& h : r.history) history.append(record_dict(h, stage));
  out["history"] = history;
  out["time_s"] = r.time_s;
  out["summary"] = to_python(summary);
  return out;
}

const char* history_stage(const SolverOptions& s, bool local_global) {
  if (local_global) return "local-global";
  switch (s.method) {
    case Method::Direct:
    case Method::Exact: return "strict";
    case Method::Relax: return "relax";
    case Method::Lp: return "lp";
    case Method::Irls: return "irls";
    case Method::Linf: return "linf";
    case Method::L2: return "l2";
  }
  return "";
}

Measure measure_of(const std::string& name) {
  const auto m = parse_measure(name);
  if (!m) throw InputError("unknown measure '" + name + "' (use fd, arap, asap, qc or iso)");
  return *m;
}

py::dict deform_py(const RowMatrixXd& V, const RowMatrixXi& F, const Eigen::VectorXi& handle_indices,
                   const RowMatrixXd& handle_positions, const std::string& method, const std::string& measure,
                   const py::dict& kwargs, const py::object& progress) {
  const auto t0 = Clock::now();
  TaskOptions o = parse_options(Task::Deform, "deform", method, kwargs);
  DeformOptions options;
  options.measure = measure_of(measure);
  refuse_local_global_keys(o, options.measure);
  refuse_measure_keys(o, options.measure);
  const Mesh mesh = make_mesh(V, F, "mesh", true, nullptr);
  // Tets and triangle surfaces in 3D move in 3D; planar triangles in 2D (as the CLI).
  const int dim = mesh.element_type() == ElementType::Tetrahedron || !mesh.is_planar() ? 3 : 2;
  const std::vector<Handle> handles = make_handles(handle_indices, handle_positions, mesh.num_vertices(), dim);
  wire_progress(o, callback_or_null(progress));
  options.solver = o.solver;
  options.local_global = o.local_global;
  options.start = o.start == "l2" ? DeformStart::L2 : DeformStart::Rest;
  options.no_flips = o.no_flips;
  std::optional<DeformOutcome> d;
  run_released([&] {
    const auto threads = limit_threads(o.threads);
    d = deform(mesh, handles, options);
  });
  nlohmann::json s = deform_summary(mesh, handles.size(), options, *d, {});
  s["time_s"] = seconds_since(t0);
  add_provenance_summary(s);
  const bool lg = options.measure == Measure::Arap || options.measure == Measure::Asap;
  py::dict out = result_dict(d->result, "positions", d->deformed.V, d->measured.distortion, d->measured.weights,
                             history_stage(options.solver, lg), s);
  out["flipped"] = d->measured.flipped;
  return out;
}

py::dict param_py(const RowMatrixXd& V, const RowMatrixXi& F, const std::string& method, const std::string& measure,
                  const py::dict& kwargs, const py::object& progress) {
  const auto t0 = Clock::now();
  TaskOptions o = parse_options(Task::Param, "param", method, kwargs);
  ParamOptions options;
  options.measure = measure_of(measure);
  refuse_local_global_keys(o, options.measure);
  refuse_measure_keys(o, options.measure);
  // init names the starting map (tutte, lscm); a method name there is relax's start.
  if ((method == "tutte" || method == "lscm") && (o.init == "tutte" || o.init == "lscm") && o.init != method)
    throw InputError("init='" + o.init + "' contradicts method='" + method + "': that method is the " + method +
                     " starting map itself (give method='" + o.init + "', or init='" + method + "')");
  if (o.init == "lscm") options.init = ParamInit::Lscm;
  if (method == "tutte" || method == "lscm") {
    options.init = method == "tutte" ? ParamInit::Tutte : ParamInit::Lscm;
    options.init_only = true;
  }
  const Mesh mesh = make_mesh(V, F, "mesh", true, nullptr);
  wire_progress(o, callback_or_null(progress));
  options.solver = o.solver;
  options.local_global = o.local_global;
  options.no_flips = o.no_flips;
  std::optional<ParamOutcome> p;
  run_released([&] {
    const auto threads = limit_threads(o.threads);
    p = parametrize(mesh, options, "mesh");
  });
  nlohmann::json s = param_summary(mesh, options, *p, {});
  s["time_s"] = seconds_since(t0);
  add_provenance_summary(s);
  const bool lg = !options.init_only && options.measure != Measure::FieldDeviation;
  py::dict out = result_dict(p->result, "uv", p->result.positions, p->measured.distortion, p->measured.weights,
                             history_stage(options.solver, lg), s);
  out["flipped"] = p->measured.flipped;
  out["flips"] = p->flips;
  out["boundary"] = p->boundary;
  out["boundary_overlap"] = p->boundary_overlap;
  out["warnings"] = p->warnings;
  out["initial"] = RowMatrixXd(p->initial);
  return out;
}

// The library names its options by their command-line flags where only it can check them
// (an edge length out of the surface's scale, which needs the surface's area): here they are
// keywords.
std::string with_keyword_names(std::string message) {
  const std::string flag = "--edge-length";
  if (message.rfind(flag, 0) == 0) message.replace(0, flag.size(), "edge_length");
  return message;
}

// integer_grid=True: the rounding's account as attributes, as the docstring says (the
// summary's keys of the same names).
void add_integer_grid_attributes(py::dict& out, const GParamOutcome& g) {
  out["integer_error"] = g.integer_error;
  out["rounded_singularities"] = g.rounding.singularities;
  out["rounded_translations"] = g.rounding.translations;
  out["off_grid_singularities"] = g.rounding.singularities_off_grid;
  out["off_grid_translations"] = g.rounding.translations_off_grid;
}

// field_name: "smoothest", "unit", "curvature" or "given" (then `directions`, #F by 3).
// edge_length / quads: None for the default (about 1000 unit squares).
py::dict gparam_py(const RowMatrixXd& V, const RowMatrixXi& F, const std::string& method, const std::string& measure,
                   const std::string& field_name, const std::optional<RowMatrixXd>& directions,
                   const std::optional<double>& edge_length, const std::optional<int>& quads,
                   double curvature_alignment, bool parallel, const std::optional<std::vector<int>>& cones,
                   bool integer_grid, const std::string& grid_guide, const py::dict& kwargs,
                   const py::object& progress) {
  const auto t0 = Clock::now();
  TaskOptions o = parse_options(Task::GParam, "gparam", method, kwargs);
  GParamOptions options;
  const auto m = parse_measure(measure);
  if (!m || (*m != Measure::FieldDeviation && *m != Measure::Arap))
    throw InputError("unknown or unavailable measure '" + measure + "' for gparam (use fd or arap)");
  options.measure = *m;
  refuse_local_global_keys(o, options.measure);
  refuse_measure_keys(o, options.measure);
  if (edge_length && quads) throw InputError("give edge_length or quads, not both");
  if (edge_length && !(*edge_length > 0 && std::isfinite(*edge_length)))
    throw InputError("edge_length must be a positive finite number, got " + io_detail::number_text(*edge_length));
  if (quads && *quads <= 0) throw InputError("quads must be positive, got " + std::to_string(*quads));
  if (edge_length) options.edge_length = *edge_length;
  if (quads) options.quads = *quads;
  if (!(curvature_alignment > 0 && std::isfinite(curvature_alignment)))
    throw InputError("curvature_alignment must be a positive number, got " + io_detail::number_text(curvature_alignment));
  options.curvature_alignment = curvature_alignment;
  if (field_name != "smoothest" && field_name != "unit" && field_name != "curvature" && field_name != "given")
    throw InputError("field takes 'smoothest', 'unit', 'curvature' or a #F by 3 array of directions, not '" + field_name + "'");
  options.curvature_field = field_name == "curvature";
  options.field_options.unit = field_name == "unit";
  options.parallel_field = parallel;
  options.integer_grid = integer_grid;
  if (grid_guide != "l2" && grid_guide != "linf")
    throw InputError("grid_guide takes 'l2' or 'linf', not '" + grid_guide + "'");
  options.grid_guide = grid_guide == "linf" ? GParamOptions::GridGuide::Linf : GParamOptions::GridGuide::L2;
  if (cones) {
    if (field_name != "smoothest") throw InputError("give cones or field, not both");
    options.cones = *cones;
    options.field_source = "cones";
  }
  const Mesh mesh = make_mesh(V, F, "mesh", true, nullptr);
  if (field_name == "given") {
    if (!directions) throw InputError("field: no directions given");
    options.field = Eigen::MatrixXd(*directions);
    options.field_source = "field";
  }
  PyObject* callback = callback_or_null(progress);
  wire_progress(o, callback);
  if (callback)
    options.progress = [callback](const std::string& line) {
      py::gil_scoped_acquire gil;
      py::dict record;
      record["stage"] = "gparam";
      record["message"] = line;
      const py::handle function(callback);
      function(record);
    };
  options.solver = o.solver;
  options.local_global = o.local_global;
  std::optional<GParamOutcome> g;
  try {
    run_released([&] {
      const auto threads = limit_threads(o.threads);
      g = global_parametrize(mesh, options, "mesh");
    });
  } catch (const InputError& e) {
    throw InputError(with_keyword_names(e.what()));
  }
  nlohmann::json s = gparam_summary(mesh, options, *g, field_name, {});
  s["time_s"] = seconds_since(t0);
  add_provenance_summary(s);
  const bool lg = options.measure != Measure::FieldDeviation;
  py::dict out = result_dict(g->result, "uv", g->mapped.UV, g->measured.distortion, g->measured.weights,
                             history_stage(options.solver, lg), s);
  out["fuv"] = RowMatrixXi(g->mapped.FUV);
  out["flipped"] = g->measured.flipped;
  py::list singular;
  for (const Singularity& x : g->singular) singular.append(py::make_tuple(x.vertex, x.quarters));
  out["singularities"] = singular;
  out["euler_characteristic"] = g->graph.euler_characteristic();
  out["boundary_loops"] = g->graph.num_boundary_loops;
  out["edge_length"] = g->edge_length;
  out["seam_error"] = g->seam_error;
  out["warnings"] = g->warnings;
  out["field"] = RowMatrixXd(field_directions(g->field, g->frames));
  if (integer_grid) {
    add_integer_grid_attributes(out, *g);
    out["grid_guide"] = g->grid_guide == GParamOptions::GridGuide::Linf ? "linf" : "l2";  // the one followed
  }
  return out;
}

py::list interp_py(const RowMatrixXd& V, const RowMatrixXi& F, const RowMatrixXd& V_target,
                   const std::vector<double>& times, const std::string& method, const py::dict& kwargs,
                   const py::object& progress) {
  TaskOptions o = parse_options(Task::Interp, "interp", method, kwargs);
  refuse_measure_keys(o, std::nullopt);
  if (times.empty()) throw InputError("t needs at least one time in [0, 1]");
  for (double t : times)
    if (!(t >= 0.0 && t <= 1.0)) throw InputError("t: " + io_detail::exact_text(t) + " is outside [0, 1]");
  const Mesh source = make_mesh(V, F, "source", true, nullptr);
  // The same vertices; their dimensions may differ (a planar source and a 3D target: a
  // surface interpolation, as the command line reads such files).
  if (V_target.rows() != V.rows())
    throw InputError("target has " + std::to_string(V_target.rows()) + " by " + std::to_string(V_target.cols()) +
                     " vertices, source " + std::to_string(V.rows()) + " by " + std::to_string(V.cols()));
  const Mesh target = make_mesh(V_target, F, "target", false, nullptr);
  if (o.pin >= source.num_vertices())
    throw InputError("pin " + std::to_string(o.pin) + ": source has " + std::to_string(source.num_vertices()) +
                     " vertices (0-based indices)");
  wire_progress(o, callback_or_null(progress));
  InterpOptions options;
  options.solver = o.solver;
  options.local_global = o.local_global;
  options.pin_vertex = o.pin;
  std::optional<Interpolator> interp;
  std::vector<InterpFrame> frames;
  std::vector<double> seconds;
  run_released([&] {
    const auto threads = limit_threads(o.threads);
    interp.emplace(source, target, "source", "target", parse_rotation_blend(o.rotation_blend, "rotation_blend"));
    for (double t : times) {
      const auto tf = Clock::now();
      frames.push_back(interp->at(t, options));
      seconds.push_back(seconds_since(tf));
    }
  });
  py::list out;
  for (size_t i = 0; i < frames.size(); ++i) {
    const InterpFrame& f = frames[i];
    nlohmann::json s = interp_summary(source, *interp, options, "", "");
    nlohmann::json frame = interp_frame_summary(f, options, "");
    frame["time_s"] = seconds[i];
    s["frames"] = nlohmann::json::array({frame});
    s["time_s"] = seconds[i];
    add_provenance_summary(s);
    py::dict r = result_dict(f.result, "positions", f.mesh.V, f.result.distortion, f.weights, "local-global", s);
    r["t"] = f.t;
    r["rotation_jumps"] = interp->rotation_jumps();
    r["rotation_blend"] = interp->rotation_blend();
    r["rotation_disagreements"] = interp->rotation_disagreements();
    r["warnings"] = s["warnings"].get<std::vector<std::string>>();
    out.append(r);
  }
  return out;
}

}  // namespace

void bind_tasks(py::module_& m) {
  m.def("deform", &deform_py, py::arg("V"), py::arg("F"), py::arg("handle_indices"), py::arg("handle_positions"),
        py::arg("method"), py::arg("measure"), py::arg("options"), py::arg("progress"));
  m.def("param", &param_py, py::arg("V"), py::arg("F"), py::arg("method"), py::arg("measure"), py::arg("options"),
        py::arg("progress"));
  m.def("gparam", &gparam_py, py::arg("V"), py::arg("F"), py::arg("method"), py::arg("measure"), py::arg("field"),
        py::arg("directions"), py::arg("edge_length"), py::arg("quads"), py::arg("curvature_alignment"),
        py::arg("parallel"), py::arg("cones"), py::arg("integer_grid"), py::arg("grid_guide"), py::arg("options"),
        py::arg("progress"));
  m.def("interp", &interp_py, py::arg("V"), py::arg("F"), py::arg("V_target"), py::arg("t"), py::arg("method"),
        py::arg("options"), py::arg("progress"));
}

}  // namespace strictmin::python
