// Runs the Pixel-Planes 5 engines on a bare simulator and keeps what they report.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "latsim/stats/stats.hpp"
#include "latsim/pxpl5/rc_engine.hpp"
#include "latsim/pxpl5/slats_engine.hpp"

namespace latsim::pxpl5::testing {

/// Everything one engine run reported.
struct RunRecord {
  std::vector<StageInterval> stages;
  std::map<std::string, stats::Distribution> samples;
  std::vector<FrameReady> frames;
  std::vector<des::Time> frame_ready_at;  ///< when each of `frames` was handed over (RC)
  std::vector<RegionWrite> writes;
  FieldCounts counts;
  Utilisation utilisation;
  int64_t missed_fields = 0;
  int64_t torn_fields = 0;
  uint64_t sim_fingerprint = 0;
  double field_ms = 0.0;

  const stats::Distribution& dist(const std::string& name) const;
  /// Order-sensitive hash of every stage interval (stage, frame, eye, unit, times).
  uint64_t stage_fingerprint() const;
};

/// 640 x 480 interlaced NTSC timing at exactly 60 Hz, retraces from t = 0.
FieldTiming ntsc_timing();
RegionGrid ntsc_grid();

/// A tracker feeding the host a new sample token every tracker period.
RunRecord run_rc(const RcParams& params, const Workload& workload, des::Time duration, uint64_t seed = 1);
RunRecord run_rc(const RcParams& params, WorkloadSource& source, des::Time duration);
/// RC fed by a tracker whose sample k becomes visible to the host at
/// k x `tracker_period` (the engine told of each), for a host that waits for samples.
RunRecord run_rc_with_tracker(const RcParams& params, const Workload& workload, des::Time duration,
                              des::RationalSeconds tracker_period);
/// Slats on `triangles` synthetic on-screen triangles, or on any workload.
RunRecord run_slats(const SlatsParams& params, int64_t triangles, des::Time duration);
RunRecord run_slats(const SlatsParams& params, WorkloadSource& source, des::Time duration);

/// What the display lit during one field of one eye, span by span.
struct LitSpan {
  int line;
  int x_begin, x_end;
  int64_t image_field;  ///< the field whose pixels were shown (-1: nothing yet)
  des::Time photon_time;
};

/// Slats driving a line-scanned NTSC display: every region write goes into the
/// eye's frame buffer (image id = the field it was rendered for); returns the
/// spans lit in `field` for `eye`.
std::vector<LitSpan> run_slats_on_display(const SlatsParams& params, WorkloadSource& source, des::Time duration,
                                          int64_t field, int eye, RunRecord& record);

/// RC with every TRANSFORM and RENDER cost set to zero except the copy.
RcParams trivial_rc_params();

/// A display list of `list` triangles of which the first on_screen(token) are
/// inside both eyes' views (one bin entry each, in region 0): a load that
/// changes with the host sample, for provoking late fields on purpose.
class VaryingWorkload final : public WorkloadSource {
 public:
  VaryingWorkload(int64_t list, std::function<int64_t(int64_t token)> on_screen)
      : list_(list), on_screen_(std::move(on_screen)) {}
  int64_t triangles() const override { return list_; }
  const EyeWork& work(int64_t token, int eye, int processors) override;

 private:
  int64_t list_;
  std::function<int64_t(int64_t)> on_screen_;
  EyeWork work_;
};

}  // namespace latsim::pxpl5::testing
