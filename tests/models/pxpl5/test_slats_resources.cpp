// Slats as processes on resources: the copy schedule follows from the ports,
// every resource appears on the timeline, and none does two things at once.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "harness.hpp"

using namespace latsim;
using namespace latsim::pxpl5;
using namespace latsim::pxpl5::testing;

namespace {

std::vector<StageInterval> of_field(const RunRecord& r, const std::string& stage, int64_t field) {
  std::vector<StageInterval> out;
  for (const StageInterval& s : r.stages)
    if (s.stage == stage && s.frame == field) out.push_back(s);
  return out;
}

}  // namespace

// The 11-slot schedule of SPEC.md section 5 derived by hand from the port
// resources: each eye's frame-buffer port takes its 10 regions in order (top
// row, then bottom row; region i is column i mod 5, owned by renderer i mod 5);
// a copy needs the port and the owning renderer's port for 780 us; renderer c
// is free from the end of its RENDER; on a tie the left eye's port, queued
// first, goes first. Greedy list scheduling over those resources gives the
// copy start times, which the simulation must reproduce exactly.
TEST_CASE("the Slats copy schedule follows from the frame-buffer and renderer ports", "[pxpl5][slats][resources]") {
  const RunRecord r = run_slats(SlatsParams{}, 140, des::Time::ms(200));
  const int64_t field = 5;
  std::vector<des::Time> renderer_free(5, des::Time::zero());
  for (const StageInterval& s : of_field(r, "RENDER", field)) renderer_free[s.unit[1] - '0'] = s.end;
  const des::Time copy = des::Time::us(780);
  std::vector<des::Time> port_free(2, des::Time::zero());
  std::vector<int> next(2, 0);
  std::map<std::string, std::vector<des::Time>> expected;  // per port, copy starts in order
  while (next[0] < 10 || next[1] < 10) {
    int pick = -1;
    des::Time best = des::Time::max();
    for (int e = 0; e < 2; ++e) {
      if (next[e] >= 10) continue;
      const des::Time start = std::max(port_free[e], renderer_free[next[e] % 5]);
      if (start < best) {
        best = start;
        pick = e;
      }
    }
    const int c = next[pick]++ % 5;
    expected[pick == 0 ? "FB0" : "FB1"].push_back(best);
    port_free[pick] = renderer_free[c] = best + copy;
  }
  std::map<std::string, std::vector<des::Time>> got;
  for (const StageInterval& s : of_field(r, "COPY", field))
    if (s.unit.rfind("FB", 0) == 0) got[s.unit].push_back(s.start);
  CHECK(got == expected);
  // 20 regions in 11 slots: the right eye starts one slot after the left and ends one slot later.
  std::set<int64_t> slots;
  for (const auto& [port, starts] : got)
    for (des::Time t : starts) slots.insert(((t - got["FB0"].front()).ticks() + copy.ticks() / 2) / copy.ticks());
  CHECK(slots.size() == 11);
  CHECK(got["FB1"].front() - got["FB0"].front() == copy);
}

TEST_CASE("the Slats timeline shows the GP, ring channels, renderers and frame-buffer ports", "[pxpl5][slats][resources]") {
  const RunRecord r = run_slats(SlatsParams{}, 140, des::Time::ms(200));
  std::set<std::string> units;
  for (const StageInterval& s : r.stages) units.insert(s.unit);
  for (const char* u : {"host", "GP", "R0", "R1", "R2", "R3", "R4", "FB0", "FB1"}) CHECK(units.count(u) == 1);
  // Every one of the 8 channels carries something in 12 fields.
  for (int c = 0; c < SlatsParams{}.hw.ring_channels; ++c) CHECK(units.count("ring" + std::to_string(c)) == 1);
  // The host's message, the GP's command messages and the copies all travel the ring.
  std::set<std::string> on_ring;
  for (const StageInterval& s : r.stages)
    if (s.unit.rfind("ring", 0) == 0) on_ring.insert(s.stage);
  CHECK(on_ring == std::set<std::string>{"COPY", "MESSAGE", "SEND"});
}

TEST_CASE("no Slats resource does two things at once", "[pxpl5][slats][resources]") {
  for (int64_t triangles : {60, 140, 170}) {
    const RunRecord r = run_slats(SlatsParams{}, triangles, des::Time::ms(500));
    std::map<std::string, std::vector<std::pair<des::Time, des::Time>>> by_unit;
    for (const StageInterval& s : r.stages)
      if (s.unit != "host") by_unit[s.unit].emplace_back(s.start, s.end);
    CAPTURE(triangles);
    for (auto& [unit, iv] : by_unit) {
      std::sort(iv.begin(), iv.end());
      for (std::size_t i = 1; i < iv.size(); ++i) {
        CAPTURE(unit, iv[i].first.str());
        CHECK(iv[i].first >= iv[i - 1].second);
      }
    }
  }
}
