// Replays one process of a PresentMon capture on a display: the application
// thread does what the capture says it did between presents and in them, its
// GPU work runs on one GPU in present order, and its frames reach the screen
// by the present path the capture ran on (docs/measured.md, "Replay").
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "latsim/capture/replay.hpp"
#include "latsim/des/handoff.hpp"
#include "latsim/des/process.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "present_replay/present_path.hpp"
#include "present_replay/replay_frames.hpp"

namespace latsim::pipelines::present_replay {

/// The replay itself: an application thread process, GPU completions as
/// events, the present path stepped at each retrace.
class PresentReplayPipeline final : public Pipeline {
 public:
  struct Params {
    std::string pointer;  ///< /pipeline/capture, for the summary's entries
    std::shared_ptr<const ReplaySource> source;
    PresentPathSpec path;
    std::string mode_text;  ///< PresentMon's text for the mode replayed
    bool allows_tearing = false;
    capture::ReplayParams::AtEnd at_end = capture::ReplayParams::AtEnd::wrap;
  };

  explicit PresentReplayPipeline(const Params& p) : p_(p), path_(p.path) {}

  void start(RunContext& ctx) override;
  void finish(RunContext& ctx) override;
  std::vector<EventRate> event_rates(const sections::SharedParams& shared) const override;

 private:
  struct Frame {
    des::Time cpu_start, present, gpu_start, gpu_end;
    const ReplayFrame* values = nullptr;
    tracker::PosePrediction pose;
    std::vector<int64_t> image_ids;  ///< per eye, once its GPU work is done
    std::optional<des::Time> in_present;
    bool gpu_done = false;
  };

  des::Process application();
  des::Time start_time() const;
  des::Time expected_photon_time() const;
  void gpu_done(int64_t frame);
  void on_retrace(des::Time now);
  void show(int64_t frame);
  void maybe_complete(int64_t frame);
  void forget(int64_t frame);
  /// at_end stop: ends the run once the last frame is shown or passed over.
  void end_if_done();

  Params p_;
  PresentPath path_;
  RunContext* ctx_ = nullptr;
  des::KindId kind_gpu_ = 0;
  des::Handoff room_;
  std::map<int64_t, Frame> frames_;  ///< presented, not yet both complete and shown or passed over
  std::map<int64_t, bool> settled_;  ///< frames shown or passed over, before they complete
  des::Time gpu_free_;
  int64_t played_ = 0, wraps_ = 0, dropped_ = 0;
  bool stopped_ = false, ending_ = false;
};

/// Reads /pipeline of present_replay (bind.cpp).
void bind(scenario::Section& s, PresentReplayPipeline::Params& p, const sections::SharedParams& shared);

}  // namespace latsim::pipelines::present_replay
