// What the display memories show while renders queue: every segment (or
// object) in exactly one shown image at every presentation, checked by
// scanning the images themselves, and moves between memories only at the
// slower memory's slot.
#include <catch2/catch.hpp>

#include <map>
#include <vector>

#include "latsim/arp/priority_system.hpp"
#include "latsim/arp/region_priority_system.hpp"
#include "latsim/des/periodic.hpp"
#include "latsim/renderer/scene_generators.hpp"
#include "latsim/tracker/motion_source.hpp"

using namespace latsim;

namespace {

tracker::PolylineWalk walk(std::vector<glm::dvec3> points) {
  tracker::WalkParams w;
  w.points_m = std::move(points);
  w.speed_m_s = 1.0;
  return tracker::PolylineWalk(w);
}

const des::PeriodicSchedule kTicks(des::Time::zero(), {1, 60});

/// Scans every memory's shown image: how many images hold each item. Null
/// when some memory has shown nothing yet.
std::optional<std::vector<int>> holders(const arp::DisplayMemories& memories, size_t items) {
  std::vector<int> count(items, 0);
  for (int m = 0; m < memories.memory_count(); ++m) {
    const arp::MemoryImage* img = memories.shown(m);
    if (!img) return std::nullopt;
    for (uint32_t s : img->contents) ++count.at(s);
  }
  return count;
}

struct Scan {
  int64_t presentations = 0;
  int64_t checked = 0;
  int64_t violations = 0;
  void check(const arp::DisplayMemories& memories, size_t items) {
    ++presentations;
    const auto count = holders(memories, items);
    if (!count) return;
    ++checked;
    for (int c : *count) violations += c == 1 ? 0 : 1;
  }
};

}  // namespace

TEST_CASE("each segment is in exactly one shown region memory at every presentation") {
  const renderer::Scene scene = renderer::make_gallery(renderer::GalleryParams{});
  const renderer::RegionGrid grid(scene.bounds(), 2.0);
  const arp::SegmentedScene cut = arp::segment_scene(scene, grid);
  const auto path = walk({{-8.5, 1.6, -8.5}, {8.5, 1.6, -7.5}, {0.5, 1.6, 8.5}, {-7.5, 1.6, 0.5}});
  struct Setting {
    bool warping;
    int64_t per_segment_us;  // 300 us per segment overloads one renderer
  };
  for (const Setting setting : {Setting{false, 20}, Setting{true, 20}, Setting{false, 300}, Setting{true, 300}}) {
    des::Simulator sim;
    arp::RegionSystemParams p;
    p.model.outer_rings = {1, 2, 4};
    p.model.threshold_rad = 0.006;
    p.model.swap_margin_m = 0.5;
    p.model.warping = setting.warping;
    p.cost.per_segment = des::Time::us(setting.per_segment_us);
    arp::RegionPrioritySystem system(sim, sim.kind("arp.render"), cut, grid, p);
    Scan scan;
    system.on_present([&](const std::vector<const arp::MemoryImage*>&) {
      scan.check(system.memories(), cut.segments.size());
      // The system's own bookkeeping agrees with the scan.
      const arp::ShownRegions shown = system.shown();
      for (size_t s = 0; s < cut.segments.size(); ++s) {
        const int m = shown.memory_of_segment[s];
        if (m < 0) continue;
        const auto& contents = system.memories().shown(m)->contents;
        REQUIRE(std::binary_search(contents.begin(), contents.end(), static_cast<uint32_t>(s)));
      }
    });
    des::Periodic ticks(sim, kTicks, sim.kind("arp.tick"), [&](int64_t k) {
      system.tick(sim.now(), path.pose_at(kTicks.at(k)).position_m, k);
    });
    const des::Time end = des::Time::s(50);
    ticks.start(0, end);
    sim.run_until(end);
    INFO("warping " << setting.warping << ", " << setting.per_segment_us << " us per segment");
    CHECK(system.model().swaps() >= 10);
    // Enough presentations to mean something (overload with warping shows about 9 a second).
    CHECK(scan.checked > 300);
    CHECK(scan.violations == 0);
    int64_t skipped = 0;
    for (int m = 0; m < 4; ++m) skipped += system.memories().queue().skipped(m);
    if (setting.per_segment_us > 100) CHECK(skipped > 0);
  }
}

