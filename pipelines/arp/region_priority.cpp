// Region priority rendering on address recalculation. One configuration
// (segmentation and warping as the scenario sets them) drives the display;
// the configurations named in `compare` run beside it on the same walk, with
// renderers of their own, and are reported as variants.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "arp/frames.hpp"
#include "arp/memory_display.hpp"
#include "arp/render_keys.hpp"
#include "arp/region_report.hpp"
#include "arp/region_run.hpp"
#include "latsim/arp/memory_frames.hpp"
#include "latsim/des/periodic.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "latsim/renderer/scene_spec.hpp"
#include "latsim/results/latency_recorder.hpp"
#include "latsim/results/run_files.hpp"
#include "latsim/scenario/section.hpp"
#include "latsim/units/units.hpp"

namespace latsim::pipelines {
namespace {

// Warping looks at every region within its falloff from each warped vertex.
constexpr double kMaxWarpRegions = 16.0;
// Every region is tracked and segmented: a floor cut into more than this is
// a slip in region_size_m, not a scene.
constexpr double kMaxRegions = 1e6;

void check_region_count(const renderer::Aabb& bounds, double region_size_m) {
  const double nx = std::max(1.0, std::ceil((bounds.max_m.x - bounds.min_m.x) / region_size_m));
  const double nz = std::max(1.0, std::ceil((bounds.max_m.z - bounds.min_m.z) / region_size_m));
  if (nx * nz <= kMaxRegions) return;
  char count[32];
  std::snprintf(count, sizeof count, "%.3g", nx * nz);
  throw scenario::ScenarioError("/pipeline/region_size_m",
                                std::string("cuts the scene's floor into ") + count + " regions (at most 1e6)");
}

/// Drives region priority systems from the host's samples and shows the primary one.
class RegionPriorityPipeline final : public Pipeline {
 public:
  struct Params {
    des::RationalSeconds period{1, 60};
    double region_size_m = 2.0;
    bool segmentation = true;
    arp::RegionPriorityParams model;
    arp::MemoryRenderCost cost{.per_pixel_ns = 2.0};
    int renderers = 1;
    std::vector<std::string> compare;
    std::vector<double> position_window_s;  ///< empty, or [start, end]
    des::ClockSettings loop;  ///< the tick loop's own clock
    FrameOptions frames;
  };

  explicit RegionPriorityPipeline(const Params& p) : p_(p) {}

  // A tick at the fastest memory's rate, and at most one render completion
  // per memory per tick, in the run itself and in every variant it compares.
  std::vector<EventRate> event_rates(const sections::SharedParams&) const override {
    const double ticks_per_s = 1.0 / p_.period.to_seconds();
    const double memories = static_cast<double>(p_.model.outer_rings.size()) + 1.0;
    const double runs = 1.0 + static_cast<double>(p_.compare.size());
    return {{"/pipeline/max_update_rate_hz", "arp", ticks_per_s * (1.0 + memories * runs)}};
  }

