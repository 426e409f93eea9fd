// Jobs (application frames, compositor warps) flowing through timed stages
// on shared processors.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "frame_stages/pose_sampler.hpp"
#include "frame_stages/progress.hpp"
#include "frame_stages/span_estimate.hpp"
#include "frame_stages/spec.hpp"
#include "latsim/des/random.hpp"
#include "latsim/des/resource.hpp"
#include "latsim/results/timeline.hpp"

namespace latsim::pipelines::frame_stages {

/// What one job did: when each stage ran and which poses it read.
struct JobRecord {
  int64_t job = -1;
  std::vector<des::Time> start, end;                   ///< per stage
  std::vector<des::Time> released;                     ///< per stage: when its start rule let it go (it may then
                                                       ///< still wait for its processor)
  std::vector<des::Time> cost;                         ///< per stage: its work as drawn (preempted time excluded)
  std::optional<tracker::PosePrediction> first_pose;  ///< the first pose read (the simulation's input)
  std::optional<tracker::PosePrediction> last_pose;   ///< the last pose read (the view drawn)
  des::Time last_sample_at;                            ///< when the stage that read it began
  des::Time deadline;                                  ///< what the job's last late stage aimed for (zero: none)
  /// Not shown before this retrace (zero: as soon as it is done): a runtime
  /// that shows a frame at the refresh it was predicted for (SteamVR).
  des::Time not_before;
  bool skipped = false;                                ///< dropped by FlowHooks::on_begin
  int64_t tag = -1;                                    ///< the owner's (the compositor's source frame)
};

/// Where a flow meets the pipeline around it.
struct FlowHooks {
  int max_in_flight = 0;  ///< job j begins once job j - max_in_flight has completed (0: no limit)
  /// First deadline at or after t, for late stages (retraces, or strip starts).
  std::function<des::Time(des::Time)> next_deadline;
  /// The photon time a job completing at t is expected to reach (where poses are asked for).
  std::function<des::Time(des::Time)> photon_for_completion;
  /// Acquired before the job's last run starts; the owner releases it.
  des::Resource* image_buffers = nullptr;
  /// The first stage is about to begin; false drops the job (no stage runs).
  std::function<bool(JobRecord&)> on_begin;
  /// The job's last stage has ended (or the job was dropped).
  std::function<void(JobRecord&)> on_complete;
  /// The retrace rule waits for retraces whose index is a multiple of this.
  int retrace_divider = 1;
  /// Set: replaces the first stage's start rule; when job `rec` may begin,
  /// asked at the given time (a pacing policy; it sets rec.deadline).
  std::function<des::Time(JobRecord&, des::Time)> wake_up;
  /// How far apart jobs are expected to begin before two have (next_frame
  /// stages are expected that much after their job's first stage).
  des::Time frame_period;
};

/// The shared things a flow runs on.
struct FlowEnv {
  des::Simulator& sim;
  std::vector<des::Resource*> processors;        ///< by index, as StageSpec::processors counts
  std::vector<std::string> processor_names;
  std::vector<des::Time> preemption_slices;
  Progress& retraces;                            ///< value: index of the next retrace not yet begun
  std::function<des::Time(des::Time)> next_retrace;  ///< first retrace at or after t
  const PoseSampler& poses;
  des::RandomStream& stream;                     ///< stage durations that vary
  results::Timeline* timeline = nullptr;
  /// A stage's measured cost has played all its values and must stop
  /// (the pipeline ends the run); absent: the last value repeats.
  std::function<void(const renderer::RenderCost&)> out_of_input;
  /// Whether this flow's stages yield their processor between preemption
  /// slices (the application's do; the compositor's run to completion).
  bool yields = true;
};

/// Runs jobs 0, 1, 2 ... through a list of stages. Consecutive stages on the
/// same processors form a run, carried out by one worker process per
/// processor, which takes the run's jobs in turn (several processors:
/// alternate frame rendering). A run holds its processor from its first
/// stage to its last, as a thread does; a stage begins when its input is
/// ready, the same stage of the previous job has begun, its start rule
/// allows it and (first stage of a run) the processor is free.
class StageFlow {
 public:
  /// `kind` names the model in the event accounting, e.g. "frame.stage".
  StageFlow(const std::string& kind, std::vector<StageSpec> stages, LateParams late, FlowEnv env, FlowHooks hooks);
  StageFlow(const StageFlow&) = delete;
  StageFlow& operator=(const StageFlow&) = delete;

  /// Spawns the workers at now().
  void start();
  /// Jobs completed (or dropped) without a gap.
  PrefixProgress& completed() { return completed_; }
  const std::vector<StageSpec>& stages() const { return stages_; }
  /// The first stage of the last run: the run that draws into the image (the GPU's).
  int last_run_first() const { return runs_.back().first; }
  /// End of stage `last` when stage `first` starts at zero and every stage
  /// takes its nominal time (stream lags included, no waiting).
  des::Time nominal_span(int first, int last) const;
  /// The longest a non-yielding flow may wait for other flows' preemption
  /// slices between the start of stage `first` and the end of `last`.
  des::Time preemption_wait(int first, int last) const;
  /// When a job whose stage `from` begins at t completes, by nominal times,
  /// retrace waits, late deadlines and, for next_frame stages, the measured
  /// interval between jobs.
  des::Time expected_completion(int from, des::Time t) const;
  /// A late stage: how long before its deadline it starts now (estimate plus margin); else zero.
  des::Time late_lead(int stage) const;

 private:
  struct Run {
    int first = 0;
    int last = 0;
    std::vector<int> processors;
  };

  /// What to wait for before a stage may begin: a progress value, then a time.
  struct Wait {
    Progress* progress = nullptr;
    int64_t target = 0;
    des::Time after;  ///< once `progress` reaches `target`, wait this long more
    des::Time until;
  };

  des::Process worker(int run, int lane);
  Wait rule_wait(int stage, JobRecord& rec);
  des::Time photon_target(int stage, const JobRecord& rec) const;
  JobRecord& new_record(int64_t j);
  JobRecord& record(int64_t j) { return records_.at(static_cast<size_t>(j - base_)); }
  void release_stage(int stage, JobRecord& rec) { rec.released[static_cast<size_t>(stage)] = env_.sim.now(); }
  void begin_stage(int stage, JobRecord& rec);
  void end_stage(int stage, int processor, JobRecord& rec);
  void drop(JobRecord& rec);
  void complete(JobRecord& rec);

  std::vector<StageSpec> stages_;
  LateParams late_;
  FlowEnv env_;
  FlowHooks hooks_;
  des::KindId kind_ = 0;
  std::vector<Run> runs_;
  std::vector<std::unique_ptr<PrefixProgress>> started_, ended_;
  std::vector<SpanEstimate> estimates_;   ///< per late stage (index by stage)
  std::vector<des::Time> last_deadline_;  ///< per late stage
  des::Time last_first_start_ = des::Time::ps(-1);  ///< when the newest job began its first stage
  des::Time frame_interval_;                        ///< between the last two jobs' first stages
  PrefixProgress completed_;
  std::deque<JobRecord> records_;
  int64_t base_ = 0;  ///< job number of records_.front()
};

}  // namespace latsim::pipelines::frame_stages
