// Persistence seen through the figures: motion-to-photon moves to the middle
// of the lit interval and smear_arcmin = angular speed x lit time, derived
// by hand for the reference vsync configuration (pose read at the retrace,
// shown from the next one) and a head turning at a constant rate.
#include <catch2/catch.hpp>

#include "rig.hpp"

using latsim::des::Time;
using latsim::display::PersistenceParams;
using latsim::testing::Rig;
using latsim::testing::RigOptions;
using latsim::testing::stage;
using namespace latsim::pipelines::frame_stages;

namespace {

FrameStagesSpec vsync_config() {
  FrameStagesSpec s;
  s.processors = {ProcessorSpec{"cpu", {}}, ProcessorSpec{"gpu", {}}};
  s.stages = {stage("I", {0}, 1, StartRule::retrace, true), stage("S", {0}, 1), stage("R", {0}, 1),
              stage("G", {1}, 1)};
  return s;
}

RigOptions turning(double deg_s, PersistenceParams::Mode mode, double lit_ms, double response_ms) {
  RigOptions o;
  o.motion = std::make_shared<latsim::tracker::ConstantAngularVelocity>(latsim::tracker::Pose{},
                                                                        glm::dvec3(0, 1, 0), deg_s);
  PersistenceParams p;
  p.mode = mode;
  p.lit = Time::from_ms(lit_ms);
  p.response = Time::from_ms(response_ms);
  o.persistence = p;
  return o;
}

}  // namespace

TEST_CASE("persistence figures: rolling 2 ms flashes move every photon 1 ms plus the response later") {
  // Each line is lit [w + 0.1, w + 2.1]: the middle is 1.1 ms after it is
  // written, so 16 - 31.9 ms becomes 17.1 - 33.0 ms; smear = 120 deg/s x 2 ms
  // = 0.24 deg = 14.4 arcmin on every line.
  Rig rig(vsync_config(), turning(120, PersistenceParams::Mode::rolling, 2, 0.1));
  rig.run(1.0);
  CHECK(rig.mtp("min") == Approx(17.1).margin(1e-6));
  CHECK(rig.mtp("max") == Approx(33.0).margin(1e-6));
  CHECK(rig.stat("smear_arcmin", "min") == Approx(14.4).epsilon(1e-9));
  CHECK(rig.stat("smear_arcmin", "max") == Approx(14.4).epsilon(1e-9));
}

TEST_CASE("persistence figures: a global flash lights every line of a field at once") {
  // Frame k is written during field k+1 and flashes [V_{k+2} + 0.1, V_{k+2} + 2.1]:
  // every line's photon is at V_{k+2} + 1.1, 33.1 ms after its pose was read.
  Rig rig(vsync_config(), turning(120, PersistenceParams::Mode::global, 2, 0.1));
  rig.run(1.0);
  CHECK(rig.mtp("min") == Approx(33.1).margin(1e-6));
  CHECK(rig.mtp("max") == Approx(33.1).margin(1e-6));
}

TEST_CASE("persistence figures: full persistence holds a line for the whole refresh and smears far more") {
  // Lit [w + 0.05, w + 16.05]: the middle 8.05 ms after writing: 24.05 - 39.95 ms;
  // smear = 120 deg/s x 16 ms = 1.92 deg = 115.2 arcmin, eight times the 2 ms flash's.
  Rig rig(vsync_config(), turning(120, PersistenceParams::Mode::full, 0, 0.1));
  rig.run(1.0);
  CHECK(rig.mtp("min") == Approx(24.05).margin(1e-6));
  CHECK(rig.mtp("max") == Approx(39.95).margin(1e-6));
  CHECK(rig.stat("smear_arcmin", "mean") == Approx(115.2).epsilon(1e-9));
}

TEST_CASE("persistence figures: a still head does not smear, and without persistence there is no smear figure") {
  Rig still(vsync_config(), turning(0, PersistenceParams::Mode::rolling, 2, 0));
  still.run(0.5);
  CHECK(still.stat("smear_arcmin", "max") == 0.0);
  Rig impulse(vsync_config());
  impulse.run(0.5);
  CHECK(impulse.stat("smear_arcmin", "count") < 0);
}
