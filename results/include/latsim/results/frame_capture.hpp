// Actual images next to the numbers: ray-casts what the display shows in
// chosen fields, the ground truth at each row's photon time, their difference
// and the age of every pixel, and writes them as PNG files.
//
// Only built when a scenario has a /frames section: without one no scene is
// loaded and nothing is ray-cast. Renderer types stay in the .cpp file, so
// this header costs its users nothing of the renderer.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "latsim/des/time.hpp"
#include "latsim/display/display.hpp"
#include "latsim/display/raster_timing.hpp"
#include "latsim/sections/shared.hpp"
#include "latsim/renderer/scene_spec.hpp"
#include "latsim/results/image_record.hpp"
#include "latsim/tracker/host_feed.hpp"
#include "latsim/tracker/motion_source.hpp"

namespace latsim::results {

class LatencyRecorder;
class RunFiles;

/// What one displayed pixel shows when a pipeline computes pixels itself.
struct ShownPixel {
  bool lit = false;           ///< false: nothing computed there yet (background)
  tracker::Pose eye_pose;     ///< the eye pose its colour was computed from
  des::Time measured_at;      ///< when that pose was measured (origin of the pixel's age)
  int source_x = 0;           ///< the pixel whose ray gave the colour: the pixel itself,
  int source_y = 0;           ///< or its block's sample pixel at reduced resolution
};

/// A pipeline that writes pixels into the displayed buffer one by one (frameless
/// rendering) and can say, at any instant, what each displayed pixel shows.
class PixelSource {
 public:
  virtual ~PixelSource() = default;
  /// Fills out[i] for pixel (x_begin + i, row) of `eye` as it is shown now;
  /// out.size() == x_end - x_begin.
  virtual void shown_pixels(int eye, int row, int x_begin, std::span<ShownPixel> out) const = 0;
};

/// Everything a capture needs from the run besides its configuration.
struct FrameCaptureInputs {
  LatencyRecorder& recorder;              ///< image ids -> the pose each image was rendered from; figures
  const tracker::HostFeed& host;                   ///< newest orientation for address-recalculation images
  const tracker::MotionSource& motion;    ///< the true head pose (ground truth)
  const display::RasterTiming& timing;    ///< rows and photon times
  double hfov_deg = 90.0;
  double ipd_m = 0.064;
  bool stereo = false;
  RunFiles& files;                        ///< where the images go (or nowhere: cast and measure only)
  /// The display's persistence: the truth is taken at the middle of each
  /// pixel's lit interval (nullptr: at its scanout instant).
  const display::Persistence* persistence = nullptr;
};

/// Listens to scanout and, for each captured field of one eye, collects per
/// row (or pixel span) the image shown and its photon time; when the field is
/// complete it ray-casts the displayed image (persistent across fields, so an
/// interlaced field shows only its rows and tears show), the truth, the
/// enhanced difference and the pixel-age heat map into frames/ of the run.
/// Time-warped images are drawn as the compositor made them, with the
/// application's image before the warp beside them.
class FrameCapture final : public display::ScanoutListener {
 public:
  /// Captures as `frames` says, of `scene`; loads nothing yet.
  FrameCapture(const sections::FramesParams& frames, renderer::SceneSpec scene, FrameCaptureInputs inputs);
  ~FrameCapture() override;
  FrameCapture(const FrameCapture&) = delete;
  FrameCapture& operator=(const FrameCapture&) = delete;

  /// Pixels come from `source` instead of whole images (nullptr: back to images).
  void set_pixel_source(const PixelSource* source);

  void on_field_start(int eye, int64_t field, des::Time retrace) override;
  void on_scanout(const display::ScanoutSpan& span) override;

  /// Casts a field still being collected, then reports the figures "frames"
  /// (one entry per capture) and "frames_mean_image_error".
  void finish();


 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace latsim::results
