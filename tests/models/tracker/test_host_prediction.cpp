// The host's prediction history: each sample's basis predicts from what the
// host knew then, fixed horizons, forgetting, and no cost without prediction.
#include <catch2/catch.hpp>


#include "latsim/tracker/host_prediction.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using namespace latsim::tracker;
using latsim::des::Time;

namespace {

TrackerSample sample_at(int64_t index, Time t, const Pose& pose) {
  TrackerSample s;
  s.index = index;
  s.measured_at = t;
  s.ready_at = t;
  s.pose = pose;
  return s;
}

/// Yaw at 100 deg/s until 30 ms, then at -50 deg/s: a rate change the
/// samples after 30 ms reveal.
Pose yaw_with_reversal(Time t) {
  const double s = t.to_seconds();
  const double deg = s <= 0.03 ? 100.0 * s : 3.0 - 50.0 * (s - 0.03);
  return Pose{{0.0, 1.6, 0.0}, quat_from_yaw_pitch(units::deg_to_rad(deg), 0.0)};
}

}  // namespace

TEST_CASE("a basis predicts from what the host knew after its own sample", "[host_prediction]") {
  PredictionParams params;
  params.predictor.kind = PredictorKind::ConstantVelocity;
  HostPrediction host(params);
  std::vector<TrackerSample> samples;
  for (int k = 0; k <= 6; ++k) {
    samples.push_back(sample_at(k, Time::ms(10) * k, yaw_with_reversal(Time::ms(10) * k)));
    host.observe(samples.back());
  }
  // Sample 3 (30 ms) has seen only the 100 deg/s turn: 20 ms later it expects 5 degrees.
  const PosePrediction p3 = host.basis_of(samples[3]).for_photon_time(Time::ms(50));
  CHECK(p3.target == Time::ms(50));
  CHECK(p3.horizon() == Time::ms(20));
  CHECK(p3.sample.index == 3);
  CHECK(units::rad_to_deg(yaw_of(p3.pose.orientation)) == Approx(5.0).epsilon(1e-12));
  // Sample 6 (60 ms) has seen the reversal: at 80 ms it expects 3 - 50 * 0.05 = 0.5 degrees.
  const PosePrediction p6 = host.basis_of(samples[6]).for_photon_time(Time::ms(80));
  CHECK(units::rad_to_deg(yaw_of(p6.pose.orientation)) == Approx(0.5).epsilon(1e-9));
}

TEST_CASE("a fixed horizon ignores the photon time asked for", "[host_prediction]") {
  PredictionParams params;
  params.predictor.kind = PredictorKind::ConstantVelocity;
  params.fixed_horizon = Time::ms(15);
  HostPrediction host(params);
  const TrackerSample a = sample_at(0, Time::ms(0), yaw_with_reversal(Time::ms(0)));
  const TrackerSample b = sample_at(1, Time::ms(10), yaw_with_reversal(Time::ms(10)));
  host.observe(a);
  host.observe(b);
  const PosePrediction p = host.basis_of(b).for_photon_time(Time::s(5));
  CHECK(p.target == Time::ms(25));
  CHECK(angle_between(p.pose.orientation, yaw_with_reversal(Time::ms(25)).orientation) < 1e-12);
}

TEST_CASE("without prediction nothing is stored and poses are the samples'", "[host_prediction]") {
  HostPrediction host(PredictionParams{});
  const TrackerSample a = sample_at(0, Time::ms(0), yaw_with_reversal(Time::ms(0)));
  const TrackerSample b = sample_at(1, Time::ms(10), yaw_with_reversal(Time::ms(10)));
  host.observe(a);
  host.observe(b);
  CHECK(host.held() == 0);
  const PosePrediction p = host.basis_of(b).for_photon_time(Time::ms(70));
  CHECK(p.pose.orientation == b.pose.orientation);
  CHECK(p.pose.position_m == b.pose.position_m);
  CHECK(p.target == Time::ms(70));
}

TEST_CASE("forgotten and unknown samples are reported", "[host_prediction]") {
  PredictionParams params;
  params.predictor.kind = PredictorKind::Kalman;
  HostPrediction host(params);
  for (int k = 0; k < 10; ++k) host.observe(sample_at(k, Time::ms(10) * k, Pose{}));
  host.forget_before(5);
  CHECK(host.held() == 5);
  CHECK_THROWS_AS(host.basis_of(sample_at(4, Time::ms(40), Pose{})), std::logic_error);
  CHECK_NOTHROW(host.basis_of(sample_at(5, Time::ms(50), Pose{})));
  CHECK_THROWS_AS(host.basis_of(sample_at(12, Time::ms(120), Pose{})), std::logic_error);
  CHECK_THROWS_AS(host.observe(sample_at(9, Time::ms(200), Pose{})), std::logic_error);
  params.fixed_horizon = -Time::ms(1);
  CHECK_THROWS_AS(HostPrediction(params), std::invalid_argument);
}

TEST_CASE("a runtime host predicts from its own stamps and merges records it cannot tell apart in time",
          "[host_prediction]") {
  PredictionParams params;
  params.predictor.kind = PredictorKind::ConstantVelocity;
  params.knowledge = PredictionKnowledge::runtime;
  HostPrediction host(params);
  // Measured at 0, 10 and 20 ms (100 deg/s: 0, 1 and 2 degrees); the host
  // sees the first at its measurement and the other two together (one poll),
  // both stamped 20 ms. The newest stands for both: the rate is taken from
  // the first to it, (2 - 0) deg / 20 ms = 100 deg/s, not from the middle
  // sample over a zero interval.
  const TrackerSample a = sample_at(0, Time::ms(0), yaw_with_reversal(Time::ms(0)));
  const TrackerSample b = sample_at(1, Time::ms(10), yaw_with_reversal(Time::ms(10)));
  const TrackerSample c = sample_at(2, Time::ms(20), yaw_with_reversal(Time::ms(20)));
  host.observe(a, Time::ms(0));
  host.observe(b, Time::ms(20));
  host.observe(c, Time::ms(20));
  const PosePrediction p = host.basis_of(c).for_photon_time(Time::ms(25));
  CHECK(p.sample.index == 2);  // the latency origin stays the true sample
  CHECK(p.horizon() == Time::ms(5));
  CHECK(units::rad_to_deg(yaw_of(p.pose.orientation)) == Approx(2.5).epsilon(1e-12));
  // A sample stamped late (a wait the host does not know of) stretches the
  // interval its rate is taken over and is extrapolated from its stamp.
  HostPrediction late(params);
  late.observe(a, Time::ms(0));
  late.observe(c, Time::ms(25));
  const PosePrediction q = late.basis_of(c).for_photon_time(Time::ms(30));
  // Rate 2 deg / 25 ms = 80 deg/s, from 2 degrees at the 25 ms stamp for 5 ms: 2.4 degrees.
  CHECK(units::rad_to_deg(yaw_of(q.pose.orientation)) == Approx(2.4).epsilon(1e-12));
}
