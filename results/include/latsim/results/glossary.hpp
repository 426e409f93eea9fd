// The names of the figures the recorder computes for every pipeline, with one
// definition each (docs/figures.md). No pipeline may report under them.
#pragma once

#include <span>
#include <string_view>

namespace latsim::results {

/// One figure of the glossary: its name and a one-line definition.
struct GlossaryEntry {
  std::string_view name;
  std::string_view definition;
};

/// Every figure the recorder owns, in the order of docs/figures.md.
std::span<const GlossaryEntry> glossary();
/// Counters under "counts" that the recorder owns.
std::span<const std::string_view> recorder_counters();
/// Glossary figures also reported split by motion phase, as <name>_<phase>.
std::span<const std::string_view> phase_split_figures();
/// The phases of that split, in docs/figures.md's order.
std::span<const std::string_view> motion_phase_suffixes();
/// Whether `name` (or the first part of a dotted name) is a glossary figure
/// or a motion-phase part of one.
bool is_glossary_figure(std::string_view name);

}  // namespace latsim::results
