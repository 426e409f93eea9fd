#include "latsim/pxpl5/slats_engine.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace latsim::pxpl5 {

SlatsEngine::SlatsEngine(des::Simulator& sim, SlatsParams params, FieldTiming timing, RegionGrid grid,
                         int64_t triangles, EngineHooks hooks)
    : sim_(sim), p_(params), timing_(timing), grid_(grid), triangles_(triangles), hooks_(std::move(hooks)) {
  if (triangles < 0) throw std::invalid_argument("Slats: negative triangle count");
  // Static binding: column c of every field row of every eye belongs to
  // renderer c mod renderers (5 renderers x top/bottom x 2 eyes = 4 regions each).
  copy_order_.resize(p_.eyes());
  for (int e = 0; e < p_.eyes(); ++e)
    for (int row = 0; row < grid_.field_rows; ++row)
      for (int c = 0; c < grid_.columns; ++c) {
        copy_order_[e].push_back(static_cast<int>(regions_.size()));
        regions_.push_back(FieldRegion{e, row, c, c % p_.hw.renderers});
      }
  renderer_free_.assign(p_.hw.renderers, des::Time::zero());
  kind_field_ = sim_.kind("pxpl5.field");
  kind_ready_ = sim_.kind("pxpl5.copy");
  kind_send_ = sim_.kind("pxpl5.send");
}

void SlatsEngine::start(des::Time end) {
  end_ = end;
  gp_free_ = sim_.now();
  for (int r = 0; r < p_.hw.renderers; ++r) renderer_free_[r] = sim_.now();
  const int64_t first = timing_.field_at_or_after(sim_.now());
  if (timing_.retrace(first) < end_) sim_.at(timing_.retrace(first), kind_field_, [this, first] { field_start(first); });
}

void SlatsEngine::stage(const char* name, int64_t frame, int eye, std::string unit, des::Time start, des::Time end) {
  if (hooks_.stage) hooks_.stage(StageInterval{name, frame, eye, std::move(unit), start, end});
}

void SlatsEngine::sample(const std::string& name, double value) {
  if (hooks_.sample) hooks_.sample(name, value);
}

void SlatsEngine::host_sample(int64_t token) {
  host_pending_ = token;
  if (!host_busy_) send_to_gp();
}

// The host computes both eyes' transforms from the newest sample it has and
// sends them; a sample arriving meanwhile waits and only the newest is sent.
void SlatsEngine::send_to_gp() {
  const int64_t token = host_pending_;
  host_pending_ = -1;
  host_busy_ = true;
  const des::Time start = sim_.now();
  const des::Time message = p_.hw.transfer_time(p_.host_message_words);
  ring_busy_ += message;
  sim_.after(p_.host_compute_time + message, kind_send_, [this, token, start] {
    gp_mailbox_ = token;
    stage("SEND", -1, -1, "host", start, sim_.now());
    sample("stage_ms.SEND", (sim_.now() - start).to_ms());
    host_busy_ = false;
    if (host_pending_ >= 0) send_to_gp();
  });
}

// The GP streams a full ring message to every renderer as soon as it holds
// max_message_words of commands, so rendering overlaps transforming.
std::vector<des::Time> SlatsEngine::transform_and_render(int64_t shown, des::Time start, des::Time& gp_end) {
  const int renderers = p_.hw.renderers;
  std::vector<int> owned(renderers, 0);
  for (const FieldRegion& r : regions_) ++owned[r.renderer];
  std::vector<des::Time> busy(renderers), first(renderers);
  for (int r = 0; r < renderers; ++r) first[r] = busy[r] = std::max(start, renderer_free_[r]);

  const int64_t words_per_triangle = static_cast<int64_t>(p_.hw.words_per_command) * p_.eyes();
  const int64_t per_message = std::max<int64_t>(1, p_.hw.max_message_words / words_per_triangle);
  des::Time t = start + p_.gp_field_overhead;
  des::Time port = t;
  for (int64_t done = 0; done < triangles_;) {
    const int64_t m = std::min(per_message, triangles_ - done);
    done += m;
    t += p_.gp_time_per_triangle * m;
    port = std::max(port, t);
    const des::Time transfer = p_.hw.transfer_time(m * words_per_triangle);
    for (int r = 0; r < renderers; ++r) {
      port += transfer;  // the GP's ring port sends one copy per renderer
      ring_busy_ += transfer;
      const des::Time work = p_.hw.render_time_per_command * (m * owned[r]);
      busy[r] = std::max(busy[r], port) + work;
      renderer_busy_ += work;
    }
  }
  gp_end = t;
  gp_busy_ += t - start;
  stage("TRANSFORM", shown, -1, "GP", start, t);
  sample("stage_ms.TRANSFORM", (t - start).to_ms());
  des::Time last = start;
  for (int r = 0; r < renderers; ++r) {
    const des::Time finish = p_.region_finish_time * owned[r];
    busy[r] = std::max(busy[r], t) + finish;
    renderer_busy_ += finish;
    stage("RENDER", shown, -1, unit_name("R", r), first[r], busy[r]);
    last = std::max(last, busy[r]);
  }
  sample("stage_ms.RENDER", (last - start).to_ms());
  return busy;
}

