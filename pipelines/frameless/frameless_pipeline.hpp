// The frameless pipeline's class and the pixel state it keeps, shared by the .cpp files of this folder.
//
// Frameless rendering and double buffering on one pixel budget (SPEC section 6).
// Both strategies spend the same number of pixel computations per second;
// pixel k of the run's computation stream occupies [at(k), at(k+1)) on an
// exact periodic schedule. Frameless writes each pixel at once, from the
// newest pose when its computation starts, and the display latches what has
// been written at every retrace. Double buffering spends width x height x eyes
// consecutive pixels on one image from one pose and swaps it in at the next
// retrace. Pixels are simulated exactly but handled in chunks, one event per
// chunk, so the event count stays far below one per pixel.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "frameless/frameless_order.hpp"
#include "latsim/des/periodic.hpp"
#include "latsim/des/process.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "latsim/renderer/camera.hpp"
#include "latsim/results/frame_capture.hpp"

namespace latsim::pipelines::frameless {

/// What one buffer pixel holds: the sample its colour was computed from (a
/// slot in the pipeline's sample list; -1 = never computed), the pixel,
/// within its eye, whose ray gave the colour (itself, or its block's sample
/// pixel at reduced resolution), and the field it was expected to be shown
/// in first when it was computed (its pose is predicted to its photon time
/// there).
struct PixelState {
  int64_t slot = -1;
  int32_t source = 0;
  int64_t field = 0;
};

/// What the pipeline does with its next unit of pixel budget.
enum class Mode { Normal, LowResolution, DoubleBufferFallback };

/// Both strategies of SPEC section 6 on one pixel budget; frameless also
/// supplies its per-pixel poses to a frame capture.
class FramelessPipeline final : public Pipeline, public display::ScanoutListener, public results::PixelSource {
 public:
  /// The /pipeline keys, and what they fix before the run.
  struct Params {
    bool double_buffer = false;
    std::optional<double> pixels_per_s;
    double full_images_per_s = 5.0;
    int64_t chunk_pixels = 2048;
    int64_t sample_pixels = 1024;
    double registration_depth_m = 2.0;
    /// What happens when the head moves fast (nothing when absent).
    struct Fallback {
      Mode kind = Mode::LowResolution;
      double trigger_deg = 20.0;
      double trigger_m = 0.5;
      int block_px = 4;
    };
    std::optional<Fallback> fallback;
    int64_t budget_px_s = 1;  ///< whole pixels per second (an exact rational period)
    des::ClockSettings loop;  ///< the computation's own clock (phase over one full image)
  };

  explicit FramelessPipeline(const Params& p);

  void start(RunContext& ctx) override;
  void finish(RunContext& ctx) override;
  /// Chunks (or whole images) per second, pixels computed and, with a fallback, deliveries.
  std::vector<EventRate> event_rates(const sections::SharedParams& shared) const override;
  void on_scanout(const display::ScanoutSpan& span) override;
  // Ages (and registration) of the sampled pixels of one line of a span.
  void sample_line(const display::ScanoutSpan& span, int line, const results::ImageRecord* image);
  void shown_pixels(int eye, int row, int x_begin, std::span<results::ShownPixel> out) const override;

 private:
  void size_to_display(RunContext& ctx);

  size_t pixel_id(int eye, int x, int row) const {
    return (static_cast<size_t>(eye) * static_cast<size_t>(height_) + static_cast<size_t>(row)) *
               static_cast<size_t>(width_) + static_cast<size_t>(x);
  }

  // A fixed random subset of pixels, the same for both strategies, where
  // ages and registration are sampled at every refresh.
  void pick_sampled_pixels(des::RandomStream stream);
  void make_blocks(des::RandomStream stream);

  const tracker::PredictionBasis& basis_of(int64_t slot) const {
    return samples_[static_cast<size_t>(slot - slot_base_)];
  }

  int64_t slot_for(const tracker::TrackerSample& s);

