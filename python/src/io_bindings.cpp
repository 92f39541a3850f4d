// read_mesh, write_mesh.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "convert.h"
#include "strictmin/io/input_error.h"
#include "strictmin/io/mesh_io.h"

namespace py = pybind11;

namespace strictmin::python {
namespace {

py::tuple read(const std::string& path, bool check_geometry) {
  std::vector<std::string> warnings;
  MeshReadOptions options;
  options.check_geometry = check_geometry;
  const Mesh mesh = read_mesh(path, &warnings, options);
  py::list w;
  for (const auto& s : warnings) w.append(s);
  return py::make_tuple(RowMatrixXd(mesh.V), RowMatrixXi(mesh.F), w);
}

void write(const std::string& path, const RowMatrixXd& V, const RowMatrixXi& F, const std::optional<RowMatrixXd>& uv,
           const std::optional<Eigen::VectorXd>& quality) {
  Mesh mesh = make_mesh(V, F, path, false, nullptr);
  if (uv) {
    if (uv->rows() != V.rows() || uv->cols() != 2)
      throw InputError(path + ": uv must be #V by 2 (" + std::to_string(V.rows()) + " by 2), got " +
                       std::to_string(uv->rows()) + " by " + std::to_string(uv->cols()));
    mesh.UV = *uv;
    mesh.FUV = mesh.F;
  }
  MeshWriteOptions options;
  if (quality) {
    if (quality->size() != F.rows())
      throw InputError(path + ": quality has " + std::to_string(quality->size()) + " values, the mesh has " +
                       std::to_string(F.rows()) + " elements");
    options.element_quality = &*quality;
  }
  write_mesh(path, mesh, options);
}

}  // namespace

void bind_io(py::module_& m) {
  m.def("read_mesh", &read, py::arg("path"), py::arg("check_geometry") = true,
        "(V, F, warnings) of a .obj, .off or .mesh file (validated; check_geometry=False: no area/orientation checks)");
  m.def("write_mesh", &write, py::arg("path"), py::arg("V"), py::arg("F"), py::arg("uv") = py::none(),
        py::arg("quality") = py::none(), "Write a mesh (.obj, .off, .mesh, .ply), with UVs and per-element quality");
}

}  // namespace strictmin::python
