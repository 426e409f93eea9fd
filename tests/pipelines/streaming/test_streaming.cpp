// The streaming pipeline on hand-derivable links: an idle link with fixed
// encoder and decoder times, the gain of sending slices as they are encoded,
// the tool's own total beside the camera's motion-to-photon latency, and a
// lossy link that drops frames.
//
// Throughout: a 60 Hz progressive display (16.667 ms fields, 640 x 480, 45
// blank lines, phase 0) scanned line by line and lit as written; the tracker
// at phase 0 on a direct link; the link VHT MCS 9, 80 MHz, 2 streams, 800 ns
// GI (3120 data bits per 4 us symbol, a 44 us preamble, 2 BCC encoders: 12
// tail bits), responses at 24 Mb/s, SIFS 16 us, slot 9 us, both stations
// AIFSN 2 with contention windows of 0 (no random backoff). A packet that
// finds the medium idle goes at the next slot boundary after AIFS: within
// AIFS + one slot = 27 us of being queued.
#include <catch2/catch.hpp>

#include "run_helpers.hpp"

using latsim::testing::fig;
using latsim::testing::run;
using Json = nlohmann::json;

namespace {

constexpr double kFieldMs = 1000.0 / 60.0;
constexpr double kAccessMaxMs = 0.027;  // AIFS (18 us) + one slot (9 us)

/// Game 1 ms from 2 ms after each retrace, server compositor 1 ms, encoder
/// 3 ms, decoder 4 ms, client compositor 1 ms from 2 ms before each retrace.
Json streamed(double bitrate_mbps, int slices, double encoder_ms, int tracker_hz, bool reprojection) {
  const Json edca = {{"aifsn", 2}, {"cw_min", 0}, {"cw_max", 0}, {"txop_limit_us", 0}};
  return {{"duration_s", 2},
          {"seed", 7},
          {"motion", {{"type", "constant"}, {"axis", {0, 1, 0}}, {"rate_deg_s", 30}}},
          {"tracker", {{"rate_hz", tracker_hz}, {"phase_ms", 0}, {"internal_delay_ms", 0}}},
          {"transport", {{"type", "direct"}}},
          {"display",
           {{"refresh_hz", 60}, {"width_px", 640}, {"height_px", 480}, {"vblank_lines", 45}, {"hfov_deg", 60},
            {"phase_ms", 0}, {"scanout", "line"}}},
          {"pipeline",
           {{"type", "streaming"},
            {"server", {{"render", {{"fixed_ms", 1}}}, {"game_offset_ms", 2}, {"server_compositor_ms", 1}}},
            {"encoder", {{"bitrate_mbps", bitrate_mbps}, {"fixed_ms", encoder_ms}, {"slices", slices}}},
            {"link",
             {{"phy",
               {{"standard", "vht"}, {"mcs", 9}, {"channel_width_mhz", 80}, {"spatial_streams", 2},
                {"guard_interval_ns", 800}}},
              {"video_edca", edca},
              {"headset_edca", edca},
              {"pose_report_hz", 60},
              {"pose_report_bytes", 100}}},
            {"client",
             {{"decoder_fixed_ms", 4},
              {"client_compositor_ms", 1},
              {"compositor_lead_ms", 2},
              {"reprojection", reprojection}}}}}};
}

double stat(const Json& out, const char* name, const char* s) { return fig(out, name).at(s).get<double>(); }

}  // namespace

