#include "frame_stages/app_frame_times.hpp"

namespace latsim::pipelines::frame_stages {

results::FrameTimes app_frame_times(const JobRecord& job, int first_gpu_stage) {
  const auto gpu = static_cast<size_t>(first_gpu_stage);
  const size_t stages = job.end.size();
  results::FrameTimes f;
  f.frame = job.job;
  f.has_cpu = gpu > 0;
  f.gpu_start = job.start[gpu];
  f.gpu_end = job.end[stages - 1];
  for (size_t s = gpu; s < stages; ++s) f.gpu_busy += job.cost[s];
  if (!f.has_cpu) {
    f.present = f.gpu_end;
    return f;
  }
  f.cpu_start = job.start[0];
  for (size_t s = 0; s < gpu; ++s) f.cpu_busy += job.cost[s];
  f.present = job.end[gpu - 1];
  return f;
}

}  // namespace latsim::pipelines::frame_stages
