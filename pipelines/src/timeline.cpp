#include "latsim/pipelines/timeline.hpp"

#include <cstdio>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>


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

std::string ms_text(des::Time t) {
  // Nanosecond resolution, fixed format: identical bytes on every platform.
  char buf[40];
  const int64_t ns = t.ticks() / 1000;
  const int64_t whole = ns / 1'000'000, frac = ns % 1'000'000;
  std::snprintf(buf, sizeof buf, "%s%lld.%06lld", (ns < 0 ? "-" : ""), static_cast<long long>(whole < 0 ? -whole : whole),
                static_cast<long long>(frac < 0 ? -frac : frac));
  return buf;
}

}  // namespace

void Timeline::add(std::string stage, int64_t frame, int eye, std::string unit, des::Time start, des::Time end) {
  if (max_entries_ > 0 && entries_.size() >= max_entries_) {
    ++dropped_;
    return;
  }
  entries_.push_back(Entry{std::move(stage), frame, eye, std::move(unit), start, end});
}

uint64_t Timeline::fingerprint() const {
  uint64_t h = 1469598103934665603ull;
  for (const auto& e : entries_) {
    h = fnv1a(h, e.stage.data(), e.stage.size());
    h = fnv1a(h, e.unit.data(), e.unit.size());
    const int64_t v[4] = {e.frame, e.eye, e.start.ticks(), e.end.ticks()};
    h = fnv1a(h, v, sizeof v);
  }
  return h;
}

std::string Timeline::csv() const {
  std::ostringstream out;
  out << "stage,frame,eye,unit,start_ms,end_ms\n";
  for (const auto& e : entries_)
    out << e.stage << ',' << e.frame << ',' << e.eye << ',' << e.unit << ',' << ms_text(e.start) << ','
        << ms_text(e.end) << '\n';
  return out.str();
}

std::string Timeline::trace_json() const {
  // Chrome trace-event format: one complete ("X") event per stage interval,
  // one thread per unit, timestamps in microseconds.
  std::map<std::string, int> tids;
  for (const auto& e : entries_) tids.emplace(e.unit, 0);
  int next = 1;
  for (auto& [unit, tid] : tids) tid = next++;
  nlohmann::json events = nlohmann::json::array();
  for (const auto& [unit, tid] : tids)
    events.push_back({{"name", "thread_name"}, {"ph", "M"}, {"pid", 1}, {"tid", tid}, {"args", {{"name", unit}}}});
  for (const auto& e : entries_) {
    const std::string name = e.stage + " " + std::to_string(e.frame) + (e.eye >= 0 ? (e.eye == 0 ? " L" : " R") : "");
    events.push_back({{"name", name},
                      {"cat", e.stage},
                      {"ph", "X"},
                      {"pid", 1},
                      {"tid", tids[e.unit]},
                      {"ts", e.start.to_us()},
                      {"dur", (e.end - e.start).to_us()},
                      {"args", {{"frame", e.frame}, {"eye", e.eye}}}});
  }
  nlohmann::json doc{{"traceEvents", events}, {"displayTimeUnit", "ms"}};
  return doc.dump() + "\n";
}

}  // namespace latsim::pipelines
