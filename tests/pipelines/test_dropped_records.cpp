// The host predicts from what reaches it: a record pushed out of a full
// serial buffer never arrives, so its predictor never sees it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "latsim/des/simulator.hpp"
#include "latsim/run/tracker_host.hpp"
#include "latsim/tracker/host_prediction.hpp"
#include "latsim/tracker/motion_source.hpp"
#include "latsim/tracker/tracker.hpp"
#include "latsim/tracker/transport.hpp"

using namespace latsim;

TEST_CASE("a record dropped from the serial buffer never reaches the host's predictor", "[prediction]") {
  des::Simulator sim;
  const tracker::ConstantAngularVelocity motion(tracker::Pose{}, glm::dvec3(0, 1, 0), 30.0);
  tracker::TrackerParams tp;
  tp.period = des::RationalSeconds::period_of_hz(60);
  tracker::Tracker tracker(tp, motion, des::RandomStream(1, "tracker", 0));
  // 40 bytes x 10 bits at 19200 baud: 20.833 ms on the line per record, one
  // offered every 16.667 ms, one may wait: in 2 s the tracker offers 120,
  // the line sends at most 2 s / 20.833 ms = 96, so at least 22 are dropped.
  tracker::SerialLinkParams sp;
  sp.record_bytes = 40;
  sp.buffer_records = 1;
  tracker::SerialLink link(sp);
  tracker::PredictionParams pp;
  pp.predictor.kind = tracker::PredictorKind::ConstantVelocity;
  run::TrackerHost host(sim, tracker, link, nullptr, pp);
  std::vector<int64_t> carried;
  host.on_carried([&](const tracker::TrackerSample& s, const tracker::Carriage&) { carried.push_back(s.index); });
  host.start(des::Time::s(2));
  sim.run_until(des::Time::s(2));

  REQUIRE(host.samples_measured() == 120);
  CHECK(host.records_dropped() >= 22);
  // The same tracker again (same stream): the same samples, index by index.
  tracker::Tracker again(tp, motion, des::RandomStream(1, "tracker", 0));
  int64_t unseen = 0;
  for (int64_t i = 0; i < host.samples_measured(); ++i) {
    const tracker::TrackerSample s = again.sample(i);
    if (std::find(carried.begin(), carried.end(), i) != carried.end()) {
      CHECK_NOTHROW(host.basis_of(s));
    } else {
      CHECK_THROWS_AS(host.basis_of(s), std::logic_error);
      ++unseen;
    }
  }
  // Every record not carried was dropped or is still waiting for the line.
  CHECK(unseen == host.records_dropped() + host.records_waiting());
}
