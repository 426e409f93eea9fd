// Slats fields that do not fit: handled region by region, with the right parity.
#include <catch2/catch.hpp>

#include <map>
#include <set>

#include "harness.hpp"

using namespace latsim;
using namespace latsim::pxpl5;
using namespace latsim::pxpl5::testing;

namespace {

// Field k + 2 is computed from host sample k (the GP reads it at retrace k + 1).
constexpr int64_t kHeavySample = 30;
constexpr int64_t kHeavyField = kHeavySample + 2;

// 100 of 320 triangles on screen fit (0.3 + 100 x 0.075 + 220 x 0.0075 = 9.5 ms
// of GP time); all 320 take 24.3 ms, past the field's retrace.
int64_t one_heavy_field(int64_t token) { return token == kHeavySample ? 320 : 100; }
// Of 400 triangles: 60 on screen fit (7.35 ms of GP time); 180 (15.45 ms)
// make the top row late but the bottom row arrive in time; all 400 (30.3 ms)
// make the bottom row late as well. Fields 32 and 34 share a parity.
int64_t torn_then_late(int64_t token) {
  if (token == kHeavySample) return 180;
  if (token == kHeavySample + 2) return 400;
  return 60;
}

}  // namespace

TEST_CASE("a late Slats field shows the previous field of the same parity where its regions are late",
          "[pxpl5][slats][misses]") {
  VaryingWorkload work(320, one_heavy_field);
  RunRecord r;
  const std::vector<LitSpan> lit = run_slats_on_display(SlatsParams{}, work, des::Time::ms(800), kHeavyField, 0, r);
  REQUIRE(!lit.empty());
  // The heavy field missed; the GP, still busy at its retrace, never started the next one.
  CHECK(r.counts.missed == 2);
  CHECK(r.counts.never_started == 1);
  CHECK(r.counts.torn == 1);
  // Its top regions came too late for the retrace and were never written...
  std::set<int> rows_written;
  for (const RegionWrite& w : r.writes)
    if (w.field == kHeavyField) rows_written.insert(w.field_row);
  CHECK(rows_written.count(0) == 0);
  CHECK(rows_written.count(1) == 1);
  // ...so on screen every top-region line of the heavy field shows the field
  // two before it (the same parity), and lower lines show the heavy field
  // itself once its region has arrived (what the buffer holds at photon time).
  std::map<int64_t, int> shown;
  for (const LitSpan& s : lit) {
    if (s.line < 128) CHECK(s.image_field == kHeavyField - 2);
    ++shown[s.image_field];
  }
  CHECK(shown.count(kHeavyField) == 1);
  // The never-started field keeps its own parity's previous field everywhere.
  for (const RegionWrite& w : r.writes) CHECK(w.field != kHeavyField + 1);
}

TEST_CASE("the pixels of a late lower region switch at the end of its copy", "[pxpl5][slats][misses]") {
  VaryingWorkload work(320, one_heavy_field);
  RunRecord r;
  const std::vector<LitSpan> lit = run_slats_on_display(SlatsParams{}, work, des::Time::ms(800), kHeavyField, 0, r);
  for (const RegionWrite& w : r.writes) {
    if (w.field != kHeavyField || w.eye != 0) continue;
    for (const LitSpan& s : lit) {
      const bool inside = s.line >= 128 * w.field_row && s.line < 128 * (w.field_row + 1) && s.x_begin >= 128 * w.column &&
                          s.x_end <= 128 * (w.column + 1);
      if (!inside) continue;
      // Lit before the copy ended: the old pixels; from then on: the new ones.
      CHECK((s.image_field == kHeavyField) == (s.photon_time >= w.image.copy_end));
    }
  }
}

TEST_CASE("the backup field replaces late regions with the last complete field, at the price of copies",
          "[pxpl5][slats][misses]") {
  SlatsParams torn_params;
  VaryingWorkload torn_work(400, torn_then_late);
  const RunRecord torn = run_slats(torn_params, torn_work, des::Time::ms(1200));
  SlatsParams backup_params;
  backup_params.backup_field = true;
  VaryingWorkload backup_work(400, torn_then_late);
  const RunRecord backed = run_slats(backup_params, backup_work, des::Time::ms(1200));
  CHECK(torn.counts.backup_copies == 0);
  CHECK(backed.counts.backup_copies > 0);
  CHECK(torn.counts.missed == backed.counts.missed);
  // Field 34's late lower regions: the buffer holds field 32's torn data
  // there, so the backup of field 30, the last complete field of that parity, is copied in.
  int backups = 0;
  for (const RegionWrite& w : backed.writes) {
    if (w.image_field == w.field) continue;
    ++backups;
    CHECK(w.field == kHeavyField + 2);
    CHECK(w.image_field == kHeavyField - 2);
    CHECK(w.field_row > 0);
  }
  CHECK(backups == backed.counts.backup_copies);
  // Each backup copy held a frame-buffer port, the owning renderer and a ring channel.
  std::map<char, int> held;
  for (const StageInterval& s : backed.stages)
    if (s.stage == "BACKUP") ++held[s.unit[0]];
  CHECK(held['F'] == backed.counts.backup_copies);
  CHECK(held['R'] == backed.counts.backup_copies);
  CHECK(held['r'] == backed.counts.backup_copies);
  // Without the backup, late lower regions show their own (late) pixels instead.
  bool own_late = false;
  for (const RegionWrite& w : torn.writes)
    own_late |= w.field == kHeavyField + 2 && w.field_row > 0 && w.image.copy_end >= ntsc_timing().line_time(w.field, 128);
  CHECK(own_late);
}
