// A see-through (passthrough) headset: a camera films the world, an image
// signal processor develops each frame, the compositor re-projects it to the
// eye's viewpoint with the newest head pose and composes rendered content
// over it, and the display shows it (docs/passthrough.md).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "latsim/measurement/camera_rig.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "passthrough/camera_timing.hpp"
#include "passthrough/passthrough_spec.hpp"

namespace latsim::pipelines::passthrough {

/// Runs the camera's frames, the image signal processor and the compositor
/// as events, and reports photon-to-photon latency at one point of the
/// display with each stage's share; with a rig, what a camera filming a
/// moving real object and its image through the headset measures.
class PassthroughPipeline final : public Pipeline {
 public:
  struct Params {
    PassthroughSpec spec;
  };

  explicit PassthroughPipeline(const Params& params);
  ~PassthroughPipeline() override;

  void start(RunContext& ctx) override;
  void finish(RunContext& ctx) override;
  std::vector<EventRate> event_rates(const sections::SharedParams& shared) const override;

  /// The image signal processor's time for one frame's pixels (its fixed time excluded).
  static des::Time isp_pixel_time(const PassthroughSpec& spec);

 private:
  /// One camera frame from its exposure to its first showing.
  struct Frame {
    des::Time readout_end, isp_end;
    bool picked = false;  ///< a composition has taken it
    bool shown = false;
  };
  /// One composition: the camera frame it re-projected and when it ran.
  struct Composition {
    int64_t frame = 0;
    des::Time start, end;
  };

  void read_out(int64_t k);
  void processed(int64_t k);
  void compose_for(int64_t field);
  void compose_now(int64_t field);
  void composed(int64_t field, int64_t k, const tracker::PosePrediction& pose, des::Time start);
  void retraced(int64_t field);
  void first_shown(Frame& f, const Composition& c, int64_t field, des::Time photon);
  void light_point(int64_t field, const Composition& c, des::Time photon);
  des::Time composition_time() const { return spec_.compositor.reprojection + spec_.compositor.composition; }
  void film_object(RunContext& ctx);

  PassthroughSpec spec_;
  RunContext* ctx_ = nullptr;
  std::unique_ptr<CameraTiming> camera_;
  int64_t point_row_ = 0;     ///< the camera row imaged at the point
  int point_line_ = 0, point_x_ = 0;
  des::Time isp_free_, gpu_free_;
  std::map<int64_t, Frame> frames_;
  std::optional<int64_t> newest_processed_;
  std::map<int64_t, Composition> compositions_;  ///< by image id of eye 0
  std::optional<int64_t> last_shown_frame_;
  // The real object the rig films and what the point shows of it.
  std::unique_ptr<tracker::MotionSource> object_;
  std::unique_ptr<measurement::ObjectSignal> object_signal_;
  std::vector<measurement::LitAngle> lit_;
  std::optional<des::PeriodicSchedule> rig_camera_;
  des::KindId kind_readout_ = 0, kind_isp_ = 0, kind_compose_ = 0, kind_composed_ = 0;
  int64_t frames_read_ = 0, frames_shown_ = 0, frames_dropped_ = 0, frames_repeated_ = 0,
          refreshes_without_image_ = 0, warps_late_ = 0;
};

/// Reads /pipeline of a passthrough scenario (passthrough/bind.cpp).
void bind(scenario::Section& s, PassthroughPipeline::Params& p, const sections::SharedParams& shared);

}  // namespace latsim::pipelines::passthrough
