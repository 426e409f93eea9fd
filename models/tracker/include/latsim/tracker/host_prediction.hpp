// The host application's pose prediction: what it knew after each sample,
// and the pose it computes an image from for a given photon time.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>

#include "latsim/des/time.hpp"
#include "latsim/tracker/predictor.hpp"
#include "latsim/tracker/tracker.hpp"

namespace latsim::tracker {

/// A head pose predicted for an instant, and the sample it was predicted from.
struct PosePrediction {
  TrackerSample sample;  ///< newest sample used: motion-to-photon latency starts at its measurement
  des::Time target;      ///< the instant the pose is for (expected photon time)
  Pose pose;             ///< predicted head pose; the sample's pose when nothing is predicted
  /// When the pose was read (HostFeed::pose_for's `now`); absent when a
  /// pipeline predicted from a basis it kept.
  std::optional<des::Time> read_at;
  /// How far ahead of the measurement the pose was predicted.
  des::Time horizon() const { return target - sample.measured_at; }
};

/// What the host's predictor knows of when each sample was measured.
enum class PredictionKnowledge {
  oracle,   ///< the true measurement instant of every sample
  runtime,  ///< only its own clock: when the record became visible, less the link's nominal delay
};

/// Settings of the host's prediction (the scenario's host.prediction).
struct PredictionParams {
  PredictorParams predictor;
  PredictionKnowledge knowledge = PredictionKnowledge::oracle;
  /// When set, every pose is predicted this far past its sample's
  /// measurement, whatever the pipeline expects; otherwise to the pipeline's
  /// expected photon time.
  std::optional<des::Time> fixed_horizon;
};

/// What the host knew after one sample: enough to give the pose for any
/// photon time. Small and copyable, so pipelines that keep a sample for a
/// while (a frameless pixel, a frame in flight) keep this instead.
struct PredictionBasis {
  TrackerSample sample;
  MotionEstimate estimate;  ///< zero rates when not predicting: extrapolation holds the pose
  std::optional<des::Time> fixed_horizon;

  /// The pose for an image lit at `photon_time` (or at the fixed horizon).
  PosePrediction for_photon_time(des::Time photon_time) const;
};

/// A basis that predicts nothing: the sample's own pose for every photon time.
PredictionBasis hold_basis(const TrackerSample& sample);

/// Runs every sample the host receives through its predictor and keeps the
/// estimate after each, so that the basis of any remembered sample can be
/// looked up later: an image computed from sample k gets the pose predicted
/// from what the host knew when k was its newest sample, never from later
/// samples. Without prediction (predictor "none" and no fixed horizon)
/// nothing is stored and every basis holds its sample's pose.
class HostPrediction {
 public:
  /// Throws std::invalid_argument for invalid predictor parameters or a
  /// negative fixed horizon.
  explicit HostPrediction(PredictionParams params);

  /// Takes the next sample (increasing measurement time), as measured at
  /// `stamp` as far as the host knows (its measurement time for an oracle
  /// host; see PredictionKnowledge). A stamp earlier than the previous one counts as
  /// the previous one's; a sample stamped at the previous one's instant (several records reaching the
  /// host at one poll) replaces it in the predictor, which then goes on from
  /// its state before that one (the replaced sample keeps its estimate).
  void observe(const TrackerSample& sample, des::Time stamp);
  void observe(const TrackerSample& sample) { observe(sample, sample.measured_at); }
  /// The basis of an observed sample; throws std::logic_error if the sample
  /// was never observed or has been forgotten.
  PredictionBasis basis_of(const TrackerSample& sample) const;
  /// Forgets the estimates of samples with an index below `index`.
  void forget_before(int64_t index);
  /// Estimates held (for tests of the memory bound).
  size_t held() const { return estimates_.size(); }
  const PredictionParams& params() const { return params_; }

 private:
  struct Entry {
    int64_t index;
    MotionEstimate estimate;
  };
  PredictionParams params_;
  std::unique_ptr<Predictor> predictor_;  ///< null when nothing is predicted
  std::unique_ptr<Predictor> before_last_;  ///< the predictor before its newest sample (runtime stamps only)
  std::optional<des::Time> last_stamp_;
  std::deque<Entry> estimates_;           ///< increasing index
};

}  // namespace latsim::tracker
