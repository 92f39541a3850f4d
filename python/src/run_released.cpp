#include "run_released.h"

#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

#include "strictmin/solvers/interrupt.h"

namespace py = pybind11;

namespace strictmin::python {

void run_released(const std::function<void()>& body) {
  std::atomic<bool> stop{false};
  std::exception_ptr error;  // destroyed with the GIL held (it may hold a Python error)
  bool interrupted = false;
  {
    py::gil_scoped_release release;
    std::mutex m;
    std::condition_variable cv;
    bool done = false;
    std::thread worker([&] {
      {
        InterruptScope scope(stop);
        try {
          body();
        } catch (...) {
          error = std::current_exception();
        }
      }
      std::lock_guard<std::mutex> lock(m);
      done = true;
      cv.notify_all();
    });
    std::unique_lock<std::mutex> lock(m);
    while (!done) {
      cv.wait_for(lock, std::chrono::milliseconds(20));
      if (done || interrupted) continue;
      lock.unlock();
      {
        py::gil_scoped_acquire gil;
        // A raising handler leaves its exception set on this thread until it is raised below.
        if (PyErr_CheckSignals() != 0) {
          interrupted = true;
          stop = true;
        }
      }
      lock.lock();
    }
    lock.unlock();
    worker.join();
  }
  if (interrupted) throw py::error_already_set();
  if (error) std::rethrow_exception(error);
}

}  // namespace strictmin::python
