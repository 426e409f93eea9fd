#include "interruptible.hpp"

#include <csignal>
#include <exception>
#include <future>
#include <optional>
#include <thread>

#include <pybind11/pybind11.h>

namespace latsim::python {

namespace py = pybind11;

namespace {

// Python leaves SIGTERM to the system, which ends the process where it
// stands: a run's staging directory would stay. While work runs, a SIGTERM
// whose action is the default raises this instead, through a Python-level
// handler (set on the main thread only, where Python allows it); once the
// work has stopped and cleaned up, the default action is taken after all.
class TermSignalGuard {
 public:
  TermSignalGuard() {
    const py::module_ threading = py::module_::import("threading");
    if (!threading.attr("current_thread")().is(threading.attr("main_thread")())) return;
    signal_ = py::module_::import("signal");
    const py::object term = signal_.attr("SIGTERM");
    if (!signal_.attr("getsignal")(term).is(signal_.attr("SIG_DFL"))) return;
    signal_.attr("signal")(term, py::cpp_function([this](py::object, py::object) {
      received_ = true;
      PyErr_SetString(PyExc_SystemExit, "SIGTERM");
      throw py::error_already_set();
    }));
    installed_ = true;
  }
  ~TermSignalGuard() {
    if (!installed_) return;
    try {
      signal_.attr("signal")(signal_.attr("SIGTERM"), signal_.attr("SIG_DFL"));
    } catch (...) {
      std::signal(SIGTERM, SIG_DFL);
    }
    // What the signal would have done: the process ends by it, cleaned up.
    if (received_) std::raise(SIGTERM);
  }
  TermSignalGuard(const TermSignalGuard&) = delete;
  TermSignalGuard& operator=(const TermSignalGuard&) = delete;

 private:
  py::module_ signal_;
  bool installed_ = false;
  bool received_ = false;
};

}  // namespace

void run_interruptibly(const std::function<void(const std::atomic<bool>& stop)>& work) {
  const TermSignalGuard term;
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
