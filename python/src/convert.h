#pragma once
// Conversions between the library's types and Python objects.
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "strictmin/mesh/handle.h"
#include "strictmin/mesh/mesh.h"
#include "strictmin/solvers/result.h"
#include "strictmin/solvers/strict.h"

namespace strictmin::python {

using RowMatrixXd = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using RowMatrixXi = Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// JSON -> dict / list / str / int / float / bool / None.
pybind11::object to_python(const nlohmann::json& j);

// An iteration record as a dict: iteration, max_distortion, lower_bound, certified_gap,
// relative_change, largest_move, decrement (NaN where not applicable), time_s, and `stage`
// (which solver: "linf", "lp", "irls", "relax", "local-global").
pybind11::dict record_dict(const IterationRecord& r, const char* stage);
// A strict-minimizer level (direct, exact): step, k, fixed_now, fixed_total, solves,
// level_iterations (counted in level_iteration_unit), level_free_vertices, pinned_total, time_s, stage "strict".
pybind11::dict step_dict(const StrictStep& s);

// A mesh from V (#V by 2 or 3) and F (#F by 3 or 4), validated like a file's mesh
// (mesh/validate.h): InputError names the element and the reason. Warnings are appended.
Mesh make_mesh(const RowMatrixXd& V, const RowMatrixXi& F, const std::string& name, bool check_geometry,
               std::vector<std::string>* warnings);

// Handles from indices (#H) and positions (#H by dim), checked as a handle file's entries
// (range, dimension, finite values, one target per vertex, at least one).
std::vector<Handle> make_handles(const Eigen::VectorXi& indices, const RowMatrixXd& positions, int num_vertices,
                                 int dim);

}  // namespace strictmin::python