TEST_CASE("each object is in exactly one shown priority memory at every presentation") {
  const renderer::Scene scene = renderer::make_gallery(renderer::GalleryParams{});
  const auto path = walk({{-8.5, 1.6, -8.5}, {8.5, 1.6, -7.5}, {0.5, 1.6, 8.5}});
  for (int64_t per_object_us : {20, 2000}) {
    des::Simulator sim;
    std::vector<arp::PriorityObject> objects;
    for (const auto& obj : scene.objects()) objects.push_back({obj.bounds, 0.0, glm::dvec3(0.0)});
    arp::PrioritySystemParams p;
    p.cost.per_segment = des::Time::us(per_object_us);
    arp::PrioritySystem system(sim, sim.kind("arp.render"), scene, objects, p);
    Scan scan;
    system.memories().on_present([&](const std::vector<const arp::MemoryImage*>&) {
      scan.check(system.memories(), scene.object_count());
    });
    des::Periodic ticks(sim, kTicks, sim.kind("arp.tick"), [&](int64_t k) {
      const des::Time t = kTicks.at(k);
      const glm::dvec3 eye = path.pose_at(t).position_m;
      const glm::dvec3 velocity = (path.pose_at(t + des::Time::ms(1)).position_m - eye) / 1e-3;
      system.tick(k, sim.now(), eye, velocity, k);
    });
    const des::Time end = des::Time::s(30);
    ticks.start(0, end);
    sim.run_until(end);
    INFO(per_object_us << " us per object");
    CHECK(system.model().promotions() + system.model().demotions() > 20);
    // Enough presentations to mean something (the overloaded case shows about 16 a second).
    CHECK(scan.checked > 300);
    CHECK(scan.violations == 0);
  }
}

TEST_CASE("priority moves take effect only at a slot of the slower of the two memories") {
  const renderer::Scene scene = renderer::make_gallery(renderer::GalleryParams{});
  std::vector<arp::PriorityObject> objects;
  for (const auto& obj : scene.objects()) objects.push_back({obj.bounds, 0.0, glm::dvec3(0.0)});
  arp::PriorityParams params;
  arp::PriorityModel model(objects, params);
  const auto path = walk({{-8.5, 1.6, -8.5}, {8.5, 1.6, -7.5}, {0.5, 1.6, 8.5}});
  std::vector<int> before = model.assignment();
  int64_t moves = 0;
  for (int64_t k = 0; k < 60 * 30; ++k) {
    const des::Time t = kTicks.at(k);
    const glm::dvec3 eye = path.pose_at(t).position_m;
    const glm::dvec3 velocity = (path.pose_at(t + des::Time::ms(1)).position_m - eye) / 1e-3;
    const arp::PriorityTick tick = model.tick(k, t, eye, velocity);
    for (size_t o = 0; o < objects.size(); ++o) {
      const int from = before[o];
      const int to = model.memory_of(o);
      if (from == to) continue;
      ++moves;
      // Memory i has a slot every 2^i ticks (hand rule, not the model's).
      const int slower = std::max(from, to);
      REQUIRE(k % (int64_t{1} << slower) == 0);
      // Both memories are redrawn at that tick.
      REQUIRE(std::count(tick.updated_memories.begin(), tick.updated_memories.end(), from) == 1);
      REQUIRE(std::count(tick.updated_memories.begin(), tick.updated_memories.end(), to) == 1);
    }
    before = model.assignment();
  }
  CHECK(moves > 20);
}
