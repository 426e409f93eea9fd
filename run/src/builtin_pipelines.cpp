#include "latsim/run/builtin_pipelines.hpp"

// The pipelines latsim ships, one line each: the function, defined in the
// pipeline's own folder under pipelines/, that names the pipeline, declares
// its /pipeline keys and builds it. Adding a pipeline adds its folder and a
// line here.
#define LATSIM_BUILTIN_PIPELINES(X) \
  X(double_buffer_pipeline)         \
  X(frameless_pipeline)             \
  X(pxpl5_rc_pipeline)              \
  X(pxpl5_slats_pipeline)           \
  X(arp_pipeline)                   \
  X(priority_pipeline)              \
  X(region_priority_pipeline)       \
  X(frame_stages_pipeline)          \
  X(present_replay_pipeline)        \
  X(streaming_pipeline)            \
  X(passthrough_pipeline)

// The registry's entries are defined in the pipelines' own folders.
namespace latsim::pipelines {
#define LATSIM_DECLARE_PIPELINE(entry) PipelineEntry entry();
LATSIM_BUILTIN_PIPELINES(LATSIM_DECLARE_PIPELINE)
#undef LATSIM_DECLARE_PIPELINE
}  // namespace latsim::pipelines

namespace latsim::run {

pipelines::PipelineRegistry builtin_pipelines() {
  pipelines::PipelineRegistry r;
#define LATSIM_ADD_PIPELINE(entry) r.add(pipelines::entry());
  LATSIM_BUILTIN_PIPELINES(LATSIM_ADD_PIPELINE)
#undef LATSIM_ADD_PIPELINE
  return r;
}

}  // namespace latsim::run
