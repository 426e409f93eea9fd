// A streamed headset (Air Link, Virtual Desktop, ALVR, WiVRn): the PC renders
// and encodes, the radio link carries the frames, the headset decodes and
// re-projects the newest one before its own scanout (docs/streaming.md).
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <vector>

#include "latsim/des/random.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "latsim/radio/bss.hpp"
#include "latsim/radio/traffic.hpp"
#include "streaming/streaming_spec.hpp"

namespace latsim::pipelines::streaming {

/// Runs the server's frames, the link and the headset's decoder and
/// compositor as events, and reports each stage's time under the names of
/// ALVR's statistics beside the camera's motion-to-photon latency.
class StreamingPipeline final : public Pipeline {
 public:
  struct Params {
    StreamingSpec spec;
  };

  explicit StreamingPipeline(const Params& params);
  ~StreamingPipeline() override;

  void start(RunContext& ctx) override;
  void finish(RunContext& ctx) override;
  std::vector<EventRate> event_rates(const sections::SharedParams& shared) const override;

  /// Encoder time of one whole frame (fixed + pixels / pixel rate + bits / bit rate).
  static des::Time encode_time(const EncoderSpec& e, int64_t frame_bytes);
  /// Decoder time of one frame.
  static des::Time decode_time(const ClientSpec& c, const EncoderSpec& e);
  /// Bytes of every encoded frame: bitrate over the frame rate, whole bytes.
  static int64_t frame_bytes(const EncoderSpec& e, des::Time frame_period);

 private:
  /// One frame from the game's start to its first showing.
  struct Frame {
    tracker::PosePrediction pose;  ///< the server's pose, predicted for the expected photon time
    des::Time report_sent;         ///< when the headset sent the pose report it came from
    des::Time report_received;     ///< when that report reached the server
    des::Time game_start, game_end, compositor_end, encode_start, encode_end;
    des::Time received, decode_start, decode_end;
    int64_t packets_left = 0;
    int slices_sent = 0;
    des::Time target;              ///< the photon time the server predicted for
    bool incomplete = false;       ///< a packet never arrived
    bool picked = false;           ///< a client composition has taken it
    bool shown = false;
  };

  void start_game(int64_t k);
  void end_server_compositor(int64_t k);
  void send_slice(int64_t k, int slice);
  void on_delivered(const radio::Packet& p, des::Time at);
  void on_lost(const radio::Packet& p);
  void decoded(int64_t k);
  void compose(int64_t field);
  void composed(int64_t field, int64_t k, const tracker::PosePrediction& local, des::Time start);
  void first_shown(Frame& f, int64_t k, int64_t field, des::Time start, des::Time end);
  void report_pose(int64_t i);
  des::Time latency_estimate() const;
  void forget_older_than(int64_t k);

  StreamingSpec spec_;
  RunContext* ctx_ = nullptr;
  std::unique_ptr<radio::Bss> bss_;
  std::unique_ptr<radio::TrafficSource> background_;
  std::unique_ptr<des::RandomStream> game_stream_;
  int ap_ = 0, headset_ = 1;
  des::Time period_;                  ///< the headset's refresh period
  int64_t frame_bytes_ = 0;
  des::Time encode_;                  ///< whole-frame encoder time
  des::Time decode_;
  des::Time gpu_free_, encoder_free_, decoder_free_;
  std::optional<des::Time> newest_report_;  ///< newest pose report the server has received (its send time)
  des::Time newest_report_received_;        ///< when it arrived
  std::map<int64_t, Frame> frames_;
  std::set<int64_t> lose_ids_;        ///< link ids of the datagrams whose first transmission is lost
  std::optional<int64_t> newest_decoded_;
  std::deque<des::Time> measured_latency_;  ///< game start to photon time of recent frames
  des::KindId kind_game_ = 0, kind_compositor_ = 0, kind_slice_ = 0, kind_decode_ = 0, kind_client_ = 0,
              kind_report_ = 0;
  int64_t game_frames_ = 0, game_skipped_ = 0, frames_shown_ = 0, frames_late_ = 0, frames_incomplete_ = 0,
          frames_superseded_ = 0, frames_rewarped_ = 0, refreshes_without_image_ = 0, warps_late_ = 0,
          packets_sent_ = 0, pose_reports_sent_ = 0;
};

/// Reads /pipeline of a streaming scenario (streaming/bind.cpp).
void bind(scenario::Section& s, StreamingPipeline::Params& p, const sections::SharedParams& shared);

}  // namespace latsim::pipelines::streaming
