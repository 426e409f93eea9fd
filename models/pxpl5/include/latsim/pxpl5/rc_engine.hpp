// Rendering Control, the standard Pixel-Planes 5 pipeline (SPEC.md section 4).
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "latsim/des/process.hpp"
#include "latsim/des/resource.hpp"
#include "latsim/des/signal.hpp"
#include "latsim/des/simulator.hpp"
#include "latsim/pxpl5/engine_hooks.hpp"
#include "latsim/pxpl5/field_timing.hpp"
#include "latsim/pxpl5/hardware.hpp"
#include "latsim/pxpl5/workload.hpp"

namespace latsim::pxpl5 {

/// When the host reads the tracker for a frame's viewing transforms.
enum class HostRead {
  send_start,  ///< as SEND starts (the edits and the transforms go together)
  late,        ///< as EDIT starts, when the slaves first need the transforms
};

/// At which retraces the frame buffers may swap.
enum class SwapAt {
  any_field,    ///< the first retrace after the pair's last COPY (SPEC.md section 4)
  frame_start,  ///< interlaced: only a retrace that starts a frame (its first field), every second one
};

/// Which retrace swaps a stereo frame's two frame buffers.
enum class StereoSwap {
  together,  ///< both at the first allowed retrace after the pair's last COPY (SPEC.md section 4)
  per_eye,   ///< each at the first allowed retrace after its own eye's COPY
};

/// Costs of the RC stages on top of the shared hardware figures (derivation
/// of the defaults: docs/pxpl5.md, "Calibration of RC").
struct RcParams {
  HardwareParams hw;
  bool stereo = true;
  int graphics_processors = 13;                               ///< one master plus the slaves
  des::Time send_time = des::Time::us(500);                   ///< host: edits and viewing transforms
  int send_words = 256;                                       ///< edit commands on the ring per frame
  des::Time edit_time = des::Time::us(200);                   ///< SGPs apply edits to display lists
  des::Time transform_overhead = des::Time::us(100);          ///< per SGP and eye: matrices, bin reset
  des::Time transform_time_per_triangle = des::Time::from_us(37.5);  ///< one eye, on screen: i860 at 40 MHz
  des::Time reject_time_per_triangle = des::Time::from_us(3.75);     ///< one eye, outside the view: transform, clip test
  des::Time binitize_time_per_bin = des::Time::us(5);         ///< one command (either kind) into one region's bin
  // Spheres (docs/pxpl5.md, "Spheres"; assumptions with the ranges given there).
  des::Time sphere_transform_time = des::Time::us(15);        ///< one eye, on screen: centre, radius, quadratic set-up
  des::Time sphere_reject_time = des::Time::from_us(1.25);    ///< one eye, outside the view: centre and clip test
  int words_per_sphere_command = 30;                          ///< disk, z and normal quadratics, colour
  des::Time render_time_per_sphere_command = des::Time::from_us(3.8);  ///< one sphere command into one region
  des::Time token_hop_time = des::Time::us(5);                ///< a region token from one GP to the next
  des::Time region_shade_time = des::Time::us(300);           ///< end-of-frame (deferred shading) commands
  int end_of_frame_words = 32;
  HostRead host_read = HostRead::send_start;
  /// SEND first waits until the host sees a tracker sample newer than the
  /// previous frame's (an application that blocks on the tracker; examined,
  /// off by default). Needs the newest_index hook and sample_visible() calls.
  bool host_waits_for_new_sample = false;
  // Mechanisms examined against the published fly-through spreads
  // (docs/pxpl5.md, "What could spread a small model's latency"); both off
  // by default, as SPEC.md section 4 has them.
  /// A region's COPY holds the renderer that rendered it (as Slats' copies
  /// do), so copies and rendering take turns on a renderer.
  bool copy_holds_renderer = false;
  SwapAt swap_at = SwapAt::any_field;
  StereoSwap stereo_swap = StereoSwap::together;

  int slaves() const { return graphics_processors - 1; }
  int eyes() const { return stereo ? 2 : 1; }
};

/// Runs SEND, EDIT, TRANSFORM, RENDER and COPY as processes with exactly the
/// start conditions of SPEC.md section 4, counting eyes for RENDER and COPY
/// in stereo (eye sequence n = frame * eyes + eye).
class RcEngine {
 public:
  /// `workload` must outlive the engine.
  RcEngine(des::Simulator& sim, RcParams params, FieldTiming timing, RegionGrid grid, WorkloadSource& workload,
           EngineHooks hooks);
  RcEngine(const RcEngine&) = delete;
  RcEngine& operator=(const RcEngine&) = delete;

