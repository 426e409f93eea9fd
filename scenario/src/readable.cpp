#include "latsim/scenario/readable.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <vector>

#include "latsim/scenario/choice_list.hpp"

namespace latsim::scenario {

namespace {

// Length of the well-formed UTF-8 sequence starting at text[i], or 0 when the
// bytes there are not one (a stray continuation byte, a truncated or overlong
// sequence, a surrogate).
size_t utf8_length(std::string_view text, size_t i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b = byte(i);
  size_t n = 0;
  unsigned min_code = 0;
  unsigned code = 0;
  if (b < 0x80) return 1;
  if ((b & 0xE0) == 0xC0) n = 2, min_code = 0x80, code = b & 0x1F;
  else if ((b & 0xF0) == 0xE0) n = 3, min_code = 0x800, code = b & 0x0F;
  else if ((b & 0xF8) == 0xF0) n = 4, min_code = 0x10000, code = b & 0x07;
  else return 0;
  if (i + n > text.size()) return 0;
  for (size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    code = (code << 6) | (byte(i + k) & 0x3F);
  }
  if (code < min_code || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return 0;
  return n;
}

void append_escaped(std::string& out, unsigned char c) {
  switch (c) {
    case '\n': out += "\\n"; return;
    case '\r': out += "\\r"; return;
    case '\t': out += "\\t"; return;
    default: {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02X", c);
      out += buf;
    }
  }
}

// The start of `text` made readable, at most about max_chars long; `cut`
// says whether anything was left out.
std::string readable_start(std::string_view text, size_t max_chars, bool& cut) {
  std::string out;
  out.reserve(std::min(text.size(), max_chars) + 16);
  size_t i = 0;
  while (i < text.size() && out.size() < max_chars) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const size_t n = utf8_length(text, i);
    if (n == 1 && c >= 0x20 && c != 0x7F) out += static_cast<char>(c);
    else if (n > 1) out.append(text.substr(i, n));
    else append_escaped(out, c);  // a control character, or a byte that is not UTF-8
    i += n == 0 ? 1 : n;
  }
  cut = i < text.size();
  return out;
}

}  // namespace

std::string readable(std::string_view text, size_t max_chars) {
  bool cut = false;
  std::string out = readable_start(text, max_chars, cut);
  if (cut) out += "\u2026 (" + std::to_string(text.size()) + " bytes)";
  return out;
}

std::string choice_list(const std::vector<std::string>& names, size_t max_chars) {
  std::string list;
  for (size_t i = 0; i < names.size(); ++i) {
    const std::string item = (i ? ", " : "") + quote_value(names[i]);
    if (i > 0 && list.size() + item.size() > max_chars)
      return list + ", \u2026 and " + std::to_string(names.size() - i) + " more";
    list += item;
  }
  return list;
}

std::string number_text(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[40];
  const auto result = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, result.ptr);
}

std::string integer_text(int64_t x) { return std::to_string(x); }
std::string integer_text(uint64_t x) { return std::to_string(x); }

std::string quote_value(std::string_view value) {
  bool cut = false;
  const std::string shown = readable_start(value, kQuotedChars, cut);
  if (!cut) return "\"" + shown + "\"";
  return "\"" + shown + "\u2026\" (" + std::to_string(value.size()) + " bytes)";
}

std::string readable_pointer(std::string_view pointer) {
  std::vector<std::string> segments;
  size_t i = 0;
  while (i < pointer.size()) {
    const size_t next = pointer.find('/', i + 1);
    const std::string_view segment = pointer.substr(i, next == std::string_view::npos ? std::string_view::npos : next - i);
    segments.push_back(readable(segment, kQuotedChars));
    if (next == std::string_view::npos) break;
    i = next;
  }
  std::string out;
  for (const auto& s : segments) out += s;
  // A pointer many levels deep keeps its first and last levels.
  constexpr size_t kEnds = 4;
  if (out.size() <= 2 * kQuotedChars || segments.size() <= 2 * kEnds) return out;
  out.clear();
  for (size_t k = 0; k < kEnds; ++k) out += segments[k];
  out += "/\u2026(" + std::to_string(segments.size() - 2 * kEnds) + " levels)";
  for (size_t k = segments.size() - kEnds; k < segments.size(); ++k) out += segments[k];
  return out;
}

}  // namespace latsim::scenario
