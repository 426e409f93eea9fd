// Priority rendering: assignment by validity, promotion and demotion, and
// on-demand redraws.
#include <catch2/catch.hpp>

#include <numeric>

#include "latsim/arp/priority_model.hpp"

using namespace latsim;

namespace {

renderer::Aabb cube_at(const glm::dvec3& centre, double half) {
  renderer::Aabb b;
  b.extend(centre - glm::dvec3(half));
  b.extend(centre + glm::dvec3(half));
  return b;
}

std::vector<arp::PriorityObject> row_of_objects() {
  std::vector<arp::PriorityObject> objects;
  for (double z : {-1.0, -3.0, -10.0, -40.0, -200.0}) objects.push_back({cube_at({2.0, 0.0, z}, 0.25), 0.0, {}});
  return objects;
}

arp::PriorityParams params() {
  arp::PriorityParams p;
  p.threshold_rad = 0.003;
  p.base_period = des::RationalSeconds{1, 60};
  p.memory_count = 4;
  return p;
}

des::Time tick_time(int64_t k) { return des::PeriodicSchedule(des::Time::zero(), {1, 60}).at(k); }

}  // namespace

TEST_CASE("a still user never re-renders static objects") {
  arp::PriorityModel model(row_of_objects(), params());
  const arp::PriorityTick first = model.tick(0, tick_time(0), glm::dvec3(0.0), glm::dvec3(0.0));
  CHECK(first.objects_rendered == 5);
  for (int64_t k = 1; k < 600; ++k) {
    const arp::PriorityTick t = model.tick(k, tick_time(k), glm::dvec3(0.0), glm::dvec3(0.0));
    REQUIRE(t.updated_memories.empty());
    REQUIRE(t.objects_rendered == 0);
  }
  // Infinite validity everywhere: everything sits in the slowest memory.
  for (size_t o = 0; o < 5; ++o) CHECK(model.memory_of(o) == 3);
}

TEST_CASE("a walking user gets near objects in fast memories and far ones in slow memories") {
  arp::PriorityModel model(row_of_objects(), params());
  const glm::dvec3 velocity(1.0, 0.0, 0.0);
  int64_t near_renders = 0;
  int64_t far_renders = 0;
  for (int64_t k = 0; k < 120; ++k) {
    const glm::dvec3 eye = velocity * tick_time(k).to_seconds();
    model.tick(k, tick_time(k), eye, velocity);
    const auto lists = model.objects_per_memory();
    size_t total = 0;
    for (const auto& l : lists) total += l.size();
    REQUIRE(total == 5);  // each object in exactly one memory
  }
  CHECK(model.memory_of(0) == 0);
  CHECK(model.memory_of(4) == 3);
  CHECK(model.memory_of(1) <= model.memory_of(2));
  CHECK(model.memory_of(2) <= model.memory_of(3));
  near_renders = model.counters()[0].updates;
  far_renders = model.counters()[3].updates;
  CHECK(near_renders > 100);     // redrawn at (almost) every 60 Hz tick
  CHECK(far_renders <= 16);      // at most every 8th tick
}

TEST_CASE("objects are promoted when the user approaches and demoted when the user leaves") {
  std::vector<arp::PriorityObject> objects{{cube_at({0.0, 0.0, -60.0}, 0.25), 0.0, {}}};
  arp::PriorityModel model(objects, params());
  const double speed = 2.0;
  const int64_t leg = 1500;  // 25 s: 50 m
  model.tick(0, tick_time(0), glm::dvec3(0.0), glm::dvec3(0.0, 0.0, -speed));
  const int far_memory = model.memory_of(0);
  CHECK(far_memory >= 2);
  for (int64_t k = 1; k <= leg; ++k) {
    const glm::dvec3 eye(0.0, 0.0, -speed * tick_time(k).to_seconds());
    model.tick(k, tick_time(k), eye, glm::dvec3(0.0, 0.0, -speed));
  }
  CHECK(model.memory_of(0) == 0);
  CHECK(model.promotions() >= 1);
  CHECK(model.demotions() == 0);
  for (int64_t k = leg + 1; k <= 2 * leg; ++k) {
    const double back_s = (tick_time(k) - tick_time(leg)).to_seconds();
    const glm::dvec3 eye(0.0, 0.0, -speed * tick_time(leg).to_seconds() + speed * back_s);
    model.tick(k, tick_time(k), eye, glm::dvec3(0.0, 0.0, speed));
  }
  CHECK(model.demotions() >= 1);
  CHECK(model.memory_of(0) == far_memory);
}

TEST_CASE("an animated object is redrawn at its own validity period") {
  std::vector<arp::PriorityObject> objects{{cube_at({0.0, 0.0, -50.0}, 0.25), 0.1, {}}};
  arp::PriorityModel model(objects, params());
  for (int64_t k = 0; k < 600; ++k) model.tick(k, tick_time(k), glm::dvec3(0.0), glm::dvec3(0.0));
  // 0.1 s validity: memory 2 (15 Hz slots, period 66.7 ms <= 100 ms), redrawn whenever
  // the next slot would come too late, i.e. every 66.7 ms slot: 150 renders in 10 s.
  CHECK(model.memory_of(0) == 2);
  CHECK(model.counters()[2].updates == 150);
}
