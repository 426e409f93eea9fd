#include "latsim/tracker/host_prediction.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace latsim::tracker {

PosePrediction PredictionBasis::for_photon_time(des::Time photon_time) const {
  const des::Time target = fixed_horizon ? sample.measured_at + *fixed_horizon : photon_time;
  return PosePrediction{sample, target, extrapolate(estimate, target), std::nullopt};
}

PredictionBasis hold_basis(const TrackerSample& sample) {
  PredictionBasis b;
  b.sample = sample;
  b.estimate.at = sample.measured_at;
  b.estimate.pose = sample.pose;
  return b;
}

HostPrediction::HostPrediction(PredictionParams params) : params_(std::move(params)) {
  if (params_.fixed_horizon && *params_.fixed_horizon < des::Time::zero())
    throw std::invalid_argument("a fixed prediction horizon must not be negative");
  if (params_.predictor.kind != PredictorKind::None || params_.fixed_horizon)
    predictor_ = make_predictor(params_.predictor);
}

void HostPrediction::observe(const TrackerSample& sample, des::Time stamp) {
  if (!predictor_) return;
  if (!estimates_.empty() && sample.index <= estimates_.back().index)
    throw std::logic_error("host prediction: sample " + std::to_string(sample.index) + " arrived after sample " +
                           std::to_string(estimates_.back().index));
  // A record cannot be known to be older than the one before it.
  if (last_stamp_) stamp = std::max(stamp, *last_stamp_);
  TrackerSample seen = sample;
  seen.measured_at = stamp;
  if (last_stamp_ && stamp == *last_stamp_ && before_last_) {
    // Two records the host cannot tell apart in time: the newer one stands
    // for both, observed from the state before the older one.
    predictor_ = before_last_->clone();
  } else if (params_.knowledge == PredictionKnowledge::runtime) {
    before_last_ = predictor_->clone();
  }
  last_stamp_ = stamp;
  predictor_->observe(seen);
  estimates_.push_back(Entry{sample.index, *predictor_->estimate()});
}

PredictionBasis HostPrediction::basis_of(const TrackerSample& sample) const {
  PredictionBasis b = hold_basis(sample);
  b.fixed_horizon = params_.fixed_horizon;
  if (!predictor_) return b;
  const auto it = std::lower_bound(estimates_.begin(), estimates_.end(), sample.index,
                                   [](const Entry& e, int64_t i) { return e.index < i; });
  if (it == estimates_.end() || it->index != sample.index)
    throw std::logic_error("host prediction: no estimate kept for sample " + std::to_string(sample.index));
  b.estimate = it->estimate;
  return b;
}

void HostPrediction::forget_before(int64_t index) {
  while (!estimates_.empty() && estimates_.front().index < index) estimates_.pop_front();
}

}  // namespace latsim::tracker
