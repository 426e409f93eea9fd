#include "harness.hpp"

#include <algorithm>
#include <functional>
#include <stdexcept>

#include "latsim/des/random.hpp"
#include "latsim/des/simulator.hpp"
#include "latsim/display/display.hpp"

namespace latsim::pxpl5::testing {

const stats::Distribution& RunRecord::dist(const std::string& name) const {
  const auto it = samples.find(name);
  if (it == samples.end()) throw std::out_of_range("no samples named " + name);
  return it->second;
}

uint64_t RunRecord::stage_fingerprint() const {
  uint64_t h = 0xcbf29ce484222325ULL;
  const auto mix = [&h](uint64_t v) { h = des::mix64(h ^ v); };
  for (const StageInterval& s : stages) {
    mix(des::fnv1a64(s.stage));
    mix(static_cast<uint64_t>(s.frame));
    mix(static_cast<uint64_t>(s.eye));
    mix(des::fnv1a64(s.unit));
    mix(static_cast<uint64_t>(s.start.ticks()));
    mix(static_cast<uint64_t>(s.end.ticks()));
  }
  return h;
}

FieldTiming ntsc_timing() { return FieldTiming(des::Time::zero(), des::RationalSeconds{1, 60}, 22, 240, true); }

RegionGrid ntsc_grid() { return RegionGrid::for_screen(640, 480, true, 128); }

namespace {

EngineHooks recording_hooks(RunRecord& rec, std::function<int64_t(des::Time)> newest) {
  EngineHooks h;
  h.newest_sample = std::move(newest);
  h.frame_ready = [&rec](const FrameReady& f) { rec.frames.push_back(f); };
  h.stage = [&rec](const StageInterval& s) { rec.stages.push_back(s); };
  h.sample = [&rec](const std::string& name, double v) { rec.samples[name].add(v); };
  h.region_written = [&rec](const RegionWrite& w) { rec.writes.push_back(w); };
  // Sample k of the 60 Hz tracker is measured at k / 60 s.
  h.sample_age_ms = [](int64_t older, int64_t newer) { return static_cast<double>(newer - older) * 1000.0 / 60.0; };
  return h;
}

// A 60 Hz tracker whose sample k is visible from k / 60 s.
const des::RationalSeconds kTrackerPeriod{1, 60};

}  // namespace

RunRecord run_rc(const RcParams& params, const Workload& workload, des::Time duration, uint64_t seed) {
  SyntheticWorkload source(workload, ntsc_grid().regions(), des::RandomStream(seed, "pxpl5.bins"));
  return run_rc(params, source, duration);
}

RunRecord run_rc(const RcParams& params, WorkloadSource& source, des::Time duration) {
  RunRecord rec;
  des::Simulator sim;
  const des::PeriodicSchedule tracker(des::Time::zero(), kTrackerPeriod);
  auto newest = [tracker](des::Time t) { return tracker.index_at_or_before(t); };
  EngineHooks hooks = recording_hooks(rec, newest);
  hooks.frame_ready = [&rec, &sim](const FrameReady& f) {
    rec.frames.push_back(f);
    rec.frame_ready_at.push_back(sim.now());
  };
  RcEngine engine(sim, params, ntsc_timing(), ntsc_grid(), source, hooks);
  engine.start(duration);
  sim.run_until(duration);
  rec.utilisation = engine.utilisation(duration);
  rec.sim_fingerprint = sim.fingerprint();
  rec.field_ms = ntsc_timing().period_ms();
  return rec;
}

namespace {

des::Process tell_samples(des::Simulator& sim, RcEngine& engine, des::PeriodicSchedule tracker, des::Time end) {
  for (int64_t k = 1; tracker.at(k) < end; ++k) {
    co_await sim.until(tracker.at(k));
    engine.sample_visible();
  }
}

}  // namespace

RunRecord run_rc_with_tracker(const RcParams& params, const Workload& workload, des::Time duration,
                              des::RationalSeconds tracker_period) {
  RunRecord rec;
  des::Simulator sim;
  SyntheticWorkload source(workload, ntsc_grid().regions(), des::RandomStream(1, "pxpl5.bins"));
  const des::PeriodicSchedule tracker(des::Time::zero(), tracker_period);
  auto newest = [tracker](des::Time t) { return tracker.index_at_or_before(t); };
  EngineHooks hooks = recording_hooks(rec, newest);
  hooks.newest_index = newest;
  RcEngine engine(sim, params, ntsc_timing(), ntsc_grid(), source, hooks);
  sim.spawn(tell_samples(sim, engine, tracker, duration), sim.kind("test.tracker"));
  engine.start(duration);
  sim.run_until(duration);
  rec.sim_fingerprint = sim.fingerprint();
  rec.field_ms = ntsc_timing().period_ms();
  return rec;
}

RunRecord run_slats_with(const SlatsParams& params, WorkloadSource& source, des::Time duration, des::Simulator* shared,
                         const std::function<void(const RegionWrite&)>& on_write = {});

RunRecord run_slats(const SlatsParams& params, int64_t triangles, des::Time duration) {
  SyntheticWorkload source(Workload{triangles, 1.3}, ntsc_grid().regions(), des::RandomStream(1, "pxpl5.bins"));
  return run_slats(params, source, duration);
}

RunRecord run_slats(const SlatsParams& params, WorkloadSource& source, des::Time duration) {
  return run_slats_with(params, source, duration, nullptr);
}

namespace {

/// Keeps the spans of one field and eye.
class FieldSpans final : public display::ScanoutListener {
 public:
  FieldSpans(int64_t field, int eye) : field_(field), eye_(eye) {}
  void on_scanout(const display::ScanoutSpan& s) override {
    if (s.field == field_ && s.eye == eye_) spans.push_back(LitSpan{s.line, s.x_begin, s.x_end, s.image_id, s.photon_time});
  }
  std::vector<LitSpan> spans;

