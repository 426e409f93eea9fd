// Slats: one field of rendering latency while the work fits, missed fields beyond.
#include <catch2/catch.hpp>

#include "harness.hpp"

using namespace latsim;
using namespace latsim::pxpl5;
using namespace latsim::pxpl5::testing;

namespace {

int64_t fields_in(des::Time duration) { return ntsc_timing().field_at_or_after(duration) - 1; }

// By hand from SPEC.md section 5: the top row (every row without the COPY
// optimisation) is due at the field's retrace, a lower row when the beam
// reaches its first line: 22 blank lines plus 128 per region row, of 262.
des::Time hand_deadline(int64_t field, int row, bool optimised) {
  const des::Time retrace = des::Time::from_seconds(static_cast<double>(field) / 60.0);
  if (row == 0 || !optimised) return retrace;
  return retrace + des::Time::from_seconds((22.0 + 128.0 * row) / 262.0 / 60.0);
}

}  // namespace

TEST_CASE("Slats rendering latency is exactly one field for every field that fits", "[pxpl5][slats]") {
  const FieldTiming timing = ntsc_timing();
  for (int64_t triangles : {0, 50, 140}) {
    CAPTURE(triangles);
    const RunRecord r = run_slats(SlatsParams{}, triangles, des::Time::s(2));
    CHECK(r.counts.missed == 0);
    REQUIRE(r.writes.size() > 100);
    for (const RegionWrite& w : r.writes) {
      // Each region holds its own field's pixels, from a TRANSFORM begun one retrace earlier...
      CHECK(w.image_field == w.field);
      CHECK(w.image.transform_start == timing.retrace(w.field - 1));
      // ...and arrived before its deadline (a microsecond covers rounding of the hand value).
      CHECK(w.image.copy_end < hand_deadline(w.field, w.field_row, true) + des::Time::us(1));
    }
    const auto latency = r.dist("transform_to_retrace_fields").summary();
    CHECK(latency.min == Approx(1.0).epsilon(1e-9));
    CHECK(latency.max == Approx(1.0).epsilon(1e-9));
  }
}

TEST_CASE("Slats with the COPY optimisation sustains 140 triangles per field at 60 Hz", "[pxpl5][slats]") {
  const des::Time duration = des::Time::s(10);
  const RunRecord r = run_slats(SlatsParams{}, 140, duration);
  CHECK(r.counts.missed == 0);
  CHECK(r.counts.complete >= fields_in(duration) - 2);
  // 11 slots of 780 us: both ports at once, the right eye one slot behind.
  CHECK(r.dist("copy_ms_per_frame").summary().mean == Approx(11 * 0.78).margin(1e-6));
  // The top rows wait for the GP: 0.3 ms + 140 x 75 us, then the tail and 6 slots.
  CHECK(r.dist("deadline_slack_ms").summary().min > 0.0);
}

TEST_CASE("Slats misses fields beyond its capacity", "[pxpl5][slats]") {
  SlatsParams optimised;
  const RunRecord heavy = run_slats(optimised, 160, des::Time::s(1));
  CHECK(heavy.counts.missed > 0);
  CHECK(heavy.counts.missed_fraction() > 0.0);
  CHECK(heavy.dist("deadline_slack_ms").summary().max < 0.0);
  SlatsParams plain;
  plain.copy_optimisation = false;
  // Without the optimisation all 11 copy slots precede the retrace.
  CHECK(run_slats(plain, 140, des::Time::s(1)).counts.missed > 0);
  CHECK(run_slats(plain, 80, des::Time::s(1)).counts.missed == 0);
}

TEST_CASE("Slats capacity with the COPY optimisation lies between 140 and 150 triangles", "[pxpl5][slats]") {
  int64_t capacity = 0;
  for (int64_t n = 120; n <= 170; ++n)
    if (run_slats(SlatsParams{}, n, des::Time::ms(200)).counts.missed == 0) capacity = n;
  CAPTURE(capacity);
  CHECK(capacity >= 140);
  CHECK(capacity < 150);
}

TEST_CASE("Slats uses the newest transforms the GP holds at each retrace", "[pxpl5][slats]") {
  // Tracker sample k is visible at retrace k; the host needs 1 ms to compute
  // and send it, so at retrace k the GP holds sample k-1 and field k+1 shows it.
  const RunRecord r = run_slats(SlatsParams{}, 100, des::Time::s(1));
  REQUIRE(!r.writes.empty());
  for (const RegionWrite& w : r.writes) CHECK(w.image.sample_token == w.image_field - 2);
}

TEST_CASE("Slats timeline is fingerprint-stable", "[pxpl5][slats]") {
  const RunRecord a = run_slats(SlatsParams{}, 140, des::Time::s(1));
  const RunRecord b = run_slats(SlatsParams{}, 140, des::Time::s(1));
  const RunRecord c = run_slats(SlatsParams{}, 141, des::Time::s(1));
  CHECK(a.stage_fingerprint() == b.stage_fingerprint());
  CHECK(a.sim_fingerprint == b.sim_fingerprint);
  CHECK(a.stage_fingerprint() != c.stage_fingerprint());
}
