// A finished run as its record in the results store: its summary as text,
// made smaller where it repeats itself and read back to the same values.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace latsim::sweep {

/// The record of a run's summary (summary.json's content): one line of JSON
/// with everything but the resolved scenario, then the scenario on a second
/// line, so that the tables read the first line alone. A histogram whose
/// bucket edges are those of its distribution's min and max (the equal
/// widths of des::Distribution::plot_histogram, edge b = min + (max - min) /
/// n * b) keeps its counts alone, as "histogram_counts"; the others are kept
/// whole. Consumes the summary.
std::string encode_record(nlohmann::json&& summary);

/// How much of a record to read back.
enum class RecordRead {
  whole,   ///< the summary as it was, every value
  tables,  ///< what the tables read: no scenario, histograms left as "histogram_counts"
};

/// The summary of a record. Throws std::runtime_error on text that is no record.
nlohmann::json decode_record(std::string_view record, RecordRead read = RecordRead::whole);

}  // namespace latsim::sweep
