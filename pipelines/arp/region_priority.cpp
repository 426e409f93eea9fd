// Region priority rendering on address recalculation. The primary model
// (segmentation and warping as configured) drives what is displayed; shadow
// models with segmentation or warping flipped run on the same user positions,
// which costs no events and gives the with/without comparisons in one run.
#include <algorithm>
#include <array>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "arp/frames.hpp"
#include "latsim/arp/memory_frames.hpp"
#include "latsim/arp/region_priority_model.hpp"
#include "latsim/des/periodic.hpp"
#include "latsim/des/stats.hpp"
#include "latsim/pipelines/latency_recorder.hpp"
#include "latsim/pipelines/run_files.hpp"
#include "latsim/pipelines/timeline.hpp"
#include "latsim/renderer/scene_spec.hpp"

namespace latsim::pipelines {
namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

/// One configuration of segmentation and warping and what it measured.
struct Variant {
  bool segmented = false;
  bool warping = false;
  std::unique_ptr<arp::RegionPriorityModel> model;
  des::Distribution tear_gap_px{0.005, true};
  std::string label() const {
    return std::string(segmented ? "segmented" : "whole objects") + (warping ? ", warped" : ", not warped");
  }
};

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
}

/// Drives region priority models from the host's samples and reports them.
class RegionPriorityPipeline final : public Pipeline {
 public:
  struct Params {
    des::RationalSeconds period{1, 60};
    double region_size_m = 2.0;
    bool segmentation = true;
    arp::RegionPriorityParams model;
    des::Time render_fixed = des::Time::ms(1);
    des::Time render_per_segment = des::Time::us(20);
    FrameOptions frames;
  };

  explicit RegionPriorityPipeline(const Params& p) : p_(p) {}

  void start(RunContext& ctx) override {
    ctx_ = &ctx;
    scene_ = renderer::make_scene(ctx.scene->geometry);
    grid_.emplace(scene_.bounds(), p_.region_size_m);
    segmented_ = std::make_unique<arp::SegmentedScene>(arp::segment_scene(scene_, *grid_));
    whole_ = std::make_unique<arp::SegmentedScene>(arp::whole_objects(scene_, *grid_));
    const arp::RegionPriorityParams& params = p_.model;
    add_variant(p_.segmentation, params.warping, params);
    add_variant(!p_.segmentation, params.warping, params);
    add_variant(true, !params.warping, params);
    if (!p_.segmentation) add_variant(true, params.warping, params);
    memory_sample_.assign(static_cast<size_t>(variants_[0].model->memory_count()), std::nullopt);

    const auto& raster = ctx.display.timing().params();
    screen_.emplace(ctx.display_params.hfov_deg, raster.width_px, raster.height_px);
    const des::KindId kind_tick = ctx.sim.kind("arp.region_tick");
    kind_done_ = ctx.sim.kind("arp.region_render");
    ticks_.emplace(ctx.sim, des::PeriodicSchedule(des::Time::zero(), p_.period), kind_tick, [this](int64_t k) { tick(k); });
    ticks_->start(0, ctx.duration);
    ctx.display.on_retrace([this](int64_t field, des::Time) { record_memory_ages(field); });
    if ((ctx.frames != nullptr || !p_.frames.times_s.empty()) && ctx.files.enabled())
      schedule_frames(ctx, p_.frames, [this] { write_frames(); });
  }

  void finish(RunContext& ctx) override {
    const double duration_s = ctx.duration.to_seconds();
    LatencyRecorder& r = ctx.recorder;
    const Variant& primary = variants_[0];
    report_memories(r, "memories.", primary, duration_s);
    int64_t rendered = 0;
    for (const auto& m : primary.model->memories()) rendered += m.segments_rendered;
    r.set("render_load", static_cast<double>(rendered) / duration_s);
    r.set("region_swaps", primary.model->swaps());
    r.set("segments_in_scene", static_cast<int64_t>(primary.model->scene().segments.size()));
    r.set("shared_vertices", static_cast<int64_t>(primary.model->scene().shared_vertices.size()));
    for (size_t i = 0; i < variants_.size(); ++i) {
      const Variant& v = variants_[i];
      const std::string at = "variants." + std::to_string(i) + ".";
      int64_t n = 0;
      for (const auto& m : v.model->memories()) n += m.segments_rendered;
      const auto s = v.tear_gap_px.summary();
      r.set(at + "segmentation", v.segmented);
      r.set(at + "warping", v.warping);
      report_memories(r, at + "memories.", v, duration_s);
      r.set(at + "render_load", static_cast<double>(n) / duration_s);
      r.set(at + "tear_gap_max_px", s.max);
      r.set(at + "tear_gap_p99_px", v.tear_gap_px.quantile(0.99));
      r.set(at + "tear_gap_samples", static_cast<int64_t>(s.count));
    }
    write_tables(ctx, duration_s);
  }