TEST_CASE("streaming: an idle link with fixed encoder and decoder times gives the derived latency") {
  // One 1000-byte frame (0.48 Mb/s at 60 Hz: 480000 / 60 / 8 bytes), one
  // 1028-byte datagram with its IP and UDP headers: MPDU 1028 + 8 + 26 + 4 =
  // 1066 bytes, subframe 1070: 16 + 8560 + 12 bits -> 3 symbols, 56 us.
  // The report sent at retrace k carries sample k (tracker at 60 Hz, phase
  // 0): its 100-byte datagram (a 142-byte subframe, one symbol, 48 us) is at
  // the server within 27 + 48 us, long before the game starts at k + 2 ms.
  // Game ends at 3 ms, compositor at 4, encoder at 7, the packet is received
  // 56 to 83 us later, decoded 4 ms later (about 11.1 ms); the client
  // compositor for retrace k + 1 starts at 16.667 - 2 = 14.667 ms and ends at
  // 15.667: shown at retrace k + 1. Every frame: sample k at retrace k shown
  // from retrace k + 1. The tool's total ends, as ALVR's does, at the display
  // time the runtime predicts for that refresh: the photon time of its middle
  // active line, 480 / 2 = 240, lit as written 45 + 240 = 285 line periods
  // (of 16.667 / 525 ms) after the retrace: 16.667 + 9.048 = 25.714 ms. The
  // camera sees the first active line (45 blank lines of 525 into the field,
  // 1.429 ms) lit 18.095 ms after the sample.
  const Json out = run(streamed(0.48, 1, 3.0, 60, false));
  const Json& f = out.at("figures");
  CHECK(f.at("frame_bytes").get<int64_t>() == 1000);
  // The stages as ALVR names them: the game from the report's arrival
  // (48 to 75 us after the retrace) to its end at 3 ms; the decoder queue
  // from the decoder's end to the composition at 14.667 ms; the network the
  // rest of the total: the report's uplink and the frame's downlink.
  CHECK(stat(out, "uplink_ms", "min") >= 0.048 - 1e-9);
  CHECK(stat(out, "uplink_ms", "max") <= 0.048 + kAccessMaxMs + 1e-9);
  CHECK(stat(out, "downlink_ms", "min") >= 0.056 - 1e-9);
  CHECK(stat(out, "downlink_ms", "max") <= 0.056 + kAccessMaxMs + 1e-9);
  CHECK(stat(out, "game_ms", "mean") == Approx(3.0 - stat(out, "uplink_ms", "mean")).margin(1e-9));
  CHECK(stat(out, "server_compositor_ms", "mean") == Approx(1.0));
  CHECK(stat(out, "encoder_ms", "max") == Approx(3.0));
  CHECK(stat(out, "decoder_ms", "mean") == Approx(4.0));
  CHECK(stat(out, "decoder_queue_ms", "mean") ==
        Approx(kFieldMs - 2.0 - 7.0 - stat(out, "downlink_ms", "mean") - 4.0).margin(1e-9));
  CHECK(stat(out, "network_ms", "mean") ==
        Approx(stat(out, "uplink_ms", "mean") + stat(out, "downlink_ms", "mean")).margin(1e-9));
  CHECK(stat(out, "client_compositor_ms", "mean") == Approx(1.0));
  const double line_ms = kFieldMs / 525.0;
  // From the composition's end, 1 ms before the retrace, to the predicted display time.
  CHECK(stat(out, "vsync_queue_ms", "mean") == Approx(1.0 + 285 * line_ms).margin(1e-6));
  CHECK(stat(out, "reported_total_ms", "min") == Approx(kFieldMs + 285 * line_ms).margin(1e-6));
  CHECK(stat(out, "reported_total_ms", "max") == Approx(kFieldMs + 285 * line_ms).margin(1e-6));
  CHECK(stat(out, "motion_to_photon_ms", "min") == Approx(kFieldMs + 45 * line_ms).margin(1e-6));
  CHECK(stat(out, "motion_to_photon_ms", "max") == Approx(kFieldMs + 524 * line_ms).margin(1e-6));
  // The camera's mean is over the active lines, 45 + 479 / 2 = 284.5 line
  // periods after the retrace: half a line period before the tool's end.
  CHECK(stat(out, "motion_to_photon_ms", "mean") - stat(out, "reported_total_ms", "mean") ==
        Approx(-0.5 * line_ms).margin(1e-3));
  CHECK(f.at("frames_late").get<int64_t>() == 0);
  CHECK(f.at("frames_dropped").get<int64_t>() == 0);
  CHECK(f.at("frames_rewarped").get<int64_t>() == 0);
  // Retraces 0 to 120 in 2 s. Report 0 leaves as the run starts, before the
  // tracker's first sample is visible, so it is not sent and frame 0 has no
  // pose: frames 1 to 119 are shown at retraces 2 to 120 (the last at exactly
  // 2 s), and retrace 1 has no image.
  CHECK(f.at("pose_reports_sent").get<int64_t>() == 120);
  CHECK(f.at("frames_shown").get<int64_t>() == 119);
  CHECK(f.at("refreshes_without_image").get<int64_t>() == 1);
}

