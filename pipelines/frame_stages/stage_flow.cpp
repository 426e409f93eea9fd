#include "frame_stages/stage_flow.hpp"

#include <algorithm>
#include <stdexcept>

namespace latsim::pipelines::frame_stages {

namespace {

// Records of completed jobs kept behind the oldest unfinished one (a later
// run may still read the start time of a job's stage it streams from).
constexpr int64_t kKeepCompleted = 4;

int until_of(const StageSpec& s, int index) { return s.until < 0 ? index : s.until; }

}  // namespace

StageFlow::StageFlow(const std::string& kind, std::vector<StageSpec> stages, LateParams late, FlowEnv env,
                     FlowHooks hooks)
    : stages_(std::move(stages)),
      late_(late),
      env_(std::move(env)),
      hooks_(std::move(hooks)),
      completed_(env_.sim) {
  frame_interval_ = hooks_.frame_period;
  if (stages_.empty()) throw std::invalid_argument("a stage flow needs at least one stage");
  kind_ = env_.sim.kind(kind);
  for (size_t i = 0; i < stages_.size(); ++i) {
    const StageSpec& s = stages_[i];
    if (s.processors.empty()) throw std::invalid_argument("stage " + s.name + " has no processor");
    for (int p : s.processors)
      if (p < 0 || p >= static_cast<int>(env_.processors.size()))
        throw std::invalid_argument("stage " + s.name + " names a processor that does not exist");
    const int u = until_of(s, static_cast<int>(i));
    if (u < static_cast<int>(i) || u >= static_cast<int>(stages_.size()))
      throw std::invalid_argument("stage " + s.name + ": a late span must end at this stage or a later one");
    if (i == 0 && (s.start == StartRule::stream || s.start == StartRule::next_frame))
      throw std::invalid_argument("the first stage has nothing to stream from or hand over");
    if (i > 0 && s.start == StartRule::stream && stages_[i - 1].processors == s.processors)
      throw std::invalid_argument("stage " + s.name + " streams from a stage on its own processor");
    if (i == 0 || stages_[i - 1].processors != s.processors) runs_.push_back(Run{static_cast<int>(i), 0, s.processors});
    runs_.back().last = static_cast<int>(i);
    started_.push_back(std::make_unique<PrefixProgress>(env_.sim));
    ended_.push_back(std::make_unique<PrefixProgress>(env_.sim));
    estimates_.emplace_back(nominal_span(static_cast<int>(i), u) + preemption_wait(static_cast<int>(i), u),
                            late_.window);
    last_deadline_.push_back(des::Time::ps(-1));
  }
}

void StageFlow::start() {
  for (int r = 0; r < static_cast<int>(runs_.size()); ++r)
    for (int lane = 0; lane < static_cast<int>(runs_[static_cast<size_t>(r)].processors.size()); ++lane)
      env_.sim.spawn(worker(r, lane), kind_);
}

des::Time StageFlow::nominal_span(int first, int last) const {
  des::Time start, end = stages_[static_cast<size_t>(first)].cost.nominal_frame_time();
  for (int k = first + 1; k <= last; ++k) {
    const StageSpec& s = stages_[static_cast<size_t>(k)];
    const des::Time prev_end = end;
    start = s.start == StartRule::stream ? start + s.lag : end;
    end = start + s.cost.nominal_frame_time();
    if (s.start == StartRule::stream && end < prev_end) end = prev_end;
  }
  return end;
}

des::Time StageFlow::preemption_wait(int first, int last) const {
  // A flow that does not yield may still find a processor in the middle of
  // another flow's slice: once per run, the longest slice of its processors.
  if (env_.yields) return des::Time::zero();
  des::Time wait;
  for (int k = first; k <= last; ++k) {
    const StageSpec& s = stages_[static_cast<size_t>(k)];
    if (k > first && stages_[static_cast<size_t>(k - 1)].processors == s.processors) continue;
    des::Time longest;
    for (int p : s.processors) longest = std::max(longest, env_.preemption_slices[static_cast<size_t>(p)]);
    wait += longest;
  }
  return wait;
}

des::Time StageFlow::expected_completion(int from, des::Time t) const {
  des::Time start = t, end = t + stages_[static_cast<size_t>(from)].cost.nominal_frame_time();
  int handovers = 0;
  for (int k = from + 1; k < static_cast<int>(stages_.size()); ++k) {
    const StageSpec& s = stages_[static_cast<size_t>(k)];
    const des::Time prev_end = end;
    switch (s.start) {
      case StartRule::next_frame:
        // Handed over when the next job reaches the stage before: a job interval later per handover.
        start = std::max(end, t + frame_interval_ * ++handovers);
        break;
      case StartRule::after: start = end; break;
      case StartRule::stream: start = start + s.lag; break;
      case StartRule::retrace: start = env_.next_retrace(end) + s.offset; break;
      case StartRule::late: {
        const des::Time est = estimates_[static_cast<size_t>(k)].estimate() + late_.margin;
        start = hooks_.next_deadline(end + est) - est;
        break;
      }
    }
    end = start + s.cost.nominal_frame_time();
    if (s.start == StartRule::stream && end < prev_end) end = prev_end;
  }
  return end;
}

des::Time StageFlow::late_lead(int stage) const {
  if (stages_[static_cast<size_t>(stage)].start != StartRule::late) return des::Time::zero();
  return estimates_[static_cast<size_t>(stage)].estimate() + late_.margin;
}

des::Time StageFlow::photon_target(int stage, const JobRecord& rec) const {
  // A frame held until a later retrace is predicted for that one.
  return hooks_.photon_for_completion(std::max(expected_completion(stage, env_.sim.now()), rec.not_before));
}

JobRecord& StageFlow::new_record(int64_t j) {
  if (j != base_ + static_cast<int64_t>(records_.size())) throw std::logic_error("stage flow: jobs out of order");
  JobRecord& rec = records_.emplace_back();
  rec.job = j;
  rec.start.assign(stages_.size(), des::Time::zero());
  rec.end.assign(stages_.size(), des::Time::zero());
  rec.released.assign(stages_.size(), des::Time::zero());
  rec.cost.assign(stages_.size(), des::Time::zero());
  return rec;
}

StageFlow::Wait StageFlow::rule_wait(int stage, JobRecord& rec) {
  const StageSpec& s = stages_[static_cast<size_t>(stage)];
  Wait w;
  if (stage == 0 && hooks_.wake_up) {
    // A pacing policy decides instead of the stage's rule (it sets the deadline).
    w.until = hooks_.wake_up(rec, env_.sim.now());
  } else if (s.start == StartRule::retrace) {
    int64_t f = env_.retraces.value();
    while (f % hooks_.retrace_divider != 0) ++f;
    w.progress = &env_.retraces;
    w.target = f + 1;
    w.after = s.offset;
  } else if (s.start == StartRule::next_frame) {
    // The next job's previous stage has begun: this job is handed over.
    w.progress = &started_[static_cast<size_t>(stage - 1)]->progress();
    w.target = rec.job + 2;
  } else if (s.start == StartRule::late) {
    // The latest start from which the estimated span still meets a deadline
    // this stage has not aimed for yet.
    const des::Time est = estimates_[static_cast<size_t>(stage)].estimate() + late_.margin;
    des::Time d = hooks_.next_deadline(env_.sim.now() + est);
    des::Time& last = last_deadline_[static_cast<size_t>(stage)];
    while (d <= last) d = hooks_.next_deadline(d + des::Time::ps(1));
    last = d;
    rec.deadline = d;
    w.until = d - est;
  }
  return w;
}

void StageFlow::begin_stage(int stage, JobRecord& rec) {
  rec.start[static_cast<size_t>(stage)] = env_.sim.now();
  if (stage == 0) {
    if (last_first_start_ >= des::Time::zero()) frame_interval_ = env_.sim.now() - last_first_start_;
    last_first_start_ = env_.sim.now();
  }
  started_[static_cast<size_t>(stage)]->mark(rec.job);
}

void StageFlow::end_stage(int stage, int processor, JobRecord& rec) {
  const des::Time now = env_.sim.now();
  rec.end[static_cast<size_t>(stage)] = now;
  // A late span is measured from its release, so that waiting for a busy
  // processor (a preempted GPU) is learnt as part of it.
  for (size_t k = 0; k <= static_cast<size_t>(stage); ++k)
    if (stages_[k].start == StartRule::late && until_of(stages_[k], static_cast<int>(k)) == stage)
      estimates_[k].add(now - rec.released[k]);
  if (env_.timeline)
    env_.timeline->add(stages_[static_cast<size_t>(stage)].name, rec.job, -1,
                       env_.processor_names[static_cast<size_t>(processor)], rec.start[static_cast<size_t>(stage)], now);
  ended_[static_cast<size_t>(stage)]->mark(rec.job);
}

void StageFlow::drop(JobRecord& rec) {
  rec.skipped = true;
  for (size_t s = 0; s < stages_.size(); ++s) {
    started_[s]->mark(rec.job);
    ended_[s]->mark(rec.job);
  }
  complete(rec);
}

void StageFlow::complete(JobRecord& rec) {
  if (hooks_.on_complete) hooks_.on_complete(rec);
  completed_.mark(rec.job);
  while (base_ < completed_.value() - kKeepCompleted && !records_.empty()) {
    records_.pop_front();
    ++base_;
  }
}

des::Process StageFlow::worker(int r, int lane) {
  des::Simulator& sim = env_.sim;
  const Run& run = runs_[static_cast<size_t>(r)];
  const int lanes = static_cast<int>(run.processors.size());
  const int proc_index = run.processors[static_cast<size_t>(lane)];
  des::Resource& proc = *env_.processors[static_cast<size_t>(proc_index)];
  const des::Time slice = env_.yields ? env_.preemption_slices[static_cast<size_t>(proc_index)] : des::Time::zero();
  const bool last_run = r + 1 == static_cast<int>(runs_.size());
  for (int64_t j = lane;; j += lanes) {
    // Input: admission for the first run, the feeding stage for the others.
    if (r == 0) {
      if (hooks_.max_in_flight > 0) co_await completed_.reached(j - hooks_.max_in_flight + 1);
      if (j > 0) co_await started_[0]->reached(j);
      new_record(j);
    } else {
      const int feed = run.first - 1;
      if (stages_[static_cast<size_t>(run.first)].start == StartRule::stream) {
        co_await started_[static_cast<size_t>(feed)]->reached(j + 1);
        const des::Time t = record(j).start[static_cast<size_t>(feed)] + stages_[static_cast<size_t>(run.first)].lag;
        if (t > sim.now()) co_await sim.until(t);
      } else {
        co_await ended_[static_cast<size_t>(feed)]->reached(j + 1);
      }
      if (j > 0) co_await started_[static_cast<size_t>(run.first)]->reached(j);
    }
    if (record(j).skipped) continue;
    if (last_run && hooks_.image_buffers) co_await hooks_.image_buffers->acquire();
    // The first stage's own rule is waited for before taking the processor:
    // a thread waiting for vsync leaves the core to others.
    {
      const Wait w = rule_wait(run.first, record(j));
      if (w.progress) co_await w.progress->reached(w.target);
      if (w.after > des::Time::zero()) co_await sim.delay(w.after);
      if (w.until > sim.now()) co_await sim.until(w.until);
      release_stage(run.first, record(j));
    }
    co_await proc.acquire();
    if (r == 0 && hooks_.on_begin && !hooks_.on_begin(record(j))) {
      proc.release();
      drop(record(j));
      continue;
    }
    for (int s = run.first; s <= run.last; ++s) {
      StageSpec& st = stages_[static_cast<size_t>(s)];
      if (s > run.first) {
        const Wait w = rule_wait(s, record(j));
        if (w.progress) co_await w.progress->reached(w.target);
        if (w.after > des::Time::zero()) co_await sim.delay(w.after);
        if (w.until > sim.now()) co_await sim.until(w.until);
        release_stage(s, record(j));
      }
      if (st.samples_pose) {
        const des::Time target = photon_target(s, record(j));
        std::optional<tracker::PosePrediction> pose;
        // Before the first tracker sample there is nothing to read: try again shortly.
        while (!(pose = env_.poses.pose(sim.now(), target))) co_await sim.delay(des::Time::ms(1));
        JobRecord& rec = record(j);
        if (!rec.first_pose) rec.first_pose = pose;
        rec.last_pose = pose;
        rec.last_sample_at = sim.now();
      }
      begin_stage(s, record(j));
      // A measured cost with nothing left ends the run after this event.
      if (st.cost.exhausted() && env_.out_of_input) env_.out_of_input(st.cost);
      des::Time remaining = shaped_cost(st.cost, st.shape, j, env_.stream);
      record(j).cost[static_cast<size_t>(s)] = remaining;
      while (remaining > des::Time::zero()) {
        const des::Time step = slice > des::Time::zero() && slice < remaining ? slice : remaining;
        co_await sim.delay(step);
        remaining -= step;
        if (remaining > des::Time::zero() && proc.queue_length() > 0) {
          // Preempted: whoever waits goes first, then this stage continues.
          proc.release();
          co_await proc.acquire();
        }
      }
      // Commands executed as they are issued: not done before the issuing is.
      if (st.start == StartRule::stream && s == run.first && s > 0)
        co_await ended_[static_cast<size_t>(s - 1)]->reached(j + 1);
      end_stage(s, proc_index, record(j));
    }
    proc.release();
    if (last_run) complete(record(j));
  }
}

}  // namespace latsim::pipelines::frame_stages
