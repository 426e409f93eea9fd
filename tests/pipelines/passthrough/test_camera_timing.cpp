// The see-through camera's exposure and readout instants, from the frame
// index: phase-locked to a display or on its own clock, global or rolling.
#include <catch2/catch.hpp>

#include "passthrough/camera_timing.hpp"

using latsim::des::PeriodicSchedule;
using latsim::des::RationalSeconds;
using latsim::des::Time;
using latsim::pipelines::passthrough::CameraSpec;
using latsim::pipelines::passthrough::CameraTiming;

namespace {

CameraSpec spec(CameraSpec::Shutter shutter) {
  CameraSpec c;
  c.height_px = 1200;
  c.exposure = Time::us(3000);
  c.row_readout = Time::ns(7500);  // 1200 rows: 9 ms
  c.shutter = shutter;
  return c;
}

}  // namespace

TEST_CASE("camera timing: a free-running rolling shutter from its clock") {
  // A 90 Hz clock (1/90 s exact) of phase 0.4 ms: frame 900 opens at 10 s +
  // 0.4 ms. Row 600 opens 600 x 7.5 us = 4.5 ms after row 0, its exposure
  // middle 1.5 ms later; the last row is read 3 + 9 ms after the first opens.
  const CameraTiming t(spec(CameraSpec::Shutter::rolling),
                       PeriodicSchedule(Time::us(400), RationalSeconds::period_of_hz(90)));
  CHECK(t.frame_start(900) == Time::ms(10000) + Time::us(400));
  CHECK(t.row_at(0.5) == 600);
  CHECK(t.row_at(1.0) == 1199);
  CHECK(t.row_open(900, 600) == Time::ms(10000) + Time::us(400) + Time::us(4500));
  CHECK(t.exposure_middle(900, 600) == Time::ms(10000) + Time::us(400 + 4500 + 1500));
  CHECK(t.readout_start(900) == Time::ms(10000) + Time::us(400 + 3000) + Time::ns(7500));
  CHECK(t.readout_end(900) == Time::ms(10000) + Time::us(400 + 3000 + 9000));
}

TEST_CASE("camera timing: a global shutter exposes every row at once") {
  const CameraTiming t(spec(CameraSpec::Shutter::global),
                       PeriodicSchedule(Time::zero(), RationalSeconds::period_of_hz(60)));
  CHECK(t.row_open(3, 1199) == t.frame_start(3));
  CHECK(t.exposure_middle(3, 0) == t.exposure_middle(3, 1199));
  CHECK(t.readout_end(3) - t.frame_start(3) == Time::ms(12));
}