TEST_CASE("streaming: the client re-projects with its newest local orientation") {
  // The same chain with a 1000 Hz tracker: the report sent at retrace k
  // still carries the sample of retrace k (on a whole millisecond only every
  // third field: k * 16.667 ms), but the client compositor reads the newest
  // local sample at 14.667 ms after retrace k, the one at floor(...) ms. The
  // orientation's latency at the first active line is then the retrace
  // k + 1 (16.667 ms after k), less that sample, plus 1.429 ms of blanking:
  // over k mod 3 = 0, 1, 2 the compositor starts at 14.667, 31.333, 48.0 ms
  // and reads the samples at 14, 31, 48 ms: 2.667, 2.333 and 2.0 ms before
  // the retrace.
  const Json out = run(streamed(0.48, 1, 3.0, 1000, true));
  const double blank_ms = 45 * kFieldMs / 525.0;
  CHECK(stat(out, "rotation_latency_ms", "min") == Approx(2.0 + blank_ms).margin(1e-6));
  // The position stays the server's: its latency is the whole chain's.
  CHECK(stat(out, "motion_to_photon_ms", "min") == Approx(kFieldMs + blank_ms).margin(1e-6));
}

TEST_CASE("streaming: slices sent as they are encoded save the airtime of all but the last slice") {
  // A frame of 56000 bytes (26.88 Mb/s at 60 Hz), 40 datagrams of 1428
  // bytes: MPDUs of 1466 bytes, subframes of 1470 padded to 1472.
  // Whole frame: the 40 MPDUs go in one A-MPDU (39 * 1472 + 1470 = 58878
  // bytes, under 65535) after the 8 ms encoder: 16 + 471024 + 12 bits ->
  // 151 symbols, 44 + 604 = 648 us, its last MPDU received at its end.
  // Four slices of 14000 bytes (10 datagrams each), each sent when its
  // quarter of the 8 ms is done: the first three are on the air and answered
  // long before the encoder ends (196 + 16 + 32 us each, every 2 ms); the
  // last, 9 * 1472 + 1470 = 14718 bytes, 16 + 117744 + 12 bits -> 38
  // symbols, 44 + 152 = 196 us after the encoder ends. Either way the
  // packets wait up to 27 us for the medium. The gain: 648 - 196 = 452 us.
  const Json whole = run(streamed(26.88, 1, 8.0, 60, false));
  const Json sliced = run(streamed(26.88, 4, 8.0, 60, false));
  CHECK(whole.at("figures").at("frame_bytes").get<int64_t>() == 56000);
  CHECK(stat(whole, "downlink_ms", "min") >= 0.648 - 1e-9);
  CHECK(stat(whole, "downlink_ms", "max") <= 0.648 + kAccessMaxMs + 1e-9);
  CHECK(stat(sliced, "downlink_ms", "min") >= 0.196 - 1e-9);
  CHECK(stat(sliced, "downlink_ms", "max") <= 0.196 + kAccessMaxMs + 1e-9);
  CHECK(stat(whole, "downlink_ms", "mean") - stat(sliced, "downlink_ms", "mean") ==
        Approx(0.452).margin(kAccessMaxMs));
  // Either way the frame is decoded by 2 + 1 + 1 + 8 + 0.675 + 4 = 16.7 ms
  // after retrace k, after the composition for retrace k + 1 (14.667 ms) and
  // long before the one for k + 2: the saving waits in the decoder queue.
  CHECK(whole.at("figures").at("frames_dropped").get<int64_t>() == 0);
  CHECK(sliced.at("figures").at("frames_dropped").get<int64_t>() == 0);
  CHECK(stat(sliced, "reported_total_ms", "mean") == Approx(stat(whole, "reported_total_ms", "mean")));
}

