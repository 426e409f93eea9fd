// A PresentMon capture read as PresentMon defines its columns, whatever the
// generation: per frame of one process, the present-to-present interval, the
// application's own time before the present (busy) against the time it
// spent in Present() (wait), GPU work, display, and the limiters it ran
// under (sync interval, present mode, tearing); per file, the display's
// refresh period (docs/measured.md, "PresentMon's definitions").
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "latsim/capture/capture.hpp"

namespace latsim::capture {

/// How the system showed a frame: PresentMon's PresentMode column.
enum class PresentMode {
  hardware_legacy_flip,                ///< "Hardware: Legacy Flip": the application owns the screen and flips
  hardware_legacy_copy,                ///< "Hardware: Legacy Copy to front buffer"
  hardware_independent_flip,           ///< "Hardware: Independent Flip": flips without owning the screen
  hardware_composed_independent_flip,  ///< "Hardware Composed: Independent Flip": a hardware overlay plane
  composed_flip,                       ///< "Composed: Flip": flip-model surfaces composed by DWM
  composed_copy_gpu_gdi,               ///< "Composed: Copy with GPU GDI"
  composed_copy_cpu_gdi,               ///< "Composed: Copy with CPU GDI"
  unknown,                             ///< "Other", or a capture without the column
};

/// PresentMon's text for a mode; parse_present_mode reads it back (unknown for any other text).
const char* present_mode_text(PresentMode m);
PresentMode parse_present_mode(std::string_view text);
/// Whether the desktop compositor (DWM) composed the frame: the "Composed:" modes.
bool is_composed(PresentMode m);

/// One frame of one process in PresentMon's terms. A quantity the generation
/// does not give, or NA, is absent.
struct PresentMonFrame {
  int64_t line = 0;
  std::optional<double> between_presents_ms;  ///< this Present() call's start minus the previous one's
  std::optional<double> in_present_ms;        ///< time inside Present(): PresentMon's CPU wait
  std::optional<double> cpu_busy_ms;          ///< the previous Present()'s return to this one's call, waiting included
  std::optional<double> gpu_busy_ms;          ///< GPU engines working on the frame
  std::optional<double> gpu_time_ms;          ///< its first GPU work's start to its last's end
  std::optional<double> until_displayed_ms;   ///< Present() to the flip that first shows it (screen time, not light)
  std::optional<double> between_display_change_ms;  ///< that flip minus the previous displayed frame's
  std::optional<double> present_time_s;       ///< the Present() call, TimeInSeconds (none with QPC times)
  std::optional<double> until_scanout_ms;     ///< a latsim run's MsUntilScanout (its flip; none in a capture)
  bool displayed = false;
  int sync_interval = -1;  ///< as the application asked; -1: the runtime did not say (D3D9, others)
  PresentMode mode = PresentMode::unknown;
  bool allows_tearing = false;
  std::string runtime;     ///< PresentRuntime (v1: Runtime): DXGI, D3D9, Other, ...
  bool application_frame = true;  ///< FrameType Application (or no FrameType): not one a driver generated
};

/// The frames of one process of a capture.
struct PresentMonProcess {
  std::filesystem::path source;
  Generation generation = Generation::current;
  std::string application;
  std::optional<int64_t> process_id;
  int64_t rows_read = 0;
  std::vector<PresentMonFrame> frames;  ///< in file order
  /// The mode, sync interval and tearing most of its frames ran under.
  PresentMode mode() const;
  int sync_interval() const;
  bool allows_tearing() const;
};

/// Reads the frames of one process (ProcessSelect as read_capture's; a
/// capture of several processes needs a choice). Per generation:
/// - current: the columns of the same names (MsInPresentAPI, else MsCPUWait, for the time in Present);
/// - v2: CPUBusy, CPUWait; the interval between presents is CPUWait of the
///   frame before plus CPUBusy (PresentMon's CPU start is the previous
///   present's start plus its time in Present); until displayed is
///   DisplayLatency (from the CPU start) less CPUBusy; the display change is
///   the DisplayedTime of the previous displayed frame;
/// - v1: msBetweenPresents, msInPresentAPI; CPU busy is msBetweenPresents
///   less the previous frame's msInPresentAPI; GPU busy msGPUActive; GPU time
///   msUntilRenderComplete less msUntilRenderStart; Dropped 1: not displayed.
/// Throws CaptureError (file and line) for a file that is not a PresentMon
/// capture, a cell that is not a number, no frames of the process.
PresentMonProcess read_presentmon(const std::filesystem::path& file, const ProcessSelect& select);

/// The processes of a capture with their frame counts, most frames first
/// (ties in order of first appearance).
struct ProcessCount {
  std::string application;
  int64_t process_id = 0;
  int64_t frames = 0;
};
std::vector<ProcessCount> presentmon_processes(const std::filesystem::path& file);

/// The display's refresh period a capture shows, from the display-change
/// intervals of frames flipped at a vertical blank (sync interval 1 or more,
/// no tearing) of every process: each interval is a whole number of periods,
/// so the period is the sum of the intervals over the sum of their whole
/// numbers, the numbers found from the median interval under 50 ms. None
/// when the capture has no such interval, or none within 10 % of a whole
/// number of that median.
std::optional<double> refresh_period_ms(const std::filesystem::path& file);

/// Warnings on replaying a process's frames on a display of `refresh_hz`:
/// uncapped (sync interval 0: its frame rate is its own, not the display's),
/// composed by the desktop compositor (DWM adds its own frame of latency),
/// taken at another refresh rate (more than 0.5 % away), and, with
/// `cpu_busy_as_work` (the CPU busy time read as work), CPU busy that holds
/// waiting (the median busy time within 10 % of the median interval).
std::vector<std::string> presentmon_warnings(const PresentMonProcess& p, std::optional<double> capture_period_ms,
                                             double refresh_hz, bool cpu_busy_as_work);

}  // namespace latsim::capture
