#include "streaming/streaming_pipeline.hpp"

#include <algorithm>
#include <cmath>

#include "latsim/results/figure_writer.hpp"
#include "latsim/results/frame_recorder.hpp"
#include "latsim/results/timeline.hpp"

namespace latsim::pipelines::streaming {

namespace {
// A video packet's tag: frame and slice (slices are at most this many).
constexpr int64_t kSlicesPerTag = 1024;
// Frames kept after they are shown or dropped: enough for any late packet.
constexpr int64_t kKeepFrames = 64;

des::Time seconds_for(double amount, double per_second) {
  return per_second > 0.0 ? des::Time::from_seconds(amount / per_second) : des::Time::zero();
}
}  // namespace

StreamingPipeline::StreamingPipeline(const Params& params) : spec_(params.spec) {}
StreamingPipeline::~StreamingPipeline() = default;

int64_t StreamingPipeline::frame_bytes(const EncoderSpec& e, des::Time frame_period) {
  return std::max<int64_t>(1, std::llround(e.bitrate_mbps * 1e6 * frame_period.to_seconds() / 8.0));
}

des::Time StreamingPipeline::encode_time(const EncoderSpec& e, int64_t bytes) {
  return e.fixed + seconds_for(static_cast<double>(e.width_px * e.height_px), e.pixel_rate_mpx_s * 1e6) +
         seconds_for(8.0 * static_cast<double>(bytes), e.bit_rate_mbit_s * 1e6);
}

des::Time StreamingPipeline::decode_time(const ClientSpec& c, const EncoderSpec& e) {
  return c.decoder_fixed + seconds_for(static_cast<double>(e.width_px * e.height_px), c.decoder_pixel_rate_mpx_s * 1e6);
}

void StreamingPipeline::start(RunContext& ctx) {
  ctx_ = &ctx;
  ctx.signals.shows_images();
  ctx.app_frames.declare({.missed = false, .rate = true}, {.sync_interval = 1, .allows_tearing = false});
  const display::RasterTiming& timing = ctx.display.timing();
  period_ = timing.field_start(1) - timing.field_start(0);
  frame_bytes_ = frame_bytes(spec_.encoder, period_);
  encode_ = encode_time(spec_.encoder, frame_bytes_);
  decode_ = decode_time(spec_.client, spec_.encoder);
  game_stream_ = std::make_unique<des::RandomStream>(ctx.stream("streaming.game"));
  kind_game_ = ctx.sim.kind("streaming.game");
  kind_compositor_ = ctx.sim.kind("streaming.server_compositor");
  kind_slice_ = ctx.sim.kind("streaming.encoder");
  kind_decode_ = ctx.sim.kind("streaming.decoder");
  kind_client_ = ctx.sim.kind("streaming.client_compositor");
  kind_report_ = ctx.sim.kind("streaming.pose_report");

  const LinkSpec& l = spec_.link;
  bss_ = std::make_unique<radio::Bss>(ctx.sim, radio::PhyRate(l.phy), l.mac, ctx.stream("radio"), "radio");
  ap_ = bss_->add_station("ap", l.video_edca);
  headset_ = bss_->add_station("headset", l.headset_edca);
  if (l.mpdu_error_rate > 0.0) bss_->set_error_rate(l.mpdu_error_rate);
  if (!l.lose_first_transmission.empty())
    bss_->set_forced_loss([this](const radio::Packet& p) { return p.retries == 0 && lose_ids_.count(p.id) > 0; });
  bss_->on_delivered([this](const radio::Packet& p, des::Time at) { on_delivered(p, at); });
  bss_->on_lost([this](const radio::Packet& p, radio::LossReason) { on_lost(p); });
  if (l.background_mbps > 0.0) {
    // Another client's upload to the same access point, best effort.
    const int other = bss_->add_station("other", radio::EdcaParams::for_category("BE"));
    radio::TrafficParams t{other, ap_, l.background_mbps * 1e6, l.background_packet_bytes,
                           radio::TrafficParams::Arrivals::poisson};
    background_ = std::make_unique<radio::TrafficSource>(ctx.sim, *bss_, t, ctx.stream("radio.background"));
    background_->start(des::Time::zero(), ctx.duration);
  }
  ctx.display.on_retrace([this](int64_t field, des::Time retrace) {
    const des::Time game = retrace + spec_.server.game_offset;
    if (game <= ctx_->duration) ctx_->sim.at(game, kind_game_, [this, field] { start_game(field); });
    const des::Time next = ctx_->display.timing().field_start(field + 1) - spec_.client.compositor_lead;
    if (next >= ctx_->sim.now() && next <= ctx_->duration)
      ctx_->sim.at(next, kind_client_, [this, field] { compose(field + 1); });
  });
  report_pose(0);
}

void StreamingPipeline::report_pose(int64_t i) {
  // Report i leaves the headset at i report periods: the newest sample it sees then.
  const des::PeriodicSchedule reports(des::Time::zero(), spec_.link.pose_report_period);
  if (ctx_->host.newest_at(ctx_->sim.now())) {
    bss_->send(headset_, ap_, spec_.link.pose_report_bytes, i);
    ++pose_reports_sent_;
  }
  const des::Time next = reports.at(i + 1);
  if (next <= ctx_->duration) ctx_->sim.at(next, kind_report_, [this, i] { report_pose(i + 1); });
}

des::Time StreamingPipeline::latency_estimate() const {
  if (measured_latency_.empty()) return spec_.server.initial_latency_estimate;
  des::Time sum;
  for (const des::Time t : measured_latency_) sum += t;
  return des::Time::ps(sum.ticks() / static_cast<int64_t>(measured_latency_.size()));
}

void StreamingPipeline::start_game(int64_t k) {
  const des::Time now = ctx_->sim.now();
  if (!newest_report_) return;  // the server has no pose yet
  if (gpu_free_ > now) {
    ++game_skipped_;  // the previous frame still holds the PC's GPU
    return;
  }
  // The pose the newest report carried, predicted to the expected photon time.
  const des::Time target = now + latency_estimate();
  const std::optional<tracker::PosePrediction> pose = ctx_->host.pose_for(*newest_report_, target);
  if (!pose) return;
  Frame f;
  f.pose = *pose;
  f.report_sent = *newest_report_;
  f.report_received = newest_report_received_;
  f.game_start = now;
  f.target = target;
  f.game_end = now + spec_.server.game.frame_time(*game_stream_);
  f.compositor_end = f.game_end + spec_.server.server_compositor;
  gpu_free_ = f.compositor_end;
  frames_.emplace(k, f);
  ++game_frames_;
  results::FrameTimes times;
  times.frame = k;
  times.gpu_start = now;
  times.present = times.gpu_end = f.game_end;
  times.gpu_busy = f.game_end - now;
  ctx_->app_frames.rendered(times);
  ctx_->sim.at(f.compositor_end, kind_compositor_, [this, k] { end_server_compositor(k); });
}

void StreamingPipeline::end_server_compositor(int64_t k) {
  Frame& f = frames_.at(k);
  // The encoder takes frames in order, one at a time.
  f.encode_start = std::max(ctx_->sim.now(), encoder_free_);
  f.encode_end = f.encode_start + encode_;
  encoder_free_ = f.encode_end;
  const int n = spec_.encoder.slices;
  for (int s = 0; s < n; ++s) {
    // Slice s is encoded by the (s + 1)-th n-th of the frame's encoder time.
    const des::Time done = f.encode_start + des::Time::ps(encode_.ticks() * (s + 1) / n);
    ctx_->sim.at(done, kind_slice_, [this, k, s] { send_slice(k, s); });
  }
}

void StreamingPipeline::send_slice(int64_t k, int slice) {
  auto it = frames_.find(k);
  if (it == frames_.end()) return;
  const int n = spec_.encoder.slices;
  const int64_t bytes = frame_bytes_ * (slice + 1) / n - frame_bytes_ * slice / n;
  const int64_t payload = spec_.link.payload_bytes;
  const int64_t packets = std::max<int64_t>(1, (bytes + payload - 1) / payload);
  it->second.packets_left += packets;
  ++it->second.slices_sent;
  if (slice == n - 1 && ctx_->timeline)
    ctx_->timeline->add("ENCODE", k, -1, "encoder", it->second.encode_start, it->second.encode_end);
  for (int64_t i = 0; i < packets; ++i) {
    const int64_t body = std::min(payload, bytes - i * payload);
    const int64_t id =
        bss_->send(ap_, headset_, std::max<int64_t>(1, body) + spec_.link.header_bytes, k * kSlicesPerTag + slice);
    const std::vector<int64_t>& lose = spec_.link.lose_first_transmission;
    if (std::find(lose.begin(), lose.end(), packets_sent_) != lose.end()) lose_ids_.insert(id);
    ++packets_sent_;
  }
}

void StreamingPipeline::on_delivered(const radio::Packet& p, des::Time at) {
  if (p.from == headset_) {
    // A pose report reached the server: its pose is the newest the server has.
    const des::Time sent = des::PeriodicSchedule(des::Time::zero(), spec_.link.pose_report_period).at(p.tag);
    if (!newest_report_ || sent > *newest_report_) {
      newest_report_ = sent;
      newest_report_received_ = at;
    }
    return;
  }
  if (p.from != ap_) return;  // background traffic
  const int64_t k = p.tag / kSlicesPerTag;
  auto it = frames_.find(k);
  if (it == frames_.end()) return;
  Frame& f = it->second;
  // Slices yet to be encoded have not added their packets: complete only after the last slice.
  if (--f.packets_left > 0 || f.incomplete || f.slices_sent < spec_.encoder.slices) return;
  f.received = at;
  // The decoder takes whole frames in order of arrival, one at a time.
  f.decode_start = std::max(at, decoder_free_);
  f.decode_end = f.decode_start + decode_;
  decoder_free_ = f.decode_end;
  ctx_->sim.at(f.decode_end, kind_decode_, [this, k] { decoded(k); });
}

void StreamingPipeline::on_lost(const radio::Packet& p) {
  if (p.from != ap_) return;  // a lost pose report: the server keeps the previous one
  auto it = frames_.find(p.tag / kSlicesPerTag);
  if (it == frames_.end() || it->second.incomplete) return;
  // A frame missing a packet cannot be decoded: it is dropped.
  it->second.incomplete = true;
  ++frames_incomplete_;
}

void StreamingPipeline::decoded(int64_t k) {
  if (ctx_->timeline) {
    const Frame& f = frames_.at(k);
    ctx_->timeline->add("DECODE", k, -1, "decoder", f.decode_start, f.decode_end);
  }
  if (newest_decoded_ && *newest_decoded_ > k) return;  // an older frame decoded after a newer one
  if (newest_decoded_ && !frames_.at(*newest_decoded_).picked) ++frames_superseded_;
  newest_decoded_ = k;
  forget_older_than(k - kKeepFrames);
}

void StreamingPipeline::forget_older_than(int64_t k) {
  while (!frames_.empty() && frames_.begin()->first < k) frames_.erase(frames_.begin());
}

void StreamingPipeline::compose(int64_t field) {
  if (!newest_decoded_) {
    ++refreshes_without_image_;
    return;
  }
  ctx_->signals.image_due(ctx_->display.timing().field_start(field));
  const des::Time now = ctx_->sim.now();
  const std::optional<tracker::PosePrediction> local = ctx_->host.pose_for(now, ctx_->frame_photon_time(field));
  const int64_t k = *newest_decoded_;
  Frame& f = frames_.at(k);
  if (f.picked) ++frames_rewarped_;
  f.picked = true;
  const des::Time end = now + spec_.client.client_compositor;
  ctx_->sim.at(end, kind_client_, [this, field, k, pose = *local, now] { composed(field, k, pose, now); });
}

void StreamingPipeline::composed(int64_t field, int64_t k, const tracker::PosePrediction& local, des::Time start) {
  Frame& f = frames_.at(k);
  const des::Time now = ctx_->sim.now();
  const int64_t shown_field = ctx_->display.timing().field_at_or_after(now);
  if (shown_field > field) ++warps_late_;
  for (int eye = 0; eye < ctx_->display.eyes(); ++eye) {
    results::ImageRecord rec = ctx_->image_record(k, eye, f.pose, start, now);
    if (spec_.client.reprojection) {
      // Rotation re-projection: the position stays the server's, the
      // orientation is the headset's newest, predicted to this refresh.
      rec.warp = results::ImageRecord::Warp::rotation;
      rec.source_pose = ctx_->eye_pose(f.pose.pose, eye);
      rec.eye_pose.position_m = rec.source_pose.position_m;
      rec.eye_pose.orientation = ctx_->eye_pose(local.pose, eye).orientation;
      rec.orientation_measured_at = local.sample.measured_at;
      rec.predicted_for = local.target;
      rec.head_pose.orientation = local.pose.orientation;
    }
    ctx_->display.present_at_next_retrace(eye, ctx_->images.add(rec));
  }
  if (ctx_->timeline) ctx_->timeline->add("CLIENT_COMPOSITOR", k, -1, "headset_gpu", start, now);
  if (!f.shown) first_shown(f, k, shown_field, start, now);
}

void StreamingPipeline::first_shown(Frame& f, int64_t k, int64_t field, des::Time start, des::Time end) {
  f.shown = true;
  ++frames_shown_;
  ctx_->app_frames.flipped(k, ctx_->display.timing().field_start(field));
  // Late: lit a refresh or more after the photon time the server predicted for.
  const des::Time photon = ctx_->frame_photon_time(field);
  if (photon > f.target + des::Time::ps(period_.ticks() / 2)) ++frames_late_;
  results::FigureWriter& r = ctx_->figures;
  // ALVR's statistics (alvr/client_core/src/statistics.rs and
  // alvr/server_core/src/statistics.rs): the total from the tracking's
  // sending to the submit plus the runtime's vsync queue, which ends at the
  // display time the runtime predicts for the refresh (OpenXR's
  // predictedDisplayTime: the photon time of the field, not its retrace).
  // The game from the tracking's arrival at the server to the frame's
  // present; the decoder from the frame's arrival (its wait for the decoder
  // included); the decoder queue until a composition takes it; the network
  // the rest of the total, uplink and downlink together.
  const des::Time display_time = photon;
  const des::Time total = display_time - f.report_sent;
  const des::Time game = f.game_end - f.report_received;
  const des::Time server_compositor = f.compositor_end - f.game_end;
  const des::Time encoder = f.encode_end - f.compositor_end;
  const des::Time decoder = f.decode_end - f.received;
  const des::Time decoder_queue = start - f.decode_end;
  const des::Time client_compositor = end - start;
  const des::Time vsync_queue = display_time - end;
  r.add("game_ms", game.to_ms());
  r.add("server_compositor_ms", server_compositor.to_ms());
  r.add("encoder_ms", encoder.to_ms());
  r.add("network_ms",
        (total - game - server_compositor - encoder - decoder - decoder_queue - client_compositor - vsync_queue).to_ms());
  r.add("decoder_ms", decoder.to_ms());
  r.add("decoder_queue_ms", decoder_queue.to_ms());
  r.add("client_compositor_ms", client_compositor.to_ms());
  r.add("vsync_queue_ms", vsync_queue.to_ms());
  // What the tool reports: from the tracking the headset sent to the predicted display time of the refresh that showed it.
  r.add("reported_total_ms", total.to_ms());
  // Measured directly: the encoder's end to the frame's last packet received; the report's trip.
  r.add("downlink_ms", (f.received - f.encode_end).to_ms());
  r.add("uplink_ms", (f.report_received - f.report_sent).to_ms());
  measured_latency_.push_back(photon - f.game_start);
  while (static_cast<int>(measured_latency_.size()) > spec_.server.latency_estimate_frames) measured_latency_.pop_front();
}

void StreamingPipeline::finish(RunContext& ctx) {
  results::FigureWriter& r = ctx.figures;
  // Frames never shown: dropped on the link, or superseded by a newer one before any refresh picked them.
  r.set("game_frames", game_frames_);
  r.set("game_frames_skipped", game_skipped_);
  r.set("frames_shown", frames_shown_);
  r.set("frames_late", frames_late_);
  r.set("frames_dropped", frames_incomplete_ + frames_superseded_);
  r.set("frames_incomplete", frames_incomplete_);
  r.set("frames_superseded", frames_superseded_);
  r.set("frames_rewarped", frames_rewarped_);
  r.set("refreshes_without_image", refreshes_without_image_);
  r.set("warps_late", warps_late_);
  r.set("encoder_frame_time_ms", encode_.to_ms());
  r.set("frame_bytes", frame_bytes_);
  r.set("pose_reports_sent", pose_reports_sent_);
  const radio::LinkCounts& c = bss_->counts();
  r.set("link.data_rate_mbps", bss_->phy().data_rate_bps() / 1e6);
  r.set("link.packets_sent", packets_sent_);
  r.set("link.ppdus", c.ppdus);
  r.set("link.collisions", c.collisions);
  r.set("link.retransmissions", c.retransmissions);
  r.set("link.lost", c.lost);
  r.set("link.busy_fraction", ctx.sim.now() > des::Time::zero() ? c.busy.to_seconds() / ctx.sim.now().to_seconds() : 0.0);
  r.use_headline("streaming");
  if (frames_incomplete_ > 0)
    r.warn(std::to_string(frames_incomplete_) + " frames lost a packet on the link and were dropped (frames_incomplete)");
}

std::vector<EventRate> StreamingPipeline::event_rates(const sections::SharedParams& shared) const {
  const double fields_per_s = 1.0 / shared.display.raster.field_period.to_seconds();
  const int64_t bytes =
      frame_bytes(spec_.encoder, des::Time::from_seconds(shared.display.raster.field_period.to_seconds()));
  const double packets = std::ceil(static_cast<double>(bytes) / static_cast<double>(spec_.link.payload_bytes));
  const double reports_per_s = 1.0 / spec_.link.pose_report_period.to_seconds();
  // Per frame: game, server compositor, one event per slice, decoder, and the
  // client compositor's start and end; per report one.
  const double streaming_per_s = (5.0 + spec_.encoder.slices) * fields_per_s + reports_per_s;
  // The link: one reception per packet, and an access and an exchange per
  // PPDU (a report, or an A-MPDU of a frame's packets: at least one per
  // slice); background packets: arrival, reception, access and exchange.
  const LinkSpec& l = spec_.link;
  const double background_per_s = l.background_mbps * 1e6 / (8.0 * static_cast<double>(l.background_packet_bytes));
  const double radio_per_s = (packets + 2.0 * spec_.encoder.slices) * fields_per_s + 3.0 * reports_per_s +
                             4.0 * background_per_s;
  return {{"/display/refresh_hz", "streaming", streaming_per_s}, {"/pipeline/link", "radio", radio_per_s}};
}

}  // namespace latsim::pipelines::streaming
