// One line of a CSV file split into its fields.
#pragma once

#include <deque>
#include <string>
#include <string_view>
#include <vector>

namespace latsim::capture {

/// The fields of one CSV line: comma separated, spaces and tabs around a
/// field dropped, a field in double quotes taken literally ("" is a quote).
/// Views stay valid until the next split() and while the line lives.
class CsvRow {
 public:
  /// Splits `line` (without its line end); returns false for an unterminated quote.
  bool split(std::string_view line);
  size_t size() const { return fields_.size(); }
  std::string_view operator[](size_t i) const { return fields_[i]; }
  const std::vector<std::string_view>& fields() const { return fields_; }

 private:
  std::vector<std::string_view> fields_;
  std::deque<std::string> unescaped_;  // quoted fields that held "" (deque: views into it stay valid)
};

}  // namespace latsim::capture
