// Slats: construction, the host, the GP and its ring port, the renderers.
// The copy slots, region deadlines and field verdicts are in slats_copy.cpp.
#include "latsim/pxpl5/slats_engine.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace latsim::pxpl5 {

SlatsEngine::FieldWork::FieldWork(des::Simulator& sim, int renderers, int eyes)
    : eye_copy_end(static_cast<std::size_t>(eyes), des::Time::zero()), eye_on_time(static_cast<std::size_t>(eyes), 0) {
  render_start = des::Time::max();
  for (int r = 0; r < renderers; ++r) rendered.push_back(std::make_unique<des::Signal>(sim, "pxpl5.slats.rendered"));
}

SlatsEngine::SlatsEngine(des::Simulator& sim, SlatsParams params, FieldTiming timing, RegionGrid grid,
                         WorkloadSource& workload, EngineHooks hooks)
    : sim_(sim),
      p_(params),
      timing_(timing),
      grid_(grid),
      workload_(workload),
      hooks_(std::move(hooks)),
      ring_(sim, params.hw.ring_channels),
      port_work_(sim, "pxpl5.slats.port"),
      field_started_(sim, "pxpl5.slats.field"),
      host_wake_(sim, "pxpl5.slats.host") {
  if (p_.hw.frame_buffers < p_.eyes()) throw std::invalid_argument("Slats needs a frame buffer per eye");
  // Static binding: column c of every field row of every eye belongs to
  // renderer c mod renderers (5 renderers x top/bottom x 2 eyes = 4 regions each).
  copy_order_.resize(p_.eyes());
  owned_.assign(p_.hw.renderers, 0);
  for (int e = 0; e < p_.eyes(); ++e)
    for (int row = 0; row < grid_.field_rows; ++row)
      for (int c = 0; c < grid_.columns; ++c) {
        copy_order_[e].push_back(static_cast<int>(regions_.size()));
        regions_.push_back(FieldRegion{e, row, c, c % p_.hw.renderers});
        ++owned_[c % p_.hw.renderers];
      }
  for (int e = 0; e < p_.eyes(); ++e) {
    fb_ports_.push_back(std::make_unique<des::Resource>(sim, 1, unit_name("pxpl5.FB", e)));
    shown_field_.push_back({std::vector<int64_t>(grid_.field_regions(), -1),
                            std::vector<int64_t>(grid_.field_regions(), -1)});
  }
  backup_.resize(p_.eyes());
  copy_position_.assign(p_.eyes(), 0);
  for (int r = 0; r < p_.hw.renderers; ++r) {
    renderer_ports_.push_back(std::make_unique<des::Resource>(sim, 1, unit_name("pxpl5.R", r)));
    renderer_free_.push_back(std::make_unique<des::Signal>(sim, "pxpl5.slats.free"));
    renderer_free_.back()->trigger();  // empty pixel memory; nobody waits yet
    inbox_arrival_.push_back(std::make_unique<des::Signal>(sim, "pxpl5.slats.inbox"));
  }
  inbox_.resize(p_.hw.renderers);
  if (!timing_.interlaced()) kind_swap_ = sim_.kind("pxpl5.swap");
}

void SlatsEngine::start(des::Time end) {
  end_ = end;
  sim_.spawn(host_process(), sim_.kind("pxpl5.send"));
  sim_.spawn(gp_process(), sim_.kind("pxpl5.transform"));
  sim_.spawn(port_process(), sim_.kind("pxpl5.ring"));
  const des::KindId render = sim_.kind("pxpl5.render");
  for (int r = 0; r < p_.hw.renderers; ++r) sim_.spawn(renderer_process(r), render);
  const des::KindId copy = sim_.kind("pxpl5.copy");
  for (int e = 0; e < p_.eyes(); ++e) sim_.spawn(copy_process(e), copy);
}

void SlatsEngine::stage(const char* name, int64_t frame, int eye, std::string unit, des::Time start, des::Time end) {
  if (hooks_.stage) hooks_.stage(StageInterval{name, frame, eye, std::move(unit), start, end});
}

void SlatsEngine::sample(const std::string& name, double value) {
  if (hooks_.sample) hooks_.sample(name, value);
}

void SlatsEngine::host_sample(int64_t token) {
  host_pending_ = token;
  host_wake_.trigger();
  host_wake_.reset();
}

