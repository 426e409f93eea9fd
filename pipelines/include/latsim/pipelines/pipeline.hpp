// The pipeline interface: how a display strategy plugs into a latsim run.
//
// A run reads the scenario's shared sections into typed parameters, builds
// the shared models (head motion, tracker, transport, host mailbox, display,
// recorder) into a RunContext, reads /pipeline through the registered
// pipeline's own parameter declaration, calls start() to let it schedule its
// events, runs the simulator, then calls finish() to let it report figures.
// Pipelines present images to the display; the display and the recorder turn
// what is lit into latency and registration figures.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "latsim/des/clock.hpp"
#include "latsim/des/random.hpp"
#include "latsim/des/simulator.hpp"
#include "latsim/display/display.hpp"
#include "latsim/params/shared.hpp"
#include "latsim/scenario/params.hpp"
#include "latsim/tracker/host.hpp"
#include "latsim/tracker/host_prediction.hpp"
#include "latsim/tracker/motion_source.hpp"
#include "latsim/tracker/transport.hpp"

namespace latsim::pipelines {

class LatencyRecorder;
class Timeline;
class FrameCapture;
class RunFiles;
class RunClocks;

/// One image a pipeline puts in a front buffer: the pose it was computed from
/// and when each stage ran. Registered with the recorder before presenting.
struct ImageRecord {
  int64_t frame = -1;                 ///< pipeline's frame (or field) number
  int eye = 0;
  tracker::TrackerSample sample;      ///< the newest sample the pose came from (latency origin)
  des::Time host_received;            ///< when the host could first see that sample
  des::Time render_start;             ///< rendering latency starts here
  des::Time render_end;
  /// The instant the head pose was predicted for (the pipeline's expected
  /// photon time, or the sample's time plus a fixed horizon) and that pose;
  /// without prediction it is the sample's own pose.
  des::Time predicted_for;
  tracker::Pose head_pose;
  tracker::Pose eye_pose;             ///< the eye pose the image was rendered from
  /// Address recalculation: orientation is taken from the newest sample at
  /// scanout, so rotation and translation latency differ.
  bool orientation_at_scanout = false;
  /// Time warp: the image is an image rendered from `source_pose` re-projected
  /// to `eye_pose`. A rotation-only warp keeps the source's position: its
  /// orientation was measured at `orientation_measured_at`, later than `sample`.
  enum class Warp : uint8_t { none, rotation, positional };
  Warp warp = Warp::none;
  tracker::Pose source_pose;
  des::Time orientation_measured_at;
  /// A later strip of a refresh's image (continuous time warp): its latency
  /// is its own, but it is not another image in the frame rate.
  bool continues_image = false;
};

/// The pose of one eye of a head: stereo eyes sit ipd/2 either side along the
/// head's x axis (eye 0 = left); mono returns the head pose.
tracker::Pose eye_pose_of(const tracker::Pose& head, int eye, double ipd_m, bool stereo);

/// Newest tracker data available to the host at any instant.
class HostFeed {
 public:
  virtual ~HostFeed() = default;
  /// Newest sample the host application can see at time t (nullopt before the first).
  virtual std::optional<tracker::TrackerSample> newest_at(des::Time t) const = 0;
  /// When that sample became visible to the host.
  virtual des::Time received_at(const tracker::TrackerSample& s) const = 0;
  /// Called whenever a new sample becomes visible to the host (async senders).
  virtual void on_delivery(std::function<void(const tracker::TrackerSample&, des::Time)> fn) = 0;
  /// What the host knew when `s` was its newest sample: enough to predict
  /// the pose for any photon time. `s` must be recent (the host keeps about
  /// one second); pipelines that hold a sample longer keep its basis.
  virtual tracker::PredictionBasis basis_of(const tracker::TrackerSample& s) const = 0;
  /// Whether the scenario asks the host to predict (/host/prediction).
  virtual bool predicts() const = 0;

  /// The pose for an image computed at `now` that the pipeline expects to be
  /// lit at `photon_time`: the newest sample visible at `now`, predicted by
  /// the host's predictor to `photon_time` (or to its fixed horizon; the
  /// sample's pose when the host does not predict). nullopt before the first
  /// sample. Every pipeline takes the pose of an image (or line, or pixel)
  /// through this call.
  std::optional<tracker::PosePrediction> pose_for(des::Time now, des::Time photon_time) const {
    const std::optional<tracker::TrackerSample> s = newest_at(now);
    if (!s) return std::nullopt;
    return basis_of(*s).for_photon_time(photon_time);
  }
};

/// Everything a pipeline may use during a run: the shared models and the
/// parameters of the shared sections it may need, never the scenario itself.
struct RunContext {
  des::Simulator& sim;
  uint64_t seed = 1;
  uint64_t replication = 0;
  des::Time duration;                          ///< simulated time to run
  const tracker::MotionSource& motion;         ///< true head motion
  const tracker::TrackerParams& tracker;       ///< how the head is sampled
  const tracker::Transport& transport;         ///< the link from tracker to host
  HostFeed& host;
  display::Display& display;
  const display::DisplayParams& display_params;
  const params::SceneParams* scene;            ///< /scene, when the scenario has one
  LatencyRecorder& recorder;                   ///< every figure and warning goes here
  RunFiles& files;                             ///< every result file goes here
  RunClocks& clocks;                           ///< every clock of the run, with its phase
  double ipd_m = 0.064;
  bool stereo = false;
  Timeline* timeline = nullptr;                ///< stage timeline, when the pipeline keeps one
  FrameCapture* frames = nullptr;              ///< frame capture, only when the scenario asks for frames

