#include "latsim/pxpl5/rc_engine.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace latsim::pxpl5 {

RcEngine::RcEngine(des::Simulator& sim, RcParams params, FieldTiming timing, RegionGrid grid,
                   WorkloadSource& workload, EngineHooks hooks)
    : sim_(sim),
      p_(params),
      timing_(timing),
      grid_(grid),
      workload_(workload),
      hooks_(std::move(hooks)),
      work_available_(sim, "pxpl5.rc.work"),
      sample_arrived_(sim, "pxpl5.rc.sample"),
      ring_(sim, params.hw.ring_channels, "pxpl5.ring") {
  if (p_.slaves() < 1) throw std::invalid_argument("RC needs a master and at least one slave GP");
  for (int s = 0; s < p_.slaves(); ++s) sgp_ports_.push_back(std::make_unique<des::Resource>(sim, 1));
  for (int f = 0; f < p_.hw.frame_buffers; ++f) fb_ports_.push_back(std::make_unique<des::Resource>(sim, 1));
  for (int k = 0; k < p_.hw.renderers; ++k) renderers_.push_back(std::make_unique<des::Resource>(sim, 1));
  sgp_busy_.assign(p_.slaves(), des::Time::zero());
  renderer_busy_.assign(p_.hw.renderers, des::Time::zero());
}

void RcEngine::start(des::Time end) {
  end_ = end;
  const des::KindId host = sim_.kind("pxpl5.send");
  sim_.spawn(send_process(), host);
  sim_.spawn(edit_process(), sim_.kind("pxpl5.edit"));
  sim_.spawn(transform_process(), sim_.kind("pxpl5.transform"));
  const des::KindId render = sim_.kind("pxpl5.render");
  for (int k = 0; k < p_.hw.renderers; ++k) sim_.spawn(renderer_process(k), render);
  sim_.spawn(copy_process(), sim_.kind("pxpl5.copy"));
}

void RcEngine::sample_visible() {
  sample_arrived_.trigger();
  sample_arrived_.reset();
}

RcEngine::FrameState& RcEngine::frame(int64_t i) {
  while (static_cast<int64_t>(frames_.size()) <= i) frames_.emplace_back(sim_);
  return frames_[static_cast<std::size_t>(i)];
}

RcEngine::EyeState& RcEngine::eye(int64_t n) {
  while (static_cast<int64_t>(eyes_.size()) <= n) eyes_.emplace_back(sim_);
  return eyes_[static_cast<std::size_t>(n)];
}

std::vector<des::Signal*> RcEngine::eye_conditions(int64_t render_n, int64_t copy_n, int64_t transform_n) {
  std::vector<des::Signal*> s;
  if (render_n >= 0) s.push_back(&eye(render_n).render_done);
  if (copy_n >= 0) s.push_back(&eye(copy_n).copy_done);
  if (transform_n >= 0) s.push_back(&eye(transform_n).transform_done);
  return s;
}

void RcEngine::stage(const char* name, int64_t frame, int eye, std::string unit, des::Time start, des::Time end) {
  if (hooks_.stage) hooks_.stage(StageInterval{name, frame, eye, std::move(unit), start, end});
}

void RcEngine::sample(const std::string& name, double value) {
  if (hooks_.sample) hooks_.sample(name, value);
}

int64_t RcEngine::newest_sample(des::Time t) const { return hooks_.newest_sample ? hooks_.newest_sample(t) : -1; }

// One slave's TRANSFORM of one eye: set-up, every primitive of its display
// list (on screen: transform, light, set up; elsewhere: transform and reject)
// and one bin entry per region an on-screen primitive covers.
des::Time RcEngine::transform_time(const BinCounts& bins, int s) const {
  return p_.transform_overhead + p_.transform_time_per_triangle * bins.on_screen(s) +
         p_.reject_time_per_triangle * (bins.triangles(s) - bins.on_screen(s)) +
         p_.sphere_transform_time * bins.spheres_on_screen(s) +
         p_.sphere_reject_time * (bins.spheres(s) - bins.spheres_on_screen(s)) +
         p_.binitize_time_per_bin * bins.bin_entries(s);
}

