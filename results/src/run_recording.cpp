#include "latsim/results/run_recording.hpp"

namespace latsim::results {

RunRecording::RunRecording(const des::Simulator& sim, const tracker::MotionSource& motion,
                           const tracker::HostFeed& host, ImageBook& images, const display::RasterTiming& timing,
                           ProbeSet probes, double ipd_m, bool stereo, bool keep_samples)
    : book_(sim, keep_samples),
      motion_(motion),
      image_book_(images),
      pipeline_(book_.writer("pipeline")),
      run_(book_.writer("run")),
      latencies_(book_.writer("span latencies"), sim, timing),
      images_(book_.writer("images"), timing),
      registration_(book_.writer("registration"), motion, timing, std::move(probes), ipd_m, stereo),
      prediction_(book_.writer("prediction"), motion),
      seen_(book_.writer("seen"), motion, timing),
      link_(book_.writer("link"), ledger_),
      shown_(run_, sim, host, images, timing,
             SpanListeners{latencies_, images_, registration_, prediction_, seen_, ledger_}, ipd_m, stereo),
      signals_(latencies_, images_, registration_, prediction_) {
  // The span figures' gathered runs are added before anything reads them.
  book_.before_reading([this] { latencies_.complete(); });
}

void RunRecording::split_by_phase(const tracker::MotionPhaseParams& params) {
  phases_.emplace(motion_, params);
  registration_.split_by(&*phases_);
  prediction_.split_by(&*phases_);
}

void RunRecording::keep_ledger(bool on) {
  ledger_.enable(on);
  shown_.set_continuation(!ledger_.on() && !book_.sample_log().on());
}

void RunRecording::keep_sample_log(bool on) {
  book_.sample_log().enable(on);
  shown_.set_continuation(!ledger_.on() && !book_.sample_log().on());
}

void RunRecording::finish(const RunTotals& totals) {
  shown_.flush();
  latencies_.complete();
  images_.finish(totals.duration, image_book_.registered());
  run_.set("fields", totals.fields);
  run_.set("tracker_samples", totals.tracker_samples);
  seen_.finish(totals.duration);
  images_.warn(totals.duration, totals.fields);
  link_.finish(totals);
}

}  // namespace latsim::results