// The host computes both eyes' transforms from the newest sample it has and
// sends them over a ring channel; a sample arriving meanwhile waits and only
// the newest is sent.
des::Process SlatsEngine::host_process() {
  for (;;) {
    while (host_pending_ < 0) co_await host_wake_;
    const int64_t token = host_pending_;
    host_pending_ = -1;
    const des::Time start = sim_.now();
    co_await sim_.delay(p_.host_compute_time);
    co_await ring_.acquire();
    const int channel = ring_.claim();
    const des::Time sent = sim_.now();
    co_await sim_.delay(p_.hw.transfer_time(p_.host_message_words));
    ring_.release(channel);
    gp_mailbox_ = token;
    stage("SEND", -1, -1, unit_name("ring", channel), sent, sim_.now());
    stage("SEND", -1, -1, "host", start, sim_.now());
    sample("stage_ms.SEND", (sim_.now() - start).to_ms());
  }
}

// At the first retrace at which it is free the GP starts the next field with
// the newest transforms it holds; fields whose retraces passed while it was
// busy get no new image. A full message goes to the port as soon as it is full.
des::Process SlatsEngine::gp_process() {
  const int64_t words_per_triangle = static_cast<int64_t>(p_.hw.words_per_command) * p_.eyes();
  const int64_t per_message = std::max<int64_t>(1, p_.hw.max_message_words / words_per_triangle);
  for (;;) {
    const int64_t k = timing_.field_at_or_after(sim_.now());
    const des::Time retrace = timing_.retrace(k);
    if (retrace >= end_) co_return;
    co_await sim_.until(retrace);
    if (last_started_ < 0) last_started_ = k;  // the field shown at the first retrace had no work
    give_up_fields(last_started_ + 1, k);
    FieldWork& w = begin_field(k + 1);
    const des::Time start = sim_.now();
    std::vector<uint8_t> on_screen;  // either eye; empty: every triangle
    for (int e = 0; e < p_.eyes(); ++e) {
      const EyeWork& work = workload_.work(w.sample_token, e, 1);
      if (work.on_screen.empty()) continue;
      if (on_screen.empty()) on_screen = work.on_screen;
      else
        for (std::size_t t = 0; t < on_screen.size(); ++t) on_screen[t] |= work.on_screen[t];
    }
    w.on_screen = on_screen.empty() ? workload_.triangles()
                                    : static_cast<int64_t>(std::count(on_screen.begin(), on_screen.end(), 1));
    std::vector<int64_t> sizes;
    const std::vector<des::Time> due = message_times(on_screen, per_message, sizes);
    for (std::size_t i = 0; i < due.size(); ++i) {
      co_await sim_.until(start + due[i]);
      port_queue_.push_back(Message{&w, sizes[i], i + 1 == due.size()});
      port_work_.trigger();
      port_work_.reset();
    }
    gp_busy_ += sim_.now() - start;
    stage("TRANSFORM", w.field, -1, "GP", start, sim_.now());
    sample("stage_ms.TRANSFORM", (sim_.now() - start).to_ms());
    sample("triangles_on_screen", static_cast<double>(w.on_screen));
  }
}

// When each message is full, from the field's start: the overhead, then every
// display-list triangle in order (on screen: the full cost; elsewhere: the
// reject cost). The last message also ends the field, after the last triangle.
std::vector<des::Time> SlatsEngine::message_times(const std::vector<uint8_t>& on_screen, int64_t per_message,
                                                  std::vector<int64_t>& sizes) const {
  std::vector<des::Time> due;
  const int64_t n = workload_.triangles();
  if (on_screen.empty()) {
    // Every triangle on screen: the times follow from the index alone.
    for (int64_t done = 0; done < n;) {
      const int64_t m = std::min(per_message, n - done);
      done += m;
      due.push_back(p_.gp_field_overhead + p_.gp_time_per_triangle * done);
      sizes.push_back(m);
    }
  } else {
    des::Time t = p_.gp_field_overhead;
    int64_t filling = 0;
    for (int64_t i = 0; i < n; ++i) {
      const bool visible = on_screen[static_cast<std::size_t>(i)] != 0;
      t += visible ? p_.gp_time_per_triangle : p_.gp_time_per_rejected_triangle;
      if (visible && ++filling == per_message) {
        due.push_back(t);
        sizes.push_back(filling);
        filling = 0;
      }
    }
    // Whatever is left (perhaps nothing) goes with the end of the field.
    if (filling > 0 || due.empty() || due.back() != t) {
      due.push_back(t);
      sizes.push_back(filling);
    }
  }
  if (due.empty()) {
    due.push_back(p_.gp_field_overhead);
    sizes.push_back(0);
  }
  return due;
}

