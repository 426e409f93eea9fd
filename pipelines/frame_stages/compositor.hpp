// The time-warp compositor: once per refresh, or strip by strip just ahead of
// the beam, it re-projects the newest application image to the newest pose.
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "frame_stages/spec.hpp"
#include "frame_stages/stage_flow.hpp"
#include "frame_stages/warp_clock.hpp"
#include "latsim/des/resource.hpp"
#include "latsim/pipelines/pipeline.hpp"

namespace latsim::pipelines::frame_stages {

/// Chooses what each warp re-projects, registers and presents the warped
/// images, and counts what the application missed. The application draws
/// into eye buffers; the newest complete one is warped, again and again if
/// no newer one arrives (asynchronous time warp).
class Compositor {
 public:
  Compositor(RunContext& ctx, const WarpSpec& spec, des::Resource& eye_buffers);

  const WarpClock& clock() const { return clock_; }
  /// Half rate from now on (or not): a second showing of an image is synthesised, not missed.
  void set_half_rate(bool on) { planned_showings_ = on ? 2 : 1; }
  /// Each image is planned for n refreshes from now on (a runtime's throttle
  /// level): its showings after the first, up to n, are synthesised, not missed.
  void set_planned_showings(int n) { planned_showings_ = n; }

  /// An application frame is complete: it becomes the newest image.
  void on_frame_complete(const JobRecord& frame);
  /// A warp is about to begin: pick its source; false when there is none to warp.
  bool on_begin(JobRecord& warp);
  /// A warp has ended: register and present what it made.
  void on_complete(JobRecord& warp);

  /// For an image this compositor made: how many refreshes its source image
  /// had been shown in before (0: new); -1 for any other image.
  int rewarps_of(int64_t image_id) const;

  int64_t warps() const { return warps_; }
  int64_t frames_shown() const { return frames_shown_; }
  int64_t frames_rewarped() const { return frames_rewarped_; }
  int64_t frames_synthesised() const { return frames_synthesised_; }
  int64_t warps_late() const { return warps_late_; }
  int64_t refreshes_without_image() const { return refreshes_without_image_; }
  /// Refreshes skipped before field `fields_seen` (the first the run did not
  /// see start): the last warp may have aimed past the run's end.
  int64_t refreshes_without_warp(int64_t fields_seen) const {
    const int64_t beyond = gap_end_ - std::max(gap_begin_, fields_seen);
    return refreshes_without_warp_ - std::max<int64_t>(0, beyond);
  }

 private:
  /// A completed application image in an eye buffer.
  struct EyeImage {
    tracker::PosePrediction pose;  ///< the pose it was rendered from
    std::vector<tracker::Pose> eye_poses;  ///< per eye, as rendered
    int refreshes = 0;                     ///< refreshes whose first strip showed it
    int readers = 0;                       ///< warps reading it now
    bool superseded = false;
  };
  /// A completed frame held until its retrace (JobRecord::not_before).
  struct Held {
    int64_t job;
    tracker::PosePrediction pose;
    des::Time not_before;
  };
  /// Makes a completed frame the newest image.
  void adopt(int64_t job, const tracker::PosePrediction& pose);
  /// Adopts the held frames whose retrace has come by `retrace`.
  void release_held(des::Time retrace);
  void count_refresh(EyeImage& src, const JobRecord& warp);
  /// Accounts for the refresh of a warp's first strip, and for the refreshes
  /// since the last one that no warp was begun for.
  void account_refresh(int64_t field);
  void release_if_unused(int64_t frame);
  results::ImageRecord warped_record(const JobRecord& warp, int64_t frame, const EyeImage* src, int eye) const;

  RunContext& ctx_;
  WarpSpec spec_;
  int planned_showings_ = 1;  ///< refreshes each image is planned for (2 at half rate)
  des::Resource& eye_buffers_;
  WarpClock clock_;
  std::map<int64_t, EyeImage> images_;  ///< by application frame
  std::optional<int64_t> newest_;
  std::vector<Held> held_;  ///< in job order
  std::map<int64_t, int> rewarps_;      ///< image id -> rewarps (recent images only)
  int64_t warps_ = 0;
  int64_t frames_shown_ = 0;  ///< refreshes that showed an application frame for the first time
  int64_t frames_rewarped_ = 0;
  int64_t frames_synthesised_ = 0;
  int64_t warps_late_ = 0;
  int64_t refreshes_without_image_ = 0;
  int64_t refreshes_without_warp_ = 0;  ///< refreshes skipped: the warp aimed past them
  int64_t last_accounted_field_ = -1;
  int64_t gap_begin_ = 0, gap_end_ = 0;  ///< the last run of skipped refreshes, [begin, end)
};

}  // namespace latsim::pipelines::frame_stages
