// The compiled part of `import strictmin` (python/strictmin/__init__.py wraps it).
#include <pybind11/pybind11.h>

#include "strictmin/version.h"
#include "bindings.h"
#include "runtime/blas_kernels.h"
#include "strictmin/io/input_error.h"
#include "strictmin/solvers/interrupt.h"

namespace py = pybind11;

PYBIND11_MODULE(_strictmin, m) {
  m.doc() = "strictmin: maps of meshes with the least possible worst-case distortion (compiled part)";
  m.attr("__version__") = STRICTMIN_VERSION;
  // Bad input raises ValueError with the library's message (the one the command line prints).
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const strictmin::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const strictmin::Interrupted&) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    }
  });
  // The BLAS kernels (src/runtime/blas_kernels.h): the interpreter cannot be re-run as the
  // command is, so the module only reports them.
  m.def("blas_kernels", [] {
    const char* better = strictmin::runtime::better_openblas_core();
    return py::make_tuple(strictmin::runtime::openblas_core(), better ? py::object(py::str(better)) : py::none());
  });
  strictmin::python::bind_io(m);
  strictmin::python::bind_tasks(m);
  strictmin::python::bind_measures(m);
  strictmin::python::bind_quads(m);
}
