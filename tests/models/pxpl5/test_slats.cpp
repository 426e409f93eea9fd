// Slats: one field of rendering latency while the work fits, missed fields beyond.
#include <catch2/catch.hpp>

#include <algorithm>

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

// With the COPY optimisation only the top row (5 regions per eye, 6 slots:
// the right eye's port one behind) must be copied before the retrace; the
// rows below go after it. The top row starts when R0, the first slot's
// renderer, has finished its regions; every other renderer is done before its
// slot comes. By hand, from the field start, with N triangles in 21-triangle
// messages and m in the last one (as in the test below):
//   the previous full message leaves the GP at p = 0.3 + (N - m) x 0.075 ms,
//   reaches R0 at p + 0.0504 ms (21 x 48 words at 20 Mwords/s), is rendered
//   into R0's 4 regions by p + 0.4368 ms, and has left the GP's port (one
//   transfer per renderer) at p + 0.252 ms;
//   the last message leaves at g = 0.3 + N x 0.075 ms, reaches R0 at
//   max(g, p + 0.252) + m x 0.0024 ms, is rendered (m x 0.0184 ms) after the
//   previous one, and the regions are finished (4 x 0.05 ms);
//   the 6 top slots then take 4.68 ms and must end before the retrace.
// N = 140 (m = 14): R0 done at 10.8336 + 0.2576 + 0.2 = 11.2912, top row
//   ends 15.9712 ms: 0.6955 ms early.
// N = 148 (m = 1): R0 is still rendering message 7 (done 11.7618) when the
//   last arrives (11.5794): done 11.9802, top row ends 16.6602: 0.0065 early.
// N = 149 (m = 2): done 11.9986, top row ends 16.6786: 0.0119 ms late.
// So the largest count is 148, 8 above the published 140 (docs/pxpl5.md,
// "Calibration" of Slats: the GP cost, 75 us, lies below the 79.97 us that
// would make 140 the largest).
TEST_CASE("Slats capacity with the COPY optimisation is 148 triangles, derived by hand", "[pxpl5][slats]") {
  const double field_ms = 1000.0 / 60.0;
  const auto hand_top_row_end_ms = [](int64_t n) {
    const int64_t m = n - 21 * ((n - 1) / 21);
    const double p = 0.3 + 0.075 * static_cast<double>(n - m);
    const double g = 0.3 + 0.075 * static_cast<double>(n);
    const double previous_rendered = p + 21 * 48 / 20.0e3 + 21 * 4 * 4.6e-3;
    const double last_arrived = std::max(g, p + 5 * 21 * 48 / 20.0e3) + static_cast<double>(m) * 48 / 20.0e3;
    const double done = std::max(previous_rendered, last_arrived) + static_cast<double>(m) * 4 * 4.6e-3 + 4 * 0.05;
    return done + 6 * 0.78;
  };
  CHECK(hand_top_row_end_ms(140) == Approx(15.9712).margin(1e-4));
  CHECK(hand_top_row_end_ms(148) == Approx(16.6602).margin(1e-4));
  CHECK(hand_top_row_end_ms(149) == Approx(16.6786).margin(1e-4));
  int64_t hand_capacity = 0;
  for (int64_t n = 22; n <= 200; ++n)
    if (hand_top_row_end_ms(n) < field_ms) hand_capacity = n;
  CHECK(hand_capacity == 148);

  int64_t capacity = 0;
  for (int64_t n = 135; n <= 160; ++n)
    if (run_slats(SlatsParams{}, n, des::Time::ms(200)).counts.missed == 0) capacity = n;
  CHECK(capacity == hand_capacity);
  constexpr int64_t published = 140;
  CHECK(capacity - published == 8);
  for (int64_t n : {140, 148, 149}) {
    CAPTURE(n);
    const auto slack = run_slats(SlatsParams{}, n, des::Time::ms(200)).dist("deadline_slack_ms").summary();
    CHECK(slack.min == Approx(field_ms - hand_top_row_end_ms(n)).margin(1e-4));
  }
}

