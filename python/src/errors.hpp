// latsim's errors as Python exceptions: bad input is latsim.ScenarioError
// (a ValueError carrying the line `latsim` prints, the file and the JSON
// pointer), a failed simulation latsim.RunFailure (a RuntimeError naming the
// model and the simulated time), a result that cannot be written OSError.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>

#include <pybind11/pybind11.h>

#include "latsim/scenario/config.hpp"

namespace latsim::python {

/// Bad input, reported as the command line reports it (one line), with its parts.
class BadInput : public std::runtime_error {
 public:
  /// `line` is what latsim prints; `pointer` is empty for the whole document
  /// and unset when the message does not come with one of its own.
  BadInput(std::string line, std::string file, std::optional<std::string> pointer, std::string message);
  /// A ScenarioError in a scenario the user named `named_file`.
  static BadInput of(const scenario::ScenarioError& e, const std::string& named_file);

  const std::string& file() const { return file_; }
  const std::optional<std::string>& pointer() const { return pointer_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  std::optional<std::string> pointer_;
  std::string message_;
};

/// Failed runs of a sweep: the sweep's tables hold the others.
class SweepFailures : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Adds ScenarioError and RunFailure to `m` and translates latsim's C++
/// exceptions into them (and WriteError into OSError) wherever they escape.
void add_errors(pybind11::module_& m);

}  // namespace latsim::python
