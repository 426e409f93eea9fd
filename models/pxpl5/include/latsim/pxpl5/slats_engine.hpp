// Slats, the single-field-latency Pixel-Planes 5 pipeline (SPEC.md section 5).
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "latsim/des/process.hpp"
#include "latsim/des/resource.hpp"
#include "latsim/des/signal.hpp"
#include "latsim/des/simulator.hpp"
#include "latsim/pxpl5/engine_hooks.hpp"
#include "latsim/pxpl5/field_timing.hpp"
#include "latsim/pxpl5/hardware.hpp"
#include "latsim/pxpl5/ring.hpp"
#include "latsim/pxpl5/workload.hpp"

namespace latsim::pxpl5 {

/// Costs and options of Slats on top of the shared hardware figures.
///
/// Calibration (SPEC.md section 5: 140 triangles per field at 60 Hz with the
/// COPY optimisation; derivation in docs/pxpl5.md). A 16.67 ms field must
/// hold the GP overhead (0.3 ms), N triangles of GP work, the tail after the
/// last triangle (the last ring message to 5 renderers, its rendering and the
/// region finish) and the 6 copy slots of the top regions (4.68 ms): at 75 us
/// per on-screen triangle (both eyes: transform, clip, light and set up the
/// plane equations twice) 140 fit and 150 do not. A triangle outside both
/// eyes' views costs only its vertex transforms and the clip test.
struct SlatsParams {
  HardwareParams hw;
  bool stereo = true;
  des::Time gp_time_per_triangle = des::Time::us(75);            ///< on screen, both eyes, one pass
  des::Time gp_time_per_rejected_triangle = des::Time::from_us(7.5);  ///< outside both views: transform, reject
  des::Time gp_field_overhead = des::Time::us(300);              ///< take the newest transforms, set up, flush
  des::Time region_finish_time = des::Time::us(50);              ///< Gouraud: no deferred shading, just wrap up
  des::Time host_compute_time = des::Time::us(1000);             ///< host: both eyes' viewing transforms
  int host_message_words = 64;
  bool copy_optimisation = true;
  bool backup_field = false;

  int eyes() const { return stereo ? 2 : 1; }
};

/// Field-synchronous rendering as processes on the machine's resources: the
/// host sends viewing transforms whenever it has a new sample; at each retrace
/// the single GP takes the newest and transforms every triangle for both eyes
/// into one bin, whose full ring messages its port sends to every renderer
/// over a free ring channel; each renderer rasterises the commands into its
/// statically bound field regions once its previous regions are copied out;
/// each frame buffer's port takes its eye's regions in a fixed order, each copy
/// holding the port, the sending renderer and a ring channel. Which field is
/// shown, how much slack a copy had and which fields are missed all come from
/// when these activities end.
class SlatsEngine {
 public:
  /// `workload` must outlive the engine.
  SlatsEngine(des::Simulator& sim, SlatsParams params, FieldTiming timing, RegionGrid grid,
              WorkloadSource& workload, EngineHooks hooks);
  SlatsEngine(const SlatsEngine&) = delete;
  SlatsEngine& operator=(const SlatsEngine&) = delete;

  /// Starts the processes; the GP starts no field at or after `end`.
  void start(des::Time end);
  /// The host can see a new tracker sample now: it computes both eyes'
  /// transforms and sends them to the GP as soon as it is free (SEND runs
  /// asynchronously, as often as new data allow).
  void host_sample(int64_t token);

  Utilisation utilisation(des::Time elapsed) const;
  const FieldCounts& counts() const { return counts_; }
  const SlatsParams& params() const { return p_; }

