// The streaming pipeline's /pipeline keys: server, encoder, link and client.
#include "latsim/sections/render_cost.hpp"
#include "streaming/streaming_pipeline.hpp"

namespace latsim::pipelines::streaming {

namespace {

void bind_server(scenario::Section& s, ServerSpec& p) {
  s.object("render", p.render, [](scenario::Section& r, renderer::RenderCost::Params& v) { sections::bind(r, v); },
           {.required = true, .doc = "the game's frame on the PC's GPU"});
  s.duration("game_offset_ms", p.game_offset,
             {.unit = "ms", .doc = "frame k starts this long after the headset's retrace k (the server paces to it)"});
  s.duration("server_compositor_ms", p.server_compositor, {.unit = "ms", .doc = "the streaming server's compositor"});
  s.duration("initial_latency_estimate_ms", p.initial_latency_estimate,
             {.unit = "ms", .doc = "prediction horizon from the game's start before any frame has been shown"});
  s.integer("latency_estimate_frames", p.latency_estimate_frames,
            {.min = 1.0, .max = 1000.0, .doc = "frames whose game-start-to-vsync time the server averages"});
}

void bind_encoder(scenario::Section& s, EncoderSpec& p) {
  s.integer("width_px", p.width_px, {.unit = "px", .min = 1.0, .max = 16384.0, .doc = "encoded frame width"});
  s.integer("height_px", p.height_px, {.unit = "px", .min = 1.0, .max = 16384.0, .doc = "encoded frame height"});
  s.number("bitrate_mbps", p.bitrate_mbps, {.unit = "Mb/s", .min = 0.01, .max = 10000.0, .doc = "constant bit rate"});
  s.duration("fixed_ms", p.fixed, {.unit = "ms", .doc = "per frame"});
  s.number("pixel_rate_mpx_s", p.pixel_rate_mpx_s,
           {.unit = "Mpx/s", .min = 0.0, .max = 1e6, .doc = "pixels encoded per second (0: no per-pixel time)"});
  s.number("bit_rate_mbit_s", p.bit_rate_mbit_s,
           {.unit = "Mb/s", .min = 0.0, .max = 1e6, .doc = "bits entropy-coded per second (0: no per-bit time)"});
  s.integer("slices", p.slices, {.min = 1.0, .max = 64.0, .doc = "slices per frame, each sent when encoded"});
}

void bind_edca(scenario::Section& s, radio::EdcaParams& p) {
  s.integer("aifsn", p.aifsn, {.min = 1.0, .max = 15.0, .doc = "slots after SIFS before the backoff counts"});
  s.integer("cw_min", p.cw_min, {.min = 0.0, .max = 32767.0, .doc = "contention window after a success"});
  s.integer("cw_max", p.cw_max, {.min = 0.0, .max = 32767.0, .doc = "largest contention window"});
  s.duration("txop_limit_us", p.txop_limit, {.unit = "us", .doc = "0: one PPDU per access"});
  s.check("cw_max", p.cw_max >= p.cw_min, "cw_max must be at least cw_min");
}

void bind_phy(scenario::Section& s, radio::PhyParams& p) {
  s.choice("standard", p.standard, {{"vht", radio::Standard::vht}, {"he", radio::Standard::he}},
           {.doc = "802.11ac (vht) or 802.11ax (he) single-user PPDUs"});
  s.integer("mcs", p.mcs, {.min = 0.0, .max = 11.0, .doc = "modulation and coding scheme"});
  s.integer("channel_width_mhz", p.channel_width_mhz, {.unit = "MHz", .min = 20.0, .max = 160.0, .doc = "20, 40, 80 or 160"});
  s.integer("spatial_streams", p.spatial_streams, {.min = 1.0, .max = 8.0, .doc = "spatial streams"});
  s.integer("guard_interval_ns", p.guard_interval_ns, {.unit = "ns", .min = 400.0, .max = 3200.0, .doc = "VHT 400/800, HE 800/1600/3200"});
  s.integer("control_rate_mbps", p.control_rate_mbps, {.unit = "Mb/s", .min = 6.0, .max = 54.0, .doc = "Ack and BlockAck rate"});
  s.guard("mcs", [&] { radio::PhyRate check(p); });
}

void bind_link(scenario::Section& s, LinkSpec& p) {
  s.integer("payload_bytes", p.payload_bytes, {.unit = "B", .min = 1.0, .max = 8000.0, .doc = "video bytes per datagram"});
  s.integer("header_bytes", p.header_bytes, {.unit = "B", .min = 0.0, .max = 100.0, .doc = "IP and UDP headers"});
  s.object("phy", p.phy, bind_phy, {.doc = "the PHY of the data frames"});
  s.duration("slot_us", p.mac.slot, {.unit = "us", .above_min = true, .doc = "aSlotTime"});
  s.duration("sifs_us", p.mac.sifs, {.unit = "us", .above_min = true, .doc = "aSIFSTime"});
  s.integer("max_ampdu_bytes", p.mac.max_ampdu_bytes, {.unit = "B", .min = 1600.0, .max = 6500631.0, .doc = "A-MPDU length limit"});
  s.integer("max_ampdu_mpdus", p.mac.max_ampdu_mpdus, {.min = 1.0, .max = 1024.0, .doc = "block-ack window"});
  s.integer("retry_limit", p.mac.retry_limit, {.min = 0.0, .max = 255.0, .doc = "retransmissions of an MPDU"});
  s.integer("queue_packets", p.mac.queue_packets, {.min = 1.0, .max = 1e6, .doc = "per station"});
  s.duration("queue_max_delay_ms", p.mac.queue_max_delay, {.unit = "ms", .above_min = true, .doc = "older packets are discarded"});
  s.object("video_edca", p.video_edca, bind_edca, {.doc = "the access point's EDCA for the video (default AC_VI)"});
  s.object("headset_edca", p.headset_edca, bind_edca, {.doc = "the headset's EDCA for its reports (default AC_VI)"});
  s.number("mpdu_error_rate", p.mpdu_error_rate, {.min = 0.0, .max = 1.0, .doc = "each MPDU transmission lost with it"});
  std::vector<double> lose;
  for (const int64_t n : p.lose_first_transmission) lose.push_back(static_cast<double>(n));
  s.numbers("lose_first_transmission", lose,
            {.min = 0.0, .doc = "video datagrams (from 0, in sending order) whose first transmission is lost"});
  p.lose_first_transmission.clear();
  for (const double n : lose) {
    s.check("lose_first_transmission", n == static_cast<double>(static_cast<int64_t>(n)), "datagram numbers are whole");
    p.lose_first_transmission.push_back(static_cast<int64_t>(n));
  }
  s.number("background_mbps", p.background_mbps, {.unit = "Mb/s", .min = 0.0, .max = 10000.0, .doc = "another client's best-effort upload"});
  s.integer("background_packet_bytes", p.background_packet_bytes, {.unit = "B", .min = 1.0, .max = 8000.0, .doc = "its datagrams"});
  s.rate("pose_report_hz", p.pose_report_period, {.unit = "Hz", .doc = "tracking reports from the headset"});
  s.integer("pose_report_bytes", p.pose_report_bytes, {.unit = "B", .min = 1.0, .max = 8000.0, .doc = "one report's datagram"});
}

void bind_client(scenario::Section& s, ClientSpec& p) {
  s.duration("decoder_fixed_ms", p.decoder_fixed, {.unit = "ms", .doc = "per frame"});
  s.number("decoder_pixel_rate_mpx_s", p.decoder_pixel_rate_mpx_s,
           {.unit = "Mpx/s", .min = 0.0, .max = 1e6, .doc = "pixels decoded per second (0: none)"});
  s.duration("client_compositor_ms", p.client_compositor, {.unit = "ms", .doc = "re-projection on the headset's GPU"});
  s.duration("compositor_lead_ms", p.compositor_lead, {.unit = "ms", .doc = "it starts this long before each retrace"});
  s.flag("reprojection", p.reprojection, {.doc = "re-project the newest frame to the newest local orientation"});
}

}  // namespace

/// Reads /pipeline of a streaming scenario (found by pipeline_entry through its Params).
void bind(scenario::Section& s, StreamingPipeline::Params& p, const sections::SharedParams& shared) {
  StreamingSpec& spec = p.spec;
  s.object("server", spec.server, bind_server, {.required = true, .doc = "the PC: game, compositor"});
  s.object("encoder", spec.encoder, bind_encoder, {.doc = "the video encoder"});
  s.object("link", spec.link, bind_link, {.doc = "the Wi-Fi link"});
  s.object("client", spec.client, bind_client, {.doc = "the headset"});
  const display::RasterParams& raster = shared.display.raster;
  s.guard("server", [&] {
    spec.server.game = sections::render_cost_for_scene(spec.server.render, shared.scene ? &*shared.scene : nullptr,
                                                       raster.width_px, raster.height_px, shared.host.stereo ? 2 : 1);
  });
  s.check("client", spec.client.compositor_lead.to_seconds() < raster.field_period.to_seconds() &&
              spec.client.client_compositor.to_seconds() <= raster.field_period.to_seconds(),
          "the client compositor's lead and time must be shorter than a refresh");
}

}  // namespace latsim::pipelines::streaming

namespace latsim::pipelines {

PipelineEntry streaming_pipeline() {
  return pipeline_entry<streaming::StreamingPipeline>(
      "streaming",
      "A streamed headset: the PC's game and compositor, a video encoder (whole frames or slices), UDP packets over a "
      "packet-level Wi-Fi link (PHY rate, aggregation, EDCA contention, retransmission, loss), the headset's decoder "
      "and its compositor re-projecting the newest decoded frame to the newest local pose; stage times named as "
      "ALVR's statistics name them (docs/streaming.md).");
}

}  // namespace latsim::pipelines
