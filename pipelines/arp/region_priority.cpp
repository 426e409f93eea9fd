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

#include "latsim/arp/memory_frames.hpp"
#include "latsim/arp/region_priority_model.hpp"
#include "latsim/arp/scene_config.hpp"
#include "latsim/des/stats.hpp"
#include "latsim/pipelines/arp.hpp"
#include "latsim/pipelines/latency_recorder.hpp"
#include "latsim/pipelines/runner.hpp"
#include "latsim/pipelines/timeline.hpp"
#include "latsim/renderer/png_writer.hpp"

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
  std::string name() const override { return "region_priority"; }

  void start(RunContext& ctx) override {
    ctx_ = &ctx;
    const auto& p = ctx.pipeline;
    period_ = p.rate_as_period("max_update_rate_hz", "60");
    face_px_ = static_cast<int>(p.integer("face_px", 256, 1, 8192));
    const double region_size_m = p.positive("region_size_m", 2.0);
    const bool segmentation = p.boolean("segmentation", true);
    arp::RegionPriorityParams params;
    params.threshold_rad = p.number_in("threshold_angle_deg", 90.0 / face_px_, 1e-9, 90.0) * kDegToRad;
    params.swap_margin_m = p.non_negative("swap_margin_m", 0.25 * region_size_m);
    params.warping = p.boolean("warping", false);
    params.warp_falloff_m = p.non_negative("warp_falloff_m", 0.5 * region_size_m);
    params.outer_rings.clear();
    for (double r : p.numbers("outer_rings", {1, 2, 4})) params.outer_rings.push_back(static_cast<int>(r));
    fixed_time_ = p.duration_ms("render_fixed_ms", 1.0);
    per_segment_ = des::Time::from_us(p.non_negative("render_per_segment_us", 20.0));
    background_ = glm::vec3(1.0f);
    const std::vector<double> bg = p.numbers("background", {1.0, 1.0, 1.0});
    if (bg.size() != 3) p.fail("background", "a colour needs three linear components [r, g, b]");
    background_ = glm::vec3(static_cast<float>(bg[0]), static_cast<float>(bg[1]), static_cast<float>(bg[2]));
    frame_times_s_ = p.numbers("frame_times_s", {});
    threads_ = static_cast<int>(p.integer("frame_threads", 1, 1, 256));
    // The display's field of view, read where the runner reads it.
    if (const auto display = ctx.root.optional_child("display")) hfov_deg_ = display->number("hfov_deg", 90.0);

    scene_ = arp::scene_from_config(ctx.root.child("scene"));
    grid_.emplace(scene_.bounds(), region_size_m);
    segmented_ = std::make_unique<arp::SegmentedScene>(arp::segment_scene(scene_, *grid_));
    whole_ = std::make_unique<arp::SegmentedScene>(arp::whole_objects(scene_, *grid_));
    add_variant(segmentation, params.warping, params);
    add_variant(!segmentation, params.warping, params);
    add_variant(true, !params.warping, params);
    if (!segmentation) add_variant(true, params.warping, params);
    memory_sample_.assign(static_cast<size_t>(variants_[0].model->memory_count()), std::nullopt);

    const auto& raster = ctx.display.timing().params();
    screen_.emplace(hfov_deg_, raster.width_px, raster.height_px);
    schedule_ = des::PeriodicSchedule(des::Time::zero(), period_);
    kind_tick_ = ctx.sim.kind("arp.region_tick");
    kind_done_ = ctx.sim.kind("arp.region_render");
    kind_frame_ = ctx.sim.kind("arp.frame");
    schedule_tick(0);
    ctx.display.on_retrace([this](int64_t field, des::Time) { record_memory_ages(field); });
    if ((ctx.frames != nullptr || !frame_times_s_.empty()) && !ctx.out_dir.empty()) {
      for (double t : frame_times_s_) {
        const des::Time at = des::Time::from_seconds(t);
        if (at >= des::Time::zero() && at < ctx.duration) ctx.sim.at(at, kind_frame_, [this] { write_frames(); }, 10);
      }
    }
  }

  void finish(RunContext& ctx, nlohmann::json& figures) override {
    const double duration_s = ctx.duration.to_seconds();
    const Variant& primary = variants_[0];
    figures["memories"] = memory_figures(primary, duration_s);
    int64_t rendered = 0;
    for (const auto& m : primary.model->memories()) rendered += m.segments_rendered;
    figures["render_load"] = static_cast<double>(rendered) / duration_s;
    figures["region_swaps"] = primary.model->swaps();
    figures["segments_in_scene"] = primary.model->scene().segments.size();
    figures["shared_vertices"] = primary.model->scene().shared_vertices.size();
    nlohmann::json variants = nlohmann::json::array();
    for (const Variant& v : variants_) {
      int64_t n = 0;
      for (const auto& m : v.model->memories()) n += m.segments_rendered;
      const auto s = v.tear_gap_px.summary();
      variants.push_back({{"segmentation", v.segmented},
                          {"warping", v.warping},
                          {"memories", memory_figures(v, duration_s)},
                          {"render_load", static_cast<double>(n) / duration_s},
                          {"tear_gap_max_px", s.max},
                          {"tear_gap_p99_px", v.tear_gap_px.quantile(0.99)},
                          {"tear_gap_samples", s.count}});
    }
    figures["variants"] = variants;
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

  nlohmann::json memory_figures(const Variant& v, double duration_s) const {
    nlohmann::json out = nlohmann::json::array();
    const auto lists = v.model->segments_per_memory();
    for (int m = 0; m < v.model->memory_count(); ++m) {
      const arp::RegionMemoryState& st = v.model->memories()[static_cast<size_t>(m)];
      out.push_back({{"memory", m},
                     {"update_rate_hz", static_cast<double>(st.renders) / duration_s},
                     {"segments", st.renders > 0 ? static_cast<double>(st.segments_rendered) / st.renders : 0.0},
                     {"segments_at_end", lists[static_cast<size_t>(m)].size()},
                     {"regions_at_end", v.model->map().regions_of_memory(m).size()},
                     {"renders", st.renders}});
    }
    return out;
  }

  void schedule_tick(int64_t k) {
    const des::Time at = schedule_.at(k);
    if (at >= ctx_->duration) return;
    ctx_->sim.at(at, kind_tick_, [this, k] { tick(k); });
  }

  void tick(int64_t k) {
    schedule_tick(k + 1);
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
    const des::Time end = now + fixed_time_ + per_segment_ * primary_tick.segments_rendered;
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
    const renderer::Camera camera(hfov_deg_, raster.width_px, raster.height_px);
    const std::string stem = "region_frame_" + std::to_string(static_cast<int64_t>(ctx_->sim.now().to_ms())) + "ms";
    const Variant& primary = variants_[0];
    const std::vector<renderer::CubeMap> cubes = renderer_for(primary).render(*primary.model);
    std::vector<const renderer::CubeMap*> all;
    for (size_t m = 0; m < cubes.size(); ++m) {
      all.push_back(&cubes[m]);
      const renderer::CubeMap* one[] = {&cubes[m]};
      const renderer::Frame f = arp::view_through_cubes(one, camera, head, background_);
      renderer::write_png(ctx_->out_dir / (stem + "_memory" + std::to_string(m) + ".png"), f.colour);
    }
    const renderer::Frame composite = arp::view_through_cubes(all, camera, head, background_);
    renderer::write_png(ctx_->out_dir / (stem + "_composite.png"), composite.colour);
    // Close-ups at the widest tear of the unwarped segmented model, and the warped model at the same spot.
    const Variant* torn = find(true, false);
    const Variant* warped = find(true, true);
    if (!torn || !warped) return;
    const auto at = worst_tear_pixel(*torn, head);
    for (const Variant* v : {torn, warped}) {
      const std::vector<renderer::CubeMap> vc = renderer_for(*v).render(*v->model);
      std::vector<const renderer::CubeMap*> ptrs;
      for (const auto& c : vc) ptrs.push_back(&c);
      const renderer::Frame f = arp::view_through_cubes(ptrs, camera, head, background_);
      const std::string tag = v->warping ? "_warped" : "_torn";
      renderer::write_png(ctx_->out_dir / (stem + tag + ".png"), f.colour);
      renderer::write_png(ctx_->out_dir / (stem + tag + "_closeup.png"), arp::close_up(f.colour, at[0], at[1], 24, 8));
    }
  }

  const arp::MemoryRenderer& renderer_for(const Variant& v) {
    auto& slot = v.segmented ? segmented_renderer_ : whole_renderer_;
    if (!slot) slot = std::make_unique<arp::MemoryRenderer>(v.segmented ? *segmented_ : *whole_, face_px_, background_, threads_);
    return *slot;
  }

  void write_tables(RunContext& ctx, double duration_s) const {
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
    if (ctx.out_dir.empty()) return;
    write_file_atomically(ctx.out_dir / "arp_memories.csv", csv.str());
    write_file_atomically(ctx.out_dir / "arp_memories.md", md.str());
  }

  RunContext* ctx_ = nullptr;
  des::RationalSeconds period_;
  des::PeriodicSchedule schedule_;
  int face_px_ = 256;
  int threads_ = 1;
  double hfov_deg_ = 90.0;
  glm::vec3 background_{1.0f};
  std::vector<double> frame_times_s_;
  des::Time fixed_time_;
  des::Time per_segment_;
  renderer::Scene scene_;
  std::optional<renderer::RegionGrid> grid_;
  std::unique_ptr<arp::SegmentedScene> segmented_;
  std::unique_ptr<arp::SegmentedScene> whole_;
  std::vector<Variant> variants_;
  std::vector<std::optional<tracker::TrackerSample>> memory_sample_;
  std::optional<arp::ScreenProjection> screen_;
  std::unique_ptr<arp::MemoryRenderer> segmented_renderer_;
  std::unique_ptr<arp::MemoryRenderer> whole_renderer_;
  des::KindId kind_tick_ = 0;
  des::KindId kind_done_ = 0;
  des::KindId kind_frame_ = 0;
};

}  // namespace

std::unique_ptr<Pipeline> make_region_priority_pipeline() { return std::make_unique<RegionPriorityPipeline>(); }

}  // namespace latsim::pipelines
