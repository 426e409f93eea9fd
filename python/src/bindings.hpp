// The functions of the compiled module latsim._latsim, one file per area.
#pragma once

#include <pybind11/pybind11.h>

namespace latsim::python {

/// run(): one scenario, its summary and its tables in memory.
void add_run(pybind11::module_& m);
/// sweep(): every run of a sweep into a sweep directory and its tables.
void add_sweep(pybind11::module_& m);
/// compare(): a capture beside a run, as latsim compare's table.
void add_compare(pybind11::module_& m);

}  // namespace latsim::python