  void start(RunContext& ctx) override {
    ctx_ = &ctx;
    ctx.fetch_orientation_at_scanout();
    scene_ = renderer::make_scene(ctx.scene->geometry);
    check_region_count(scene_.bounds(), p_.region_size_m);
    grid_.emplace(scene_.bounds(), p_.region_size_m);
    occluder_ = std::make_unique<renderer::RayCaster>(scene_);
    const des::KindId kind_render = ctx.sim.kind("arp.region_render");
    runs_.push_back(make_run(p_.segmentation, p_.model.warping, kind_render));
    const des::KindId kind_variant = ctx.sim.kind("arp.variant_render");
    for (const std::string& name : p_.compare) {
      const bool segmented = name == "segmented" || (name != "unsegmented" && p_.segmentation);
      const bool warped = name == "warped" || (name != "unwarped" && p_.model.warping);
      if (find(segmented, warped)) {
        ctx.recorder.warn("/pipeline/compare: \"" + name + "\" is already run; listed once or it is the run itself");
        continue;
      }
      runs_.push_back(make_run(segmented, warped, kind_variant));
    }
    // One update may draw every segment of the scene (whole objects count as one segment each).
    const size_t segments = std::max(segmented_ ? segmented_->segments.size() : size_t{0},
                                     whole_ ? whole_->segments.size() : size_t{0});
    scenario::check_span_at("/pipeline/render_per_segment_us", p_.cost.per_segment.to_seconds(),
                            static_cast<double>(segments), "the scene's segments");
    runs_[0]->on_present([this](const std::vector<const arp::MemoryImage*>& batch) { present(batch); });

    const auto& raster = ctx.display.timing().params();
    screen_.emplace(ctx.display_params.hfov_deg, raster.width_px, raster.height_px);
    ctx.recorder.expects_images();
    const des::Clock& loop = ctx.clock("loop", "/pipeline/loop_phase_ms", p_.period, p_.loop);
    ticks_.emplace(ctx.sim, loop.schedule(), ctx.sim.kind("arp.region_tick"), [this](int64_t k) { tick(k); });
    ticks_->start(0, ctx.duration);
    ctx.display.on_retrace([this](int64_t field, des::Time) { retrace(field); });
    schedule_window(ctx);
    if ((ctx.frames != nullptr || !p_.frames.times_s.empty()) && ctx.files.enabled())
      schedule_frames(ctx, p_.frames, [this] { write_frames(); });
  }

  void finish(RunContext& ctx) override {
    results::LatencyRecorder& r = ctx.recorder;
    // Address recalculation reads the orientation per line at scanout: its
    // rotation latency is the point; positions come with the renders.
    r.declare_headline({"rotation_latency_ms", "translation_latency_ms", "registration_error_arcmin",
                        "motion_to_photon_ms"});
    const RegionRun& primary = *runs_[0];
    primary.report(r, "", ctx.duration);
    if (window_end_ > window_start_ && window_end_ >= ctx.duration) {
      for (auto& run : runs_) run->mark_window();
    }
    primary.report_window(r, "", window_end_ - window_start_);
    r.set("region_swaps", primary.system().model().swaps());
    r.set("segments_in_scene", static_cast<int64_t>(primary.system().model().scene().segments.size()));
    r.set("shared_vertices", static_cast<int64_t>(primary.system().model().scene().shared_vertices.size()));
    if (runs_.size() > 1) r.list("variants");
    for (size_t i = 1; i < runs_.size(); ++i) {
      const std::string at = "variants." + std::to_string(i - 1) + ".";
      r.set(at + "configuration", runs_[i]->label());
      r.set(at + "segmentation", runs_[i]->segmented());
      r.set(at + "warping", runs_[i]->warping());
      runs_[i]->report(r, at, ctx.duration);
      runs_[i]->report_window(r, at, window_end_ - window_start_);
    }
    if (ctx.files.enabled()) {
      std::vector<const RegionRun*> runs;
      for (const auto& run : runs_) runs.push_back(run.get());
      ctx.files.write_text("arp_memories.md", memories_markdown(runs, ctx.duration, window_end_ - window_start_));
      ctx.files.write_text("arp_memories.csv", memories_csv(runs, ctx.duration));
    }
  }

 private:
  // The counts at the window's start and end, after everything else that
  // happens at those instants (the end of the run marks itself in finish()).
  void schedule_window(RunContext& ctx) {
    if (p_.position_window_s.empty()) return;
    window_start_ = des::Time::from_seconds(p_.position_window_s[0]);
    window_end_ = des::Time::from_seconds(p_.position_window_s[1]);
    if (window_end_ > ctx.duration) {
      // A shortened run (a --set /duration_s) has no figures for that position rather than others.
      ctx.recorder.warn("/pipeline/position_window_s ends after the run: no window figures");
      window_start_ = window_end_ = des::Time::zero();
      return;
    }
    const des::KindId kind = ctx.sim.kind("arp.window");
    const auto mark = [this] {
      for (auto& run : runs_) run->mark_window();
    };
    ctx.sim.at(window_start_, kind, mark, 20);
    if (window_end_ < ctx.duration) ctx.sim.at(window_end_, kind, mark, 20);
  }

