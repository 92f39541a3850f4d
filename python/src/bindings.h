#pragma once
// The module's functions, one group per file (module.cpp puts them together).
#include <pybind11/pybind11.h>

namespace strictmin::python {

void bind_io(pybind11::module_& m);        // read_mesh, write_mesh
void bind_tasks(pybind11::module_& m);     // deform, param, interp
void bind_measures(pybind11::module_& m);  // distortion, compare
void bind_quads(pybind11::module_& m);     // quads

}  // namespace strictmin::python
