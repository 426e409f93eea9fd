// The names of the figures the recorder computes for every pipeline, with one
// definition each (docs/figures.md). No pipeline may report under them.
#pragma once

#include <span>
#include <string_view>

namespace latsim::pipelines {

/// One figure of the glossary: its name and a one-line definition.
struct GlossaryEntry {
  std::string_view name;
  std::string_view definition;
};

/// Every figure the recorder owns, in the order of docs/figures.md.
std::span<const GlossaryEntry> glossary();
/// Counters under "counts" that the recorder owns.
std::span<const std::string_view> recorder_counters();
/// Whether `name` (or the first part of a dotted name) is a glossary figure.
bool is_glossary_figure(std::string_view name);

}  // namespace latsim::pipelines
