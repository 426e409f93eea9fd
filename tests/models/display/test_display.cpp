// Raster timing, scanout fidelity and what each costs in events.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "latsim/display/display.hpp"
#include "latsim/display/raster_timing.hpp"
#include "run_helpers.hpp"

using latsim::des::RationalSeconds;
using latsim::des::Time;
using latsim::display::RasterParams;
using latsim::display::RasterTiming;
using latsim::testing::base_scenario;
using latsim::testing::fig;
using latsim::testing::run;
using Json = nlohmann::json;

TEST_CASE("line and pixel photon times are exact fractions of the field", "[display]") {
  RasterParams p;
  p.field_period = RationalSeconds{1, 60};
  p.width_px = 640;
  p.height_px = 480;
  p.vblank_lines = 20;
  p.hblank_px = 160;
  const RasterTiming t(p);
  // 500 line slots of 800 pixel times in 1/60 s: line j starts (20 + j)/500 of a field in.
  CHECK(t.line_time(0, 0).ticks() == 20 * 1'000'000'000'000LL / 60 / 500);
  CHECK(t.line_time(3, 10) == t.field_start(3) + Time::ps(30 * 1'000'000'000'000LL / 30000));
  // Half a line later, to within the one-picosecond flooring of each instant.
  const int64_t half_line = 1'000'000'000'000LL / 60 / 500 / 2;
  const int64_t got = (t.pixel_time(0, 0, 400) - t.line_time(0, 0)).ticks();
  CHECK(std::llabs(got - half_line) <= 1);
  for (int j = 1; j < t.lines_per_field(); ++j) CHECK(t.line_time(5, j) > t.line_time(5, j - 1));
}

TEST_CASE("59.94 Hz retraces do not drift over a hundred million fields", "[display]") {
  RasterParams p;
  p.field_period = RationalSeconds{1001, 60000};
  const RasterTiming t(p);
  // 1e8 fields of 1001/60000 s = 1668333.333... s exactly; floored to a picosecond.
  CHECK(t.field_start(100'000'000).ticks() == 1'668'333'333'333'333'333LL);
  // A billion fields (193 days) is beyond int64 picoseconds: an error, not a wrap.
  CHECK_THROWS_AS(t.field_start(1'000'000'000), latsim::des::TimeOverflow);
  CHECK(t.field_at_or_after(t.field_start(123456789)) == 123456789);
  CHECK(t.field_at_or_before(t.field_start(123456789) - Time::ps(1)) == 123456788);
}

TEST_CASE("interlaced fields alternate odd and even rows", "[display]") {
  RasterParams p;
  p.interlaced = true;
  p.height_px = 480;
  const RasterTiming t(p);
  CHECK(t.lines_per_field() == 240);
  CHECK(t.row_of(0, 0) == 0);
  CHECK(t.row_of(0, 5) == 10);
  CHECK(t.row_of(1, 5) == 11);
  CHECK(t.line_of_row(1, 11) == 5);
  CHECK(t.line_of_row(0, 11) == -1);
  CHECK(t.parity(-1) == 1);
}

TEST_CASE("scanout fidelity costs O(fields), O(lines) or O(pixels) events", "[display][fidelity]") {
  Json s = base_scenario();
  s["duration_s"] = 1;
  s["display"]["height_px"] = 48;
  s["display"]["width_px"] = 64;
  const Json field = run(s);
  s["display"]["scanout"] = "line";
  const Json line = run(s);
  s["display"]["scanout"] = "pixel";
  s["display"]["pixel_stride"] = 8;
  const Json pixel = run(s);
  s["display"]["pixel_events"] = true;
  const Json pixel_events = run(s);
  const int64_t fields = fig(field, "fields").get<int64_t>();
  CHECK(fields == 60);
  CHECK(field["events_per_model"]["display"].get<int64_t>() == fields);
  CHECK(line["events_per_model"]["display"].get<int64_t>() == fields * (1 + 48));
  // Batched pixels: one event per line (no swap falls inside a line here);
  // the reference path: one per 8-pixel sample.
  CHECK(pixel["events_per_model"]["display"].get<int64_t>() == fields * (1 + 48));
  CHECK(pixel_events["events_per_model"]["display"].get<int64_t>() == fields * (1 + 48 * 8));
  CHECK(pixel["figures"] == pixel_events["figures"]);
  // The same image content: field-level sampling is exact here (no mid-field swaps).
  CHECK(fig(field, "motion_to_photon_ms")["mean"].get<double>() ==
        Approx(fig(line, "motion_to_photon_ms")["mean"].get<double>()).epsilon(1e-9));
}

TEST_CASE("effects not asked for produce no events", "[fidelity]") {
  Json s = base_scenario();
  s["duration_s"] = 1;
  const Json plain = run(s);
  CHECK_FALSE(plain["events_per_model"].contains("transport"));
  CHECK(plain["events_per_model"]["renderer"].get<int64_t>() > 0);
  CHECK(plain["events_per_model"]["tracker"].get<int64_t>() == 60);
  s["tracker"]["rate_hz"] = 120;
  CHECK(run(s)["events_per_model"]["tracker"].get<int64_t>() == 120);
}

namespace {

/// Keeps every span of eye 0 as (row, x_begin, x_end, image).
struct SpanLog final : latsim::display::ScanoutListener {
  struct Span {
    int row, x_begin, x_end;
    int64_t image;
  };
  std::vector<Span> spans;
  void on_scanout(const latsim::display::ScanoutSpan& s) override {
    if (s.eye == 0) spans.push_back({s.row, s.x_begin, s.x_end, s.image_id});
  }
};

}  // namespace

TEST_CASE("a region written into the displayed buffer splits the lines that cross it", "[display][regions]") {
  using latsim::display::BufferRegion;
  using latsim::display::Display;
  RasterParams p;
  p.width_px = 64;
  p.height_px = 8;
  p.interlaced = true;
  latsim::des::Simulator sim;
  Display d(sim, RasterTiming(p), 1, latsim::display::ScanoutFidelity::Line);
  SpanLog log;
  d.add_listener(&log);
  d.present_now(0, 7);
  // Field 0 lights rows 0, 2, 4, 6; the region holds columns 16-31 of rows 2 and 4 (step 2).
  d.write_region_now(0, BufferRegion{16, 32, 2, 5, 2}, 9);
  CHECK_THROWS_AS(d.write_region_now(0, BufferRegion{20, 40, 4, 5, 1}, 3), std::invalid_argument);
  d.start(Time::ms(40));
  sim.run_until(Time::us(16500));  // field 0's four lines are lit 22 to 25 line periods of 26 in
  std::vector<SpanLog::Span> want{{0, 0, 64, 7}, {2, 0, 16, 7}, {2, 16, 32, 9}, {2, 32, 64, 7},
                                  {4, 0, 16, 7}, {4, 16, 32, 9}, {4, 32, 64, 7}, {6, 0, 64, 7}};
  REQUIRE(log.spans.size() == want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    CAPTURE(i);
    CHECK(log.spans[i].row == want[i].row);
    CHECK(log.spans[i].x_begin == want[i].x_begin);
    CHECK(log.spans[i].x_end == want[i].x_end);
    CHECK(log.spans[i].image == want[i].image);
  }
  // A whole image swapped in replaces every region.
  d.present_at_next_retrace(0, 5);
  log.spans.clear();
  sim.run_until(Time::ms(40));
  for (const auto& s : log.spans) CHECK(s.image == 5);
}