 private:
  void add_variant(bool segmented, bool warping, arp::RegionPriorityParams params) {
    for (const Variant& v : variants_) {
      if (v.segmented == segmented && v.warping == warping) return;
    }
    params.warping = warping;
    Variant v;
    v.segmented = segmented;
    v.warping = warping;
    v.model = std::make_unique<arp::RegionPriorityModel>(segmented ? *segmented_ : *whole_, *grid_, params);
    variants_.push_back(std::move(v));
  }

  const Variant* find(bool segmented, bool warping) const {
    for (const Variant& v : variants_) {
      if (v.segmented == segmented && v.warping == warping) return &v;
    }
    return nullptr;
  }

  void report_memories(LatencyRecorder& r, const std::string& prefix, const Variant& v, double duration_s) const {
    const auto lists = v.model->segments_per_memory();
    for (int m = 0; m < v.model->memory_count(); ++m) {
      const arp::RegionMemoryState& st = v.model->memories()[static_cast<size_t>(m)];
      const std::string at = prefix + std::to_string(m) + ".";
      r.set(at + "memory", int64_t{m});
      r.set(at + "update_rate_hz", static_cast<double>(st.renders) / duration_s);
      r.set(at + "segments", st.renders > 0 ? static_cast<double>(st.segments_rendered) / st.renders : 0.0);
      r.set(at + "segments_at_end", static_cast<int64_t>(lists[static_cast<size_t>(m)].size()));
      r.set(at + "regions_at_end", static_cast<int64_t>(v.model->map().regions_of_memory(m).size()));
      r.set(at + "renders", st.renders);
    }
  }

  void tick(int64_t k) {
    const auto sample = ctx_->host.newest_at(ctx_->sim.now());
    if (!sample) return;
    const des::Time now = ctx_->sim.now();
    const glm::dvec3 eye = sample->pose.position_m;
    std::vector<double> gaps;
    arp::RegionTick primary_tick;
    for (size_t i = 0; i < variants_.size(); ++i) {
      Variant& v = variants_[i];
      const arp::RegionTick t = v.model->tick(now, eye);
      if (i == 0) primary_tick = t;
      if (!v.segmented) continue;
      gaps.clear();
      v.model->tear_gaps_px(sample->pose.orientation, *screen_, gaps);
      for (double g : gaps) {
        v.tear_gap_px.add(g);
        if (i == 0) ctx_->recorder.add("tear_gap_px", g);
      }
    }
    if (primary_tick.updated.empty()) return;
    for (int m : primary_tick.updated) memory_sample_[static_cast<size_t>(m)] = *sample;
    const des::Time end = now + p_.render_fixed + p_.render_per_segment * primary_tick.segments_rendered;
    const tracker::TrackerSample s = *sample;
    ctx_->sim.at(end, kind_done_, [this, s, now, k] { present(s, now, k); });
  }

  void present(const tracker::TrackerSample& s, des::Time start, int64_t k) {
    ctx_->present_display_memory(k, s, start, "region_priority");
  }

  // Each memory shows the scene from its own update's sample: its translation latency.
  void record_memory_ages(int64_t field) {
    const des::Time scan = ctx_->display.timing().scanout_start(field);
    for (size_t m = 0; m < memory_sample_.size(); ++m) {
      if (!memory_sample_[m]) continue;
      ctx_->recorder.add("translation_latency_memory" + std::to_string(m) + "_ms",
                         (scan - memory_sample_[m]->measured_at).to_ms());
    }
  }

