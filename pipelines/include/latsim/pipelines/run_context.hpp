// The run context: everything a pipeline may use during a run, the shared
// models and the parameters of the shared sections, never the scenario
// itself. The run builder (run/) makes one per run; results/ holds what it
// records into.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "latsim/des/clock.hpp"
#include "latsim/des/random.hpp"
#include "latsim/des/simulator.hpp"
#include "latsim/display/display.hpp"
#include "latsim/sections/shared.hpp"
#include "latsim/results/figure_writer.hpp"
#include "latsim/results/image_book.hpp"
#include "latsim/results/image_record.hpp"
#include "latsim/results/run_signals.hpp"
#include "latsim/tracker/host_feed.hpp"
#include "latsim/tracker/host_prediction.hpp"
#include "latsim/tracker/motion_source.hpp"
#include "latsim/tracker/transport.hpp"

namespace latsim::des {
class RunClocks;
}

namespace latsim::results {
class ImageBook;
class Timeline;
class FrameCapture;
class FrameRecorder;
class RunFiles;
}  // namespace latsim::results

namespace latsim::pipelines {

/// Everything a pipeline may use during a run: the shared models and the
/// parameters of the shared sections it may need, never the scenario itself.
struct RunContext {
  des::Simulator& sim;
  uint64_t seed = 1;
  uint64_t replication = 0;
  /// The span simulated: the scenario's duration, or where the run ended
  /// early (end_run_early). The run's one value, read here, never copied.
  const des::Time& duration;
  const tracker::MotionSource& motion;         ///< true head motion
  const tracker::TrackerParams& tracker;       ///< how the head is sampled
  const tracker::Transport& transport;         ///< the link from tracker to host
  tracker::HostFeed& host;
  display::Display& display;
  const display::DisplayParams& display_params;
  const sections::SceneParams* scene;            ///< /scene, when the scenario has one
  results::ImageBook& images;                  ///< every image shown is registered here first
  results::FigureWriter& figures;              ///< the pipeline's own figures and warnings (docs/adding-a-figure.md)
  results::RunSignals& signals;                ///< what happens that the recorders turn into figures
  results::FrameRecorder& app_frames;          ///< the application's frames: rendered, missed
  results::RunFiles& files;                    ///< every result file goes here
  des::RunClocks& clocks;                      ///< every clock of the run, with its phase
  double ipd_m = 0.064;
  bool stereo = false;
  results::Timeline* timeline = nullptr;       ///< stage timeline, when the pipeline keeps one
  results::FrameCapture* frames = nullptr;     ///< frame capture, only when the scenario asks for frames
  std::optional<std::string> ended_early;      ///< why end_run_early() was called, if it was

  /// Ends the run at now(): the simulator stops after the running event, the
  /// figures cover the time simulated until then, and `why` becomes a
  /// warning (a measured cost that must stop at its end has run out). Only
  /// the first call counts.
  void end_run_early(std::string why);

  des::RandomStream stream(std::string_view name) const { return des::RandomStream(seed, name, replication); }
  /// A clock of the pipeline's own (its host application loop): phase fixed
  /// by the scenario or drawn from stream "clock.<name>", recorded at
  /// `phase_pointer` in the resolved scenario; rate error applied.
  const des::Clock& clock(const std::string& name, const std::string& phase_pointer, des::RationalSeconds nominal,
                          const des::ClockSettings& settings) const;
  /// The eye pose of a head pose (mono: the head pose).
  tracker::Pose eye_pose(const tracker::Pose& head, int eye) const;
  /// An image of `eye` rendered from the predicted pose `p` between `start`
  /// and `end`, with the host's receive time and the eye pose filled in, and
  /// the tracked controller (if any) drawn as predicted with `p`.
  results::ImageRecord image_record(int64_t frame, int eye, const tracker::PosePrediction& p, des::Time start,
                           des::Time end) const;
  /// Draws the tracked controller (if any) into `rec` as the render from
  /// `rendered` drew it: re-projecting an image moves the view, not the
  /// objects in it.
  void draw_controller(results::ImageRecord& rec, const tracker::PosePrediction& rendered) const;
  /// Display memories of the address recalculation pipelines: registers the
  /// cube rendered from `p` since `start` for every eye (orientation looked up
  /// at scanout), swaps it in at the next retrace, and logs a RENDER interval.
  void present_display_memory(int64_t frame, const tracker::PosePrediction& p, des::Time start,
                              const std::string& unit);
  /// The same for a render that ended at `end`, before it is presented now
  /// (it waited for the images it must be shown with).
  void present_display_memory(int64_t frame, const tracker::PosePrediction& p, des::Time start, des::Time end,
                              const std::string& unit);

  // Expected photon times, the horizons of prediction. Every one is the
  // middle of a lit interval under the display's persistence (the scanout
  // instant itself on an impulse display): what a predictor must aim at for
  // the drawn pose to match the head while the pixel emits light. An image
  // is represented by its middle active line: the lines above and below it
  // are lit up to half a field earlier and later, a skew that prediction per
  // image cannot remove (per-line and per-pixel pipelines predict per line
  // or pixel instead).

  /// The middle of the lit interval of pixel `x` of `field`'s active line
  /// `line`; every prediction target of every pipeline goes through here.
  des::Time photon_time(int64_t field, int line, int x = 0) const;
  /// The photon time of the middle line of `field`.
  des::Time frame_photon_time(int64_t field) const;
  /// The photon time of the middle line of the first field whose retrace is
  /// at or after `ready`, plus `later_fields` (an image swapped in at the
  /// next retrace after it is ready, behind that many queued images).
  des::Time photon_time_after(des::Time ready, int64_t later_fields = 0) const;
  /// An image shown at once, without vsync, at `t`: the photon time of the
  /// first active line written at or after `t`, the line on which it first
  /// appears (the lines below it follow, each a line period later).
  des::Time first_line_photon_time(des::Time t) const;
  /// Address recalculation reads the newest orientation as each pixel is
  /// fetched: at batched pixel fidelity every arrival splits the line being
  /// scanned (arrival events exist only then).
  void fetch_orientation_at_scanout();
};

}  // namespace latsim::pipelines
