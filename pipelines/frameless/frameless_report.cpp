// What the frameless pipeline reports: figures, pixel ages and registration at scanout, poses for a frame capture.
#include "frameless/frameless_pipeline.hpp"

#include <algorithm>
#include <string>

#include "latsim/results/figure_writer.hpp"

namespace latsim::pipelines::frameless {

void FramelessPipeline::finish(RunContext& ctx) {
  if (ctx.frames) ctx.frames->set_pixel_source(nullptr);
  const double cycle_ms = static_cast<double>(pixels_) / static_cast<double>(budget_px_s_) * 1e3;
  results::FigureWriter& r = ctx.figures;
  // No whole images: each pixel's own latency and age.
  r.use_headline("frameless");
  r.set("frameless.strategy", std::string(double_buffer_ ? "double_buffer" : "frameless"));
  r.set("frameless.pixels_per_s", budget_px_s_);
  r.set("frameless.pixels_per_cycle", int64_t{pixels_});
  r.set("frameless.cycle_ms", cycle_ms);
  r.set("frameless.pixels_computed", computed_units_);
  r.set("frameless.images_rendered", images_);
  r.set("frameless.fallbacks", fallbacks_);
  r.set("frameless.sampled_pixels", int64_t{sampled_count_});
  r.set("frameless.chunk_pixels", chunk_px_);
  // Frameless shows no whole images (no frame_rate_hz): it completes update cycles.
  r.set("frameless.cycle_rate_hz", 1e3 / cycle_ms);
}

void FramelessPipeline::on_scanout(const display::ScanoutSpan& span) {
  const results::ImageRecord* image = double_buffer_ ? ctx_->images.find(span.image_id) : nullptr;
  if (double_buffer_ && image == nullptr) return;
  for (int line = span.line; line < span.line_end; ++line) sample_line(span, line, image);
}

void FramelessPipeline::sample_line(const display::ScanoutSpan& span, int line, const results::ImageRecord* image) {
  const int row = ctx_->display.timing().row_of(span.field, line);
  const auto& xs = sampled_[static_cast<size_t>(span.eye) * static_cast<size_t>(height_) + static_cast<size_t>(row)];
  for (auto it = std::lower_bound(xs.begin(), xs.end(), span.x_begin); it != xs.end() && *it < span.x_end; ++it) {
    // Lit as the display lights the pixel (the middle of its lit interval).
    const des::Time photon = ctx_->photon_time(span.field, line, *it);
    if (image != nullptr) {
      ctx_->signals.pixel_shown(image->sample, photon);
      continue;
    }
    const PixelState& st = visible_[pixel_id(span.eye, *it, row)];
    if (st.slot < 0) continue;
    const auto [first_field, pose] = pixel_pose(st, *it, row);
    ctx_->signals.pixel_lit(pose.sample, photon);
    registration(span.eye, *it, row, st, pose.pose, photon);
    // Each pixel's own prediction, judged once: where it was first shown.
    if (ctx_->host.predicts() && span.eye == 0 && span.field == first_field)
      ctx_->signals.pose_predicted(pose, true, true);
  }
}

void FramelessPipeline::shown_pixels(int eye, int row, int x_begin, std::span<results::ShownPixel> out) const {
  for (size_t i = 0; i < out.size(); ++i) {
    const int x = x_begin + static_cast<int>(i);
    const PixelState& st = visible_[pixel_id(eye, x, row)];
    results::ShownPixel& p = out[i];
    p.lit = st.slot >= 0;
    if (!p.lit) continue;
    const tracker::PosePrediction pose = pixel_pose(st, x, row).second;
    p.eye_pose = ctx_->eye_pose(pose.pose, eye);
    p.measured_at = pose.sample.measured_at;
    p.source_x = st.source % width_;
    p.source_y = st.source / width_;
  }
}

std::pair<int64_t, tracker::PosePrediction> FramelessPipeline::pixel_pose(const PixelState& st, int x, int row) const {
  const display::RasterTiming& t = ctx_->display.timing();
  int64_t field = st.field;
  int line = t.line_of_row(field, row);
  if (line < 0) line = t.line_of_row(++field, row);
  return {field, basis_of(st.slot).for_photon_time(ctx_->photon_time(field, line, x))};
}

void FramelessPipeline::registration(int eye, int x, int row, const PixelState& st, const tracker::Pose& head,
                                     des::Time photon) {
  const tracker::Pose drawn = ctx_->eye_pose(head, eye);
  // The pixel shows the surface point its source ray met, taken at a fixed
  // depth, drawn along the pixel's own direction.
  const int sx = st.source % width_, sy = st.source / width_;
  const glm::dvec3 point = drawn.position_m + depth_m_ * (drawn.orientation * camera_->head_direction(sx + 0.5, sy + 0.5));
  ctx_->signals.point_drawn(eye, point, camera_->head_direction(x + 0.5, row + 0.5), photon);
}

}  // namespace latsim::pipelines::frameless