  // Where the worst tear of a model lies on screen now (centre when there is none).
  std::array<int, 2> worst_tear_pixel(const Variant& v, const glm::dquat& head) const {
    std::array<int, 2> best{screen_->width_px() / 2, screen_->height_px() / 2};
    double worst = -1.0;
    const auto& sv = v.model->scene().shared_vertices;
    for (const arp::SharedVertex& s : sv) {
      const int ma = v.model->memory_of_segment(s.segment_a);
      const int mb = v.model->memory_of_segment(s.segment_b);
      if (ma == mb) continue;
      glm::dvec2 pa, pb;
      if (!screen_->project(head, v.model->drawn_direction(ma, s.position_m), pa)) continue;
      if (!screen_->project(head, v.model->drawn_direction(mb, s.position_m), pb)) continue;
      const double gap = glm::length(pa - pb);
      if (gap > worst) {
        worst = gap;
        best = {static_cast<int>(pa.x), static_cast<int>(pa.y)};
      }
    }
    return best;
  }

  void write_frames() {
    const auto newest = ctx_->host.newest_at(ctx_->sim.now());
    if (!newest) return;
    const glm::dquat head = newest->pose.orientation;
    const auto& raster = ctx_->display.timing().params();
    const renderer::Camera camera(ctx_->display_params.hfov_deg, raster.width_px, raster.height_px);
    const std::string stem = "region_frame_" + std::to_string(static_cast<int64_t>(ctx_->sim.now().to_ms())) + "ms";
    const Variant& primary = variants_[0];
    const std::vector<renderer::CubeMap> cubes = renderer_for(primary).render(*primary.model);
    std::vector<const renderer::CubeMap*> all;
    for (size_t m = 0; m < cubes.size(); ++m) {
      all.push_back(&cubes[m]);
      const renderer::CubeMap* one[] = {&cubes[m]};
      const renderer::Frame f = arp::view_through_cubes(one, camera, head, p_.frames.background);
      ctx_->files.write_png(stem + "_memory" + std::to_string(m) + ".png", f.colour);
    }
    const renderer::Frame composite = arp::view_through_cubes(all, camera, head, p_.frames.background);
    ctx_->files.write_png(stem + "_composite.png", composite.colour);
    // Close-ups at the widest tear of the unwarped segmented model, and the warped model at the same spot.
    const Variant* torn = find(true, false);
    const Variant* warped = find(true, true);
    if (!torn || !warped) return;
    const auto at = worst_tear_pixel(*torn, head);
    for (const Variant* v : {torn, warped}) {
      const std::vector<renderer::CubeMap> vc = renderer_for(*v).render(*v->model);
      std::vector<const renderer::CubeMap*> ptrs;
      for (const auto& c : vc) ptrs.push_back(&c);
      const renderer::Frame f = arp::view_through_cubes(ptrs, camera, head, p_.frames.background);
      const std::string tag = v->warping ? "_warped" : "_torn";
      ctx_->files.write_png(stem + tag + ".png", f.colour);
      ctx_->files.write_png(stem + tag + "_closeup.png", arp::close_up(f.colour, at[0], at[1], 24, 8));
    }
  }

  const arp::MemoryRenderer& renderer_for(const Variant& v) {
    auto& slot = v.segmented ? segmented_renderer_ : whole_renderer_;
    if (!slot)
      slot = std::make_unique<arp::MemoryRenderer>(v.segmented ? *segmented_ : *whole_, p_.frames.face_px,
                                                   p_.frames.background, p_.frames.threads);
    return *slot;
  }

  void write_tables(RunContext& ctx, double duration_s) const {
    if (!ctx.files.enabled()) return;
    const Variant& primary = variants_[0];
    const Variant* seg = find(true, primary.warping);
    const Variant* whole = find(false, primary.warping);
    std::ostringstream csv;
    std::ostringstream md;
    csv << "memory,update_rate_hz_segmented,update_rate_hz_whole,segments_segmented,segments_whole\n";
    md << "| memory | update rate, segmented (Hz) | update rate, whole objects (Hz) | segments per update, segmented "
          "| segments per update, whole objects |\n|---|---|---|---|---|\n";
    for (int m = 0; m < primary.model->memory_count(); ++m) {
      const auto& a = seg->model->memories()[static_cast<size_t>(m)];
      const auto& b = whole->model->memories()[static_cast<size_t>(m)];
      const double ra = static_cast<double>(a.renders) / duration_s;
      const double rb = static_cast<double>(b.renders) / duration_s;
      const double sa = a.renders > 0 ? static_cast<double>(a.segments_rendered) / a.renders : 0.0;
      const double sb = b.renders > 0 ? static_cast<double>(b.segments_rendered) / b.renders : 0.0;
      csv << m << ',' << fixed(ra, 3) << ',' << fixed(rb, 3) << ',' << fixed(sa, 2) << ',' << fixed(sb, 2) << '\n';
      md << "| " << m << " | " << fixed(ra, 2) << " | " << fixed(rb, 2) << " | " << fixed(sa, 1) << " | " << fixed(sb, 1)
         << " |\n";
    }
    md << "\n| model | tear gap max (px) | tear gap p99 (px) | samples |\n|---|---|---|---|\n";
    csv << "\nvariant,tear_gap_max_px,tear_gap_p99_px,samples\n";
    for (const Variant& v : variants_) {
      if (!v.segmented) continue;
      const auto s = v.tear_gap_px.summary();
      md << "| " << v.label() << " | " << fixed(s.max, 4) << " | " << fixed(v.tear_gap_px.quantile(0.99), 4) << " | "
         << s.count << " |\n";
      csv << '"' << v.label() << "\"," << fixed(s.max, 6) << ',' << fixed(v.tear_gap_px.quantile(0.99), 6) << ','
          << s.count << '\n';
    }
    ctx.files.write_text("arp_memories.csv", csv.str());
    ctx.files.write_text("arp_memories.md", md.str());
  }

