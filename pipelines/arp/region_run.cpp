#include "arp/region_run.hpp"

#include <algorithm>

#include "latsim/results/figure_writer.hpp"

namespace latsim::pipelines {

RegionRun::RegionRun(des::Simulator& sim, des::KindId render_kind, const arp::SegmentedScene& scene,
                     const renderer::RegionGrid& grid, arp::RegionSystemParams params,
                     const renderer::RayCaster* occluder)
    : system_(sim, render_kind, scene, grid, std::move(params)),
      meter_(system_.model(), occluder),
      warped_points_(static_cast<size_t>(system_.model().memory_count())) {
  system_.on_present([this](const std::vector<const arp::MemoryImage*>& batch) {
    // Warped points depend only on the image: computed once when it is presented.
    for (const arp::MemoryImage* img : batch) {
      if (warping())
        warped_points_[static_cast<size_t>(img->memory)] = meter_.warped_points(img->memory, img->contents, *img->view);
    }
    if (present_fn_) present_fn_(batch);
  });
}

std::string RegionRun::label() const {
  return std::string(segmented() ? "segmented" : "whole objects") + (warping() ? ", warped" : ", not warped");
}

void RegionRun::measure(const glm::dquat& head, const glm::dvec3& eye_m, const arp::ScreenProjection& screen) {
  scratch_.clear();
  meter_.tear_gaps_px(system_.shown(), head, eye_m, screen, scratch_);
  for (double g : scratch_) tear_gap_px_.add(g);
  if (!warping()) return;
  scratch_.clear();
  for (int m = 0; m < system_.model().memory_count(); ++m) {
    const arp::MemoryImage* img = system_.memories().shown(m);
    if (img) meter_.stretch_px(warped_points_[static_cast<size_t>(m)], img->eye_m, head, eye_m, screen, scratch_);
  }
  for (double s : scratch_) stretch_px_.add(s);
}

void RegionRun::report(results::FigureWriter& r, const std::string& prefix, des::Time duration) const {
  const double duration_s = duration.to_seconds();
  const arp::DisplayMemories& memories = system_.memories();
  const arp::RegionPriorityModel& model = system_.model();
  const auto lists = model.segments_per_memory();
  int64_t segments = 0;
  int64_t skipped = 0;
  for (int m = 0; m < model.memory_count(); ++m) {
    const arp::MemoryRenderCounts& c = memories.counts(m);
    const std::string at = prefix + "memories." + std::to_string(m) + ".";
    const double renders = static_cast<double>(c.renders);
    r.set(at + "memory", int64_t{m});
    r.set(at + "update_rate_hz", renders / duration_s);
    r.set(at + "segments", c.renders > 0 ? static_cast<double>(c.object_segments) / renders : 0.0);
    r.set(at + "pixels", c.renders > 0 ? c.texels / renders : 0.0);
    r.set(at + "renders", c.renders);
    r.set(at + "renders_skipped", memories.queue().skipped(m));
    r.set(at + "segments_at_end", static_cast<int64_t>(lists[static_cast<size_t>(m)].size()));
    r.set(at + "regions_at_end", static_cast<int64_t>(model.map().regions_of_memory(m).size()));
    segments += c.object_segments;
    skipped += memories.queue().skipped(m);
  }
  const double utilisation = memories.queue().utilisation(duration);
  r.set(prefix + "render_load", static_cast<double>(segments) / duration_s);
  r.set(prefix + "renders_skipped", skipped);
  r.set(prefix + "renderer_utilisation", utilisation);
  r.publish(prefix + "render_queue_ms", memories.queue().queue_ms());
  r.publish(prefix + "tear_gap_px", tear_gap_px_);
  if (warping()) r.publish(prefix + "stretch_px", stretch_px_);
  if (skipped > 0 || utilisation > 0.95) {
    r.warn("region_priority (" + label() + "): the renderers cannot keep up: " + std::to_string(skipped) +
           " renders skipped, renderer utilisation " + std::to_string(utilisation) + ", render queue mean " +
           std::to_string(memories.queue().queue_ms().stats().mean()) + " ms");
  }
}

void RegionRun::mark_window() {
  std::vector<arp::MemoryRenderCounts> now;
  for (int m = 0; m < system_.model().memory_count(); ++m) now.push_back(system_.memories().counts(m));
  window_marks_.push_back(std::move(now));
}

RegionRun::WindowRow RegionRun::window_row(int memory, des::Time length) const {
  const arp::MemoryRenderCounts& a = window_marks_.at(0).at(static_cast<size_t>(memory));
  const arp::MemoryRenderCounts& b = window_marks_.at(1).at(static_cast<size_t>(memory));
  WindowRow row;
  row.renders = b.renders - a.renders;
  const double renders = static_cast<double>(row.renders);
  row.rate_hz = renders / length.to_seconds();
  if (row.renders == 0) return row;
  row.segments = static_cast<double>(b.object_segments - a.object_segments) / renders;
  row.drawn = static_cast<double>(b.drawn - a.drawn) / renders;
  row.pixels = (b.texels - a.texels) / renders;
  return row;
}

void RegionRun::report_window(results::FigureWriter& r, const std::string& prefix, des::Time length) const {
  if (!has_window()) return;
  double segments = 0.0;
  for (int m = 0; m < system_.model().memory_count(); ++m) {
    const WindowRow row = window_row(m, length);
    const std::string at = prefix + "window.memories." + std::to_string(m) + ".";
    r.set(at + "memory", int64_t{m});
    r.set(at + "update_rate_hz", row.rate_hz);
    r.set(at + "segments", row.segments);
    r.set(at + "drawn", row.drawn);
    r.set(at + "pixels", row.pixels);
    r.set(at + "renders", row.renders);
    segments += row.segments * static_cast<double>(row.renders);
  }
  r.set(prefix + "window.render_load", segments / length.to_seconds());
}

}  // namespace latsim::pipelines
