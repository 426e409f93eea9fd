#include "latsim/pipelines/timeline.hpp"

#include <charconv>
#include <cstdio>
#include <stdexcept>
#include <string_view>

namespace latsim::pipelines {

namespace {

uint64_t fnv1a(uint64_t h, const void* data, size_t n) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

void append_int(std::string& out, int64_t v) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

// ticks / per_unit as a decimal with six digits after the point, from
// integers: identical bytes on every platform, no rounding.
void append_fixed6(std::string& out, int64_t ticks, int64_t per_unit) {
  const uint64_t mag = ticks < 0 ? uint64_t{0} - static_cast<uint64_t>(ticks) : static_cast<uint64_t>(ticks);
  if (ticks < 0) out += '-';
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, mag / static_cast<uint64_t>(per_unit));
  out.append(buf, r.ptr);
  out += '.';
  uint64_t frac = mag % static_cast<uint64_t>(per_unit);
  char digits[6];
  for (int i = 5; i >= 0; --i, frac /= 10) digits[i] = static_cast<char>('0' + frac % 10);
  out.append(digits, 6);
}

// Milliseconds with nanosecond resolution (the CSV's established format).
void append_ms(std::string& out, des::Time t) { append_fixed6(out, t.ticks() / 1000, 1'000'000); }
// Microseconds with picosecond resolution: exact.
void append_us(std::string& out, des::Time t) { append_fixed6(out, t.ticks(), 1'000'000); }

// s as a JSON string literal, appended to out.
void append_json_string(std::string& out, std::string_view s) {
  out += '"';
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += buf;
    } else {
      out += c;
    }
  }
  out += '"';
}

}  // namespace

void Timeline::Writer::open(RunFiles& files) {
  csv_ = files.stream("timeline.csv");
  json_ = files.stream("timeline.json");
  csv_.write("stage,frame,eye,unit,start_ms,end_ms\n");
  // Chrome trace-event format: one complete ("X") event per stage interval,
  // one thread per unit (named when it first appears), timestamps in microseconds.
  json_.write("{\"displayTimeUnit\":\"ms\",\"traceEvents\":[");
}

void Timeline::Writer::write(const Entry& e) {
  std::string& b = buffer_;
  b.clear();
  b += e.stage;
  b += ',';
  append_int(b, e.frame);
  b += ',';
  append_int(b, e.eye);
  b += ',';
  b += e.unit;
  b += ',';
  append_ms(b, e.start);
  b += ',';
  append_ms(b, e.end);
  b += '\n';
  csv_.write(b);

  // Appended in place: no temporary strings (a few entries every field).
  b.clear();
  auto it = tids_.find(e.unit);
  if (it == tids_.end()) {
    it = tids_.emplace(e.unit, static_cast<int>(tids_.size()) + 1).first;
    b += first_event_ ? "\n" : ",\n";
    b += "{\"args\":{\"name\":";
    append_json_string(b, e.unit);
    b += "},\"name\":\"thread_name\",\"ph\":\"M\",\"pid\":1,\"tid\":";
    append_int(b, it->second);
    b += '}';
    first_event_ = false;
  }
  b += first_event_ ? "\n" : ",\n";
  b += "{\"args\":{\"eye\":";
  append_int(b, e.eye);
  b += ",\"frame\":";
  append_int(b, e.frame);
  b += "},\"cat\":";
  append_json_string(b, e.stage);
  b += ",\"dur\":";
  append_us(b, e.end - e.start);
  // The name, "<stage> <frame>[ L| R]", as a JSON string: the frame and
  // the eye need no escaping.
  b += ",\"name\":";
  append_json_string(b, e.stage);
  b.pop_back();
  b += ' ';
  append_int(b, e.frame);
  if (e.eye >= 0) b += e.eye == 0 ? " L" : " R";
  b += '"';
  b += ",\"ph\":\"X\",\"pid\":1,\"tid\":";
  append_int(b, it->second);
  b += ",\"ts\":";
  append_us(b, e.start);
  b += '}';
  json_.write(b);
  first_event_ = false;
}

void Timeline::Writer::finish(RunFiles& files) {
  json_.write("\n]}\n");
  files.commit(csv_, "timeline.csv");
  files.commit(json_, "timeline.json");
}

void Timeline::add(std::string stage, int64_t frame, int eye, std::string unit, des::Time start, des::Time end) {
  if (max_entries_ > 0 && accepted_ >= max_entries_) {
    ++dropped_;
    return;
  }
  ++accepted_;
  fingerprint_ = fnv1a(fingerprint_, stage.data(), stage.size());
  fingerprint_ = fnv1a(fingerprint_, unit.data(), unit.size());
  const int64_t v[4] = {frame, eye, start.ticks(), end.ticks()};
  fingerprint_ = fnv1a(fingerprint_, v, sizeof v);
  Entry e{std::move(stage), frame, eye, std::move(unit), start, end};
  if (files_ == nullptr) {
    entries_.push_back(std::move(e));
    return;
  }
  if (!stream_.is_open()) stream_.open(*files_);
  stream_.write(e);
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

}  // namespace latsim::pipelines
