// latsim._latsim: runs, sweeps and the schema on latsim's own libraries, for
// the Python package latsim (python/latsim), which turns what they return
// into dicts and pandas DataFrames.
#include <string>

#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "errors.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/schema.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_latsim, m) {
  m.doc() = "latsim's simulator, compiled; use the package latsim, which wraps it.";
  latsim::python::add_errors(m);
  latsim::python::add_run(m);
  latsim::python::add_sweep(m);
  latsim::python::add_compare(m);
  m.def(
      "schema",
      [](const std::string& format) {
        const latsim::scenario::ObjectSchema& schema = latsim::run::scenario_schema();
        if (format == "markdown") return latsim::scenario::markdown_reference(schema);
        if (format != "json-schema") throw py::value_error("format must be \"json-schema\" or \"markdown\"");
        return latsim::scenario::json_schema(schema).dump(2) + "\n";
      },
      py::arg("format") = "json-schema",
      "Every scenario key: JSON Schema text (json-schema) or the Markdown reference (markdown), as `latsim schema` "
      "prints them.");
  m.attr("version") = latsim::run::latsim_version();
  m.attr("git_revision") = latsim::run::latsim_git_revision();
}
