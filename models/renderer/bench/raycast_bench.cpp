// Measures ray-casting throughput for one 640 x 480 frame of the room scene: the naive
// one-query-per-pixel loop against the row-stream frame path on one and two threads.
#include "latsim/renderer/image_ops.hpp"
#include "latsim/renderer/png_writer.hpp"
#include "latsim/renderer/ray_caster.hpp"
#include "latsim/renderer/scene_generators.hpp"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

namespace {

using latsim::renderer::Camera;
using latsim::tracker::Pose;
using latsim::renderer::Frame;
using latsim::renderer::RayCaster;
using latsim::renderer::RenderOptions;

// Wall time in seconds of `repeats` runs after one untimed warm-up run: median and best.
// The best run is the least disturbed by other load on a shared machine.
struct Timing {
  double median_s;
  double best_s;
};

Timing time_runs(int repeats, const std::function<void()>& run) {
  run();
  std::vector<double> times;
  for (int k = 0; k < repeats; ++k) {
    const auto start = std::chrono::steady_clock::now();
    run();
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(times.begin(), times.end());
  return {times[times.size() / 2], times.front()};
}

// The naive baseline: one rtcIntersect1 query per pixel, on the calling thread.
Frame naive_frame(const RayCaster& caster, const Camera& camera, const latsim::tracker::Pose& pose) {
  Frame frame = Frame::cleared(camera.width_px(), camera.height_px(), glm::vec3(0.0f));
  for (int y = 0; y < camera.height_px(); ++y) {
    for (int x = 0; x < camera.width_px(); ++x) {
      const auto hit = caster.cast(pose.position_m, camera.pixel_ray(x, y, pose.orientation));
      frame.colour.at(x, y) = hit.colour;
      frame.depth.at(x, y) = hit.distance_m;
    }
  }
  return frame;
}

uint64_t frame_hash(const Frame& frame) {
  return latsim::renderer::fnv1a_64(latsim::renderer::to_srgb8(frame.colour));
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 9;
  const Camera camera(60.0, 640, 480);
  // Standing by the south wall, turned slightly left: furniture, walls, floor, ceiling.
  const latsim::tracker::Pose pose{{0.0, 1.6, 3.5}, glm::angleAxis(0.2, glm::dvec3(0.0, 1.0, 0.0))};
  const RayCaster caster(latsim::renderer::make_room());
  const double rays = static_cast<double>(camera.width_px()) * camera.height_px();

  Frame naive;
  Frame one;
  Frame two;
  RenderOptions single;
  single.thread_count = 1;
  RenderOptions dual;
  dual.thread_count = 2;
  const Timing t_naive = time_runs(repeats, [&] { naive = naive_frame(caster, camera, pose); });
  const Timing t_one = time_runs(repeats, [&] { one = caster.render_frame(camera, pose, single); });
  const Timing t_two = time_runs(repeats, [&] { two = caster.render_frame(camera, pose, dual); });

  std::printf("room scene: %u triangles, %u objects; 640 x 480 frame, median of %d runs\n\n",
              caster.scene().triangle_count(), caster.scene().object_count(), repeats);
  std::printf("| path | threads | median ms / frame | median Mrays/s | best ms | best Mrays/s | speed-up (median) |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|\n");
  const auto row = [&](const char* name, int threads, const Timing& t) {
    std::printf("| %s | %d | %.2f | %.2f | %.2f | %.2f | %.2f |\n", name, threads, t.median_s * 1e3,
                rays / t.median_s * 1e-6, t.best_s * 1e3, rays / t.best_s * 1e-6, t_naive.median_s / t.median_s);
  };
  row("naive rtcIntersect1 per pixel", 1, t_naive);
  row("frame path (row streams)", 1, t_one);
  row("frame path (row streams)", 2, t_two);
  std::printf("\nframe hashes: naive %016llx, 1 thread %016llx, 2 threads %016llx\n",
              static_cast<unsigned long long>(frame_hash(naive)), static_cast<unsigned long long>(frame_hash(one)),
              static_cast<unsigned long long>(frame_hash(two)));
  const bool threads_identical = one.colour.pixels == two.colour.pixels && one.depth.depth_m == two.depth.depth_m;
  std::printf("1 and 2 threads bit-identical: %s\n", threads_identical ? "yes" : "NO");
  return threads_identical ? 0 : 1;
}
