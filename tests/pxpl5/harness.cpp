#include "harness.hpp"

#include <functional>
#include <stdexcept>

#include "latsim/des/random.hpp"
#include "latsim/des/simulator.hpp"

namespace latsim::pxpl5::testing {

const des::Distribution& RunRecord::dist(const std::string& name) const {
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
  return h;
}

// A 60 Hz tracker whose sample k is visible from k / 60 s.
const des::RationalSeconds kTrackerPeriod{1, 60};

}  // namespace

RunRecord run_rc(const RcParams& params, const Workload& workload, des::Time duration, uint64_t seed) {
  RunRecord rec;
  des::Simulator sim;
  const des::PeriodicSchedule tracker(des::Time::zero(), kTrackerPeriod);
  auto newest = [tracker](des::Time t) { return tracker.index_at_or_before(t); };
  SyntheticWorkload source(workload, ntsc_grid().regions(), des::RandomStream(seed, "pxpl5.bins"));
  RcEngine engine(sim, params, ntsc_timing(), ntsc_grid(), source, recording_hooks(rec, newest));
  engine.start(duration);
  sim.run_until(duration);
  rec.utilisation = engine.utilisation(duration);
  rec.sim_fingerprint = sim.fingerprint();
  rec.field_ms = ntsc_timing().period_ms();
  return rec;
}

RunRecord run_slats(const SlatsParams& params, int64_t triangles, des::Time duration) {
  SyntheticWorkload source(Workload{triangles, 1.3}, ntsc_grid().regions(), des::RandomStream(1, "pxpl5.bins"));
  return run_slats(params, source, duration);
}

RunRecord run_slats(const SlatsParams& params, WorkloadSource& source, des::Time duration) {
  RunRecord rec;
  des::Simulator sim;
  SlatsEngine engine(sim, params, ntsc_timing(), ntsc_grid(), source, recording_hooks(rec, {}));
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

}  // namespace latsim::pxpl5::testing