  Params p_;
  RunContext* ctx_ = nullptr;
  std::optional<des::Periodic> ticks_;
  renderer::Scene scene_;
  std::optional<renderer::RegionGrid> grid_;
  std::unique_ptr<arp::SegmentedScene> segmented_;
  std::unique_ptr<arp::SegmentedScene> whole_;
  std::vector<Variant> variants_;
  std::vector<std::optional<tracker::TrackerSample>> memory_sample_;
  std::optional<arp::ScreenProjection> screen_;
  std::unique_ptr<arp::MemoryRenderer> segmented_renderer_;
  std::unique_ptr<arp::MemoryRenderer> whole_renderer_;
  des::KindId kind_done_ = 0;
};

void bind(scenario::Section& s, RegionPriorityPipeline::Params& p, const params::SharedParams& shared) {
  arp::RegionPriorityParams& m = p.model;
  s.rate("max_update_rate_hz", p.period, {.unit = "Hz", .doc = "rate of the fastest display memory (and of the ticks)"});
  bind(s, p.frames);
  s.number("region_size_m", p.region_size_m, {.unit = "m", .min = 0.0, .above_min = true, .doc = "edge of a square floor region"});
  s.flag("segmentation", p.segmentation, {.doc = "cut objects at region boundaries; false: whole objects"});
  // Default threshold: one texel of the cube memory at a face centre.
  double threshold_deg = 90.0 / p.frames.face_px;
  s.number("threshold_angle_deg", threshold_deg,
           {.unit = "deg", .min = 1e-9, .max = 90.0, .doc = "error an image may reach before it is redrawn",
            .default_doc = "90 / face_px (one texel)"});
  m.threshold_rad = threshold_deg * kDegToRad;
  m.swap_margin_m = 0.25 * p.region_size_m;
  s.number("swap_margin_m", m.swap_margin_m,
           {.unit = "m", .min = 0.0, .doc = "hysteresis before a region changes memory", .default_doc = "region_size_m / 4"});
  s.flag("warping", m.warping, {.doc = "edge vertices follow the slower neighbour's viewpoint, closing tears"});
  m.warp_falloff_m = 0.5 * p.region_size_m;
  s.number("warp_falloff_m", m.warp_falloff_m,
           {.unit = "m", .min = 0.0, .doc = "distance over which warping fades", .default_doc = "region_size_m / 2"});
  std::vector<double> rings(m.outer_rings.begin(), m.outer_rings.end());
  s.numbers("outer_rings", rings, {.doc = "ring limits, one per display memory after the first"});
  m.outer_rings.assign(rings.begin(), rings.end());
  s.duration("render_fixed_ms", p.render_fixed, {.unit = "ms", .doc = "fixed time per render"});
  s.duration("render_per_segment_us", p.render_per_segment, {.unit = "us", .doc = "time per segment rendered"});
  s.check_pointer("/scene", shared.scene.has_value(), "region priority rendering needs a scene");
}

}  // namespace

PipelineEntry region_priority_pipeline() {
  return pipeline_entry<RegionPriorityPipeline>(
      "region_priority",
      "Region priority rendering on address recalculation: floor regions near the user go to faster display "
      "memories; shadow models with segmentation or warping flipped run on the same positions for comparison "
      "(see docs/arp.md). Needs a /scene.");
}

}  // namespace latsim::pipelines