TEST_CASE("streaming: a lossy link drops the frames it cannot deliver, deterministically") {
  // With every MPDU transmission lost, nothing arrives: no pose report
  // reaches the server, so no frame is ever rendered or shown.
  Json dead = streamed(0.48, 1, 3.0, 60, false);
  dead["pipeline"]["link"]["mpdu_error_rate"] = 1.0;
  const Json none = run(dead);
  CHECK(none.at("figures").at("frames_shown").get<int64_t>() == 0);
  CHECK(none.at("figures").at("game_frames").get<int64_t>() == 0);
  // With a retry limit of 0 and a 30 % MPDU error rate, a 40-packet frame
  // arrives whole with probability 0.7^40 (about 6e-7): nearly every frame
  // is dropped, and the display re-projects the few that came through.
  Json lossy = streamed(26.88, 1, 8.0, 60, false);
  lossy["pipeline"]["link"]["mpdu_error_rate"] = 0.3;
  lossy["pipeline"]["link"]["retry_limit"] = 0;
  const Json a = run(lossy);
  const Json b = run(lossy);
  CHECK(a.at("figures") == b.at("figures"));
  const Json& f = a.at("figures");
  CHECK(f.at("frames_dropped").get<int64_t>() >= f.at("game_frames").get<int64_t>() - 1);
}

TEST_CASE("streaming: one lost packet and its retransmission make a frame miss its refresh") {
  // The idle link's chain with a 7.55 ms decoder. A frame's datagram goes
  // at t0, 7.000 to 7.027 ms after its retrace k, and is received 56 us
  // later: decoded by 7.083 + 7.55 = 14.633 ms, before the composition for
  // retrace k + 1 at 14.667 ms. Datagram 10 (frame 11: frame 0 has no pose)
  // loses its first transmission: no BlockAck, the AP times out at
  // t0 + 56 + 16 + 9 + 20 = t0 + 101 us, may count SIFS later (t0 + 117),
  // its AIFS of 2 slots ends at t0 + 135 us, where the retransmission
  // starts (CW 0): received at t0 + 191 us, 7.191 to 7.218 ms, decoded at
  // 14.741 to 14.768 ms: too late for retrace k + 1, whose composition
  // re-projects frame 10 again. By the composition for retrace k + 2,
  // frame 12 (decoded 16.667 + 14.633 = 31.300 ms at the latest, before
  // 16.667 + 14.667 = 31.333 ms) is newer: frame 11 is never shown.
  Json s = streamed(0.48, 1, 3.0, 60, false);
  s["pipeline"]["client"]["decoder_fixed_ms"] = 7.55;
  s["pipeline"]["link"]["lose_first_transmission"] = {10};
  const Json out = run(s);
  const Json& f = out.at("figures");
  CHECK(f.at("link").at("retransmissions").get<int64_t>() == 1);
  CHECK(f.at("frames_rewarped").get<int64_t>() == 1);
  CHECK(f.at("frames_superseded").get<int64_t>() == 1);
  CHECK(f.at("frames_dropped").get<int64_t>() == 1);
  CHECK(f.at("frames_incomplete").get<int64_t>() == 0);
  CHECK(f.at("frames_shown").get<int64_t>() == 118);
  CHECK(stat(out, "downlink_ms", "max") <= 0.056 + kAccessMaxMs + 1e-9);  // frame 11, never shown, is not counted
  // Without the loss every frame makes its refresh.
  s["pipeline"]["link"].erase("lose_first_transmission");
  const Json clean = run(s);
  CHECK(clean.at("figures").at("frames_dropped").get<int64_t>() == 0);
  CHECK(clean.at("figures").at("frames_rewarped").get<int64_t>() == 0);
  CHECK(clean.at("figures").at("frames_shown").get<int64_t>() == 119);
}
