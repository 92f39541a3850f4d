#pragma once
// Runs a solve with the GIL released and Ctrl-C honoured.
#include <functional>

namespace strictmin::python {

// Runs `body` on a worker thread while the calling thread, without the GIL, waits for it and
// every 20 ms takes the GIL to let Python handle pending signals (PyErr_CheckSignals). When a
// handler raises (Ctrl-C: KeyboardInterrupt), the worker's interrupt flag is set: the solver
// throws Interrupted at its next iteration (solvers/interrupt.h), the worker is joined, and
// the Python exception is raised here. An exception of `body` is rethrown here. No thread
// is left running either way. `body` must take the GIL itself to touch Python objects.
void run_released(const std::function<void()>& body);

}  // namespace strictmin::python
