#include "row_source.hpp"

#include <algorithm>
#include <cctype>

#include "latsim/capture/capture.hpp"

namespace latsim::capture {

namespace {

bool blank(std::string_view line) { return line.find_first_not_of(" \t\r") == std::string_view::npos; }

}  // namespace

std::optional<size_t> find_column(const std::vector<std::string>& header, std::string_view name) {
  const auto it = std::find(header.begin(), header.end(), name);
  if (it == header.end()) return std::nullopt;
  return static_cast<size_t>(it - header.begin());
}

bool split_vrapi(std::string_view line, VrApiFields& out) {
  out.keys.clear();
  out.values.clear();
  const size_t at = line.find("FPS=");
  if (at == std::string_view::npos || line.find(",Prd=", at) == std::string_view::npos) return false;
  std::string_view rest = line.substr(at);
  while (!rest.empty()) {
    const size_t comma = rest.find(',');
    const std::string_view piece = rest.substr(0, comma);
    const size_t eq = piece.find('=');
    if (eq == std::string_view::npos) {
      // The rest of the value before it: widen that value to the end of this piece.
      if (!out.values.empty()) {
        const std::string_view& v = out.values.back();
        out.values.back() = std::string_view(v.data(), static_cast<size_t>(piece.data() + piece.size() - v.data()));
      }
    } else {
      out.keys.push_back(piece.substr(0, eq));
      out.values.push_back(piece.substr(eq + 1));
    }
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return true;
}

namespace {

// A line logcat writes: "--------- beginning of main", or one that starts
// with a date ("01-02 12:00:00.000 ...") or a priority and tag ("I/VrApi").
bool logcat_line(std::string_view line) {
  if (line.rfind("---------", 0) == 0) return true;
  const bool date = line.size() > 6 && std::isdigit(static_cast<unsigned char>(line[0])) &&
                    std::isdigit(static_cast<unsigned char>(line[1])) && line[2] == '-';
  return date || (line.size() > 2 && line[1] == '/' && std::string_view("VDIWEF").find(line[0]) != std::string_view::npos);
}

}  // namespace

std::string shown(std::string_view v) {
  std::string out;
  for (char c : v.substr(0, 40)) out.push_back(static_cast<unsigned char>(c) < 0x20 || c == 0x7f ? '?' : c);
  if (v.size() > 40) out += "...";
  return out;
}

std::string name_list(const std::vector<std::string>& names) {
  // Past this a list of names in a message is cut short: an error is one line.
  constexpr size_t kListBudgetChars = 110;
  std::string out;
  size_t shown_count = 0;
  for (const std::string& n : names) {
    if (out.size() + n.size() > kListBudgetChars) break;
    out += (shown_count ? ", " : "") + shown(n);
    ++shown_count;
  }
  if (shown_count < names.size()) out += ", ... (" + std::to_string(names.size()) + " in all)";
  return out;
}

RowSource::RowSource(const std::filesystem::path& file) : lines_(file) {
  std::string_view line;
  do {
    if (!lines_.next(line)) throw CaptureError(file, lines_.number(), "empty capture file: no header line");
  } while (blank(line));
  // A VrApi log has no header: its first statistics line names the fields.
  if (!split_vrapi(line, kv_) && logcat_line(line)) {
    do {
      if (!blank(line)) ++other_lines_;
      if (!lines_.next(line)) fail("a logcat file without a VrApi statistics line (FPS=..,Prd=..)");
    } while (!split_vrapi(line, kv_));
  }
  if (!kv_.keys.empty()) {
    vrapi_ = true;
    for (std::string_view k : kv_.keys) header_.emplace_back(k);
    by_key_.assign(header_.size(), std::string_view());
    pending_first_ = true;
  } else {
    if (!csv_.split(line)) fail("an unterminated quote in the header");
    for (std::string_view f : csv_.fields()) header_.emplace_back(f);
  }
}

std::optional<size_t> RowSource::column(std::string_view name) const {
  const auto at = find_column(header_, name);
  // Two columns (or VrApi keys) of the name looked up: which one is meant
  // cannot be told, whichever reader asks (the first was taken, silently).
  // A column no reader asks for may repeat.
  if (at && std::find(header_.begin() + static_cast<std::ptrdiff_t>(*at) + 1, header_.end(), name) != header_.end())
    fail("column \"" + shown(name) + "\" appears twice in the header: which one is meant cannot be told");
  return at;
}

bool RowSource::next(size_t max_fields) {
  if (vrapi_) return next_vrapi();
  std::string_view line;
  do {
    if (!lines_.next(line)) return false;
  } while (blank(line));
  if (!csv_.split(line, max_fields)) fail("an unterminated quote");
  fields_ = &csv_.fields();
  return true;
}

bool RowSource::next_vrapi() {
  if (!pending_first_) {
    std::string_view line;
    for (;;) {
      if (!lines_.next(line)) return false;
      if (split_vrapi(line, kv_)) break;
      if (!blank(line)) ++other_lines_;
    }
  }
  pending_first_ = false;
  std::fill(by_key_.begin(), by_key_.end(), std::string_view());
  for (size_t i = 0; i < kv_.keys.size(); ++i) {
    const auto it = std::find(header_.begin(), header_.end(), kv_.keys[i]);
    if (it != header_.end()) by_key_[static_cast<size_t>(it - header_.begin())] = kv_.values[i];
  }
  fields_ = &by_key_;
  return true;
}

void RowSource::fail(const std::string& reason) const { throw CaptureError(lines_.file(), lines_.number(), reason); }

}  // namespace latsim::capture
