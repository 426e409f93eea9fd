// Measured frame timing: PresentMon captures (or any CSV with a header) read
// into compact columns of durations, one process's rows only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "latsim/des/time.hpp"
#include "latsim/io/line_error.hpp"

namespace latsim::capture {

/// A capture that cannot be used; what() is exactly "<file>:<line>: <reason>"
/// ("<file>: <reason>" for a problem of the whole file, line 0).
class CaptureError : public io::LineError {
 public:
  using io::LineError::LineError;
};

/// Which of PresentMon's column sets a header is, which runtime statistics a
/// file holds, or a CSV of any other origin.
enum class Generation {
  current,      ///< PresentMon 2: MsBetweenPresents, MsCPUBusy, MsGPUBusy, MsUntilDisplayed, TimeInQPC, ...
  v1,           ///< PresentMon 1: TimeInSeconds, msBetweenPresents, msUntilDisplayed, Dropped, ...
  v2,           ///< PresentMon 2's --v2_metrics: CPUStartQPC, CPUBusy, GPUBusy, DisplayLatency, ...
  ovr_metrics,  ///< OVR Metrics Tool's CSV export: one row a second (average_frame_rate, app_gpu_time_microseconds, ...)
  vrapi,        ///< the VrApi statistics lines of a Quest's logcat: one a second (FPS=72/72,Prd=28ms,...)
  steamvr,      ///< SteamVR's Compositor_FrameTiming, one row a frame, the struct's field names as the header
  generic,      ///< any other CSV with a header line
};

/// "current", "v1", "v2", "ovr_metrics", "vrapi", "steamvr" or "generic".
const char* generation_name(Generation g);

/// Whether a generation is one of PresentMon's (current, v1, v2).
bool is_presentmon(Generation g);

/// The generation a header's column names show (tested in the order current,
/// v1, v2: the current set also has CPUStartQPC, but only it has MsCPUBusy or
/// MsBetweenPresents; v1 alone has TimeInSeconds or msBetweenPresents; v2
/// alone has CPUBusy without a prefix; then OVR Metrics Tool's
/// average_frame_rate or app_gpu_time_microseconds, SteamVR's m_nFrameIndex
/// or m_flClientFrameIntervalMs). A VrApi log has no header: the reader
/// tells it by its lines.
Generation detect_generation(const std::vector<std::string>& header);

/// The generation of a capture file, from its header or its VrApi lines
/// (throws CaptureError for a file that cannot be read).
Generation file_generation(const std::filesystem::path& file);

/// Whose rows to keep, by the `Application` and `ProcessID` columns. Empty
/// application and no process_id: the capture must hold one process only.
struct ProcessSelect {
  std::string application;  ///< compared without regard to ASCII case (Windows' file names)
  std::optional<int64_t> process_id;
};

/// What to read: the columns, and whose rows.
struct CaptureRequest {
  std::vector<std::string> columns;  ///< header names, exact (case matters: v1's msUntilDisplayed)
  ProcessSelect select;
};

/// One column of the selected rows, in file order, as durations.
struct CaptureColumn {
  std::string name;
  std::vector<des::Time> values;  ///< the cells read as milliseconds
  int64_t skipped_na = 0;         ///< `NA` or empty cells (unknown)
  int64_t skipped_not_displayed = 0;  ///< display columns: frames never displayed
  int64_t min_line = 0;           ///< the file line of the smallest value (the first such)
  int64_t max_line = 0;           ///< the file line of the largest value
  des::Time min() const;
  des::Time max() const;
  /// The values in milliseconds (a copy, for callers that compare or plot).
  std::vector<double> values_ms() const;
  /// The mean, exactly rounded from the integer sum.
  des::Time mean() const;
};

/// The columns asked for, of the rows of one process.
struct Capture {
  std::filesystem::path source;
  Generation generation = Generation::generic;
  std::string application;   ///< of the rows kept (empty: the file has no Application column)
  std::optional<int64_t> process_id;  ///< of the rows kept (none: no ProcessID column, or not an integer)
  int64_t rows_read = 0;     ///< data rows in the file
  int64_t rows_of_other_processes = 0;
  int64_t rows_selected = 0;
  std::vector<CaptureColumn> columns;  ///< in the order asked for
  /// The column named `name`; throws std::out_of_range if it was not asked for.
  const CaptureColumn& column(const std::string& name) const;
};

/// Whether a column times the display (never displayed frames have no value
/// there): its name contains "Display" in any case (MsUntilDisplayed,
/// msBetweenDisplayChange, DisplayLatency, DisplayedTime).
bool is_display_column(const std::string& name);

/// Reads `request.columns` of the rows of one process from a capture,
/// streaming it: memory grows with the values kept, not with the file.
///
/// The file: a regular file of at most kMaxCaptureBytes; an optional UTF-8
/// byte-order mark; LF or CRLF line ends; blank lines skipped; the first line
/// is the header; fields separated by commas, optionally in double quotes
/// ("" for a quote inside); spaces around a field ignored; columns in any
/// order, extra columns ignored, a row may lack trailing columns nobody asked
/// for.
///
/// Cells: a number of milliseconds (finite, |x| <= 1e9); in an OVR Metrics
/// export a column's unit is its name's (_microseconds, _milliseconds; other
/// columns are not durations) and 9999 means "not available"; a VrApi field
/// is a number of ms written with its unit ("App=1.73ms"). `NA` or empty
/// skips that row for that column only (counted in skipped_na); in a display column
/// a frame never displayed is skipped too (v1: `Dropped` is 1; the other
/// generations write NA there), counted in skipped_not_displayed. Values that
/// are merely large (spikes of hundreds of ms) are kept: they happened.
///
/// Throws CaptureError naming the file and line for: a file that cannot be
/// read, no header, a column asked for that is not in the header (naming the
/// columns that are, and the column's name in this generation when it is a
/// known alias), a cell that is not a number (naming the column and value),
/// a selection on a file without Application/ProcessID columns, several
/// processes and none chosen (naming them), no rows of the chosen one, or a
/// column left without values.
Capture read_capture(const std::filesystem::path& file, const CaptureRequest& request);

/// The largest capture read_capture accepts: about three million rows of the
/// 32 columns of PresentMon's current set (some 330 bytes a row), an hour at
/// 800 frames per second. The file is streamed, so this bounds the time a
/// load takes, not its memory. A larger file, a FIFO or a device is refused
/// before anything is read.
inline constexpr size_t kMaxCaptureBytes = size_t{1} << 30;

}  // namespace latsim::capture