int64_t RcEngine::bin_words(const BinCounts& bins, int s, int region) const {
  const int64_t spheres = bins.sphere_commands(s, region);
  return (bins.commands(s, region) - spheres) * p_.hw.words_per_command + spheres * p_.words_per_sphere_command;
}

des::Time RcEngine::bin_render_time(const BinCounts& bins, int s, int region) const {
  const int64_t spheres = bins.sphere_commands(s, region);
  return p_.hw.render_time_per_command * (bins.commands(s, region) - spheres) +
         p_.render_time_per_sphere_command * spheres;
}

// SEND(i) may start once EDIT(i-1) has finished; unless the read is late,
// the host takes the newest tracker sample as it starts computing the
// viewing transforms.
des::Process RcEngine::send_process() {
  for (int64_t i = 0;; ++i) {
    if (i > 0) co_await frame(i - 1).edit_done;
    if (sim_.now() >= end_) co_return;
    FrameState& f = frame(i);
    const des::Time start = sim_.now();
    if (p_.host_waits_for_new_sample && hooks_.newest_index) {
      // The application blocks until the tracker delivers a newer sample.
      while (hooks_.newest_index(sim_.now()) <= last_sent_index_) co_await sample_arrived_;
      last_sent_index_ = hooks_.newest_index(sim_.now());
    }
    if (p_.host_read == HostRead::send_start) {
      f.sample_read_at = sim_.now();
      f.sample_token = newest_sample(sim_.now());
    }
    co_await sim_.delay(p_.send_time + p_.hw.transfer_time(p_.send_words));
    stage("SEND", i, -1, "host", start, sim_.now());
    sample("stage_ms.SEND", (sim_.now() - start).to_ms());
    f.send_done.trigger();
  }
}

// EDIT(i) needs SEND(i), TRANSFORM of the previous frame (its last eye),
// RENDER of the 2nd previous eye and COPY of the 3rd previous eye.
des::Process RcEngine::edit_process() {
  for (int64_t i = 0;; ++i) {
    const int64_t first = i * p_.eyes();
    co_await frame(i).send_done;
    for (des::Signal* done : eye_conditions(first - 2, first - 3, first - 1)) co_await *done;
    const des::Time start = sim_.now();
    // The slaves need the viewing transforms from here on: a late read takes
    // the newest sample now; either way, note how much newer that is.
    FrameState& f = frame(i);
    f.measured_token = newest_sample(start);
    if (p_.host_read == HostRead::late) {
      f.sample_read_at = start;
      f.sample_token = f.measured_token;
    }
    if (hooks_.sample_age_ms && f.sample_token >= 0 && f.measured_token >= 0)
      sample("late_read_saving_ms", hooks_.sample_age_ms(f.sample_token, f.measured_token));
    co_await sim_.delay(p_.edit_time);
    for (int s = 0; s < p_.slaves(); ++s) {
      stage("EDIT", i, -1, unit_name("SGP", s + 1), start, sim_.now());
      sgp_busy_[s] += p_.edit_time;
    }
    sample("stage_ms.EDIT", (sim_.now() - start).to_ms());
    frame(i).edit_done.trigger();
  }
}

