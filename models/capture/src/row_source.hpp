// The rows of a capture, whatever its form: a CSV with a header line
// (PresentMon, OVR Metrics Tool, SteamVR frame timing, any other), or the
// VrApi statistics lines a Quest writes to logcat.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "csv_row.hpp"
#include "line_source.hpp"

namespace latsim::capture {

/// One VrApi statistics line as key=value fields ("FPS=72/72,Prd=28ms,...").
/// A piece without '=' belongs to the value before it ("CPU4/GPU=2/3,1171/490MHz").
struct VrApiFields {
  std::vector<std::string_view> keys, values;
};

/// A capture's text as a message quotes it: control characters as '?', at
/// most 40 characters (then "...").
std::string shown(std::string_view v);

/// "a, b, c, ... (N in all)": names shown as above, cut at a whole name
/// within about 110 characters, so that an error stays one readable line.
std::string name_list(const std::vector<std::string>& names);

/// Where column `name` is in a header (none: it has no such column).
std::optional<size_t> find_column(const std::vector<std::string>& header, std::string_view name);

/// The fields of a VrApi statistics line: the text from "FPS=" on, whatever
/// logcat wrote before it ("I VrApi   : "); none when the line is no such line.
bool split_vrapi(std::string_view line, VrApiFields& out);

/// Header and data rows of a capture file, streamed: blank lines skipped; in
/// a VrApi log, lines that are not statistics lines skipped (counted). Each
/// row's fields are in the header's order (a VrApi line's by key; a key the
/// line lacks is an empty field).
class RowSource {
 public:
  /// Opens `file` and reads its header (the first non-blank line, or the
  /// keys of the first VrApi statistics line). Throws CaptureError.
  explicit RowSource(const std::filesystem::path& file);

  const std::vector<std::string>& header() const { return header_; }
  /// Where column `name` is (none: no such column); throws CaptureError when
  /// the header names it twice.
  std::optional<size_t> column(std::string_view name) const;
  bool vrapi() const { return vrapi_; }
  /// The next data row, split into at most `max_fields` fields; false at the end.
  bool next(size_t max_fields = SIZE_MAX);
  size_t size() const { return fields_->size(); }
  std::string_view operator[](size_t i) const { return (*fields_)[i]; }
  /// The line of the row last returned.
  int64_t line() const { return lines_.number(); }
  /// Lines of a VrApi log that were not statistics lines.
  int64_t other_lines() const { return other_lines_; }
  const std::filesystem::path& file() const { return lines_.file(); }
  /// Throws CaptureError at the current line.
  [[noreturn]] void fail(const std::string& reason) const;

 private:
  bool next_vrapi();

  LineSource lines_;
  std::vector<std::string> header_;
  bool vrapi_ = false;
  bool pending_first_ = false;  ///< the first statistics line, read for the header, is the first row
  CsvRow csv_;
  VrApiFields kv_;
  std::vector<std::string_view> by_key_;
  const std::vector<std::string_view>* fields_ = nullptr;
  int64_t other_lines_ = 0;
};

}  // namespace latsim::capture
