#include "errors.hpp"

#include <cstring>

#include "latsim/results/run_files.hpp"
#include "latsim/run/runner.hpp"

namespace latsim::python {

namespace py = pybind11;

namespace {

// The exception classes the module defines. They live as long as the
// process, like Python's own (PyExc_ValueError): never freed, so that no
// reference is dropped after the interpreter has finalised.
struct ErrorClasses {
  PyObject* scenario_error = nullptr;
  PyObject* run_failure = nullptr;
};

ErrorClasses& classes() {
  static ErrorClasses* the_classes = new ErrorClasses;
  return *the_classes;
}

// Raises an instance of `type` made from `line`, with `attributes` set on it.
void raise_with(PyObject* type, const std::string& line, const py::dict& attributes) {
  py::object error = py::reinterpret_borrow<py::object>(type)(line);
  for (const auto& [name, value] : attributes) py::setattr(error, name, value);
  PyErr_SetObject(type, error.ptr());
}

void translate(std::exception_ptr thrown) {
  try {
    if (thrown) std::rethrow_exception(thrown);
  } catch (const BadInput& e) {
    py::dict attrs;
    attrs["file"] = e.file();
    attrs["pointer"] = e.pointer() ? py::object(py::str(*e.pointer())) : py::object(py::none());
    attrs["message"] = e.message();
    raise_with(classes().scenario_error, e.what(), attrs);
  } catch (const run::RunFailure& e) {
    py::dict attrs;
    attrs["model"] = e.model();
    attrs["at_s"] = e.at().to_seconds();
    raise_with(classes().run_failure, e.what(), attrs);
  } catch (const SweepFailures& e) {
    py::dict attrs;
    attrs["model"] = py::none();
    attrs["at_s"] = py::none();
    raise_with(classes().run_failure, e.what(), attrs);
  } catch (const run::RunInterrupted& e) {
    // Stopped without a Python signal handler having raised first.
    PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
  } catch (const results::WriteError& e) {
    py::object error = py::reinterpret_borrow<py::object>(PyExc_OSError)(e.error_number(), std::strerror(e.error_number()),
                                                                         e.file().string());
    PyErr_SetObject(PyExc_OSError, error.ptr());
  }
}

}  // namespace

BadInput::BadInput(std::string line, std::string file, std::optional<std::string> pointer, std::string message)
    : std::runtime_error(std::move(line)),
      file_(std::move(file)),
      pointer_(std::move(pointer)),
      message_(std::move(message)) {}

BadInput BadInput::of(const scenario::ScenarioError& e, const std::string& named_file) {
  const std::string file = e.file().empty() ? named_file : e.file().string();
  return BadInput(e.line(named_file), file, e.pointer(), e.message());
}

void add_errors(py::module_& m) {
  ErrorClasses& c = classes();
  if (c.scenario_error == nullptr) {
    c.scenario_error = PyErr_NewExceptionWithDoc(
        "latsim.ScenarioError",
        "Bad scenario or sweep input: str() is the line `latsim` prints; .file, .pointer (the JSON pointer, "
        "None when the message names none) and .message are its parts.",
        PyExc_ValueError, nullptr);
    c.run_failure = PyErr_NewExceptionWithDoc(
        "latsim.RunFailure",
        "The simulation failed, not the input: .model and .at_s (simulated seconds) say where; both are None "
        "for failed runs of a sweep.",
        PyExc_RuntimeError, nullptr);
    if (c.scenario_error == nullptr || c.run_failure == nullptr) throw py::error_already_set();
  }
  m.attr("ScenarioError") = py::handle(c.scenario_error);
  m.attr("RunFailure") = py::handle(c.run_failure);
  py::register_exception_translator(translate);
}

}  // namespace latsim::python