// TRANSFORM(n) needs EDIT of its frame, RENDER(n-2) (which frees the bin
// context TRANSFORM(n) fills: two per SGP) and COPY(n-3). All SGPs work in
// parallel; the MGP starts RENDER when the slowest has finished.
des::Process RcEngine::transform_process() {
  for (int64_t n = 0;; ++n) {
    const int64_t i = n / p_.eyes();
    const int e = static_cast<int>(n % p_.eyes());
    co_await frame(i).edit_done;
    for (des::Signal* done : eye_conditions(n - 2, n - 3, -1)) co_await *done;
    EyeState& es = eye(n);
    const des::Time start = sim_.now();
    es.transform_start = start;
    const EyeWork& work = workload_.work(frame(i).sample_token, e, p_.slaves());
    es.bins = work.bins;
    const BinCounts& bins = es.bins;
    std::vector<des::Time> busy(static_cast<std::size_t>(p_.slaves()));
    des::Time slowest = des::Time::zero();
    for (int s = 0; s < p_.slaves(); ++s) {
      busy[s] = transform_time(bins, s);
      stage("TRANSFORM", i, e, unit_name("SGP", s + 1), start, start + busy[s]);
      slowest = std::max(slowest, busy[s]);
    }
    co_await sim_.delay(slowest);
    // Counted once finished, so utilisation never includes work past the run's end.
    for (int s = 0; s < p_.slaves(); ++s) sgp_busy_[s] += busy[s];
    sample("stage_ms.TRANSFORM", slowest.to_ms());
    sample("triangles_on_screen", static_cast<double>(work.on_screen_count));
    if (workload_.spheres() > 0) sample("spheres_on_screen", static_cast<double>(work.spheres_on_screen_count));
    // How many regions an on-screen primitive touches in this view (SPEC.md section 4: typically 1.3).
    if (const int64_t shown = work.on_screen_count + work.spheres_on_screen_count; shown > 0) {
      int64_t entries = 0;
      for (int s = 0; s < p_.slaves(); ++s) entries += bins.bin_entries(s);
      sample("regions_per_primitive", static_cast<double>(entries) / static_cast<double>(shown));
    }
    es.transform_done.trigger();
    // Busiest region (most waiting commands) first; ties in screen order.
    std::vector<int> order(grid_.regions());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return bins.region_commands(a) > bins.region_commands(b); });
    for (int r : order) unrendered_.push_back(RegionTask{n, r});
    work_available_.trigger();
    work_available_.reset();
  }
}

// A renderer takes the next unrendered region from the MGP; the region's
// token visits every SGP in ring order, each sending its bin for the region;
// the last adds the end-of-frame commands and returns the token. The
// renderer consumes commands as they arrive, so sending and rasterising overlap.
des::Process RcEngine::renderer_process(int k) {
  const std::string unit = unit_name("R", k);
  for (;;) {
    while (unrendered_.empty()) co_await work_available_;
    if (p_.copy_holds_renderer) {
      // A copy out of this renderer may hold it; meanwhile a free renderer may take the region.
      co_await renderers_[k]->acquire();
      if (unrendered_.empty()) {
        renderers_[k]->release();
        continue;
      }
    }
    const RegionTask task = unrendered_.front();
    unrendered_.pop_front();
    EyeState& es = eye(task.eye_seq);
    const int e = static_cast<int>(task.eye_seq % p_.eyes());
    const BinCounts& bins = es.bins;
    const des::Time start = sim_.now();
    if (!es.render_started) {
      es.render_started = true;
      es.render_start = start;
    }
    des::Time processed = start;  // when the renderer has consumed everything received so far
    for (int s = 0; s < p_.slaves(); ++s) {
      co_await sim_.delay(p_.token_hop_time);
      if (bins.commands(s, task.region) == 0) continue;
      co_await sgp_ports_[s]->acquire();
      co_await ring_.acquire();
      co_await sim_.delay(p_.hw.transfer_time(bin_words(bins, s, task.region)));
      ring_.release();
      sgp_ports_[s]->release();
      processed = std::max(processed, sim_.now()) + bin_render_time(bins, s, task.region);
    }
    co_await ring_.acquire();
    co_await sim_.delay(p_.hw.transfer_time(p_.end_of_frame_words));
    ring_.release();
    processed = std::max(processed, sim_.now()) + p_.region_shade_time;
    co_await sim_.delay(p_.token_hop_time);  // token back to the MGP
    co_await sim_.until(std::max(processed, sim_.now()));
    const int64_t i = task.eye_seq / p_.eyes();
    stage("RENDER", i, e, unit, start, sim_.now());
    renderer_busy_[k] += sim_.now() - start;
    if (p_.copy_holds_renderer) renderers_[k]->release();
    if (es.renderer_of_region.empty()) es.renderer_of_region.assign(static_cast<std::size_t>(grid_.regions()), -1);
    es.renderer_of_region[static_cast<std::size_t>(task.region)] = k;
    es.render_order.push_back(task.region);
    es.rendered.trigger();
    es.rendered.reset();
    if (static_cast<int>(es.render_order.size()) == grid_.regions()) {
      es.render_end = sim_.now();
      sample("stage_ms.RENDER", (es.render_end - es.render_start).to_ms());
      es.render_done.trigger();
    }
  }
}

