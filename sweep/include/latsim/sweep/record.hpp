// A finished run as its record in the results store: its summary as text,
// made smaller where it repeats itself and read back to the same values.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace latsim::sweep {

/// A run's record: two lines of JSON. The first is the summary
/// (summary.json's content) without its resolved scenario, where a histogram
/// whose bucket edges are those of its distribution's min and max (the equal
/// widths of stats::Distribution::plot_histogram, edge b = min + (max - min) /
/// n * b) keeps its counts alone, as "histogram_counts". The second is the
/// scenario: whole (an object) for the first record of a segment, otherwise
/// what it changes in that first one's, as an array of ["=", pointer, value]
/// and ["-", pointer] (a few axis values and clock phases).
struct EncodedRecord {
  std::string text;
  nlohmann::json scenario;  ///< the run's scenario, handed back for the records after it
};

/// Encodes a summary, its scenario against `base` (the scenario of the
/// segment's first record; null for that first record). Consumes the summary.
/// `figures`, when not empty, is the text of the summary's "figures" (a run
/// asked for it as text, run::RunOptions::figures_text), written in the
/// place of that key's value, the same bytes as its JSON tree's would be.
EncodedRecord encode_record(nlohmann::json&& summary, const nlohmann::json* base = nullptr,
                            std::string_view figures = {});

/// How much of a record to read back.
enum class RecordRead {
  whole,   ///< the summary as it was, every value
  tables,  ///< what the tables read: no scenario, histograms left as "histogram_counts"
};

/// The summary of a record, its scenario patched onto `base` when it is a
/// patch. Throws std::runtime_error on text that is no record.
nlohmann::json decode_record(std::string_view record, const nlohmann::json* base = nullptr,
                             RecordRead read = RecordRead::whole);

/// The scenario of a record: its second line, whole or patched onto `base`.
nlohmann::json record_scenario(std::string_view record, const nlohmann::json* base = nullptr);

}  // namespace latsim::sweep