// Without the COPY optimisation every region is due at the retrace, so the
// whole 11-slot copy (both ports at once, the right eye one slot behind: 20
// regions) must follow the GP's work inside the field. By hand, from the field
// start (a retrace), with N triangles in 21-triangle messages (1024 words /
// 48 words per triangle for both eyes) and m = N - 21 x floor((N - 1) / 21)
// in the last one:
//   GP:        0.3 ms + N x 75 us
//   tail (R0, the first slot's renderer): the last message crosses the ring
//              (m x 48 words at 20 Mwords/s), is rendered into R0's 4 regions
//              (m x 4 x 4.6 us) and the 4 regions are finished (4 x 50 us);
//              R0 has rendered the previous full message by then (it arrived
//              m x 75 us earlier and took 21 x 4 x 4.6 = 386 us) when m >= 6
//   copies:    11 x 780 us = 8.58 ms, the last ending before the next retrace.
// N = 97 (m = 13): 0.3 + 7.275 + (0.0312 + 0.2392 + 0.2) + 8.58 = 16.6254 ms < 16.6667 ms.
// N = 98 (m = 14): 0.3 + 7.35 + (0.0336 + 0.2576 + 0.2) + 8.58 = 16.7212 ms: late by 0.0545 ms.
// The published capacity without the optimisation is 110 (SPEC.md section 5
// gives only 140 with it). At N = 110 (m = 5) R0 is still rendering message 5
// (arrived at 0.3 + 105 x 0.075 + 0.0504 = 8.2254 ms, done 0.3864 ms later)
// when the last arrives, so the tail ends 8.6118 + 5 x 4 x 4.6e-3 + 0.2 =
// 8.9038 ms and the last copy 17.4838 ms: 0.817 ms late. Under the published
// copy facts no GP cost gives both 110 without and 140 with the optimisation
// (docs/pxpl5.md, "Capacity without the COPY optimisation").
TEST_CASE("Slats capacity without the COPY optimisation is 97 triangles, derived by hand", "[pxpl5][slats]") {
  SlatsParams plain;
  plain.copy_optimisation = false;
  const double field_ms = 1000.0 / 60.0;
  const auto hand_last_copy_end_ms = [](int64_t n) {
    const int64_t m = n - 21 * ((n - 1) / 21);
    const double gp = 0.3 + 0.075 * static_cast<double>(n);
    const double previous_rendered = 0.3 + 0.075 * static_cast<double>(n - m) + 21 * 48 / 20.0e3 + 21 * 4 * 4.6e-3;
    const double last_arrived = gp + static_cast<double>(m) * 48 / 20.0e3;
    const double tail_end = std::max(previous_rendered, last_arrived) + static_cast<double>(m) * 4 * 4.6e-3 + 4 * 0.05;
    return tail_end + 11 * 0.78;
  };
  CHECK(hand_last_copy_end_ms(97) == Approx(16.6254).margin(1e-4));
  CHECK(hand_last_copy_end_ms(98) == Approx(16.7212).margin(1e-4));
  CHECK(hand_last_copy_end_ms(110) == Approx(17.4838).margin(1e-4));
  int64_t hand_capacity = 0;
  for (int64_t n = 22; n <= 200; ++n)
    if (hand_last_copy_end_ms(n) < field_ms) hand_capacity = n;
  CHECK(hand_capacity == 97);

  int64_t capacity = 0;
  for (int64_t n = 85; n <= 115; ++n)
    if (run_slats(plain, n, des::Time::ms(200)).counts.missed == 0) capacity = n;
  CHECK(capacity == hand_capacity);
  // How early or late the last copy is: the field's smallest slack, every field alike.
  for (int64_t n : {97, 98}) {
    CAPTURE(n);
    const auto slack = run_slats(plain, n, des::Time::ms(200)).dist("deadline_slack_ms").summary();
    CHECK(slack.min == Approx(field_ms - hand_last_copy_end_ms(n)).margin(1e-4));
    CHECK(slack.max == Approx(slack.min).margin(1e-9));
  }
  // At the published 110 every field misses: late regions are not sent, so
  // the slots after the first late one move up and only that one shows as slack.
  const RunRecord published = run_slats(plain, 110, des::Time::ms(200));
  CHECK(published.counts.complete == 0);
  CHECK(published.counts.missed > 0);
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
