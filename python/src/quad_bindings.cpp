// quads: the quad mesh of an integer-grid map (tasks/quad_extraction.h).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "convert.h"
#include "run_released.h"
#include "report/summary.h"  // private (src/): the CLI and the Python module
#include "strictmin/io/input_error.h"
#include "strictmin/tasks/quad_extraction.h"

namespace py = pybind11;

namespace strictmin::python {
namespace {

py::dict quads_py(const RowMatrixXd& V, const RowMatrixXi& F, const RowMatrixXd& uv, const RowMatrixXi& fuv,
                  double tolerance, bool fill_holes) {
  Mesh map = make_mesh(V, F, "mesh", true, nullptr);
  if (uv.cols() != 2) throw InputError("uv must be #UV by 2, got " + std::to_string(uv.cols()) + " columns");
  if (fuv.rows() != F.rows() || fuv.cols() != 3)
    throw InputError("fuv must be #F by 3 (" + std::to_string(F.rows()) + " by 3), got " + std::to_string(fuv.rows()) +
                     " by " + std::to_string(fuv.cols()));
  map.UV = uv;
  map.FUV = fuv;
  QuadExtractionOptions options;
  options.tolerance = tolerance;
  options.fill_holes = fill_holes;
  QuadExtraction x;
  run_released([&] { x = extract_quads(map, options, "mesh"); });  // Ctrl-C honoured, the GIL released
  nlohmann::json s = quad_extraction_summary(x, options);
  s["task"] = "quads";
  add_provenance_summary(s);
  py::dict out;
  out["V"] = RowMatrixXd(x.mesh.V);
  out["Q"] = RowMatrixXi(x.mesh.Q);
  out["uv"] = RowMatrixXd(x.mesh.UV);
  out["quv"] = RowMatrixXi(x.mesh.QUV);
  out["vertex_face"] = Eigen::VectorXi(x.mesh.vertex_face);
  out["vertex_barycentric"] = RowMatrixXd(x.mesh.vertex_barycentric);
  out["complete"] = x.complete;
  out["summary"] = to_python(s);
  return out;
}

}  // namespace

void bind_quads(py::module_& m) {
  m.def("quads", &quads_py, py::arg("V"), py::arg("F"), py::arg("uv"), py::arg("fuv"), py::arg("tolerance"),
        py::arg("fill_holes"));
}

}  // namespace strictmin::python