  /// The field in which a pixel is first shown and the pose it was computed
  /// from, predicted to its own photon time there (frameless computes pixel
  /// by pixel, so each has its own horizon). Interlaced, a row missing from
  /// the field it was latched for is first lit in the next one.
  std::pair<int64_t, tracker::PosePrediction> pixel_pose(const PixelState& st, int x, int row) const;

  /// The field whose retrace first latches a pixel computed in unit k: the
  /// first retrace at or after the unit ends (a double-buffering fallback:
  /// after its whole image).
  int64_t latch_field(int64_t k) const;

  // ---- frameless: the pixel stream -------------------------------------

  /// Computes the pixel stream a chunk at a time (retraces also catch it up).
  des::Process pixel_stream();
  /// Computes every pixel whose computation ends at or before t.
  void advance_to(des::Time t);
  /// The newest sample when unit k starts; a cache holds it for the units
  /// after k that still see it (found by bisection: newest_at only moves on).
  std::optional<tracker::TrackerSample> newest_for(int64_t k, int64_t end);
  void compute(int64_t k, int64_t end);
  void write(int32_t p, int64_t slot, int32_t source, int64_t field);
  void write_block(int32_t b, int64_t slot, int64_t field);
  void delivered(const tracker::TrackerSample& s, des::Time t);
  void begin_fallback(int64_t k);
  // Drops samples no pixel refers to any more (checked once per cycle).
  void prune_samples();

  // ---- both strategies at each refresh ---------------------------------

  void retrace(int64_t, des::Time now);

  // ---- double buffering at the same budget -----------------------------

  /// Image after image, each from the newest pose when it starts (none yet:
  /// it renders nothing), presented when its pixels are spent.
  des::Process images();
  void registration(int eye, int x, int row, const PixelState& st, const tracker::Pose& head, des::Time photon);

  RunContext* ctx_ = nullptr;
  bool double_buffer_ = false;
  int64_t budget_px_s_ = 1;
  std::string budget_pointer_;  ///< the key that gave the budget
  int64_t chunk_px_ = 2048;
  double depth_m_ = 2.0;
  Mode fallback_ = Mode::Normal;
  double trigger_deg_ = 20.0, trigger_m_ = 0.5;
  int block_px_ = 4;
  int64_t sample_pixels_ = 1024;
  des::ClockSettings loop_;
  int width_ = 0, height_ = 0, eyes_ = 1;
  int32_t pixels_ = 0;
  int32_t sampled_count_ = 0;
  std::optional<renderer::Camera> camera_;
  des::PeriodicSchedule schedule_;
  std::vector<std::vector<int>> sampled_;  ///< per (eye, row): sampled columns, sorted

  // Frameless state.
  std::optional<FramelessOrder> order_;
  std::optional<FramelessOrder> block_order_;
  int blocks_x_ = 0, blocks_y_ = 0;
  std::vector<PixelState> computed_;  ///< what has been written
  std::vector<PixelState> visible_;   ///< what the display shows (latched at retrace)
  std::vector<int64_t> stamp_;        ///< refresh generation a pixel was last written in
  std::vector<int32_t> dirty_;        ///< pixels written since the last latch
  int64_t generation_ = 0;
  std::deque<tracker::PredictionBasis> samples_;
  int64_t slot_base_ = 0;
  int64_t next_unit_ = 0;   ///< next unit of pixel budget to compute
  int64_t cursor_ = 0;      ///< updates taken from the permutation table
  int32_t block_cursor_ = 0;
  Mode mode_ = Mode::Normal;
  int64_t fallback_slot_ = -1;
  int32_t fallback_left_ = 0;
  int64_t fallback_end_unit_ = 0;  ///< the unit after the fallback image's last pixel
  std::deque<int64_t> triggers_;
  std::optional<tracker::Pose> last_delivered_;
  std::optional<tracker::TrackerSample> cached_;
  int64_t cached_until_ = -1;

  // Double-buffering state.
  int64_t last_front_ = -1;

  int64_t computed_units_ = 0;
  int64_t images_ = 0;
  int64_t fallbacks_ = 0;
};

}  // namespace latsim::pipelines::frameless
