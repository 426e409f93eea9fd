#include "present_replay/replay_frames.hpp"

namespace latsim::pipelines::present_replay {

std::shared_ptr<const ReplaySource> load_replay_source(const std::filesystem::path& file,
                                                       const capture::ProcessSelect& select) {
  auto src = std::make_shared<ReplaySource>();
  src->process = capture::read_presentmon(file, select);
  __int128 cpu = 0, wait = 0, gpu = 0;
  for (const capture::PresentMonFrame& f : src->process.frames) {
    if (!f.cpu_busy_ms || !f.in_present_ms || !f.gpu_busy_ms || *f.cpu_busy_ms < 0.0 || *f.in_present_ms < 0.0 ||
        *f.gpu_busy_ms < 0.0) {
      ++src->frames_left_out;
      continue;
    }
    ReplayFrame r{des::Time::from_ms(*f.cpu_busy_ms), des::Time::from_ms(*f.in_present_ms),
                  des::Time::from_ms(*f.gpu_busy_ms), std::nullopt};
    if (f.until_displayed_ms) r.until_displayed = des::Time::from_ms(*f.until_displayed_ms);
    cpu += r.cpu_busy.ticks();
    wait += r.in_present.ticks();
    gpu += r.gpu_busy.ticks();
    src->frames.push_back(r);
  }
  if (src->frames.empty())
    throw capture::CaptureError(file, 0, "no frame of the process has CPU busy, CPU wait and GPU busy values to replay");
  const auto n = static_cast<__int128>(src->frames.size());
  src->mean_cpu_busy = des::Time::ps(static_cast<int64_t>(cpu / n));
  src->mean_in_present = des::Time::ps(static_cast<int64_t>(wait / n));
  src->mean_gpu_busy = des::Time::ps(static_cast<int64_t>(gpu / n));
  src->capture_period_ms = capture::refresh_period_ms(file);
  return src;
}

PresentPathSpec capture_path(const capture::PresentMonProcess& p, int max_frame_latency) {
  PresentPathSpec s;
  s.max_frame_latency = max_frame_latency;
  const capture::PresentMode mode = p.mode();
  s.composed = capture::is_composed(mode);
  const int sync = p.sync_interval();
  s.sync_interval = sync < 0 ? 1 : sync;
  if (s.sync_interval == 0 && (s.composed || !p.allows_tearing()))
    s.show = PresentPathSpec::Show::newest;
  else if (s.sync_interval == 0)
    s.show = PresentPathSpec::Show::immediate;
  else
    s.show = PresentPathSpec::Show::queued;
  return s;
}

}  // namespace latsim::pipelines::present_replay
