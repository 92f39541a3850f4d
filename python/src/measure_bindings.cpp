// distortion, compare.
#include <pybind11/eigen.h>

#include "bindings.h"
#include "convert.h"
#include "strictmin/io/input_error.h"
#include "strictmin/report/strict_order.h"
#include "strictmin/tasks/map_distortion.h"

namespace py = pybind11;

namespace strictmin::python {
namespace {

py::dict distortion_of(const RowMatrixXd& V, const RowMatrixXi& F, const RowMatrixXd& U, const std::string& measure) {
  const auto m = parse_measure(measure);
  if (!m) throw InputError("unknown measure '" + measure + "' (use fd, arap, asap, qc or iso)");
  const Mesh rest = make_mesh(V, F, "mesh", true, nullptr);
  const Eigen::Index corners = rest.F.cols();
  MapDistortion d;
  if (U.rows() == rest.V.rows()) {
    // As `strictmin eval REST MAPPED` with the same connectivity (a planar map given in 3D
    // with a constant z is taken in 2D).
    Mesh mapped;
    mapped.V = U;
    mapped.F = rest.F;
    d = map_distortion(rest, mapped, *m, "V", "U");
  } else if (U.rows() == rest.F.rows() * corners) {
    d = map_distortion(rest, Eigen::MatrixXd(U), *m, "U");  // one image per element corner (seamed UV layouts)
  } else {
    throw InputError("U has " + std::to_string(U.rows()) + " rows: give one per vertex (" +
                     std::to_string(rest.V.rows()) + ") or one per element corner (" +
                     std::to_string(rest.F.rows() * corners) + ")");
  }
  py::dict out;
  out["distortion"] = d.distortion;
  out["weights"] = d.weights;
  out["flipped"] = d.flipped;
  return out;
}

py::tuple compare(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& weights,
                  double value_tolerance, double area_tolerance) {
  if (a.size() != b.size() || a.size() != weights.size())
    throw InputError("compare needs d1, d2 and weights of one length, got " + std::to_string(a.size()) + ", " +
                     std::to_string(b.size()) + " and " + std::to_string(weights.size()));
  if (!weights.allFinite() || (weights.array() < 0).any()) throw InputError("weights must be finite and >= 0");
  if (a.hasNaN() || b.hasNaN()) throw InputError("distortions must not be NaN");
  const StrictComparison c = compare_strict(a, b, weights, value_tolerance, area_tolerance);
  const int order = c.order == StrictOrder::Less ? -1 : c.order == StrictOrder::Greater ? 1 : 0;
  return py::make_tuple(order, c.level, c.value_a, c.value_b, c.area_a, c.area_b);
}

}  // namespace

void bind_measures(py::module_& m) {
  m.def("distortion", &distortion_of, py::arg("V"), py::arg("F"), py::arg("U"), py::arg("measure"));
  m.def("compare", &compare, py::arg("d1"), py::arg("d2"), py::arg("weights"), py::arg("value_tolerance"),
        py::arg("area_tolerance"));
}

}  // namespace strictmin::python
