// Slats, the single-field-latency Pixel-Planes 5 pipeline (SPEC.md section 5).
#pragma once

#include <cstdint>
#include <vector>

#include "latsim/des/simulator.hpp"
#include "latsim/pxpl5/engine_hooks.hpp"
#include "latsim/pxpl5/field_timing.hpp"
#include "latsim/pxpl5/hardware.hpp"

namespace latsim::pxpl5 {

/// Costs and options of Slats on top of the shared hardware figures.
///
/// Calibration (SPEC.md section 5: 140 triangles per field at 60 Hz with the
/// COPY optimisation). A 16.67 ms field must hold the GP overhead (0.3 ms),
/// N triangles of GP work, the tail after the last triangle (the last ring
/// message to 5 renderers, its rendering and the region finish, about
/// 0.8 ms) and the 6 copy slots of the top regions (6 x 0.78 = 4.68 ms):
/// N * t <= 16.67 - 0.3 - 0.8 - 4.68 = 10.9 ms. t = 75 us per triangle (both
/// eyes: transform, clip, light and set up the plane equations twice) gives
/// 140 x 75 = 10.5 ms (fits, 0.4 ms to spare) while 150 x 75 = 11.25 ms does
/// not: capacity about 145. Without the optimisation all 11 slots (8.58 ms)
/// precede the retrace, leaving room for about 90 triangles. Rendering one
/// command into one region costs 6 us, so a renderer (4 regions, 24 us per
/// triangle) keeps pace with the GP and the GP sets the capacity.
struct SlatsParams {
  HardwareParams hw;
  bool stereo = true;
  des::Time gp_time_per_triangle = des::Time::us(75);   ///< both eyes, one pass
  des::Time gp_field_overhead = des::Time::us(300);     ///< take the newest transforms, set up, flush
  des::Time region_finish_time = des::Time::us(50);     ///< Gouraud: no deferred shading, just wrap up
  des::Time host_compute_time = des::Time::us(1000);    ///< host: both eyes' viewing transforms
  int host_message_words = 64;
  bool copy_optimisation = true;
  bool backup_field = false;

  int eyes() const { return stereo ? 2 : 1; }
};

/// Field-synchronous rendering: at each retrace the single GP takes the
/// newest viewing transforms, transforms every triangle for both eyes into
/// one bin streamed to the renderers in full ring messages, each renderer
/// rasterises its statically bound field regions, and the regions are copied
/// to both frame buffers at once in a fixed slot order, to be shown at the
/// next retrace. A field whose regions miss their deadlines is a missed field.
class SlatsEngine {
 public:
  SlatsEngine(des::Simulator& sim, SlatsParams params, FieldTiming timing, RegionGrid grid, int64_t triangles,
              EngineHooks hooks);
  SlatsEngine(const SlatsEngine&) = delete;
  SlatsEngine& operator=(const SlatsEngine&) = delete;

  /// Schedules the field retraces in [now, end).
  void start(des::Time end);
  /// The host can see a new tracker sample now: it computes both eyes'
  /// transforms and sends them to the GP as soon as it is free (SEND runs
  /// asynchronously, as often as new data allow).
  void host_sample(int64_t token);

  Utilisation utilisation(des::Time elapsed) const;
  int64_t fields_shown() const { return fields_shown_; }
  int64_t missed_fields() const { return missed_fields_; }
  int64_t torn_fields() const { return torn_fields_; }
  const SlatsParams& params() const { return p_; }

 private:
  /// One field region: which eye, which row of the field, which renderer owns it.
  struct FieldRegion {
    int eye;
    int row;
    int column;
    int renderer;
  };
  /// One region transfer of the copy schedule.
  struct Transfer {
    int region;  // index into regions_
    des::Time start, end, deadline;
  };

  void field_start(int64_t k);
  void send_to_gp();
  void stage(const char* name, int64_t frame, int eye, std::string unit, des::Time start, des::Time end);
  void sample(const std::string& name, double value);
  // Renderer finish times for this field's work, given the GP start time.
  std::vector<des::Time> transform_and_render(int64_t shown, des::Time start, des::Time& gp_end);
  std::vector<Transfer> copy_schedule(int64_t shown, const std::vector<des::Time>& rendered);

  des::Simulator& sim_;
  SlatsParams p_;
  FieldTiming timing_;
  RegionGrid grid_;
  int64_t triangles_;
  EngineHooks hooks_;
  des::Time end_;
  des::KindId kind_field_ = 0, kind_ready_ = 0, kind_send_ = 0;

  std::vector<FieldRegion> regions_;           // both eyes' field regions
  std::vector<std::vector<int>> copy_order_;   // per frame buffer, region indices in slot order
  std::vector<des::Time> renderer_free_;       // pixel memory free once its regions are copied out
  des::Time gp_free_;

  // Host-to-GP mailbox: the GP reads the newest arrival at each retrace.
  bool host_busy_ = false;
  int64_t host_pending_ = -1;
  int64_t gp_mailbox_ = -1;
  des::Time gp_mailbox_read_at_;

  des::Time gp_busy_, renderer_busy_, ring_busy_, copy_busy_;
  int64_t fields_shown_ = 0;
  int64_t missed_fields_ = 0;
  int64_t torn_fields_ = 0;
};

}  // namespace latsim::pxpl5
