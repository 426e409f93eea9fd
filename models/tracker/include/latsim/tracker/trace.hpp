// Recorded head-motion traces: loading, validation and frame conversion.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "latsim/des/time.hpp"
#include "latsim/io/line_error.hpp"
#include "latsim/tracker/pose.hpp"

namespace latsim::tracker {

/// A malformed trace file; what() is exactly "<file>:<line>: <reason>".
class TraceError : public io::LineError {
 public:
  using io::LineError::LineError;
};

/// One recorded pose and the trace time it was recorded at.
struct TraceSample {
  des::Time t;
  Pose pose;
};

/// A validated recording: strictly increasing times, unit quaternions, each on
/// the same hemisphere as its predecessor (so interpolation never meets a sign
/// flip).
struct Trace {
  std::filesystem::path source;
  std::vector<TraceSample> samples;
  /// Rows dropped because they repeated the previous row's timestamp.
  int64_t repeated_timestamps_dropped = 0;
  /// Rows whose quaternion was negated to stay on the previous sample's hemisphere.
  int64_t sign_flips_removed = 0;
  /// False for orientation-only formats (positions are then all zero).
  bool has_position = false;

  des::Time start() const { return samples.front().t; }
  des::Time end() const { return samples.back().t; }
};

/// Loads a trace in either of two formats, recognised by the header line:
///
/// (a) latsim CSV: header `t_s,px,py,pz,qw,qx,qy,qz`, then one row per sample
///     (seconds, metres, quaternion head->world in latsim's frame).
/// (b) the head-trace format of Corbillon et al. (MMSys 2018): header
///     `timestamp viewpoint w x y z`, whitespace separated, orientation only,
///     in Unity's frame (left-handed, y up, +z forward). Converting to latsim's
///     right-handed frame mirrors the z axis, M = diag(1, 1, -1), on both the
///     world and the head side: R' = M R M. For a quaternion this keeps w and z
///     and negates x and y. Unity's head +z (forward) becomes latsim's -z, so
///     the viewing direction is preserved.
///
/// Blank lines and lines starting with '#' are skipped. Rows with a timestamp
/// equal (to the picosecond) to the previous row's replace it: the later row
/// is the tracker's newer report for that instant. Quaternions are normalised
/// and canonicalised to the short arc from the previous sample. Irregular
/// sampling is kept as recorded. Throws TraceError for a file that is not a
/// regular file of at most kMaxTraceBytes or cannot be read,
/// an unknown header, a wrong column count, a non-numeric or non-finite value,
/// a zero quaternion, a decreasing timestamp, or no data rows.
Trace load_trace(const std::filesystem::path& file);

/// The largest trace file load_trace reads: about three hours of a 1000 Hz
/// recording in either format. A larger file, a FIFO or a device is refused
/// before anything is read (io::read_input_file).
inline constexpr size_t kMaxTraceBytes = size_t{256} << 20;

}  // namespace latsim::tracker
