// The display on its own: every sample it hands over is lit exactly when the
// direct raster formula says, for hours of fields; batched pixel scanout hands
// over the same (pixel, image, time) samples as one event per pixel, splitting
// a line exactly where the front buffer changes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <tuple>
#include <vector>

#include "latsim/des/simulator.hpp"
#include "latsim/display/display.hpp"
#include "latsim/display/raster_timing.hpp"

using latsim::des::RationalSeconds;
using latsim::des::Simulator;
using latsim::stats::TickStepper;
using latsim::des::Time;
using latsim::display::Display;
using latsim::display::RasterParams;
using latsim::display::RasterTiming;
using latsim::display::ScanoutFidelity;
using latsim::display::ScanoutListener;
using latsim::display::ScanoutSpan;

namespace {

/// One lit sample: which eye, field, line and first pixel, what it showed and when.
struct Sample {
  int eye;
  int64_t field;
  int line;
  int x;
  int64_t image;
  int64_t photon_ps;
  friend bool operator<(const Sample& a, const Sample& b) {
    return std::tie(a.eye, a.field, a.line, a.x) < std::tie(b.eye, b.field, b.line, b.x);
  }
  friend bool operator==(const Sample&, const Sample&) = default;
};

/// Expands every span into its samples, and checks each sample's photon time
/// against the direct formula as it arrives.
class Recorder final : public ScanoutListener {
 public:
  Recorder(const RasterTiming& timing, int stride) : timing_(timing), stride_(stride) {}
  void on_scanout(const ScanoutSpan& span) override {
    ++spans;
    TickStepper t(span.photons);
    const bool per_line = span.line_end - span.line > 1 || stride_ == 0;
    for (uint64_t i = 0; i < span.photons.count; ++i, t.step()) {
      const int line = per_line ? span.line + static_cast<int>(i) : span.line;
      const int x = per_line ? span.x_begin : span.x_begin + static_cast<int>(i) * stride_;
      if (t.time() != timing_.pixel_time(span.field, line, x)) ++wrong_times;
      samples.push_back({span.eye, span.field, line, x, span.image_id, t.ticks()});
    }
  }
  std::vector<Sample> samples;
  int64_t spans = 0;
  int64_t wrong_times = 0;

 private:
  const RasterTiming& timing_;
  int stride_;  // 0: one sample per line
};

// Samples the direct formula says are lit in [begin, end] of fields whose
// retrace lies in [begin, end): per line (stride 0) or per stride pixels.
size_t expected_samples(const RasterTiming& timing, Time begin, Time end, int stride) {
  size_t n = 0;
  for (int64_t f = timing.field_at_or_after(begin); timing.field_start(f) < end; ++f)
    for (int j = 0; j < timing.lines_per_field(); ++j)
      for (int x = 0; x < (stride == 0 ? 1 : timing.params().width_px); x += std::max(stride, 1))
        n += timing.pixel_time(f, j, x) <= end ? 1 : 0;
  return n;
}

RasterParams odd_raster() {
  RasterParams p;
  p.field_period = RationalSeconds{1001, 60000};  // 59.94 Hz
  p.width_px = 13;
  p.height_px = 7;
  p.vblank_lines = 2;
  p.hblank_px = 3;
  return p;
}

}  // namespace

