#include "csv_row.hpp"

namespace latsim::capture {

namespace {

bool blank(char c) { return c == ' ' || c == '\t'; }

}  // namespace

bool CsvRow::split(std::string_view line) {
  fields_.clear();
  unescaped_.clear();
  size_t i = 0;
  const size_t n = line.size();
  for (;;) {
    while (i < n && blank(line[i])) ++i;
    if (i < n && line[i] == '"') {
      // Quoted: up to the closing quote; "" stands for one quote.
      const size_t open = ++i;
      bool escaped = false;
      for (;;) {
        if (i >= n) return false;
        if (line[i] == '"') {
          if (i + 1 < n && line[i + 1] == '"') {
            escaped = true;
            i += 2;
            continue;
          }
          break;
        }
        ++i;
      }
      std::string_view inner = line.substr(open, i - open);
      if (escaped) {
        std::string& text = unescaped_.emplace_back();
        for (size_t k = 0; k < inner.size(); ++k) {
          text.push_back(inner[k]);
          if (inner[k] == '"') ++k;  // the second quote of a pair
        }
        inner = text;
      }
      fields_.push_back(inner);
      ++i;  // past the closing quote
      while (i < n && line[i] != ',') ++i;  // anything between it and the comma is dropped
    } else {
      const size_t start = i;
      while (i < n && line[i] != ',') ++i;
      size_t end = i;
      while (end > start && blank(line[end - 1])) --end;
      fields_.push_back(line.substr(start, end - start));
    }
    if (i >= n) return true;
    ++i;  // past the comma
  }
}

}  // namespace latsim::capture