  std::unique_ptr<RegionRun> make_run(bool segmented, bool warped, des::KindId kind) {
    std::unique_ptr<arp::SegmentedScene>& cut = segmented ? segmented_ : whole_;
    if (!cut)
      cut = std::make_unique<arp::SegmentedScene>(segmented ? arp::segment_scene(scene_, *grid_)
                                                            : arp::whole_objects(scene_, *grid_));
    arp::RegionSystemParams params{p_.model, p_.cost, p_.renderers, p_.frames.face_px};
    params.model.warping = warped;
    return std::make_unique<RegionRun>(ctx_->sim, kind, *cut, *grid_, std::move(params), occluder_.get());
  }

  RegionRun* find(bool segmented, bool warped) const {
    for (const auto& run : runs_) {
      if (run->segmented() == segmented && run->warping() == warped) return run.get();
    }
    return nullptr;
  }

  void tick(int64_t k) {
    const auto sample = ctx_->host.newest_at(ctx_->sim.now());
    if (!sample) return;
    // Memories are drawn from the pose predicted for their first field: the
    // host expects this render to take as long as the last one did.
    const des::Time now = ctx_->sim.now();
    const tracker::PosePrediction pose =
        ctx_->host.basis_of(*sample).for_photon_time(ctx_->photon_time_after(now + last_render_time_));
    samples_.add(k, pose);
    bool updated = false;
    for (size_t i = 0; i < runs_.size(); ++i) {
      const arp::RegionTick& t = runs_[i]->system().tick(now, pose.pose.position_m, k);
      if (i == 0) updated = !t.updated.empty();
    }
    // The updated display memories are meant to be in use by the next tick.
    if (updated) ctx_->recorder.image_due(ticks_->schedule().at(k + 1));
  }

  void present(const std::vector<const arp::MemoryImage*>& batch) {
    show_memory_images(*ctx_, batch, samples_);
    if (!batch.empty()) last_render_time_ = batch.back()->cost;
    samples_.forget_unreachable(runs_[0]->system().memories());
  }

  // Each memory shows the scene from its own image's sample: its translation
  // latency at the field's first photon; tears and stretch as now seen.
  void retrace(int64_t field) {
    const des::Time photon = ctx_->display.timing().scanout_start(field);
    const arp::DisplayMemories& memories = runs_[0]->system().memories();
    for (int m = 0; m < memories.memory_count(); ++m) {
      const arp::MemoryImage* img = memories.shown(m);
      if (!img) continue;
      ctx_->recorder.add("translation_latency_memory" + std::to_string(m) + "_ms",
                         (photon - samples_.at(img->sample).sample.measured_at).to_ms());
    }
    const auto newest = ctx_->host.newest_at(ctx_->sim.now());
    if (!newest) return;
    for (auto& run : runs_) run->measure(newest->pose.orientation, newest->pose.position_m, *screen_);
  }

  void write_frames() {
    // The orientation the next field is looked up with (its middle line).
    const auto newest = ctx_->host.pose_for(ctx_->sim.now(), ctx_->photon_time_after(ctx_->sim.now()));
    if (!newest) return;
    const auto& raster = ctx_->display.timing().params();
    const renderer::Camera camera(ctx_->display_params.hfov_deg, raster.width_px, raster.height_px);
    const std::string stem = "region_frame_" + std::to_string(static_cast<int64_t>(ctx_->sim.now().to_ms())) + "ms";
    RegionFrames frames(camera, newest->pose.orientation, p_.frames, ctx_->files);
    frames.write_memories(stem, *runs_[0]);
    // Close-ups at the widest tear of the unwarped segmented run, and the warped run at the same spot.
    const RegionRun* torn = find(true, false);
    const RegionRun* warped = find(true, true);
    if (torn && warped) frames.write_tear_close_ups(stem, *torn, *warped, *screen_);
  }