// COPY moves rendered regions, in the order they finish, into the back
// buffer of the eye's frame buffer, one frame buffer at a time. The back
// buffer is free once the previous frame has been swapped to the front at
// its retrace: from then on it holds data already scanned out.
des::Process RcEngine::copy_process() {
  for (int64_t n = 0;; ++n) {
    const int64_t i = n / p_.eyes();
    const int e = static_cast<int>(n % p_.eyes());
    const int fb = p_.stereo ? e : 0;
    EyeState& es = eye(n);
    // The eye's back buffer is free once its previous image is swapped in.
    if (i > 0) co_await sim_.until(std::max(sim_.now(), eye(n - p_.eyes()).swap_at));
    for (int r = 0; r < grid_.regions(); ++r) {
      while (static_cast<int>(es.render_order.size()) <= r) co_await es.rendered;
      co_await fb_ports_[fb]->acquire();
      // With copy_holds_renderer the copy also takes the renderer holding the region.
      const int k = p_.copy_holds_renderer ? es.renderer_of_region[static_cast<std::size_t>(es.render_order[r])] : -1;
      des::Resource* renderer = k >= 0 ? renderers_[static_cast<std::size_t>(k)].get() : nullptr;
      if (renderer != nullptr) co_await renderer->acquire();
      co_await ring_.acquire();
      const des::Time start = sim_.now();
      if (r == 0) es.copy_start = start;
      if (r == 0 && e == 0) frame(i).copy_start = start;
      co_await sim_.delay(p_.hw.copy_time_per_region);
      ring_.release();
      if (renderer != nullptr) renderer->release();
      fb_ports_[fb]->release();
      stage("COPY", i, e, unit_name("FB", fb), start, sim_.now());
      if (renderer != nullptr) stage("COPY", i, e, unit_name("R", k), start, sim_.now());
    }
    es.copy_end = sim_.now();
    sample("stage_ms.COPY", (es.copy_end - es.copy_start).to_ms());
    es.copy_done.trigger();
    if (p_.stereo_swap == StereoSwap::per_eye) swap_eyes(i, e, e);
    if (e == p_.eyes() - 1) {
      if (p_.stereo_swap == StereoSwap::together) swap_eyes(i, 0, e);
      finish_frame(i);
    }
  }
}

Utilisation RcEngine::utilisation(des::Time elapsed) const {
  Utilisation u;
  if (elapsed <= des::Time::zero()) return u;
  const double t = elapsed.to_seconds();
  des::Time gp = des::Time::zero(), rend = des::Time::zero(), copy = des::Time::zero();
  for (des::Time b : sgp_busy_) gp += b;
  for (des::Time b : renderer_busy_) rend += b;
  for (const auto& port : fb_ports_) copy += port->busy_time();
  u.gp = gp.to_seconds() / (t * p_.slaves());
  u.renderer = rend.to_seconds() / (t * p_.hw.renderers);
  u.ring = ring_.unit_busy_time().to_seconds() / (t * p_.hw.ring_channels);
  u.copy = copy.to_seconds() / (t * static_cast<double>(fb_ports_.size()));
  return u;
}

}  // namespace latsim::pxpl5
