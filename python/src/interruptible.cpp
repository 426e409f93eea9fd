#include "interruptible.hpp"

#include <exception>
#include <future>
#include <optional>
#include <thread>

#include <pybind11/pybind11.h>

namespace latsim::python {

namespace py = pybind11;

void run_interruptibly(const std::function<void(const std::atomic<bool>& stop)>& work) {
  std::atomic<bool> stop{false};
  std::exception_ptr failure;
  std::optional<py::error_already_set> signalled;
  {
    std::promise<void> done;
    std::future<void> finished = done.get_future();
    py::gil_scoped_release released;
    std::thread worker([&] {
      try {
        work(stop);
      } catch (...) {
        failure = std::current_exception();
      }
      done.set_value();
    });
    while (finished.wait_for(kSignalPoll) != std::future_status::ready) {
      if (stop.load()) continue;
      py::gil_scoped_acquire gil;
      // Runs the Python-level handlers of signals that came (on the main thread only).
      if (PyErr_CheckSignals() != 0) {
        signalled.emplace();  // takes the handler's exception
        stop.store(true);
      }
    }
    worker.join();
  }
  if (signalled) throw std::move(*signalled);
  if (failure) std::rethrow_exception(failure);
}

}  // namespace latsim::python
