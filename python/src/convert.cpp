#include "convert.h"

#include <cmath>
#include <map>

#include "strictmin/io/input_error.h"
#include "strictmin/mesh/validate.h"

namespace py = pybind11;

namespace strictmin::python {

py::object to_python(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::null: return py::none();
    case nlohmann::json::value_t::boolean: return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer: return py::int_(j.get<long long>());
    case nlohmann::json::value_t::number_unsigned: return py::int_(j.get<unsigned long long>());
    case nlohmann::json::value_t::number_float: return py::float_(j.get<double>());
    case nlohmann::json::value_t::string: return py::str(j.get<std::string>());
    case nlohmann::json::value_t::array: {
      py::list out;
      for (const auto& x : j) out.append(to_python(x));
      return out;
    }
    case nlohmann::json::value_t::object: {
      py::dict out;
      for (const auto& [key, value] : j.items()) out[py::str(key)] = to_python(value);
      return out;
    }
    default: return py::none();
  }
}

py::dict record_dict(const IterationRecord& r, const char* stage) {
  py::dict d;
  d["stage"] = stage;
  d["iteration"] = r.iteration;
  d["max_distortion"] = r.max_distortion;
  d["lower_bound"] = r.lower_bound;
  d["certified_gap"] = r.certified_gap;
  d["relative_change"] = r.relative_change;
  d["largest_move"] = r.largest_move;
  d["decrement"] = r.decrement;
  d["time_s"] = r.time_s;
  return d;
}

py::dict step_dict(const StrictStep& s) {
  py::dict d;
  d["stage"] = "strict";
  d["step"] = s.step;
  d["k"] = s.k;
  d["fixed_now"] = s.fixed_now;
  d["fixed_total"] = s.fixed_total;
  d["solves"] = s.solves;
  d["level_iterations"] = s.level_iterations;
  d["level_iteration_unit"] = s.level_iteration_unit;
  d["level_free_vertices"] = s.level_free_vertices;
  d["pinned_total"] = s.pinned_total;
  d["time_s"] = s.time_s;
  return d;
}

Mesh make_mesh(const RowMatrixXd& V, const RowMatrixXi& F, const std::string& name, bool check_geometry,
               std::vector<std::string>* warnings) {
  if (V.cols() != 2 && V.cols() != 3)
    throw InputError(name + ": V must be #V by 2 or 3, got " + std::to_string(V.rows()) + " by " +
                     std::to_string(V.cols()));
  if (F.cols() != 3 && F.cols() != 4)
    throw InputError(name + ": F must be #F by 3 (triangles) or 4 (tets), got " + std::to_string(F.rows()) + " by " +
                     std::to_string(F.cols()));
  if (F.cols() == 4 && V.cols() != 3) throw InputError(name + ": tets need V #V by 3");
  Mesh mesh;
  mesh.V = V;
  mesh.F = F;
  validate_mesh(mesh, name, warnings, check_geometry);
  return mesh;
}

std::vector<Handle> make_handles(const Eigen::VectorXi& indices, const RowMatrixXd& positions, int num_vertices,
                                 int dim) {
  if (positions.rows() != indices.size())
    throw InputError("handles: " + std::to_string(indices.size()) + " handle_indices but " +
                     std::to_string(positions.rows()) + " rows of handle_positions");
  if (positions.cols() != dim && indices.size() > 0)
    throw InputError("handles: handle has " + std::to_string(positions.cols()) + " coordinates, the mesh is " +
                     std::to_string(dim) + "D");
  std::vector<Handle> handles;
  std::map<int, Eigen::Index> seen;  // vertex -> row
  for (Eigen::Index i = 0; i < indices.size(); ++i) {
    const std::string where = "handles: row " + std::to_string(i) + ": ";
    const int v = indices(i);
    if (v < 0 || v >= num_vertices)
      throw InputError(where + "vertex " + std::to_string(v) + " out of range (the mesh has " +
                       std::to_string(num_vertices) + " vertices, indices from 0)");
    const Eigen::VectorXd p = positions.row(i).transpose();
    if (!p.allFinite())
      throw InputError(where + "handle for vertex " + std::to_string(v) + " has a non-finite coordinate");
    const auto [it, inserted] = seen.try_emplace(v, i);
    if (!inserted) {
      if (positions.row(it->second) == positions.row(i)) continue;  // same target twice: merged
      throw InputError(where + "vertex " + std::to_string(v) + " has two different targets (the other one is on row " +
                       std::to_string(it->second) + ")");
    }
    handles.push_back(Handle{v, p});
  }
  if (handles.empty()) throw InputError("handles: no handles (no constrained vertex given)");
  return handles;
}

}  // namespace strictmin::python
