// The glossary: the figures the recorders compute alike for every pipeline,
// one definition each (docs/figures.md), as the figure registry declares
// them. No pipeline may report under them.
#pragma once

#include <string_view>

#include "latsim/results/figure_registry.hpp"

namespace latsim::results {

/// Whether `name` (or the first part of a dotted name) is a glossary figure
/// or a motion-phase part of one.
bool is_glossary_figure(std::string_view name, const FigureRegistry& registry = FigureRegistry::builtin());

}  // namespace latsim::results