 private:
  /// One field region: which eye, which row of the field, which renderer owns it.
  struct FieldRegion {
    int eye;
    int row;
    int column;
    int renderer;
  };
  /// The work of one field, from the GP's start at a retrace to the verdict.
  struct FieldWork {
    FieldWork(des::Simulator& sim, int renderers, int eyes);
    int64_t field = 0;  ///< shown from retrace(field) on
    int64_t sample_token = -1;
    des::Time transform_start, render_start, render_end, copy_start = des::Time::max();
    std::vector<std::unique_ptr<des::Signal>> rendered;  ///< per renderer
    std::vector<int> regions_held;                       ///< per renderer: not yet copied out
    std::vector<des::Time> eye_copy_end;
    std::vector<int> eye_on_time;
    int regions_open = 0;
    int late = 0;
    des::Time slack = des::Time::max();
    int64_t on_screen = 0;
  };
  /// A ring message of triangle commands from the GP to every renderer.
  struct Message {
    FieldWork* work;
    int64_t triangles;
    bool last;  ///< the field's final message (its end-of-field)
  };
  /// What a copy slot sends: the region's new pixels, or its backup.
  enum class CopyKind { none, data, backup };
  /// The last complete field a frame buffer's rows of one parity held (backup_field).
  struct Backup {
    int64_t field = -1;
    EyeImage image;
  };

  des::Process host_process();
  des::Process gp_process();
  des::Process port_process();
  des::Process renderer_process(int renderer);
  des::Process copy_process(int eye);

  FieldWork& begin_field(int64_t field);
  void give_up_fields(int64_t first, int64_t last);
  std::vector<des::Time> message_times(const std::vector<uint8_t>& on_screen, int64_t per_message,
                                       std::vector<int64_t>& sizes) const;
  des::Time deadline(const FieldWork& w, const FieldRegion& r) const;
  bool writes_displayed_buffer(const FieldRegion& r) const { return p_.copy_optimisation && r.row > 0; }
  int parity(int64_t field) const { return timing_.interlaced() ? static_cast<int>(field & 1) : 0; }
  int region_in_eye(int index) const { return index % (grid_.field_regions()); }
  CopyKind choose_copy(const FieldWork& w, int index, des::Time end_if_started) const;
  void copied(FieldWork& w, int index, CopyKind kind, des::Time start, des::Time end, int channel);
  void write_region(int64_t field, int index, int64_t image_field, const EyeImage& image);
  void region_done(FieldWork& w, int index);
  void verdict(FieldWork& w);
  EyeImage eye_image(const FieldWork& w, int eye) const;
  void stage(const char* name, int64_t frame, int eye, std::string unit, des::Time start, des::Time end);
  void sample(const std::string& name, double value);

  des::Simulator& sim_;
  SlatsParams p_;
  FieldTiming timing_;
  RegionGrid grid_;
  WorkloadSource& workload_;
  EngineHooks hooks_;
  des::Time end_;
  des::KindId kind_swap_ = 0;

  std::vector<FieldRegion> regions_;          // both eyes' field regions
  std::vector<std::vector<int>> copy_order_;  // per frame buffer, region indices in slot order
  std::vector<int> owned_;                    // regions per renderer

  RingChannels ring_;
  std::vector<std::unique_ptr<des::Resource>> fb_ports_;
  std::vector<std::unique_ptr<des::Resource>> renderer_ports_;
  std::vector<std::unique_ptr<des::Signal>> renderer_free_;  // pixel memory copied out
  std::vector<std::deque<Message>> inbox_;
  std::vector<std::unique_ptr<des::Signal>> inbox_arrival_;
  std::deque<Message> port_queue_;
  des::Signal port_work_;

  std::deque<std::unique_ptr<FieldWork>> fields_;  // started fields, oldest first
  int64_t fields_dropped_ = 0;                     // pruned from the front of fields_
  des::Signal field_started_;
  std::vector<int64_t> copy_position_;             // per frame buffer: index of the field it works on
  int64_t last_started_ = -1;

  // Host-to-GP mailbox: the GP reads the newest arrival at each retrace.
  int64_t host_pending_ = -1;
  des::Signal host_wake_;
  int64_t gp_mailbox_ = -1;

  // What each frame buffer's rows of each parity show, per field region.
  std::vector<std::array<std::vector<int64_t>, 2>> shown_field_;  // [eye][parity][region in eye]
  std::vector<std::array<Backup, 2>> backup_;                     // [eye][parity]

  des::Time gp_busy_, renderer_busy_;
  FieldCounts counts_;
};

}  // namespace latsim::pxpl5