// Both frame buffers receive at once: slot s carries region s of the left
// eye's list to FB0 and region s-1 of the right eye's list to FB1, so 20
// regions take 11 slots. A renderer sends one region at a time. Deadlines:
// top regions by the retrace; with the COPY optimisation, lower regions by
// the moment the beam reaches their first line, otherwise also by the retrace.
std::vector<SlatsEngine::Transfer> SlatsEngine::copy_schedule(int64_t shown, const std::vector<des::Time>& rendered) {
  std::vector<Transfer> out;
  std::vector<des::Time> fb_free(p_.eyes(), des::Time::zero());
  std::vector<des::Time> port_free = rendered;
  const des::Time retrace = timing_.retrace(shown);
  const std::size_t slots = copy_order_[0].size() + static_cast<std::size_t>(p_.eyes()) - 1;
  for (std::size_t s = 0; s < slots; ++s)
    for (int e = 0; e < p_.eyes(); ++e) {
      if (s < static_cast<std::size_t>(e) || s - e >= copy_order_[e].size()) continue;
      const int idx = copy_order_[e][s - e];
      const FieldRegion& reg = regions_[idx];
      Transfer tr;
      tr.region = idx;
      tr.start = std::max(fb_free[e], port_free[reg.renderer]);
      tr.end = tr.start + p_.hw.copy_time_per_region;
      const bool late_allowed = p_.copy_optimisation && reg.row > 0;
      tr.deadline = late_allowed ? timing_.line_time(shown, reg.row * grid_.region_px) : retrace;
      fb_free[e] = port_free[reg.renderer] = tr.end;
      out.push_back(tr);
    }
  return out;
}

// At retrace k the GP starts the work for field k+1 if it is free; a field
// it cannot start, or whose copies miss their deadlines, is a missed field.
void SlatsEngine::field_start(int64_t k) {
  const des::Time now = sim_.now();
  const int64_t shown = k + 1;
  const des::Time next = timing_.retrace(shown);
  if (next < end_) sim_.at(next, kind_field_, [this, shown] { field_start(shown); });

  if (gp_free_ > now) {
    ++missed_fields_;
    sample("missed_field", static_cast<double>(shown));
    return;
  }
  const int64_t token = gp_mailbox_;
  des::Time gp_end;
  const std::vector<des::Time> rendered = transform_and_render(shown, now, gp_end);
  gp_free_ = gp_end;
  const std::vector<Transfer> copies = copy_schedule(shown, rendered);

  std::vector<des::Time> eye_copy_end(p_.eyes(), des::Time::zero());
  des::Time tops_done = now, copy_start = des::Time::max(), copy_end = now;
  des::Time slack = des::Time::max();
  int late = 0;
  for (const Transfer& tr : copies) {
    const FieldRegion& reg = regions_[tr.region];
    stage("COPY", shown, reg.eye, unit_name("FB", reg.eye), tr.start, tr.end);
    renderer_free_[reg.renderer] = std::max(renderer_free_[reg.renderer], tr.end);
    eye_copy_end[reg.eye] = std::max(eye_copy_end[reg.eye], tr.end);
    copy_start = std::min(copy_start, tr.start);
    copy_end = std::max(copy_end, tr.end);
    if (reg.row == 0 || !p_.copy_optimisation) tops_done = std::max(tops_done, tr.end);
    // On time means strictly before the deadline, so a swap requested then
    // still happens at that retrace.
    if (tr.end >= tr.deadline) ++late;
    slack = std::min(slack, tr.deadline - tr.end);
    copy_busy_ += p_.hw.copy_time_per_region;
    ring_busy_ += p_.hw.copy_time_per_region;
  }
  sample("stage_ms.COPY", (copy_end - copy_start).to_ms());
  sample("copy_ms_per_frame", (copy_end - copy_start).to_ms());
  sample("deadline_slack_ms", slack.to_ms());

  if (late > 0) {
    ++missed_fields_;
    // Regions that did arrive tear the field unless a backup of the last
    // complete field is shown instead.
    if (!p_.backup_field && late < static_cast<int>(copies.size())) ++torn_fields_;
    sample("missed_field", static_cast<double>(shown));
    return;
  }
  FrameReady ready;
  ready.frame = shown;
  ready.swap_field = shown;
  ready.swap_at = next;
  const double field_ms = timing_.period_ms();
  for (int e = 0; e < p_.eyes(); ++e) {
    ready.eyes.push_back(EyeImage{e, token, now, now, eye_copy_end[e]});
    sample("render_latency_fields", (next - now).to_ms() / field_ms);
    sample("render_to_scanout_fields", (next - now).to_ms() / field_ms);
    sample("transform_to_copy_end_fields", (eye_copy_end[e] - now).to_ms() / field_ms);
  }
  ++fields_shown_;
  sim_.at(tops_done, kind_ready_, [this, ready] {
    if (hooks_.frame_ready) hooks_.frame_ready(ready);
  });
}

Utilisation SlatsEngine::utilisation(des::Time elapsed) const {
  Utilisation u;
  if (elapsed <= des::Time::zero()) return u;
  const double t = elapsed.to_seconds();
  u.gp = gp_busy_.to_seconds() / t;
  u.renderer = renderer_busy_.to_seconds() / (t * p_.hw.renderers);
  u.ring = ring_busy_.to_seconds() / (t * p_.hw.ring_channels);
  u.copy = copy_busy_.to_seconds() / (t * p_.eyes());
  return u;
}

}  // namespace latsim::pxpl5
