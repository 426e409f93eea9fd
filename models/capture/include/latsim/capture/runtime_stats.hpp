// The statistics an HMD runtime reports of itself, read from the files its
// tools write: OVR Metrics Tool's CSV export and the VrApi lines of a
// Quest's logcat (one sample a second), and SteamVR's Compositor_FrameTiming
// (one a frame), each field as its documentation defines it (docs/measured.md,
// "Runtime statistics").
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "latsim/capture/capture.hpp"

namespace latsim::capture {

/// One quantity's samples, with the file line of each.
struct StatSeries {
  std::vector<double> values;
  std::vector<int64_t> lines;
  void add(double v, int64_t line) {
    values.push_back(v);
    lines.push_back(line);
  }
};

/// The quantities read, by latsim's names for them:
/// - frame_rate_hz: application frames shown a second (OVR average_frame_rate, VrApi FPS);
/// - refresh_hz: the display's refresh rate (OVR display_refresh_rate, VrApi FPS=../R);
/// - prediction_ms: the runtime's prediction time, from the application's pose
///   query to the predicted display time (OVR average_prediction_milliseconds, VrApi Prd);
/// - stale_per_s: refreshes that showed an older application frame again
///   (OVR stale_frame_count, VrApi Stale; SteamVR m_nNumDroppedFrames summed a second);
/// - early_per_s: frames delivered a whole refresh before they were needed (OVR early_frame_count, VrApi Early);
/// - tears_per_s: refreshes the compositor finished too late, torn (OVR screen_tear_count, VrApi Tear);
/// - app_gpu_ms: the application's GPU time a frame (OVR app_gpu_time_microseconds,
///   VrApi App, SteamVR m_flPreSubmitGpuMs + m_flPostSubmitGpuMs);
/// - timewarp_gpu_ms: the compositor's GPU time a frame (OVR timewarp_gpu_time_microseconds,
///   VrApi TW, SteamVR m_flCompositorRenderGpuMs);
/// - frame_interval_ms (SteamVR): m_flClientFrameIntervalMs, between the application's WaitGetPoses calls;
/// - mispresented_per_s (SteamVR): m_nNumMisPresented summed a second.
struct RuntimeStats {
  std::filesystem::path source;
  Generation generation = Generation::generic;  ///< ovr_metrics, vrapi or steamvr
  bool per_frame = false;                       ///< SteamVR: a sample a frame; the others a second
  int64_t rows_read = 0;
  int64_t partial_rows = 0;  ///< OVR Metrics rows that are no second's figures (the first; the last when short): left out
  std::map<std::string, StatSeries> series;
  /// The series named `key`, or none.
  const StatSeries* find(const std::string& key) const;
};

/// Reads a runtime's statistics file. OVR Metrics: 9999 is "not available"
/// (no sample); the first row (counted from the tool's start, part of a
/// second) and a last row less than 0.95 s after the one before (the flush
/// when the recording stops, repeating it) are left out.
/// VrApi: every statistics line, whatever logcat wrote before it. SteamVR:
/// a CSV of Compositor_FrameTiming's fields by name (m_nFrameIndex,
/// m_flSystemTimeInSeconds, ...), a row a frame; its refresh rate comes from
/// m_flSystemTimeInSeconds (each frame's vsync). Throws CaptureError naming
/// the file and line of a cell that is not a number, or a file of another kind.
RuntimeStats read_runtime_stats(const std::filesystem::path& file);

}  // namespace latsim::capture
