// _latsim.run: one scenario (a file, or JSON text standing for one) through
// the same path as `latsim run`, returning summary.json's content as JSON
// text and the run's tables as NumPy columns.
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "errors.hpp"
#include "interruptible.hpp"
#include "latsim/results/ledger.hpp"
#include "latsim/run/prepared_run.hpp"
#include "latsim/run/runner.hpp"

namespace latsim::python {

namespace py = pybind11;
using Json = nlohmann::json;

namespace {

// Picoseconds per millisecond, for the timeline's columns in ms (as timeline.csv).
constexpr double kPsPerMs = 1e9;

// One ledger table: its columns and its rows as a 2-D int64 array.
py::dict ledger_table(const std::vector<std::string>& columns, const std::vector<std::vector<int64_t>>& rows) {
  py::array_t<int64_t> values(std::vector<py::ssize_t>{static_cast<py::ssize_t>(rows.size()),
                                                        static_cast<py::ssize_t>(columns.size())});
  auto v = values.mutable_unchecked<2>();
  for (size_t r = 0; r < rows.size(); ++r)
    for (size_t c = 0; c < columns.size(); ++c) v(static_cast<py::ssize_t>(r), static_cast<py::ssize_t>(c)) = c < rows[r].size() ? rows[r][c] : 0;
  py::dict table;
  table["columns"] = columns;
  table["values"] = std::move(values);
  return table;
}

// samples.csv's columns: t_ms, name, value.
py::dict sample_columns(const std::vector<results::SampleLog::Sample>& samples) {
  py::array_t<double> t_ms(samples.size()), value(samples.size());
  py::list name(samples.size());
  auto t = t_ms.mutable_unchecked<1>();
  auto v = value.mutable_unchecked<1>();
  for (size_t i = 0; i < samples.size(); ++i) {
    t(i) = samples[i].t_ms;
    v(i) = samples[i].value;
    name[i] = samples[i].name;
  }
  py::dict columns;
  columns["t_ms"] = std::move(t_ms);
  columns["name"] = std::move(name);
  columns["value"] = std::move(value);
  return columns;
}

// timeline.csv's columns: stage, frame, eye, unit, start_ms, end_ms.
py::dict timeline_columns(const std::vector<results::Timeline::Entry>& entries) {
  const size_t n = entries.size();
  py::list stage(n), unit(n);
  py::array_t<int64_t> frame(n), eye(n);
  py::array_t<double> start_ms(n), end_ms(n);
  auto f = frame.mutable_unchecked<1>();
  auto e = eye.mutable_unchecked<1>();
  auto s = start_ms.mutable_unchecked<1>();
  auto x = end_ms.mutable_unchecked<1>();
  for (size_t i = 0; i < n; ++i) {
    const results::Timeline::Entry& entry = entries[i];
    stage[i] = entry.stage;
    unit[i] = entry.unit;
    f(i) = entry.frame;
    e(i) = entry.eye;
    s(i) = static_cast<double>(entry.start.ticks()) / kPsPerMs;
    x(i) = static_cast<double>(entry.end.ticks()) / kPsPerMs;
  }
  py::dict columns;
  columns["stage"] = std::move(stage);
  columns["frame"] = std::move(frame);
  columns["eye"] = std::move(eye);
  columns["unit"] = std::move(unit);
  columns["start_ms"] = std::move(start_ms);
  columns["end_ms"] = std::move(end_ms);
  return columns;
}

py::dict tables_of(const run::RunTables& tables) {
  py::dict out;
  out["frames"] = ledger_table(results::Ledger::frame_columns(), tables.frames);
  out["fields"] = ledger_table(results::Ledger::field_columns(), tables.fields);
  out["tracker"] = ledger_table(results::Ledger::tracker_columns(), tables.tracker);
  out["samples"] = sample_columns(tables.samples);
  out["timeline"] = timeline_columns(tables.timeline);
  out["timeline_dropped"] = tables.timeline_dropped;
  return out;
}

// What the package passes for one run.
struct RunCall {
  std::string scenario;              // the file, or the name standing for it when `text` is given
  std::optional<std::string> text;   // the scenario as JSON text
  std::vector<std::string> overrides;  // "/pointer=value"
  std::optional<uint64_t> seed;
  uint64_t replication = 0;
  std::string out_dir;               // empty: write nothing
  bool ledger = false;
  bool samples = false;
  bool profile = false;
  std::vector<std::string> command_line;
};

// Reads, validates and runs the scenario as `latsim run` does: bad input is
// reported before anything is written.
py::tuple run(const RunCall& call) {
  // A NUL cuts a path short where the system reads it: another file or directory, silently.
  for (const auto& [what, path] : {std::pair<const char*, const std::string&>{"scenario", call.scenario},
                                   std::pair<const char*, const std::string&>{"out", call.out_dir}})
    if (path.find('\0') != std::string::npos)
      throw py::value_error(std::string(what) + ": a path with a NUL character");
  run::RunOptions options;
  options.command_start = std::chrono::steady_clock::now();
  options.seed = call.seed;
  options.replication = call.replication;
  options.out_dir = call.out_dir;
  options.write_ledger = call.ledger;
  options.write_samples = call.samples;
  options.profile = call.profile;
  options.command_line = call.command_line;
  run::RunTables tables;
  options.tables = &tables;
  Json summary;
  try {
    run_interruptibly([&](const std::atomic<bool>& stop) {
      const auto doc = call.text ? run::load_scenario_text(*call.text, call.scenario, call.overrides)
                                 : run::load_scenario(call.scenario, call.overrides);
      run::RunOptions stoppable = options;
      stoppable.stop = &stop;
      // Built once, fully validated before anything is written.
      run::PreparedRun prepared(doc, stoppable);
      summary = prepared.run();
    });
  } catch (const scenario::ScenarioError& e) {
    throw BadInput::of(e, call.scenario);
  }
  return py::make_tuple(summary.dump(-1, ' ', false, Json::error_handler_t::replace), tables_of(tables));
}

}  // namespace

void add_run(py::module_& m) {
  m.def(
      "run",
      [](std::string scenario, std::optional<std::string> text, std::vector<std::string> overrides,
         std::optional<uint64_t> seed, uint64_t replication, std::string out_dir, bool ledger, bool samples,
         bool profile, std::vector<std::string> command_line) {
        return run(RunCall{std::move(scenario), std::move(text), std::move(overrides), seed, replication,
                           std::move(out_dir), ledger, samples, profile, std::move(command_line)});
      },
      py::arg("scenario"), py::arg("text"), py::arg("overrides"), py::arg("seed"), py::arg("replication"),
      py::arg("out_dir"), py::arg("ledger"), py::arg("samples"), py::arg("profile"), py::arg("command_line"),
      "Runs one scenario; returns (summary.json's content as JSON text, the run's tables).");
}

}  // namespace latsim::python