  Params p_;
  RunContext* ctx_ = nullptr;
  std::optional<des::Periodic> ticks_;
  renderer::Scene scene_;
  std::optional<renderer::RegionGrid> grid_;
  std::unique_ptr<renderer::RayCaster> occluder_;
  std::unique_ptr<arp::SegmentedScene> segmented_;
  std::unique_ptr<arp::SegmentedScene> whole_;
  std::vector<std::unique_ptr<RegionRun>> runs_;  // the primary first, then the variants
  SampleBook samples_;
  des::Time last_render_time_;
  std::optional<arp::ScreenProjection> screen_;
  des::Time window_start_;
  des::Time window_end_;
};

void bind(scenario::Section& s, RegionPriorityPipeline::Params& p, const sections::SharedParams& shared) {
  arp::RegionPriorityParams& m = p.model;
  s.rate("max_update_rate_hz", p.period, {.unit = "Hz", .max = 1e4, .doc = "rate of the fastest display memory (and of the ticks)"});
  sections::clock(s, "loop_", p.loop, "tick loop");
  bind(s, p.frames);
  s.number("region_size_m", p.region_size_m, {.unit = "m", .min = 0.0, .above_min = true, .doc = "edge of a square floor region"});
  s.flag("segmentation", p.segmentation, {.doc = "cut objects at region boundaries; false: whole objects"});
  // Default threshold: one texel of the cube memory at a face centre.
  double threshold_deg = 90.0 / p.frames.face_px;
  s.number("threshold_angle_deg", threshold_deg,
           {.unit = "deg", .min = 1e-9, .max = 90.0, .doc = "error an image may reach before it is redrawn",
            .default_doc = "90 / face_px (one texel)"});
  m.threshold_rad = threshold_deg * units::kRadPerDeg;
  m.swap_margin_m = 0.25 * p.region_size_m;
  s.number("swap_margin_m", m.swap_margin_m,
           {.unit = "m", .min = 0.0, .doc = "hysteresis before a region changes memory", .default_doc = "region_size_m / 4"});
  s.flag("warping", m.warping, {.doc = "edge vertices follow the slower neighbour's viewpoint, closing tears"});
  m.warp_falloff_m = 0.5 * p.region_size_m;
  s.number("warp_falloff_m", m.warp_falloff_m,
           {.unit = "m", .min = 0.0, .doc = "distance over which warping fades", .default_doc = "region_size_m / 2"});
  s.check("warp_falloff_m", m.warp_falloff_m <= kMaxWarpRegions * p.region_size_m,
          "warping may fade over at most 16 regions (16 × region_size_m)");
  std::vector<double> rings(m.outer_rings.begin(), m.outer_rings.end());
  s.numbers("outer_rings", rings, {.doc = "ring limits, one per display memory after the first"});
  m.outer_rings.assign(rings.begin(), rings.end());
  bind_render_costs(s, p.cost, p.renderers, "render_per_segment_us", "segment drawn");
  s.choices("compare", p.compare, {"segmented", "unsegmented", "warped", "unwarped"},
            {.doc = "configurations run beside this one on the same walk, each with this one's settings but the "
                    "one named (variants in the figures, columns in arp_memories.md)"});
  s.numbers("position_window_s", p.position_window_s,
            {.unit = "s", .min = 0.0, .max = 1e6,
             .doc = "[start, end]: also report each memory's update rate and segments per update over this stretch "
                    "of the walk (figures window.*), for tables taken at one position; [] (default): none"});
  s.check("position_window_s",
          p.position_window_s.empty() ||
              (p.position_window_s.size() == 2 && p.position_window_s[0] < p.position_window_s[1]),
          "is [] or [start, end] with start < end");
  s.check_pointer("/scene", shared.scene.has_value(), "region priority rendering needs a scene");
}

}  // namespace

PipelineEntry region_priority_pipeline() {
  return pipeline_entry<RegionPriorityPipeline>(
      "region_priority",
      "Region priority rendering on address recalculation: floor regions near the user go to faster display "
      "memories, updated on demand by renderers shared fastest memory first; configurations named in compare run "
      "beside it for comparison (see docs/arp.md). Needs a /scene.");
}

}  // namespace latsim::pipelines