SlatsEngine::FieldWork& SlatsEngine::begin_field(int64_t field) {
  // Fields every frame-buffer port has finished are no longer referred to.
  const int64_t oldest_in_use = *std::min_element(copy_position_.begin(), copy_position_.end());
  while (!fields_.empty() && fields_.front()->regions_open == 0 && fields_dropped_ < oldest_in_use) {
    fields_.pop_front();
    ++fields_dropped_;
  }
  auto w = std::make_unique<FieldWork>(sim_, p_.hw.renderers, p_.eyes());
  w->field = field;
  w->sample_token = gp_mailbox_;
  w->transform_start = sim_.now();
  w->regions_held = owned_;
  w->regions_open = static_cast<int>(regions_.size());
  fields_.push_back(std::move(w));
  last_started_ = field;
  field_started_.trigger();
  field_started_.reset();
  return *fields_.back();
}

// Fields whose retraces came and went while the GP was busy: no region of
// theirs is ever written, so the display keeps the previous field of the same parity.
void SlatsEngine::give_up_fields(int64_t first, int64_t last) {
  const int64_t n = std::max<int64_t>(0, last - first + 1);
  counts_.missed += n;
  counts_.never_started += n;
}

// The GP's ring port sends each message to every renderer in turn, each
// transfer over whichever ring channel is free.
des::Process SlatsEngine::port_process() {
  for (;;) {
    while (port_queue_.empty()) co_await port_work_;
    const Message m = port_queue_.front();
    port_queue_.pop_front();
    const int64_t words = m.triangles * p_.hw.words_per_command * p_.eyes();
    for (int r = 0; r < p_.hw.renderers; ++r) {
      co_await ring_.acquire();
      const int channel = ring_.claim();
      const des::Time start = sim_.now();
      co_await sim_.delay(p_.hw.transfer_time(words));
      ring_.release(channel);
      if (words > 0) stage("MESSAGE", m.work->field, -1, unit_name("ring", channel), start, sim_.now());
      inbox_[r].push_back(m);
      inbox_arrival_[r]->trigger();
      inbox_arrival_[r]->reset();
    }
  }
}

// A renderer starts a field once its previous regions are copied out, then
// renders each command into every region it owns as messages arrive, and
// finishes its regions after the field's last message.
des::Process SlatsEngine::renderer_process(int r) {
  const std::string unit = unit_name("R", r);
  bool in_field = false;
  des::Time field_start;
  for (;;) {
    while (inbox_[r].empty()) co_await *inbox_arrival_[r];
    const Message m = inbox_[r].front();
    inbox_[r].pop_front();
    FieldWork& w = *m.work;
    if (!in_field) {
      co_await *renderer_free_[r];
      renderer_free_[r]->reset();
      in_field = true;
      field_start = sim_.now();
      w.render_start = std::min(w.render_start, field_start);
    }
    des::Time work = p_.hw.render_time_per_command * (m.triangles * owned_[r]);
    if (m.last) work += p_.region_finish_time * owned_[r];
    co_await sim_.delay(work);
    renderer_busy_ += work;
    if (!m.last) continue;
    in_field = false;
    w.render_end = std::max(w.render_end, sim_.now());
    stage("RENDER", w.field, -1, unit, field_start, sim_.now());
    w.rendered[r]->trigger();
  }
}

Utilisation SlatsEngine::utilisation(des::Time elapsed) const {
  Utilisation u;
  if (elapsed <= des::Time::zero()) return u;
  const double t = elapsed.to_seconds();
  des::Time copy = des::Time::zero();
  for (const auto& port : fb_ports_) copy += port->busy_time();
  u.gp = gp_busy_.to_seconds() / t;
  u.renderer = renderer_busy_.to_seconds() / (t * p_.hw.renderers);
  u.ring = ring_.unit_busy_time().to_seconds() / (t * ring_.channels());
  u.copy = copy.to_seconds() / (t * static_cast<double>(fb_ports_.size()));
  return u;
}

}  // namespace latsim::pxpl5
