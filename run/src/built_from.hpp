// Building a part of a run from the scenario: what it throws becomes a
// problem of the scenario at a pointer (private to run/).
#pragma once

#include <new>
#include <stdexcept>
#include <string>

#include "latsim/des/stop_token.hpp"
#include "latsim/scenario/config.hpp"

namespace latsim::run {

// Builds one part of a run. Building depends on the scenario alone, so
// anything it throws is a problem of the scenario at `pointer`: `validate`
// reports it exactly as `run` does, exit 2, and never a library's raw text.
template <class F>
void built_from(const char* pointer, const char* what, F&& make) {
  try {
    make();
  } catch (const scenario::ScenarioError&) {
    throw;
  } catch (const des::StopRequested&) {
    throw;  // a signal while reading a file the scenario names: no problem of the scenario
  } catch (const std::bad_alloc&) {
    throw scenario::ScenarioError(pointer, std::string("not enough memory to build the ") + what);
  } catch (const std::exception& e) {
    throw scenario::ScenarioError(pointer, std::string("cannot build the ") + what + ": " + e.what());
  }
}

}  // namespace latsim::run
