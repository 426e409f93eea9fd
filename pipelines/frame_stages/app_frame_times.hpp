// An application frame's times in the terms of presentmon.csv.
#pragma once

#include "frame_stages/stage_flow.hpp"
#include "latsim/results/frame_times.hpp"

namespace latsim::pipelines::frame_stages {

/// The times of a completed application frame: the stages of the flow's last
/// run (from `first_gpu_stage`, the run that draws into the image) are its GPU
/// work, every stage before them its CPU work, and the end of the last CPU
/// stage its present. A flow of one run has no CPU work: its present is the
/// end of its image.
results::FrameTimes app_frame_times(const JobRecord& job, int first_gpu_stage);

}  // namespace latsim::pipelines::frame_stages
