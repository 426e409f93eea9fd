// A checker over the stage timeline: no stage ever starts before its start
// conditions (SPEC.md sections 4 and 5) hold, and no unit does two things at once.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "harness.hpp"

using namespace latsim;
using namespace latsim::pxpl5;
using namespace latsim::pxpl5::testing;

namespace {

/// Earliest start and latest end of one stage of one frame/eye over all units.
struct Span {
  des::Time start = des::Time::max();
  des::Time end = des::Time::zero();
};

using SpanKey = std::pair<std::string, int64_t>;  // stage, eye sequence (or frame for SEND/EDIT)

std::map<SpanKey, Span> spans_of(const std::vector<StageInterval>& stages, int eyes) {
  std::map<SpanKey, Span> spans;
  for (const StageInterval& s : stages) {
    const bool per_frame = s.stage == "SEND" || s.stage == "EDIT";
    const int64_t key = per_frame ? s.frame : s.frame * eyes + s.eye;
    Span& sp = spans[{s.stage, key}];
    sp.start = std::min(sp.start, s.start);
    sp.end = std::max(sp.end, s.end);
  }
  return spans;
}

/// Every violated RC start condition, as text (empty when all hold).
std::vector<std::string> rc_violations(const RunRecord& r, int eyes) {
  std::vector<std::string> bad;
  const auto spans = spans_of(r.stages, eyes);
  const auto end_of = [&](const char* stage, int64_t k) -> std::optional<des::Time> {
    if (k < 0) return des::Time::zero();
    const auto it = spans.find({stage, k});
    if (it == spans.end()) return std::nullopt;
    return it->second.end;
  };
  const auto need = [&](const char* what, int64_t k, des::Time start, const char* stage, int64_t j) {
    const auto e = end_of(stage, j);
    if (!e || start < *e)
      bad.push_back(std::string(what) + " " + std::to_string(k) + " starts before " + stage + " " + std::to_string(j));
  };
  for (const auto& [key, span] : spans) {
    const auto& [stage, k] = key;
    if (stage == "SEND") need("SEND", k, span.start, "EDIT", k - 1);
    if (stage == "EDIT") {
      const int64_t first = k * eyes;
      need("EDIT", k, span.start, "SEND", k);
      need("EDIT", k, span.start, "TRANSFORM", first - 1);
      need("EDIT", k, span.start, "RENDER", first - 2);
      need("EDIT", k, span.start, "COPY", first - 3);
    }
    if (stage == "TRANSFORM") {
      need("TRANSFORM", k, span.start, "EDIT", k / eyes);
      need("TRANSFORM", k, span.start, "TRANSFORM", k - 1);
      need("TRANSFORM", k, span.start, "RENDER", k - 2);
      need("TRANSFORM", k, span.start, "COPY", k - 3);
    }
    if (stage == "RENDER") need("RENDER", k, span.start, "TRANSFORM", k);
    if (stage == "COPY") need("COPY", k, span.start, "COPY", k - 1);
  }
  // COPY writes a back buffer only after the previous frame has been swapped in.
  for (const FrameReady& f : r.frames)
    for (int e = 0; e < eyes; ++e) {
      const auto it = spans.find({"COPY", (f.frame + 1) * eyes + e});
      if (it != spans.end() && it->second.start < f.swap_at)
        bad.push_back("COPY of frame " + std::to_string(f.frame + 1) + " starts before frame " +
                      std::to_string(f.frame) + " is swapped in");
    }
  return bad;
}

/// Units that run two intervals at once (GPs, renderers, frame-buffer ports).
std::vector<std::string> overlaps(const RunRecord& r, const std::vector<std::string>& stages) {
  std::map<std::string, std::vector<std::pair<des::Time, des::Time>>> by_unit;
  for (const StageInterval& s : r.stages)
    if (std::find(stages.begin(), stages.end(), s.stage) != stages.end())
      by_unit[s.stage + "@" + s.unit].emplace_back(s.start, s.end);
  std::vector<std::string> bad;
  for (auto& [unit, iv] : by_unit) {
    std::sort(iv.begin(), iv.end());
    for (std::size_t i = 1; i < iv.size(); ++i)
      if (iv[i].first < iv[i - 1].second) bad.push_back(unit + " overlaps at " + iv[i].first.str());
  }
  return bad;
}

}  // namespace

TEST_CASE("RC never violates its start conditions", "[pxpl5][rc][conditions]") {
  struct Case {
    bool stereo;
    bool trivial;
    int64_t triangles;
    double regions;
  };
  for (const Case c : {Case{true, true, 12, 20.0}, Case{true, false, 3000, 1.3}, Case{true, false, 20000, 1.3},
                       Case{true, false, 2000, 20.0}, Case{false, false, 3000, 1.3}, Case{false, true, 12, 20.0}}) {
    RcParams p = c.trivial ? trivial_rc_params() : RcParams{};
    p.stereo = c.stereo;
    const RunRecord r = run_rc(p, Workload{c.triangles, c.regions}, des::Time::s(2));
    CAPTURE(c.stereo, c.trivial, c.triangles, c.regions);
    REQUIRE(r.frames.size() > 3);
    CHECK(rc_violations(r, p.eyes()).empty());
    CHECK(overlaps(r, {"RENDER", "COPY"}).empty());
    for (const FrameReady& f : r.frames) {
      for (const EyeImage& e : f.eyes) CHECK(e.copy_end < f.swap_at);
      CHECK(ntsc_timing().retrace(f.swap_field - 1) <= f.eyes.back().copy_end);
    }
  }
}

TEST_CASE("the start-condition checker catches a violation", "[pxpl5][rc][conditions]") {
  RunRecord r = run_rc(trivial_rc_params(), Workload{12, 20.0}, des::Time::s(1));
  REQUIRE(rc_violations(r, 2).empty());
  // Pretend the 6th eye's TRANSFORM began before the 3rd previous eye's COPY ended.
  for (StageInterval& s : r.stages)
    if (s.stage == "TRANSFORM" && s.frame == 2 && s.eye == 1) s.start = des::Time::zero();
  CHECK(!rc_violations(r, 2).empty());
  StageInterval twice = r.stages.back();
  for (const StageInterval& s : r.stages)
    if (s.stage == "COPY") twice = s;
  twice.start = twice.start + des::Time::us(1);
  r.stages.push_back(twice);
  CHECK(!overlaps(r, {"COPY"}).empty());
}

TEST_CASE("Slats starts TRANSFORM at a retrace and copies one region per frame buffer at a time", "[pxpl5][slats][conditions]") {
  const FieldTiming timing = ntsc_timing();
  for (const bool optimised : {true, false}) {
    SlatsParams p;
    p.copy_optimisation = optimised;
    const RunRecord r = run_slats(p, 90, des::Time::s(1));
    CHECK(overlaps(r, {"TRANSFORM", "COPY", "RENDER"}).empty());
    for (const StageInterval& s : r.stages) {
      if (s.stage == "TRANSFORM") CHECK(s.start == timing.retrace(s.frame - 1));
      if (s.stage == "RENDER") CHECK(s.start >= timing.retrace(s.frame - 1));
      // Without the optimisation every region is in place before the retrace.
      if (s.stage == "COPY" && !optimised) CHECK(s.end < timing.retrace(s.frame));
    }
  }
}
