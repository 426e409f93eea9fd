#include "latsim/results/span_latencies.hpp"

#include <algorithm>

#include "latsim/results/figure_book.hpp"

namespace latsim::results {

void SpanLatencies::add(stats::Distribution*& d, const char* name, des::Time value) {
  figure(d, name);
  runs_.close(d);  // a span figure's gathered run goes first
  d->add(value);
  figures_.log(name, value.to_ms());
}

void SpanLatencies::record(const display::ScanoutSpan& span, des::Time orientation_measured,
                           des::Time position_measured) {
  const des::Time origin = std::min(orientation_measured, position_measured);
  if (span.field != scan_field_) {
    scan_field_ = span.field;
    scan_start_ = timing_.scanout_start(span.field);
  }
  if (display_ms_ == nullptr || mtp_ == nullptr || rotation_ == nullptr || translation_ == nullptr) [[unlikely]] {
    figure(mtp_, "motion_to_photon_ms");
    figure(rotation_, "rotation_latency_ms");
    figure(translation_, "translation_latency_ms");
    figure(display_ms_, "display_ms");
  }
  // One open run per eye; each line of a field continues it at line fidelity.
  hot_[static_cast<size_t>(span.eye & 1)].valid = false;  // until the span is held again
  runs_.add(static_cast<size_t>(span.eye & 1), span.photons,
            {{mtp_, origin.ticks()},
             {rotation_, orientation_measured.ticks()},
             {translation_, position_measured.ticks()},
             {display_ms_, scan_start_.ticks()}});
  if (!figures_.logging()) return;
  log_run("motion_to_photon_ms", span, origin);
  log_run("rotation_latency_ms", span, orientation_measured);
  log_run("translation_latency_ms", span, position_measured);
  log_run("display_ms", span, scan_start_);
}

void SpanLatencies::log_run(const char* name, const display::ScanoutSpan& span, des::Time origin) {
  SampleLog& log = figures_.book().sample_log();
  stats::TickStepper photon(span.photons), written(span.written);
  for (uint64_t i = 0; i < span.photons.count; ++i, photon.step(), written.step())
    log.add(std::min(written.time(), sim_.now()).to_ms(), name, (photon.time() - origin).to_ms());
}

void SpanLatencies::pixel_lit(const tracker::TrackerSample& s, des::Time photon) {
  const des::Time age = photon - s.measured_at;
  add(mtp_, "motion_to_photon_ms", age);
  add(rotation_, "rotation_latency_ms", age);
  add(translation_, "translation_latency_ms", age);
  add(pixel_age_, "pixel_age_ms", age);
}

}  // namespace latsim::results
