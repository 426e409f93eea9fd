#include <stdexcept>

#include "latsim/pipelines/arp.hpp"
#include "latsim/pipelines/double_buffer.hpp"
#include "latsim/pipelines/latency_recorder.hpp"
#include "latsim/pipelines/pxpl5.hpp"
#include "latsim/pipelines/frameless.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "latsim/pipelines/timeline.hpp"

namespace latsim::pipelines {

void PipelineRegistry::add(std::string name, Factory factory) {
  if (!factories_.emplace(name, std::move(factory)).second)
    throw std::logic_error("pipeline \"" + name + "\" registered twice");
}

std::unique_ptr<Pipeline> PipelineRegistry::create(const std::string& name) const {
  auto it = factories_.find(name);
  return it == factories_.end() ? nullptr : it->second();
}

std::vector<std::string> PipelineRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& [name, f] : factories_) out.push_back(name);
  return out;
}

PipelineRegistry builtin_pipelines() {
  PipelineRegistry r;
  r.add("double_buffer", make_double_buffer_pipeline);
  register_pxpl5_pipelines(r);
  register_arp_pipelines(r);
  r.add("frameless", make_frameless_pipeline);
  return r;
}

tracker::Pose RunContext::eye_pose(const tracker::TrackerSample& s, int eye) const {
  return eye_pose_of(s.pose, eye, ipd_m, stereo);
}

ImageRecord RunContext::image_record(int64_t frame, int eye, const tracker::TrackerSample& s, des::Time start,
                                     des::Time end) const {
  ImageRecord rec;
  rec.frame = frame;
  rec.eye = eye;
  rec.sample = s;
  rec.host_received = host.received_at(s);
  rec.render_start = start;
  rec.render_end = end;
  rec.eye_pose = eye_pose(s, eye);
  return rec;
}

void RunContext::present_display_memory(int64_t frame, const tracker::TrackerSample& s, des::Time start,
                                        const std::string& unit) {
  const des::Time now = sim.now();
  for (int eye = 0; eye < display.eyes(); ++eye) {
    ImageRecord rec = image_record(frame, eye, s, start, now);
    rec.orientation_at_scanout = true;
    display.present_at_next_retrace(eye, recorder.register_image(rec));
  }
  if (timeline) timeline->add("RENDER", frame, -1, unit, start, now);
}

}  // namespace latsim::pipelines