  /// Spawns the stage processes; no new frame is sent at or after `end`.
  void start(des::Time end);
  /// A new tracker sample has become visible to the host (called by the run
  /// when host_waits_for_new_sample is set).
  void sample_visible();
  Utilisation utilisation(des::Time elapsed) const;
  int64_t frames_completed() const { return frames_completed_; }
  const RcParams& params() const { return p_; }

 private:
  struct FrameState {
    explicit FrameState(des::Simulator& sim) : send_done(sim), edit_done(sim) {}
    des::Signal send_done, edit_done;
    int64_t sample_token = -1;
    int64_t measured_token = -1;  // the newest sample when EDIT starts (what a late read takes)
    des::Time sample_read_at;
    des::Time copy_start;
    int64_t swap_field = 0;
    des::Time swap_at;
  };
  struct EyeState {
    explicit EyeState(des::Simulator& sim) : transform_done(sim), render_done(sim), copy_done(sim), rendered(sim) {}
    des::Signal transform_done, render_done, copy_done;
    des::Signal rendered;  // pulsed whenever one more region is rendered
    std::vector<int> render_order;
    std::vector<int> renderer_of_region;  // which renderer holds each finished region's pixels
    BinCounts bins;  // binned at TRANSFORM start from the frame's sample
    bool render_started = false;
    des::Time transform_start, render_start, render_end, copy_start, copy_end;
    int64_t swap_field = 0;
    des::Time swap_at;  // when this eye's image is swapped in
  };
  struct RegionTask {
    int64_t eye_seq;
    int region;
  };

  FrameState& frame(int64_t i);
  EyeState& eye(int64_t n);
  // Done-signals of earlier eyes, skipping those before the first. Awaited
  // one by one: each is triggered once and never reset, so order is immaterial.
  std::vector<des::Signal*> eye_conditions(int64_t render_n, int64_t copy_n, int64_t transform_n);
  void stage(const char* name, int64_t frame, int eye, std::string unit, des::Time start, des::Time end);
  void sample(const std::string& name, double value);
  int64_t newest_sample(des::Time t) const;
  des::Time transform_time(const BinCounts& bins, int slave) const;
  /// Ring words and renderer time of one slave's bin for one region.
  int64_t bin_words(const BinCounts& bins, int slave, int region) const;
  des::Time bin_render_time(const BinCounts& bins, int slave, int region) const;
  /// The first retrace at which a swap requested now may happen.
  int64_t swap_field_after_now() const;
  /// Swaps eyes first..last of frame i in at the first allowed retrace and
  /// hands their images to the display in time for it.
  void swap_eyes(int64_t i, int first, int last);
  /// Hands `ready` to the display between the retrace before its swap and the swap.
  des::Process present_later(FrameReady ready);
  /// Figures of frame i, once both eyes are copied and their swaps known.
  void finish_frame(int64_t i);
  /// The eye's name in per-eye figures: left and right (the left eye is
  /// transformed first), or mono.
  const char* eye_label(int eye) const;

  des::Process send_process();
  des::Process edit_process();
  des::Process transform_process();
  des::Process renderer_process(int renderer);
  des::Process copy_process();

  des::Simulator& sim_;
  RcParams p_;
  FieldTiming timing_;
  RegionGrid grid_;
  WorkloadSource& workload_;
  EngineHooks hooks_;
  des::Time end_;

  std::deque<FrameState> frames_;
  std::deque<EyeState> eyes_;
  std::deque<RegionTask> unrendered_;  // the MGP's list, busiest region first per eye
  des::Signal work_available_;         // pulsed when regions join the list
  des::Signal sample_arrived_;         // pulsed by sample_visible()
  int64_t last_sent_index_ = -1;       // tracker index of the newest sample a SEND waited for

  des::Resource ring_;
  std::vector<std::unique_ptr<des::Resource>> renderers_;  // taken only with copy_holds_renderer
  std::vector<std::unique_ptr<des::Resource>> sgp_ports_;
  std::vector<std::unique_ptr<des::Resource>> fb_ports_;
  std::vector<des::Time> sgp_busy_;
  std::vector<des::Time> renderer_busy_;
  int64_t frames_completed_ = 0;
};

}  // namespace latsim::pxpl5
