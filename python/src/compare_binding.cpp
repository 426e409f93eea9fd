// _latsim.compare: a capture beside a run by latsim compare's own reader and
// verdicts (sweep::compare_capture), returning compare.csv's text, the
// warnings and the two sides' descriptions; nothing is written.
#include <optional>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "latsim/capture/capture.hpp"
#include "latsim/sweep/compare.hpp"

namespace latsim::python {

namespace py = pybind11;

namespace {

py::dict compare(const std::string& capture, const std::string& run, const std::string& application,
                 std::optional<int64_t> process_id, double ks_threshold, double mean_tolerance) {
  sweep::CompareRequest request{capture, run, {application, process_id}, ks_threshold, mean_tolerance};
  sweep::Comparison comparison;
  try {
    py::gil_scoped_release unlocked;
    comparison = sweep::compare_capture(request);
  } catch (const capture::CaptureError& e) {
    throw py::value_error(std::string("compare: ") + e.what());
  } catch (const sweep::CompareError& e) {
    throw py::value_error(std::string("compare: ") + e.what());
  }
  py::dict out;
  out["csv"] = sweep::compare_csv(comparison);
  out["warnings"] = comparison.warnings;
  out["notes"] = comparison.notes;
  out["capture"] = comparison.capture_text;
  out["run"] = comparison.run_text;
  return out;
}

}  // namespace

void add_compare(py::module_& m) {
  m.def("compare", &compare, py::arg("capture"), py::arg("run"), py::arg("application"), py::arg("process_id"),
        py::arg("ks_threshold"), py::arg("mean_tolerance"),
        "Sets a capture beside a run as `latsim compare` does; returns compare.csv's text, warnings and notes.");
}

}  // namespace latsim::python
