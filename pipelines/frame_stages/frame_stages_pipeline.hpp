// The staged frame pipeline: application frames as timed stages on CPU
// threads and GPUs, shown through a swap chain or an optional time-warp
// compositor (SPEC section 10; docs/modern.md).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "frame_stages/compositor.hpp"
#include "frame_stages/pacing_compositor.hpp"
#include "frame_stages/pacing_driver.hpp"
#include "frame_stages/pose_sampler.hpp"
#include "frame_stages/progress.hpp"
#include "frame_stages/residual_errors.hpp"
#include "frame_stages/spec.hpp"
#include "frame_stages/stage_flow.hpp"
#include "frame_stages/swap_chain.hpp"
#include "latsim/des/random.hpp"
#include "latsim/des/resource.hpp"
#include "latsim/pipelines/pipeline.hpp"

namespace latsim::pipelines::frame_stages {

/// Builds the processors, the application's flow of frames and, with a warp,
/// the compositor's flow of warps, and reports their figures.
class FrameStagesPipeline final : public Pipeline {
 public:
  /// /pipeline as read (frame_stages/bind.cpp): processors and stages resolved by name.
  struct Params {
    FrameStagesSpec spec;
  };

  explicit FrameStagesPipeline(const Params& params);
  ~FrameStagesPipeline() override;

  void start(RunContext& ctx) override;
  /// Reports frames, misses, warps and residual errors to the recorder.
  void finish(RunContext& ctx) override;
  /// Frames per second through the stages and warps per refresh (event_rates.cpp).
  std::vector<EventRate> event_rates(const sections::SharedParams& shared) const override;
  /// The application's pacing (none with the fixed policy).
  const AppPacing* app_pacing() const { return app_pacing_.get(); }

 private:
  FlowEnv env(des::RandomStream& stream);
  FlowHooks app_hooks();
  FlowHooks warp_hooks();
  des::Time app_photon_target(des::Time completion) const;
  /// Warns when the application falls behind a compositor, or warps end late.
  void warn_about_overload(RunContext& ctx) const;
  void start_pacing(RunContext& ctx);

  FrameStagesSpec spec_;
  RunContext* ctx_ = nullptr;
  std::vector<std::unique_ptr<des::Resource>> processors_;
  std::unique_ptr<des::Resource> image_buffers_;
  std::unique_ptr<Progress> retraces_;
  std::unique_ptr<PoseSampler> poses_;
  std::unique_ptr<des::RandomStream> app_stream_, warp_stream_;
  std::unique_ptr<SwapChain> swap_chain_;
  std::unique_ptr<Compositor> compositor_;
  std::unique_ptr<ResidualErrors> residuals_;
  std::unique_ptr<StageFlow> app_, warp_;
  std::unique_ptr<AppPacing> app_pacing_;
  std::unique_ptr<CompositorPacer> compositor_pacer_;
};

}  // namespace latsim::pipelines::frame_stages
