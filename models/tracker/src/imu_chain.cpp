#include "latsim/tracker/imu_chain.hpp"

#include "latsim/tracker/tracker.hpp"

namespace latsim::tracker {

RuntimeFusion::RuntimeFusion(const ImuChainParams& params, const MotionSource& motion, des::RandomStream reference_stream)
    : motion_(motion), filter_(params.fusion) {
  if (params.reference) reference_.emplace(*params.reference, motion, std::move(reference_stream));
}

TrackerSample RuntimeFusion::fuse(const TrackerSample& report, des::Time visible) {
  TrackerSample out = report;
  if (!report.imu || report.imu->readings.empty()) return out;
  const std::vector<ImuReading>& readings = report.imu->readings;
  if (!filter_.started()) {
    // The first reading is where the runtime starts: tracked, at rest on its estimate.
    filter_.start(motion_.pose_at(readings.front().measured_at), readings.front().stamp);
  }
  for (const ImuReading& r : readings)
    if (r.index > filter_.last_index() && r.stamp >= filter_.stamp()) filter_.integrate(r);
  if (reference_) {
    // Fixes the runtime has by now, in measurement order, up to the newest reading.
    if (!pending_) pending_ = reference_->fix(reference_->first_index_at_or_after(readings.front().measured_at));
    while (pending_->available_at <= visible && pending_->measured_at <= filter_.stamp()) {
      filter_.correct(*pending_);
      pending_ = reference_->fix(pending_->index + 1);
    }
  }
  out.pose.orientation = filter_.orientation();
  out.pose.position_m = filter_.position_m();
  out.angular_velocity_rad_s = filter_.angular_velocity_rad_s();
  out.velocity_m_s = filter_.velocity_m_s();
  return out;
}

}  // namespace latsim::tracker
