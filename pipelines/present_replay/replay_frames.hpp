// The frames of one process of a PresentMon capture as a replay plays them:
// what the application itself did (its time before each Present, its time
// in each, its GPU work), read as PresentMon defines the columns.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "latsim/capture/presentmon.hpp"
#include "latsim/des/time.hpp"
#include "present_replay/present_path.hpp"

namespace latsim::pipelines::present_replay {

/// One frame's replayed values.
struct ReplayFrame {
  des::Time cpu_busy;    ///< PresentMon's CPU busy: the previous Present's return to this one's call
  des::Time in_present;  ///< PresentMon's CPU wait: the time the call took in the capture
  des::Time gpu_busy;    ///< PresentMon's GPU busy
  std::optional<des::Time> until_displayed;  ///< the capture's, for the start's alignment
};

/// The capture's process, ready to replay.
struct ReplaySource {
  capture::PresentMonProcess process;   ///< as read (its frames with every column)
  std::vector<ReplayFrame> frames;      ///< the frames that have all three values, in order
  int64_t frames_left_out = 0;          ///< frames without one of them (the first of v1, NA cells)
  std::optional<double> capture_period_ms;  ///< the capture's refresh period (capture::refresh_period_ms)
  des::Time mean_cpu_busy, mean_in_present, mean_gpu_busy;
};

/// Reads the frames of the chosen process; throws capture::CaptureError.
std::shared_ptr<const ReplaySource> load_replay_source(const std::filesystem::path& file,
                                                       const capture::ProcessSelect& select);

/// The present path a process ran on: its mode (composed or not), its sync
/// interval (-1, not reported, as 1: D3D9's default interval waits for the
/// retrace) and tearing. Sync interval 0 shows the newest frame at each
/// refresh, or, tearing allowed on a hardware path, each frame at once.
PresentPathSpec capture_path(const capture::PresentMonProcess& p, int max_frame_latency);

}  // namespace latsim::pipelines::present_replay
