// Slats: one field of rendering latency while the work fits, missed fields beyond.
#include <catch2/catch.hpp>

#include "harness.hpp"

using namespace latsim;
using namespace latsim::pxpl5;
using namespace latsim::pxpl5::testing;

namespace {

int64_t fields_in(des::Time duration) { return ntsc_timing().field_at_or_after(duration) - 1; }

}  // namespace

TEST_CASE("Slats rendering latency is exactly one field for every field that fits", "[pxpl5][slats]") {
  const FieldTiming timing = ntsc_timing();
  for (int64_t triangles : {0, 50, 140}) {
    CAPTURE(triangles);
    const RunRecord r = run_slats(SlatsParams{}, triangles, des::Time::s(2));
    CHECK(r.missed_fields == 0);
    REQUIRE(!r.frames.empty());
    for (const FrameReady& f : r.frames) {
      CHECK(f.swap_field == f.frame);
      for (const EyeImage& e : f.eyes) CHECK(e.transform_start == timing.retrace(f.frame - 1));
    }
    const auto latency = r.dist("render_latency_fields").summary();
    CHECK(latency.min == Approx(1.0).epsilon(1e-9));
    CHECK(latency.max == Approx(1.0).epsilon(1e-9));
  }
}

TEST_CASE("Slats with the COPY optimisation sustains 140 triangles per field at 60 Hz", "[pxpl5][slats]") {
  const des::Time duration = des::Time::s(10);
  const RunRecord r = run_slats(SlatsParams{}, 140, duration);
  CHECK(r.missed_fields == 0);
  CHECK(static_cast<int64_t>(r.frames.size()) >= fields_in(duration) - 1);
  CHECK(r.dist("copy_ms_per_frame").summary().mean == Approx(11 * 0.78).margin(1e-6));
}

TEST_CASE("Slats misses fields beyond its capacity", "[pxpl5][slats]") {
  SlatsParams optimised;
  CHECK(run_slats(optimised, 160, des::Time::s(1)).missed_fields > 0);
  SlatsParams plain;
  plain.copy_optimisation = false;
  // Without the optimisation all 11 copy slots precede the retrace.
  CHECK(run_slats(plain, 140, des::Time::s(1)).missed_fields > 0);
  CHECK(run_slats(plain, 80, des::Time::s(1)).missed_fields == 0);
}

TEST_CASE("Slats capacity with the COPY optimisation lies between 140 and 150 triangles", "[pxpl5][slats]") {
  int64_t capacity = 0;
  for (int64_t n = 120; n <= 170; ++n)
    if (run_slats(SlatsParams{}, n, des::Time::ms(200)).missed_fields == 0) capacity = n;
  CAPTURE(capacity);
  CHECK(capacity >= 140);
  CHECK(capacity < 150);
}

TEST_CASE("the backup field keeps a missed field from tearing", "[pxpl5][slats]") {
  SlatsParams p;
  const RunRecord torn = run_slats(p, 152, des::Time::s(1));
  CHECK(torn.missed_fields > 0);
  CHECK(torn.torn_fields > 0);
  p.backup_field = true;
  const RunRecord backed = run_slats(p, 152, des::Time::s(1));
  CHECK(backed.missed_fields == torn.missed_fields);
  CHECK(backed.torn_fields == 0);
}

TEST_CASE("Slats uses the newest transforms the GP holds at each retrace", "[pxpl5][slats]") {
  // Tracker sample k is visible at retrace k; the host needs 1 ms to compute
  // and send it, so at retrace k the GP holds sample k-1 and field k+1 shows it.
  const RunRecord r = run_slats(SlatsParams{}, 100, des::Time::s(1));
  REQUIRE(!r.frames.empty());
  for (const FrameReady& f : r.frames)
    for (const EyeImage& e : f.eyes) CHECK(e.sample_token == f.frame - 2);
}

TEST_CASE("Slats timeline is fingerprint-stable", "[pxpl5][slats]") {
  const RunRecord a = run_slats(SlatsParams{}, 140, des::Time::s(1));
  const RunRecord b = run_slats(SlatsParams{}, 140, des::Time::s(1));
  const RunRecord c = run_slats(SlatsParams{}, 141, des::Time::s(1));
  CHECK(a.stage_fingerprint() == b.stage_fingerprint());
  CHECK(a.sim_fingerprint == b.sim_fingerprint);
  CHECK(a.stage_fingerprint() != c.stage_fingerprint());
}
