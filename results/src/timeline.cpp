#include "latsim/results/timeline.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string_view>

#include "cursor_text.hpp"

namespace latsim::results {

namespace {

using cursor::put;
using cursor::put_int;

// Milliseconds with nanosecond resolution (the CSV's established format).
void put_ms(char*& p, des::Time t) { cursor::put_fixed<1'000'000, 6>(p, t.ticks() / 1000); }
// Microseconds with picosecond resolution: exact.
void put_us(char*& p, des::Time t) { cursor::put_fixed<1'000'000, 6>(p, t.ticks()); }

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
size_t entry_bytes(std::string_view stage, std::string_view unit) { return 12 * (stage.size() + unit.size()) + 1024; }

// The marks a pose-to-photon arrow runs between.
constexpr std::string_view kFlowFrom = "SAMPLE";
constexpr std::string_view kFlowTo = "PHOTON";

}  // namespace

void Timeline::Writer::open(RunFiles& files) {
  csv_ = files.stream("timeline.csv");
  json_ = files.stream("timeline.json");
  csv_.write("stage,frame,eye,unit,start_ms,end_ms,lane\n");
  // Chrome trace-event format: one complete ("X") event per stage interval,
  // one thread per lane of a unit (named when it first appears), timestamps
  // in microseconds.
  json_.write("{\"displayTimeUnit\":\"ms\",\"traceEvents\":[");
}

void Timeline::Writer::separator(char*& p) {
  put(p, first_event_ ? "\n" : ",\n");
  first_event_ = false;
}

const Timeline::Writer::Track& Timeline::Writer::track_for(std::string_view unit, des::Time start, des::Time end,
                                                           char*& p) {
  // A handful of tracks, found by a scan.
  int lanes = 0;
  for (Track& t : tracks_) {
    if (t.unit != unit) continue;
    ++lanes;
    if (t.max_end <= start) {
      t.max_end = std::max(t.max_end, end);
      return t;
    }
  }
  auto unit_it = std::find(units_.begin(), units_.end(), unit);
  if (unit_it == units_.end()) unit_it = units_.insert(units_.end(), std::string(unit));
  const int unit_index = static_cast<int>(unit_it - units_.begin());
  tracks_.push_back(Track{std::string(unit), lanes, static_cast<int>(tracks_.size()) + 1, end});
  const Track& t = tracks_.back();
  // The lane's name ("unit", "unit #2", ...) and its place: lanes of a unit
  // together, units in order of appearance.
  separator(p);
  put(p, "{\"args\":{\"name\":\"");
  put_json_chars(p, unit);
  if (t.lane > 0) {
    put(p, " #");
    put_int(p, t.lane + 1);
  }
  put(p, "\"},\"name\":\"thread_name\",\"ph\":\"M\",\"pid\":1,\"tid\":");
  put_int(p, t.tid);
  put(p, "},\n{\"args\":{\"sort_index\":");
  put_int(p, int64_t{unit_index} * 64 + t.lane);
  put(p, "},\"name\":\"thread_sort_index\",\"ph\":\"M\",\"pid\":1,\"tid\":");
  put_int(p, t.tid);
  *p++ = '}';
  return t;
}

void Timeline::Writer::write(const Entry& e) {
  switch (e.kind) {
    case Kind::interval: write(e.stage, e.frame, e.eye, e.unit, e.start, e.end); break;
    case Kind::counter: write_counter(e.stage, e.start, e.value); break;
    case Kind::flow: write_flow(e.frame, e.unit, e.start, e.to_unit, e.end); break;
  }
}

void Timeline::Writer::write(std::string_view stage, int64_t frame, int eye, std::string_view unit, des::Time start,
                             des::Time end) {
  std::string& b = buffer_;
  if (b.size() < entry_bytes(stage, unit)) b.resize(entry_bytes(stage, unit));
  char* p = b.data();
  const Track& track = track_for(unit, start, end, p);
  separator(p);
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
  put_int(p, track.tid);
  put(p, ",\"ts\":");
  put_us(p, start);
  *p++ = '}';
  json_.write(std::string_view(b.data(), static_cast<size_t>(p - b.data())));

  p = b.data();
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
  *p++ = ',';
  put_int(p, track.lane);
  *p++ = '\n';
  csv_.write(std::string_view(b.data(), static_cast<size_t>(p - b.data())));
}

void Timeline::Writer::write_counter(std::string_view name, des::Time at, double value) {
  std::string& b = buffer_;
  if (b.size() < entry_bytes(name, {})) b.resize(entry_bytes(name, {}));
  char* p = b.data();
  separator(p);
  put(p, "{\"args\":{\"value\":");
  // Shortest round-trip form: the same bytes for the same value everywhere.
  p = std::to_chars(p, p + 32, std::isfinite(value) ? value : 0.0).ptr;
  put(p, "},\"name\":");
  put_json_string(p, name);
  put(p, ",\"ph\":\"C\",\"pid\":1,\"ts\":");
  put_us(p, at);
  *p++ = '}';
  json_.write(std::string_view(b.data(), static_cast<size_t>(p - b.data())));
}

void Timeline::Writer::write_flow(int64_t id, std::string_view from_unit, des::Time from, std::string_view to_unit,
                                  des::Time to) {
  std::string& b = buffer_;
  const size_t bytes = 2 * entry_bytes(kFlowFrom, from_unit) + 2 * entry_bytes(kFlowTo, to_unit);
  if (b.size() < bytes) b.resize(bytes);
  char* p = b.data();
  // Each end is a zero-length mark on its own track, which the arrow binds to.
  auto mark = [&](std::string_view stage, std::string_view unit, des::Time at) {
    const Track& t = track_for(unit, at, at, p);
    separator(p);
    put(p, "{\"args\":{\"flow\":");
    put_int(p, id);
    put(p, "},\"cat\":");
    put_json_string(p, stage);
    put(p, ",\"dur\":0,\"name\":");
    put_json_string(p, stage);
    put(p, ",\"ph\":\"X\",\"pid\":1,\"tid\":");
    put_int(p, t.tid);
    put(p, ",\"ts\":");
    put_us(p, at);
    *p++ = '}';
    return t.tid;
  };
  auto arrow = [&](const char* phase, int tid, des::Time at) {
    separator(p);
    put(p, "{");
    if (phase[0] == 'f') put(p, "\"bp\":\"e\",");
    put(p, "\"cat\":\"flow\",\"id\":");
    put_int(p, id);
    put(p, ",\"name\":\"pose to photon\",\"ph\":\"");
    put(p, phase);
    put(p, "\",\"pid\":1,\"tid\":");
    put_int(p, tid);
    put(p, ",\"ts\":");
    put_us(p, at);
    *p++ = '}';
  };
  const int from_tid = mark(kFlowFrom, from_unit, from);
  const int to_tid = mark(kFlowTo, to_unit, to);
  arrow("s", from_tid, from);
  arrow("f", to_tid, to);
  json_.write(std::string_view(b.data(), static_cast<size_t>(p - b.data())));
}

void Timeline::Writer::finish(RunFiles& files) {
  json_.write("\n]}\n");
  files.commit(csv_, "timeline.csv");
  files.commit(json_, "timeline.json");
}

bool Timeline::accept() {
  if (max_entries_ > 0 && accepted_ >= max_entries_) {
    ++dropped_;
    return false;
  }
  ++accepted_;
  return true;
}

Timeline::Writer* Timeline::stream() {
  if (files_ == nullptr) return nullptr;
  if (!stream_.is_open()) stream_.open(*files_);
  return &stream_;
}

void Timeline::add(std::string_view stage, int64_t frame, int eye, std::string_view unit, des::Time start,
                   des::Time end) {
  if (!accept()) return;
  Writer* out = stream();
  if (out == nullptr) {
    entries_.push_back(Entry{std::string(stage), frame, eye, std::string(unit), start, end, Kind::interval, 0, {}});
    return;
  }
  out->write(stage, frame, eye, unit, start, end);
}

void Timeline::add_counter(std::string_view name, des::Time at, double value) {
  if (!accept()) return;
  Writer* out = stream();
  if (out == nullptr) {
    entries_.push_back(Entry{std::string(name), 0, -1, {}, at, at, Kind::counter, value, {}});
    return;
  }
  out->write_counter(name, at, value);
}

void Timeline::add_flow(int64_t id, std::string_view from_unit, des::Time from, std::string_view to_unit,
                        des::Time to) {
  if (!accept()) return;
  Writer* out = stream();
  if (out == nullptr) {
    entries_.push_back(Entry{{}, id, -1, std::string(from_unit), from, to, Kind::flow, 0, std::string(to_unit)});
    return;
  }
  out->write_flow(id, from_unit, from, to_unit, to);
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