TEST_CASE("line times stepped without division equal the direct formula over three hours of 59.94 Hz fields",
          "[display][raster]") {
  Simulator sim;
  const RasterTiming timing(odd_raster());
  Display display(sim, timing, 1, ScanoutFidelity::Line);
  Recorder rec(timing, 0);
  display.add_listener(&rec);
  const Time end = Time::s(3 * 3600);
  display.start(end);
  sim.run_until(end);
  // 3 h at 60000/1001 Hz = 647,352.6 fields, each of 7 lines (the last cut short).
  CHECK(display.fields_shown() == 647'353);
  CHECK(rec.samples.size() == expected_samples(timing, Time::zero(), end, 0));
  CHECK(rec.wrong_times == 0);
}

TEST_CASE("pixel samples stepped without division equal the direct formula three hours in",
          "[display][raster]") {
  for (const bool events : {true, false})
    for (const int stride : {1, 4}) {
      Simulator sim;
      sim.run_until(Time::s(3 * 3600));  // photon times near 1.08e16 ps
      const RasterTiming timing(odd_raster());
      Display display(sim, timing, 1, ScanoutFidelity::Pixel, stride, events);
      Recorder rec(timing, stride);
      display.add_listener(&rec);
      const Time begin = sim.now(), end = begin + Time::s(20);
      display.start(end);
      sim.run_until(end);
      INFO("pixel_events " << events << ", stride " << stride);
      // 20 s = 1198.8 fields; the last is cut short by the end of the run.
      CHECK(display.fields_shown() == 1199);
      CHECK(rec.samples.size() == expected_samples(timing, begin, end, stride));
      CHECK(rec.wrong_times == 0);
    }
}

TEST_CASE("batched pixel scanout splits a line where the front buffer changes, like one event per pixel",
          "[display][pixel]") {
  RasterParams p;
  p.field_period = RationalSeconds{1, 60};
  p.width_px = 8;
  p.height_px = 4;
  p.vblank_lines = 1;
  p.hblank_px = 2;
  const RasterTiming timing(p);
  // Swap instants: exactly at pixel 3 of line 1, between pixels 5 and 6 of
  // line 2 (5.5 pixel times in), in the horizontal blanking after line 0, and
  // at the end of the run, which falls inside line 3 of the last field.
  const Time at_pixel = timing.pixel_time(0, 1, 3);
  const auto halfway = [](Time a, Time b) { return a + Time::ps((b - a).ticks() / 2); };
  const Time mid_pixel = halfway(timing.pixel_time(0, 2, 5), timing.pixel_time(0, 2, 6));
  const Time in_blank = halfway(timing.pixel_time(0, 0, 7), timing.line_time(0, 1));
  const Time end = timing.pixel_time(2, 3, 4);
  std::vector<std::vector<Sample>> results;
  std::vector<int64_t> span_counts, event_counts;
  for (const bool events : {true, false}) {
    Simulator sim;
    Display display(sim, timing, 2, ScanoutFidelity::Pixel, 1, events);
    Recorder rec(timing, 1);
    display.add_listener(&rec);
    const auto kind = sim.kind("test.swap");
    int64_t next_image = 0;
    for (const Time t : {at_pixel, mid_pixel, in_blank, end})
      sim.at(t, kind, [&display, &next_image] {
        display.present_now(0, next_image);
        display.present_now(1, next_image + 100);
        ++next_image;
      });
    display.start(end);
    sim.run_until(end);
    std::sort(rec.samples.begin(), rec.samples.end());
    results.push_back(rec.samples);
    span_counts.push_back(rec.spans);
    event_counts.push_back(static_cast<int64_t>(sim.events_executed()));
    CHECK(rec.wrong_times == 0);
  }
  REQUIRE(results[0].size() == results[1].size());
  CHECK(results[0] == results[1]);
  // Three fields of 4 lines x 8 pixels, two eyes, the last field cut after pixel 4 of line 3.
  CHECK(results[1].size() == 2u * (3u * 32u - 3u));
  const auto shown = [&](int64_t field, int line, int x) {
    for (const Sample& s : results[1])
      if (s.eye == 0 && s.field == field && s.line == line && s.x == x) return s.image;
    return int64_t{-2};
  };
  // Swaps run in time order: in blanking (image 0), at a pixel (1), between
  // pixels (2), at the end (3). A pixel lit at the instant of a swap shows it.
  CHECK(shown(0, 0, 7) == -1);
  CHECK(shown(0, 1, 0) == 0);
  CHECK(shown(0, 1, 2) == 0);
  CHECK(shown(0, 1, 3) == 1);
  CHECK(shown(0, 2, 5) == 1);
  CHECK(shown(0, 2, 6) == 2);
  CHECK(shown(2, 3, 3) == 2);
  CHECK(shown(2, 3, 4) == 3);
  // Batched: one span per eye and line, plus one per eye for each of the
  // three swaps that fall inside a line (the one in blanking splits nothing).
  CHECK(span_counts[1] == 2 * (3 * 4 + 3));
  // Events: 4 swaps, 3 retraces, then one per line (batched) or per pixel.
  CHECK(event_counts[1] == 4 + 3 + 3 * 4);
  CHECK(event_counts[0] == 4 + 3 + 3 * 32 - 3);
}