  des::RandomStream stream(std::string_view name) const { return des::RandomStream(seed, name, replication); }
  /// A clock of the pipeline's own (its host application loop): phase fixed
  /// by the scenario or drawn from stream "clock.<name>", recorded at
  /// `phase_pointer` in the resolved scenario; rate error applied.
  const des::Clock& clock(const std::string& name, const std::string& phase_pointer, des::RationalSeconds nominal,
                          des::ClockSettings settings) const;
  /// The eye pose of a head pose (mono: the head pose).
  tracker::Pose eye_pose(const tracker::Pose& head, int eye) const;
  /// An image of `eye` rendered from the predicted pose `p` between `start`
  /// and `end`, with the host's receive time and the eye pose filled in.
  ImageRecord image_record(int64_t frame, int eye, const tracker::PosePrediction& p, des::Time start,
                           des::Time end) const;
  /// Display memories of the address recalculation pipelines: registers the
  /// cube rendered from `p` since `start` for every eye (orientation looked up
  /// at scanout), swaps it in at the next retrace, and logs a RENDER interval.
  void present_display_memory(int64_t frame, const tracker::PosePrediction& p, des::Time start,
                              const std::string& unit);
  /// The same for a render that ended at `end`, before it is presented now
  /// (it waited for the images it must be shown with).
  void present_display_memory(int64_t frame, const tracker::PosePrediction& p, des::Time start, des::Time end,
                              const std::string& unit);

  /// Expected photon times, the horizons of prediction. An image is
  /// represented by its middle active line: the lines above and below it are
  /// lit up to half a field earlier and later, a skew that prediction per
  /// image cannot remove (per-line and per-pixel pipelines predict per line
  /// or pixel instead).
  /// The photon time of the middle line of `field`.
  des::Time frame_photon_time(int64_t field) const;
  /// The photon time of the middle line of the first field whose retrace is
  /// at or after `ready`, plus `later_fields` (an image swapped in at the
  /// next retrace after it is ready, behind that many queued images).
  des::Time photon_time_after(des::Time ready, int64_t later_fields = 0) const;
  /// The first instant at or after `t` at which the middle line is lit (an
  /// image shown at once, without vsync).
  des::Time next_middle_line_time(des::Time t) const;
  /// Address recalculation reads the newest orientation as each pixel is
  /// fetched: at batched pixel fidelity every arrival splits the line being
  /// scanned (arrival events exist only then).
  void fetch_orientation_at_scanout();
};

/// A display strategy: schedules its events in start(), reports in finish().
class Pipeline {
 public:
  virtual ~Pipeline() = default;
  /// Schedules the pipeline's first events (its parameters came with its construction).
  virtual void start(RunContext& ctx) = 0;
  /// Reports pipeline-specific figures to ctx.recorder (e.g. missed fields).
  virtual void finish(RunContext& /*ctx*/) {}
};

/// Builds a pipeline from parameters already read.
using PipelineFactory = std::function<std::unique_ptr<Pipeline>()>;

/// One registered pipeline: its name, what it is, and the function that
/// declares (and reads) its /pipeline keys and returns its factory.
struct PipelineEntry {
  std::string name;
  std::string doc;
  std::function<PipelineFactory(scenario::Section&, const params::SharedParams&)> bind;
};

/// The entry of a pipeline class P with a nested `Params` struct, a function
/// `bind(scenario::Section&, P::Params&, const params::SharedParams&)` found by
/// argument-dependent lookup, and a constructor from its Params.
template <class P>
PipelineEntry pipeline_entry(std::string name, std::string doc) {
  return PipelineEntry{std::move(name), std::move(doc),
                       [](scenario::Section& s, const params::SharedParams& shared) -> PipelineFactory {
                         typename P::Params p{};
                         bind(s, p, shared);
                         return [p] { return std::make_unique<P>(p); };
                       }};
}

/// Pipelines by name, as the scenario's /pipeline/type selects them.
class PipelineRegistry {
 public:
  void add(PipelineEntry entry);
  const PipelineEntry* find(const std::string& name) const;
  std::vector<std::string> names() const;
  const std::map<std::string, PipelineEntry>& entries() const { return entries_; }

 private:
  std::map<std::string, PipelineEntry> entries_;
};

/// The registry with every pipeline latsim ships.
PipelineRegistry builtin_pipelines();

}  // namespace latsim::pipelines
