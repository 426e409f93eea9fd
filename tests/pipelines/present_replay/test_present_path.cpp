// The present path's rules against sequences worked by hand.
#include <catch2/catch.hpp>

#include "present_replay/present_path.hpp"

using latsim::des::Time;
using latsim::pipelines::present_replay::PresentPath;
using latsim::pipelines::present_replay::PresentPathSpec;

namespace {

PresentPathSpec spec(PresentPathSpec::Show show, int sync = 1, bool composed = false, int latency = 3) {
  PresentPathSpec s;
  s.show = show;
  s.sync_interval = sync;
  s.composed = composed;
  s.max_frame_latency = latency;
  return s;
}

Time ms(double v) { return Time::from_ms(v); }

}  // namespace

TEST_CASE("present path: a flip queue with vsync shows frames in order, one a refresh, and blocks the fourth") {
  // Four frames presented at once, ready at once, before retrace 1 (t = 16):
  // the queue holds 4 > 3 (the maximum frame latency), so the fourth
  // Present blocks. Retrace 1 flips frame 0 in (3 left: the block ends);
  // retraces 2, 3, 4 flip frames 1, 2, 3, one each.
  PresentPath p(spec(PresentPathSpec::Show::queued));
  for (int64_t j = 0; j < 4; ++j) {
    p.presented(j);
    CHECK_FALSE(p.ready(j, ms(1)));
    CHECK(p.blocks() == (j == 3));
  }
  for (int64_t k = 1; k <= 4; ++k) {
    const PresentPath::Retrace r = p.retrace(ms(16.0 * static_cast<double>(k)));
    REQUIRE(r.show);
    CHECK(*r.show == k - 1);
    CHECK(r.discarded.empty());
    CHECK_FALSE(p.blocks());
  }
  CHECK_FALSE(p.retrace(ms(80)).show);  // nothing new: the last frame stays
}

TEST_CASE("present path: sync interval 2 keeps each frame up for two refreshes") {
  // Frames 0 and 1 ready before retrace 1: frame 0 at retrace 1; retrace 2
  // is its first refresh, not its second: nothing; frame 1 at retrace 3.
  PresentPath p(spec(PresentPathSpec::Show::queued, 2));
  p.presented(0);
  p.presented(1);
  p.ready(0, ms(1));
  p.ready(1, ms(2));
  CHECK(*p.retrace(ms(16)).show == 0);
  CHECK_FALSE(p.retrace(ms(32)).show);
  CHECK(*p.retrace(ms(48)).show == 1);
}

TEST_CASE("present path: a frame not ready at the retrace waits for the next one") {
  // Ready at 17 ms: retrace 1 (16 ms) finds it not ready; retrace 2 flips it.
  PresentPath p(spec(PresentPathSpec::Show::queued));
  p.presented(0);
  p.ready(0, ms(17));
  CHECK_FALSE(p.retrace(ms(16)).show);
  CHECK(*p.retrace(ms(32)).show == 0);
}

TEST_CASE("present path: sync interval 0 without tearing shows the newest ready frame and discards the older") {
  // Frames 0, 1, 2 ready before retrace 1, frame 3 after it: retrace 1 shows
  // 2 and discards 0 and 1 (never displayed); retrace 2 shows 3.
  PresentPath p(spec(PresentPathSpec::Show::newest, 0));
  for (int64_t j = 0; j < 4; ++j) p.presented(j);
  p.ready(0, ms(2));
  p.ready(1, ms(6));
  p.ready(2, ms(10));
  p.ready(3, ms(20));
  const PresentPath::Retrace r = p.retrace(ms(16));
  CHECK(*r.show == 2);
  CHECK(r.discarded == std::vector<int64_t>{0, 1});
  CHECK(*p.retrace(ms(32)).show == 3);
}

TEST_CASE("present path: tearing allowed shows a frame the moment it is ready") {
  PresentPath p(spec(PresentPathSpec::Show::immediate, 0));
  p.presented(0);
  CHECK(p.ready(0, ms(3)));
  CHECK_FALSE(p.retrace(ms(16)).show);
}

TEST_CASE("present path: the desktop compositor shows the frame it takes a refresh later") {
  // Composed, vsync: frame 0 ready before retrace 1 is taken there and shown
  // at retrace 2; frame 1, ready before retrace 2, is taken there and shown
  // at retrace 3.
  PresentPath p(spec(PresentPathSpec::Show::queued, 1, true));
  p.presented(0);
  p.ready(0, ms(1));
  const PresentPath::Retrace r1 = p.retrace(ms(16));
  CHECK_FALSE(r1.show);
  CHECK(r1.taken == std::vector<int64_t>{0});
  p.presented(1);
  p.ready(1, ms(20));
  const PresentPath::Retrace r2 = p.retrace(ms(32));
  CHECK(*r2.show == 0);
  CHECK(r2.taken == std::vector<int64_t>{1});
  CHECK(*p.retrace(ms(48)).show == 1);
}
