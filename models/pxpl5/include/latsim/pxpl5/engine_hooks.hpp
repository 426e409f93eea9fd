// What a Pixel-Planes 5 pipeline engine tells the world, and what it asks of it.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "latsim/des/time.hpp"

namespace latsim::pxpl5 {

/// One unit running one stage of one frame (or field) and eye.
struct StageInterval {
  std::string stage;  ///< SEND, EDIT, TRANSFORM, RENDER, COPY
  int64_t frame = 0;
  int eye = -1;       ///< -1 when the stage covers both eyes
  std::string unit;   ///< host, MGP, SGP3, GP, R2, FB0
  des::Time start;
  des::Time end;
};

/// One eye's finished image: which host sample it used and when it was made.
struct EyeImage {
  int eye = 0;
  int64_t sample_token = -1;     ///< what the host hook returned (-1: no sample yet)
  des::Time sample_read_at;      ///< when the host (RC) or the GP (Slats) took that sample
  des::Time transform_start;     ///< rendering latency starts here
  des::Time copy_end;            ///< last region of this eye in the frame buffer
};

/// A frame (RC) or field (Slats) ready to be shown at the retrace `swap_field`.
struct FrameReady {
  int64_t frame = 0;
  int64_t swap_field = 0;
  des::Time swap_at;
  std::vector<EyeImage> eyes;
};

/// Pixels of one field region arriving where the display shows them (Slats):
/// from now on the lines of that region show the image's data.
struct RegionWrite {
  int eye = 0;
  int64_t field = 0;        ///< the field whose lines (parity) the region holds
  int field_row = 0;        ///< region row within the field, 0 = top
  int column = 0;
  int64_t image_field = 0;  ///< the field the pixels were rendered for (older for a backup)
  EyeImage image;           ///< how they were computed; copy_end = when this region arrived
};

/// Callbacks an engine is wired with; any may be left empty.
struct EngineHooks {
  /// The newest host sample at time t as an opaque token, -1 if none yet.
  std::function<int64_t(des::Time)> newest_sample;
  /// The tracker index of the newest sample the host can see at time t, -1 if
  /// none (for a host that waits for a new sample).
  std::function<int64_t(des::Time)> newest_index;
  /// How much newer sample `newer` was measured than sample `older`, in ms.
  std::function<double(int64_t older, int64_t newer)> sample_age_ms;
  /// A frame is complete; called at its last COPY end (before its retrace).
  std::function<void(const FrameReady&)> frame_ready;
  /// A region reached the displayed frame buffer (Slats writes region by region).
  std::function<void(const RegionWrite&)> region_written;
  /// Every stage interval, once its end is known (at its start or its end).
  std::function<void(const StageInterval&)> stage;
  /// Named samples for the figures (e.g. "render_latency_fields").
  std::function<void(const std::string&, double)> sample;
};

/// A unit's name, e.g. unit_name("SGP", 3) == "SGP3".
inline std::string unit_name(std::string_view prefix, int index) {
  std::string s(prefix);
  s += std::to_string(index);
  return s;
}

/// Busy fraction of each kind of unit over an elapsed time.
struct Utilisation {
  double gp = 0.0;        ///< mean over graphics processors
  double renderer = 0.0;  ///< mean over renderers (rendering, not holding pixels)
  double ring = 0.0;      ///< mean over ring channels
  double copy = 0.0;      ///< mean over frame-buffer ports (receiving a region)
};

/// How a Slats run's fields ended: every field whose deadlines have all passed
/// is either complete (every region in place by its deadline) or missed.
struct FieldCounts {
  int64_t complete = 0;
  int64_t missed = 0;
  int64_t torn = 0;            ///< missed fields that show some of their own regions
  int64_t never_started = 0;   ///< missed because the GP was still busy at the retrace
  int64_t backup_copies = 0;   ///< regions replaced by the backup of the last complete field

  /// missed / (complete + missed); 0 when no field has ended.
  double missed_fraction() const {
    const int64_t ended = complete + missed;
    return ended > 0 ? static_cast<double>(missed) / static_cast<double>(ended) : 0.0;
  }
};

}  // namespace latsim::pxpl5
