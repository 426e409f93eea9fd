// The first implementation of the analytic double-buffering figure, for tests:
// it enumerates every phase point and frame, at about ten times the cost of a
// short run, and is what the product's computation must reproduce exactly.
#pragma once

#include <optional>

#include "double_buffer/analytic.hpp"

namespace latsim::pipelines::testing {

/// analytic_double_buffer() as first written: the reference for its values.
std::optional<AnalyticLatency> reference_analytic_double_buffer(const AnalyticInputs& in);

}  // namespace latsim::pipelines::testing
