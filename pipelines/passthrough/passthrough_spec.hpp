// What a see-through (passthrough) headset is made of: the camera, its
// synchronisation to the display, the image signal processor, the
// compositor that re-projects the camera image to the eye, and the rig that
// films a moving real object through it, as plain values
// (passthrough/bind.cpp fills them in from /pipeline).
#pragma once

#include <cstdint>
#include <optional>

#include "latsim/des/clock.hpp"
#include "latsim/des/time.hpp"
#include "latsim/measurement/camera_rig.hpp"
#include "latsim/tracker/motion_and_transport.hpp"

namespace latsim::pipelines::passthrough {

/// The headset's see-through camera: exposure, shutter, readout and its clock.
struct CameraSpec {
  int64_t width_px = 2048;
  int64_t height_px = 2048;        ///< rows read out one after another
  des::Time exposure = des::Time::ms(2);
  enum class Shutter { global, rolling };
  /// global: every row exposed over the same interval, then read row by row;
  /// rolling: row j opens j row readout times after row 0 and is read as it closes.
  Shutter shutter = Shutter::global;
  des::Time row_readout;           ///< per row: the frame's readout takes height_px of these
  /// display: frame k's first row opens `sync_offset` after retrace k x
  /// refreshes_per_frame (phase-locked, the display's own clock); free: the
  /// camera's own clock at `fps`, with its own phase and rate error.
  enum class Sync { display, free };
  Sync sync = Sync::display;
  int refreshes_per_frame = 1;
  des::Time sync_offset;
  des::RationalSeconds frame_period = des::RationalSeconds::period_of_hz(90);  ///< free: 1 / fps
  des::ClockSettings clock;        ///< free: phase (drawn when absent) and rate error

  /// The whole frame's readout: height_px row readout times.
  des::Time readout() const { return des::Time::ps(row_readout.ticks() * height_px); }
};

/// The image signal processor: one frame at a time, in order.
struct IspSpec {
  des::Time fixed;                  ///< per frame (or, line-streamed, after the last row)
  double pixel_rate_mpx_s = 0.0;    ///< pixels processed per second (0: no per-pixel time)
  /// false: starts once the frame is read out; true: processes rows as they
  /// are read, ending `fixed` after the later of the readout's end and its
  /// own pixel time from the readout's start.
  bool line_streamed = false;
};

/// The compositor on the headset's GPU: re-projects the newest processed
/// camera image to the eye's viewpoint with the newest head pose, composes
/// rendered content over it.
struct CompositorSpec {
  /// before_retrace: starts `lead` before every retrace; on_frame: starts as
  /// soon as the ISP has a new frame (the GPU permitting).
  enum class Start { before_retrace, on_frame };
  Start start = Start::before_retrace;
  des::Time lead = des::Time::ms(2);
  des::Time reprojection;           ///< the camera image to each eye's viewpoint
  des::Time composition;            ///< rendered content composed over it (0: passthrough alone)
};

/// The rig of latsim filming a moving real object and its image through the headset.
struct RigSpec {
  tracker::MotionParams object;     ///< the real object's motion (its angle about the rig's axis is read)
  measurement::CameraRigParams rig;
};

/// The whole passthrough pipeline.
struct PassthroughSpec {
  CameraSpec camera;
  IspSpec isp;
  CompositorSpec compositor;
  std::optional<RigSpec> rig;
  measurement::ScreenPoint point{0.5, 0.5};  ///< where photon_to_photon_ms is taken (the rig's point when filmed)
};

}  // namespace latsim::pipelines::passthrough