 private:
  int64_t field_;
  int eye_;
};

}  // namespace

std::vector<LitSpan> run_slats_on_display(const SlatsParams& params, WorkloadSource& source, des::Time duration,
                                          int64_t field, int eye, RunRecord& record) {
  des::Simulator sim;
  display::RasterParams raster;
  raster.interlaced = true;
  display::Display screen(sim, display::RasterTiming(raster), params.eyes(), display::ScanoutFidelity::Line);
  FieldSpans spans(field, eye);
  screen.add_listener(&spans);
  const auto write = [&screen](const RegionWrite& w) {
    // Field region (row, column) holds field lines 128 row .. 128 row + 127
    // (240 lines per field), i.e. every other screen row from 2 x line + parity.
    const int parity = static_cast<int>(w.field % 2);
    const int first_line = 128 * w.field_row, end_line = std::min(128 * (w.field_row + 1), 240);
    const display::BufferRegion region{128 * w.column, 128 * (w.column + 1), 2 * first_line + parity,
                                       2 * end_line + parity, 2};
    screen.write_region_now(w.eye, region, w.image_field);
  };
  screen.start(duration);
  record = run_slats_with(params, source, duration, &sim, write);
  return spans.spans;
}

RunRecord run_slats_with(const SlatsParams& params, WorkloadSource& source, des::Time duration, des::Simulator* shared,
                         const std::function<void(const RegionWrite&)>& on_write) {
  RunRecord rec;
  des::Simulator own;
  des::Simulator& sim = shared ? *shared : own;
  EngineHooks hooks = recording_hooks(rec, {});
  if (on_write) hooks.region_written = [&rec, on_write](const RegionWrite& w) {
    rec.writes.push_back(w);
    on_write(w);
  };
  SlatsEngine engine(sim, params, ntsc_timing(), ntsc_grid(), source, hooks);
  const des::PeriodicSchedule tracker(des::Time::zero(), kTrackerPeriod);
  const des::KindId kind = sim.kind("tracker.sample");
  std::function<void(int64_t)> deliver = [&](int64_t k) {
    engine.host_sample(k);
    if (tracker.at(k + 1) < duration) sim.at(tracker.at(k + 1), kind, [&deliver, k] { deliver(k + 1); });
  };
  sim.at(des::Time::zero(), kind, [&deliver] { deliver(0); });
  engine.start(duration);
  sim.run_until(duration);
  rec.utilisation = engine.utilisation(duration);
  rec.counts = engine.counts();
  rec.missed_fields = rec.counts.missed;
  rec.torn_fields = rec.counts.torn;
  rec.sim_fingerprint = sim.fingerprint();
  rec.field_ms = ntsc_timing().period_ms();
  return rec;
}

RcParams trivial_rc_params() {
  RcParams p;
  p.send_time = des::Time::zero();
  p.send_words = 0;
  p.edit_time = des::Time::zero();
  p.transform_overhead = des::Time::zero();
  p.transform_time_per_triangle = des::Time::zero();
  p.binitize_time_per_bin = des::Time::zero();
  p.token_hop_time = des::Time::zero();
  p.region_shade_time = des::Time::zero();
  p.end_of_frame_words = 0;
  p.hw.render_time_per_command = des::Time::zero();
  return p;
}

const EyeWork& VaryingWorkload::work(int64_t token, int, int processors) {
  const int64_t n = std::min(list_, on_screen_(token));
  work_ = EyeWork{};
  work_.bins = BinCounts(processors, ntsc_grid().regions());
  work_.on_screen.assign(static_cast<std::size_t>(list_), 0);
  for (int64_t t = 0; t < list_; ++t) {
    work_.on_screen[static_cast<std::size_t>(t)] = t < n ? 1 : 0;
    work_.bins.add_triangle(t, t < n, {0});
  }
  work_.on_screen_count = n;
  return work_;
}

}  // namespace latsim::pxpl5::testing
