// What a streamed headset is made of: the PC's stages, the encoder, the
// packetiser, the radio link, the headset's decoder and compositor, as plain
// values (streaming/bind.cpp fills them in from /pipeline).
#pragma once

#include <cstdint>
#include <vector>

#include "latsim/des/time.hpp"
#include "latsim/radio/edca.hpp"
#include "latsim/radio/mac_params.hpp"
#include "latsim/radio/phy_rate.hpp"
#include "latsim/renderer/render_cost.hpp"

namespace latsim::pipelines::streaming {

/// The streaming server on the PC: the game, its compositor and the encoder.
struct ServerSpec {
  renderer::RenderCost::Params render;  ///< the game's frame on the PC's GPU
  renderer::RenderCost game;            ///< resolved against the scene and display
  des::Time game_offset;                ///< frame k starts this long after the headset's retrace k
  des::Time server_compositor;          ///< the server's compositor: layers into the encoder's input
  /// Time to photons the server assumes before it has measured any (the
  /// first frames' prediction horizon from the game's start).
  des::Time initial_latency_estimate = des::Time::ms(40);
  int latency_estimate_frames = 16;     ///< the estimate: mean of the last N frames' game-start-to-photon times
};

/// The video encoder: time from the frame's pixels and bits, whole frames or slices.
struct EncoderSpec {
  int64_t width_px = 3664;          ///< encoded frame, both eyes side by side
  int64_t height_px = 1920;
  double bitrate_mbps = 200.0;      ///< constant bit rate: every frame bitrate / frame rate
  des::Time fixed;                  ///< per frame: set-up and the hand-over of the bitstream
  double pixel_rate_mpx_s = 0.0;    ///< pixels encoded per second (0: no per-pixel time)
  double bit_rate_mbit_s = 0.0;     ///< entropy coding: bits written per second (0: none)
  int slices = 1;                   ///< each slice is packetised and sent as soon as it is encoded
};

/// How the encoded frames travel: UDP datagrams over one Wi-Fi BSS.
struct LinkSpec {
  int64_t payload_bytes = 1400;      ///< video bytes per datagram
  int64_t header_bytes = 28;         ///< IPv4 (20) and UDP (8) headers per datagram
  radio::PhyParams phy;
  radio::MacParams mac;
  radio::EdcaParams video_edca = radio::EdcaParams::for_category("VI");
  radio::EdcaParams headset_edca = radio::EdcaParams::for_category("VI");
  double mpdu_error_rate = 0.0;
  /// Video datagrams (numbered from 0 in the order they are sent) whose
  /// first transmission is lost: a retransmission experiment.
  std::vector<int64_t> lose_first_transmission;
  double background_mbps = 0.0;      ///< other traffic from the access point to another station (Poisson)
  int64_t background_packet_bytes = 1500;
  des::RationalSeconds pose_report_period = des::RationalSeconds::period_of_hz(72);  ///< the headset's tracking reports to the server
  int64_t pose_report_bytes = 128;
};

/// The headset: decoder, compositor and its re-projection.
struct ClientSpec {
  des::Time decoder_fixed;          ///< per frame
  double decoder_pixel_rate_mpx_s = 0.0;  ///< 0: no per-pixel time
  des::Time client_compositor;      ///< re-projection and distortion on the headset's GPU
  des::Time compositor_lead = des::Time::ms(2);  ///< it starts this long before each retrace
  bool reprojection = true;         ///< re-project the newest frame to the newest local orientation
};

/// The whole streamed pipeline.
struct StreamingSpec {
  ServerSpec server;
  EncoderSpec encoder;
  LinkSpec link;
  ClientSpec client;
};

}  // namespace latsim::pipelines::streaming
