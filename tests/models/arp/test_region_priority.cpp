// Region priority rendering: the partition invariant, swapping without
// oscillation, on-demand updates, warping and tears.
#include <catch2/catch.hpp>

#include <algorithm>
#include <memory>

#include "latsim/arp/region_priority_model.hpp"
#include "latsim/arp/seam_meter.hpp"
#include "latsim/renderer/scene_generators.hpp"
#include "latsim/tracker/motion_source.hpp"

using namespace latsim;

namespace {

struct Gallery {
  renderer::Scene scene = renderer::make_gallery(renderer::GalleryParams{});
  renderer::RegionGrid grid{scene.bounds(), 2.0};
  arp::SegmentedScene cut = arp::segment_scene(scene, grid);
};

arp::RegionPriorityParams params(bool warping, double margin_m = 0.25) {
  arp::RegionPriorityParams p;
  p.outer_rings = {1, 2, 4};
  p.threshold_rad = 0.006;
  p.swap_margin_m = margin_m;
  p.warping = warping;
  p.warp_falloff_m = 1.0;
  return p;
}

// The decided state as if every memory showed it at once.
arp::ShownRegions shown_now(const arp::RegionPriorityModel& model) {
  arp::ShownRegions shown;
  shown.views.assign(static_cast<size_t>(model.memory_count()), &model.view());
  shown.memory_of_segment = model.memory_of_segments();
  return shown;
}

des::Time tick_time(int64_t k) { return des::PeriodicSchedule(des::Time::zero(), {1, 60}).at(k); }

tracker::PolylineWalk walk(std::vector<glm::dvec3> points) {
  tracker::WalkParams w;
  w.points_m = std::move(points);
  w.speed_m_s = 1.0;
  return tracker::PolylineWalk(w);
}

}  // namespace

TEST_CASE("each region is in exactly one memory at every instant of a walk") {
  Gallery g;
  arp::RegionPriorityModel model(g.cut, g.grid, params(false));
  const auto path = walk({{-8.5, 1.6, -8.5}, {8.5, 1.6, -7.5}, {7.5, 1.6, 8.5}, {-8.0, 1.6, 3.0}});
  int64_t swaps_seen = 0;
  for (int64_t k = 0; k < 60 * 50; ++k) {
    const arp::RegionTick t = model.tick(tick_time(k), path.pose_at(tick_time(k)).position_m);
    swaps_seen += t.swapped;
    REQUIRE(model.map().is_partition());
    size_t total = 0;
    for (const auto& list : model.segments_per_memory()) total += list.size();
    REQUIRE(total == g.cut.segments.size());
  }
  CHECK(swaps_seen == model.swaps());
  CHECK(model.swaps() >= 10);
}

TEST_CASE("no swap oscillation when the path runs along a region boundary") {
  Gallery g;
  // The boundary x = 0 (grid origin -10, 2 m regions); the path zigzags across it by 10 cm.
  std::vector<glm::dvec3> points;
  for (int i = 0; i <= 16; ++i) points.push_back({(i % 2 == 0 ? 0.1 : -0.1), 1.6, -8.0 + i});
  const auto path = walk(points);
  auto run = [&](double margin_m) {
    arp::RegionPriorityModel model(g.cut, g.grid, params(false, margin_m));
    int x_changes = 0;
    int last_ix = -1;
    for (int64_t k = 0; k < 60 * 17; ++k) {
      model.tick(tick_time(k), path.pose_at(tick_time(k)).position_m);
      const int ix = model.map().home().ix;
      if (last_ix >= 0 && ix != last_ix) ++x_changes;
      last_ix = ix;
    }
    return x_changes;
  };
  CHECK(run(0.25) == 0);
  // Without a margin the home region flips across the boundary again and again.
  CHECK(run(0.0) > 4);
}

TEST_CASE("a still user never redraws region memories") {
  Gallery g;
  arp::RegionPriorityModel model(g.cut, g.grid, params(true));
  const glm::dvec3 eye(1.3, 1.6, -2.7);
  CHECK(model.tick(tick_time(0), eye).updated.size() == 4);
  for (int64_t k = 1; k < 600; ++k) REQUIRE(model.tick(tick_time(k), eye).updated.empty());
  for (const auto& m : model.memories()) CHECK(m.updates == 1);
}

TEST_CASE("slower memories update less often on a walk") {
  Gallery g;
  arp::RegionPriorityModel model(g.cut, g.grid, params(false));
  const auto path = walk({{-8.0, 1.6, 0.5}, {8.0, 1.6, 0.5}});
  for (int64_t k = 0; k < 60 * 16; ++k) model.tick(tick_time(k), path.pose_at(tick_time(k)).position_m);
  const auto& m = model.memories();
  CHECK(m[0].updates > 900);
  // Thresholds grow with distance: 2 d sin(theta/2) is 12 mm at 2 m (below one tick's
  // 16.7 mm walk), 24 mm at 4 m and 48 mm at 8 m.
  CHECK(m[1].updates <= m[0].updates);
  CHECK(m[2].updates < m[1].updates);
  CHECK(m[3].updates < m[2].updates);
  CHECK(m[3].updates >= 2);
}

TEST_CASE("with warping, shared vertices of neighbouring memories coincide on screen") {
  Gallery g;
  const arp::ScreenProjection screen(90.0, 640, 480);
  const auto path = walk({{-7.0, 1.6, -7.0}, {7.0, 1.6, -6.0}, {6.0, 1.6, 7.0}});
  auto max_gap = [&](bool warping) {
    arp::RegionPriorityModel model(g.cut, g.grid, params(warping));
    const arp::SeamMeter meter(model, nullptr);
    double worst = 0.0;
    size_t measured = 0;
    std::vector<double> gaps;
    for (int64_t k = 0; k < 60 * 25; ++k) {
      const tracker::Pose pose = path.pose_at(tick_time(k));
      model.tick(tick_time(k), pose.position_m);
      gaps.clear();
      meter.tear_gaps_px(shown_now(model), pose.orientation, pose.position_m, screen, gaps);
      measured += gaps.size();
      for (double gap : gaps) worst = std::max(worst, gap);
    }
    REQUIRE(measured > 1000);
    return worst;
  };
  CHECK(max_gap(true) < 1e-3);
  CHECK(max_gap(false) > 1.0);
}

TEST_CASE("walking parallel to a boundary, within the margin of it, still swaps across the boundaries crossed") {
  Gallery g;
  arp::RegionPriorityModel model(g.cut, g.grid, params(false, 0.5));
  // z = -8.2 lies 0.2 m from the boundary z = -8, closer than the margin.
  const auto path = walk({{-8.5, 1.6, -8.2}, {9.5, 1.6, -8.2}});
  for (int64_t k = 0; k < 60 * 19; ++k) model.tick(tick_time(k), path.pose_at(tick_time(k)).position_m);
  CHECK(model.map().home().ix == 9);
  CHECK(model.map().home().iz == 0);
  CHECK(model.swaps() >= 8);
}
