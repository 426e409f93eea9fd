// The recorder's figures that need the whole run, and the guarded way in for
// pipeline-specific figures.
#include <cstdio>
#include <stdexcept>

#include "latsim/results/glossary.hpp"
#include "latsim/results/latency_recorder.hpp"

namespace latsim::results {

namespace {

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

}  // namespace

void LatencyRecorder::refuse(const std::string& name, const char* how) const {
  if (is_glossary_figure(name))
    throw std::logic_error("figure \"" + name + "\" is computed by the recorder for every pipeline (docs/figures.md); " +
                           how + " a pipeline-specific variant under a name of its own");
}

void LatencyRecorder::add(const std::string& name, double value) {
  distribution_ref(name).add(value);
  if (sample_log_.on()) sample_log_.add(sim_.now().to_ms(), name, value);
}

stats::Distribution& LatencyRecorder::distribution_ref(const std::string& name) {
  auto it = dists_.find(name);
  if (it == dists_.end()) {
    refuse(name, "add");
    it = dists_.emplace(name, stats::Distribution(0.005, keep_samples_)).first;
  }
  return it->second;
}

void LatencyRecorder::count(const std::string& name, int64_t n) {
  for (std::string_view own : recorder_counters())
    if (own == name) throw std::logic_error("counter \"" + name + "\" is the recorder's; count under another name");
  counters_[name] += n;
}

void LatencyRecorder::set(const std::string& name, FigureValue value) {
  refuse(name, "set");
  if (dists_.count(name) != 0) throw std::logic_error("figure \"" + name + "\" is already a distribution");
  table_.set(name, std::move(value));
}

void LatencyRecorder::list(const std::string& name) {
  refuse(name, "list");
  table_.list(name);
}

void LatencyRecorder::object(const std::string& name) {
  refuse(name, "object");
  table_.object(name);
}

void LatencyRecorder::publish(const std::string& name, const stats::Distribution& d) {
  refuse(name, "publish");
  if (dists_.count(name) != 0) throw std::logic_error("figure \"" + name + "\" is already a distribution");
  table_.publish(name, d);
}

const stats::Distribution* LatencyRecorder::distribution(const std::string& name) const {
  runs_.close_all();
  auto it = dists_.find(name);
  return it == dists_.end() ? nullptr : &it->second;
}

int64_t LatencyRecorder::counter(const std::string& name) const {
  auto it = counters_.find(name);
  return it == counters_.end() ? 0 : it->second;
}

std::vector<std::string> LatencyRecorder::default_headline() {
  return {"motion_to_photon_ms", "frame_rate_hz", "missed_refreshes", "registration_error_arcmin"};
}

std::vector<std::string> LatencyRecorder::headline(const nlohmann::json& all) const {
  std::vector<std::string> present;
  for (const std::string& name : headline_.empty() ? default_headline() : headline_) {
    const auto it = all.find(name);
    // A distribution without a sample says nothing: it is no headline.
    if (it == all.end() || (it->is_object() && it->contains("count") && it->at("count").get<int64_t>() == 0)) continue;
    present.push_back(name);
  }
  return present;
}

void LatencyRecorder::finish(const RunTotals& totals) {
  flush_pending();
  runs_.close_all();
  // A field whose first line would be lit after the run showed nothing, new
  // or old: there is nothing to judge it by.
  if (open_field_ != INT64_MIN && timing_.scanout_start(open_field_) > totals.duration) open_field_ = INT64_MIN;
  close_field();
  open_field_ = INT64_MIN;
  const double duration_s = totals.duration.to_seconds();
  // A pipeline without whole images (frameless) has no frame rate.
  const bool images = expects_images_ || deadlines_ || images_.registered() > 0;
  if (images) table_.set("frame_rate_hz", static_cast<double>(first_shown_eye0_) / duration_s);
  if (deadlines_) table_.set("missed_refreshes", missed_);
  table_.set("fields", totals.fields);
  table_.set("tracker_samples", totals.tracker_samples);
  measurement_figures(totals.duration);
  if (images && first_shown_eye0_ == 0)
    warn("no image was shown in " + fixed(duration_s, 3) + " s of simulated time: rendering never finished");
  else if (missed_ > 0)
    warn(std::to_string(missed_) + " of " + std::to_string(totals.fields) +
         " refreshes showed no new image although one was due (missed_refreshes)");
  link_figures(totals);
}

void LatencyRecorder::link_figures(const RunTotals& t) {
  if (t.line_occupancy <= des::Time::zero()) return;
  const double duration_s = t.duration.to_seconds();
  const double utilisation = static_cast<double>(records_offered_ + t.records_dropped + t.records_waiting) *
                             t.line_occupancy.to_seconds() / duration_s;
  table_.set("records_dropped", t.records_dropped);
  table_.set("line_utilisation", utilisation);
  // A line exactly as fast as the tracker (32 bytes at 19200 baud, 60 Hz) is
  // busy all the time but keeps up: only rounding to the picosecond would
  // put it above 1.
  constexpr double kRounding = 1e-9;
  if (utilisation > 1.0 + kRounding || t.records_dropped > 0)
    warn("serial line overloaded: " + t.link_description + " take " + fixed(t.line_occupancy.to_ms(), 3) +
         " ms each, the tracker sends one every " + fixed(t.tracker_period.to_ms(), 3) + " ms (line_utilisation " +
         fixed(utilisation, 3) + "); " + std::to_string(t.records_dropped) + " records dropped from a buffer of " +
         std::to_string(t.buffer_records));
  if (t.handler_time <= des::Time::zero()) return;
  const double handlers = static_cast<double>(records_offered_) * t.handler_time.to_seconds() / duration_s;
  table_.set("interrupt_utilisation", handlers);
  if (handlers > 1.0 + kRounding)
    warn("interrupt handlers overloaded: " + fixed(t.handler_time.to_ms(), 3) + " ms of handlers per record (" +
         "interrupt_utilisation " + fixed(handlers, 3) + "); the host falls further behind with every record");
}

}  // namespace latsim::results
