#include "latsim/results/timeline.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string_view>

namespace latsim::results {

namespace {

// The formatters write at a cursor into a buffer sized beforehand for the
// longest possible entry (entry_bytes()): no bounds checks, no string growth.
void put(char*& p, std::string_view s) {
  std::memcpy(p, s.data(), s.size());
  p += s.size();
}

void put_int(char*& p, int64_t v) { p = std::to_chars(p, p + 24, v).ptr; }

// ticks / per_unit as a decimal with six digits after the point, from
// integers: identical bytes on every platform, no rounding.
void put_fixed6(char*& p, int64_t ticks, int64_t per_unit) {
  const uint64_t mag = ticks < 0 ? uint64_t{0} - static_cast<uint64_t>(ticks) : static_cast<uint64_t>(ticks);
  if (ticks < 0) *p++ = '-';
  p = std::to_chars(p, p + 24, mag / static_cast<uint64_t>(per_unit)).ptr;
  *p++ = '.';
  uint64_t frac = mag % static_cast<uint64_t>(per_unit);
  for (int i = 5; i >= 0; --i, frac /= 10) p[i] = static_cast<char>('0' + frac % 10);
  p += 6;
}

// Milliseconds with nanosecond resolution (the CSV's established format).
void put_ms(char*& p, des::Time t) { put_fixed6(p, t.ticks() / 1000, 1'000'000); }
// Microseconds with picosecond resolution: exact.
void put_us(char*& p, des::Time t) { put_fixed6(p, t.ticks(), 1'000'000); }

// The characters of s as the inside of a JSON string literal.
void put_json_chars(char*& p, std::string_view s) {
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      *p++ = '\\';
      *p++ = c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      constexpr char kHex[] = "0123456789abcdef";
      put(p, "\\u00");
      *p++ = kHex[static_cast<unsigned char>(c) >> 4];
      *p++ = kHex[static_cast<unsigned char>(c) & 15];
    } else {
      *p++ = c;
    }
  }
}

void put_json_string(char*& p, std::string_view s) {
  *p++ = '"';
  put_json_chars(p, s);
  *p++ = '"';
}

// An upper bound of the bytes of an entry in either format: every character
// of the names escaped (six bytes), the numbers at their longest (20 digits
// and a sign, or those and a point and six decimals), and the fixed text.
size_t entry_bytes(std::string_view stage, std::string_view unit) { return 12 * (stage.size() + unit.size()) + 512; }

}  // namespace

void Timeline::Writer::open(RunFiles& files) {
  csv_ = files.stream("timeline.csv");
  json_ = files.stream("timeline.json");
  csv_.write("stage,frame,eye,unit,start_ms,end_ms\n");
  // Chrome trace-event format: one complete ("X") event per stage interval,
  // one thread per unit (named when it first appears), timestamps in microseconds.
  json_.write("{\"displayTimeUnit\":\"ms\",\"traceEvents\":[");
}

void Timeline::Writer::write(std::string_view stage, int64_t frame, int eye, std::string_view unit, des::Time start,
                             des::Time end) {
  std::string& b = buffer_;
  if (b.size() < entry_bytes(stage, unit)) b.resize(entry_bytes(stage, unit));
  char* p = b.data();
  put(p, stage);
  *p++ = ',';
  put_int(p, frame);
  *p++ = ',';
  put_int(p, eye);
  *p++ = ',';
  put(p, unit);
  *p++ = ',';
  put_ms(p, start);
  *p++ = ',';
  put_ms(p, end);
  *p++ = '\n';
  csv_.write(std::string_view(b.data(), static_cast<size_t>(p - b.data())));

  p = b.data();
  // Thread ids in order of appearance; a handful of units, found by a scan.
  auto it = std::find_if(tids_.begin(), tids_.end(), [&](const auto& t) { return t.first == unit; });
  if (it == tids_.end()) {
    tids_.emplace_back(unit, static_cast<int>(tids_.size()) + 1);
    it = tids_.end() - 1;
    put(p, first_event_ ? "\n" : ",\n");
    put(p, "{\"args\":{\"name\":");
    put_json_string(p, unit);
    put(p, "},\"name\":\"thread_name\",\"ph\":\"M\",\"pid\":1,\"tid\":");
    put_int(p, it->second);
    *p++ = '}';
    first_event_ = false;
  }
  put(p, first_event_ ? "\n" : ",\n");
  put(p, "{\"args\":{\"eye\":");
  put_int(p, eye);
  put(p, ",\"frame\":");
  put_int(p, frame);
  put(p, "},\"cat\":");
  put_json_string(p, stage);
  put(p, ",\"dur\":");
  put_us(p, end - start);
  // The name, "<stage> <frame>[ L| R]", as a JSON string: the frame and the
  // eye need no escaping.
  put(p, ",\"name\":\"");
  put_json_chars(p, stage);
  *p++ = ' ';
  put_int(p, frame);
  if (eye >= 0) put(p, eye == 0 ? " L" : " R");
  put(p, "\",\"ph\":\"X\",\"pid\":1,\"tid\":");
  put_int(p, it->second);
  put(p, ",\"ts\":");
  put_us(p, start);
  *p++ = '}';
  json_.write(std::string_view(b.data(), static_cast<size_t>(p - b.data())));
  first_event_ = false;
}

void Timeline::Writer::finish(RunFiles& files) {
  json_.write("\n]}\n");
  files.commit(csv_, "timeline.csv");
  files.commit(json_, "timeline.json");
}

void Timeline::add(std::string_view stage, int64_t frame, int eye, std::string_view unit, des::Time start,
                   des::Time end) {
  if (max_entries_ > 0 && accepted_ >= max_entries_) {
    ++dropped_;
    return;
  }
  ++accepted_;
  if (files_ == nullptr) {
    entries_.push_back(Entry{std::string(stage), frame, eye, std::string(unit), start, end});
    return;
  }
  if (!stream_.is_open()) stream_.open(*files_);
  stream_.write(stage, frame, eye, unit, start, end);
}

void Timeline::stream_to(RunFiles& files) {
  files_ = &files;
  if (entries_.empty()) return;
  stream_.open(files);
  for (const Entry& e : entries_) stream_.write(e);
  std::vector<Entry>().swap(entries_);
}

void Timeline::finish(RunFiles& files) {
  if (stream_.is_open()) stream_.finish(files);
}

}  // namespace latsim::results
