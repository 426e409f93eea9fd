// What a staged frame pipeline declares to the event budget: jobs per second
// of each flow times the events each of its stages makes.
#include <algorithm>
#include <cmath>
#include <limits>

#include "frame_stages/frame_stages_pipeline.hpp"

namespace latsim::pipelines::frame_stages {

namespace {

// Events one stage of one job makes, counted from StageFlow::worker: the wait
// for its start rule (or for the stage feeding it), the wait for its
// processor, and the end of its work; every further preemption slice adds a
// delay and, when preempted, a wait for the processor again.
constexpr double kEventsPerStage = 3.0;
constexpr double kEventsPerExtraSlice = 2.0;

// How often a job passes through `stages` when nothing but the processors
// limits it: once per the busiest processor's work per job (stages spread
// over several units count on each by their share); and which stage's cost
// holds the most of it.
struct Bottleneck {
  double per_job_s = 0.0;
  std::string pointer;
};

Bottleneck bottleneck_of(const std::vector<StageSpec>& stages, size_t processors) {
  std::vector<double> busy_s(processors, 0.0), largest_s(processors, 0.0);
  std::vector<std::string> largest(processors);
  for (const StageSpec& st : stages) {
    const double share_s = st.cost.nominal_frame_time().to_seconds() / static_cast<double>(st.processors.size());
    for (int p : st.processors) {
      busy_s[static_cast<size_t>(p)] += share_s;
      if (share_s >= largest_s[static_cast<size_t>(p)]) {
        largest_s[static_cast<size_t>(p)] = share_s;
        largest[static_cast<size_t>(p)] = st.pointer + "/cost";
      }
    }
  }
  const auto it = std::max_element(busy_s.begin(), busy_s.end());
  if (it == busy_s.end()) return {};
  return {*it, largest[static_cast<size_t>(it - busy_s.begin())]};
}

// The events of `jobs_per_s` jobs through `stages`: kEventsPerStage each, under
// the key that sets the job rate, and the extra preemption slices under the
// key of the processor's slice.
void add_flow(std::vector<EventRate>& out, const std::vector<StageSpec>& stages,
              const std::vector<ProcessorSpec>& processors, double jobs_per_s, const std::string& rate_pointer,
              const std::string& model) {
  out.push_back({rate_pointer, model, jobs_per_s * kEventsPerStage * static_cast<double>(stages.size())});
  for (const StageSpec& st : stages) {
    for (int p : st.processors) {
      const ProcessorSpec& proc = processors[static_cast<size_t>(p)];
      if (proc.preemption_slice <= des::Time::zero()) continue;
      const double slices = std::ceil(st.cost.nominal_frame_time().to_seconds() / proc.preemption_slice.to_seconds());
      const double share = 1.0 / static_cast<double>(st.processors.size());
      if (slices > 1.0)
        out.push_back({proc.pointer + "/preemption_slice_ms", model,
                       jobs_per_s * share * (slices - 1.0) * kEventsPerExtraSlice});
    }
  }
}

}  // namespace

std::vector<EventRate> FrameStagesPipeline::event_rates(const sections::SharedParams& shared) const {
  const double fields_per_s = 1.0 / shared.display.raster.field_period.to_seconds();
  std::vector<EventRate> out;
  // Application frames: at most one per refresh when each is swapped in at
  // a retrace (vsync, no compositor) or a stage waits for a retrace or a
  // deadline; otherwise as fast as the busiest processor allows.
  bool paced = spec_.vsync && !spec_.warp;
  for (const StageSpec& st : spec_.stages) paced = paced || st.start == StartRule::retrace || st.start == StartRule::late;
  Bottleneck app = bottleneck_of(spec_.stages, spec_.processors.size());
  // N frames in flight: at most N per the time all stages of one take.
  double total_s = 0.0;
  for (const StageSpec& st : spec_.stages) total_s += st.cost.nominal_frame_time().to_seconds();
  app.per_job_s = std::max(app.per_job_s, total_s / std::max(1, spec_.max_frames_in_flight));
  const double cap_hz = paced ? fields_per_s : std::numeric_limits<double>::infinity();
  const double frames_per_s = paced_per_s(app.per_job_s, cap_hz);
  const bool refresh_bound = paced && app.per_job_s * fields_per_s <= 1.0;
  add_flow(out, spec_.stages, spec_.processors, frames_per_s, refresh_bound ? "/display/refresh_hz" : app.pointer,
           "frame");
  if (!spec_.warp) return out;
  // The compositor warps once per strip of every refresh, as far as its busiest processor keeps up.
  const double slots_per_s = fields_per_s * spec_.warp->strips;
  const Bottleneck warp = bottleneck_of(spec_.warp->stages, spec_.processors.size());
  const double warps_per_s = paced_per_s(warp.per_job_s, slots_per_s);
  const bool slot_bound = warp.per_job_s * slots_per_s <= 1.0;
  add_flow(out, spec_.warp->stages, spec_.processors, warps_per_s,
           !slot_bound ? warp.pointer : spec_.warp->strips > 1 ? "/pipeline/timewarp/strips" : "/display/refresh_hz",
           "compositor");
  return out;
}

}  // namespace latsim::pipelines::frame_stages
