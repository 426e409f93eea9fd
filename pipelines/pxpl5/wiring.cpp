// The wiring both Pixel-Planes 5 pipelines share between an engine and a run.
#include "pxpl5/wiring.hpp"

#include <algorithm>
#include <stdexcept>

#include "latsim/pipelines/pipeline.hpp"
#include "latsim/pxpl5/view_workload.hpp"
#include "latsim/renderer/scene_spec.hpp"
#include "latsim/results/latency_recorder.hpp"
#include "latsim/results/timeline.hpp"

namespace latsim::pipelines {

namespace {

// Poses of samples older than this many tracker periods can no longer be asked for.
constexpr int64_t kSamplesKept = 256;
// Images a Slats frame buffer may still show: a backup of the last complete
// field can be many fields old.
constexpr std::size_t kImagesKept = 256;

}  // namespace

Pxpl5Wiring::Pxpl5Wiring(RunContext& ctx) : ctx_(&ctx) { ctx.recorder.expects_images(); }

pxpl5::FieldTiming Pxpl5Wiring::field_timing() const {
  const display::RasterTiming& t = ctx_->display.timing();
  // The engines schedule against retraces of their own, t0 + k x period.
  if (t.clock_noise())
    throw std::invalid_argument("the Pixel-Planes 5 pipelines follow a steady display clock: remove /display/clock_noise");
  return pxpl5::FieldTiming(t.field_start(0), t.params().field_period, t.params().vblank_lines, t.lines_per_field(),
                            t.params().interlaced);
}

pxpl5::RegionGrid Pxpl5Wiring::grid() const {
  const display::RasterParams& p = ctx_->display.timing().params();
  return pxpl5::RegionGrid::for_screen(p.width_px, p.height_px, p.interlaced, 128);
}

int64_t Pxpl5Wiring::remember(const tracker::TrackerSample& sample, des::Time t) {
  const des::Time photon = expected_photon_time_ ? expected_photon_time_(t) : ctx_->photon_time_after(t);
  const int64_t token = next_token_++;
  poses_.emplace(token, ctx_->host.basis_of(sample).for_photon_time(photon));
  while (!poses_.empty() && poses_.begin()->second.sample.index < sample.index - kSamplesKept)
    poses_.erase(poses_.begin());
  return token;
}

// Before the first sample the application draws from where the head starts.
tracker::Pose Pxpl5Wiring::eye_pose_of_token(int64_t token, int eye) const {
  const auto it = poses_.find(token);
  if (it != poses_.end()) return ctx_->eye_pose(it->second.pose, eye);
  return tracker::eye_pose(ctx_->motion.pose_at(des::Time::zero()), eye, ctx_->ipd_m, ctx_->stereo);
}

pxpl5::WorkloadSource& Pxpl5Wiring::workload(const Pxpl5Common& common) {
  const pxpl5::RegionGrid g = grid();
  if (common.workload == Pxpl5WorkloadKind::synthetic) {
    workload_ = std::make_unique<pxpl5::SyntheticWorkload>(common.synthetic, g.regions(), ctx_->stream("pxpl5.bins"));
    return *workload_;
  }
  const renderer::Scene scene = renderer::make_scene(
      ctx_->scene->geometry, common.draws_spheres ? renderer::SphereForm::native : renderer::SphereForm::tessellated);
  // Every primitive of the geometry may be in view of each eye and touch
  // every region: one image must still fit the run's clock.
  for (const Pxpl5ViewSpan& span : common.view_spans) {
    double items = static_cast<double>(span.spheres ? scene.spheres().size() : scene.triangles().size());
    std::string text = span.spheres ? "spheres of /scene's geometry" : "triangles of /scene's geometry";
    if (span.per_eye && common.stereo) {
      items *= 2.0;
      text += " × 2 eyes";
    }
    if (span.per_region) {
      items *= g.regions();
      text += " × " + std::to_string(g.regions()) + " regions";
    }
    scenario::check_span_at(span.pointer, span.per_item_s, items, text);
  }
  std::vector<pxpl5::WorldTriangle> triangles;
  triangles.reserve(scene.triangles().size());
  for (const renderer::Triangle& t : scene.triangles())
    triangles.push_back({glm::dvec3(t.position_m[0]), glm::dvec3(t.position_m[1]), glm::dvec3(t.position_m[2])});
  std::vector<pxpl5::WorldSphere> spheres;
  spheres.reserve(scene.spheres().size());
  for (const renderer::Sphere& s : scene.spheres()) spheres.push_back({glm::dvec3(s.centre_m), s.radius_m});
  const display::RasterParams& p = ctx_->display.timing().params();
  pxpl5::ViewScreen screen;
  screen.hfov_deg = ctx_->display_params.hfov_deg;
  screen.width_px = p.width_px;
  screen.height_px = p.height_px;
  screen.region_px = g.region_px;
  screen.cull_back_faces = common.cull_back_faces;
  workload_ = std::make_unique<pxpl5::ViewWorkload>(pxpl5::ViewBinner(std::move(triangles), screen, std::move(spheres)),
                                                    [this](int64_t token, int eye) {
                                                      const tracker::Pose pose = eye_pose_of_token(token, eye);
                                                      return tracker::Pose{pose.position_m, pose.orientation};
                                                    });
  return *workload_;
}

pxpl5::EngineHooks Pxpl5Wiring::hooks() {
  pxpl5::EngineHooks h;
  h.newest_sample = [this](des::Time t) -> int64_t {
    const auto s = ctx_->host.newest_at(t);
    return s ? remember(*s, t) : -1;
  };
  h.newest_index = [this](des::Time t) -> int64_t {
    const auto s = ctx_->host.newest_at(t);
    return s ? s->index : -1;
  };
  h.sample_age_ms = [this](int64_t older, int64_t newer) {
    const auto a = poses_.find(older), b = poses_.find(newer);
    if (a == poses_.end() || b == poses_.end()) return 0.0;
    return (b->second.sample.measured_at - a->second.sample.measured_at).to_ms();
  };
  h.frame_ready = [this](const pxpl5::FrameReady& f) { present(f); };
  h.region_written = [this](const pxpl5::RegionWrite& w) { region_written(w); };
  h.stage = [this](const pxpl5::StageInterval& s) {
    if (s.stage == "SEND") transforms_sent_ = true;
    if (ctx_->timeline != nullptr) ctx_->timeline->add(s.stage, s.frame, s.eye, s.unit, s.start, s.end);
  };
  h.sample = [this](const std::string& name, double v) { samples_by_name_[name].add(v); };
  return h;
}

int64_t Pxpl5Wiring::image_id(int64_t frame, const pxpl5::EyeImage& e) {
  const auto key = std::make_pair(frame, e.eye);
  if (const auto it = image_ids_.find(key); it != image_ids_.end()) return it->second;
  const auto it = poses_.find(e.sample_token);
  int64_t id = -1;
  if (it == poses_.end()) {
    ++images_without_sample_;  // nothing tracked yet: the display keeps what it has
  } else {
    id = ctx_->images.add(ctx_->image_record(frame, e.eye, it->second, e.transform_start, e.copy_end));
  }
  image_ids_.emplace(key, id);
  while (image_ids_.size() > kImagesKept) image_ids_.erase(image_ids_.begin());
  return id;
}

// Each eye's image is registered with the pose it was computed from and
// swapped in at the next retrace (both eyes together in stereo).
void Pxpl5Wiring::present(const pxpl5::FrameReady& f) {
  des::Time last_copy_end = des::Time::zero();
  for (const pxpl5::EyeImage& e : f.eyes) {
    last_copy_end = std::max(last_copy_end, e.copy_end);
    const int64_t id = image_id(f.frame, e);
    if (id >= 0) ctx_->display.present_at_next_retrace(e.eye, id);
  }
  if (!f.eyes.empty()) read_to_copy_end_ = last_copy_end - f.eyes.front().sample_read_at;
}

// A Slats region reached the displayed buffer: its rectangle of the field's
// rows shows the image from now on.
void Pxpl5Wiring::region_written(const pxpl5::RegionWrite& w) {
  const int64_t id = image_id(w.image_field, w.image);
  if (id < 0) return;
  const display::RasterTiming& t = ctx_->display.timing();
  const int region = grid().region_px;
  const int first_line = w.field_row * region;
  const int last_line = std::min(first_line + region, t.lines_per_field()) - 1;
  display::BufferRegion r;
  r.x_begin = w.column * region;
  r.x_end = std::min(r.x_begin + region, t.params().width_px);
  r.row_begin = t.row_of(w.field, first_line);
  r.row_end = t.row_of(w.field, last_line) + 1;
  r.row_step = t.params().interlaced ? 2 : 1;
  ctx_->display.write_region_now(w.eye, r, id);
}

void Pxpl5Wiring::report(const pxpl5::Utilisation& u, int64_t frames_completed) const {
  results::LatencyRecorder& r = ctx_->recorder;
  r.object("stage_ms");
  for (const auto& [name, dist] : samples_by_name_) r.publish(name, dist);
  r.set("utilisation.gp", u.gp);
  r.set("utilisation.renderer", u.renderer);
  r.set("utilisation.ring", u.ring);
  r.set("utilisation.copy", u.copy);
  r.set("frames_completed", frames_completed);
  if (workload_) r.set("display_list_triangles", workload_->triangles());
  if (workload_ && workload_->spheres() > 0) r.set("display_list_spheres", workload_->spheres());
  r.set("images_without_sample", images_without_sample_);
  for (const char* name : {"transform_to_copy_end_fields", "copy_ms_per_frame"})
    if (!samples_by_name_.count(name)) r.publish(name, stats::Distribution{});
}

void bind_hardware(scenario::Section& s, pxpl5::HardwareParams& h) {
  s.integer("ring_channels", h.ring_channels, {.min = 1.0, .max = 64.0, .doc = "independent channels of the ring"});
  s.number("ring_mwords_per_s", h.ring_mwords_per_s,
           {.unit = "Mword/s", .min = 0.0, .above_min = true, .doc = "per channel (8 × 20 = 160 Mwords/s in all)"});
  s.integer("renderers", h.renderers, {.min = 1.0, .max = 256.0, .doc = "renderer boards"});
  s.integer("frame_buffers", h.frame_buffers, {.min = 1.0, .max = 2.0, .doc = "one per eye in stereo"});
  s.integer("words_per_command", h.words_per_command,
            {.min = 1.0, .max = 4096.0, .doc = "one Gouraud triangle for one eye: edge, z and colour planes"});
  s.integer("max_message_words", h.max_message_words, {.min = 1.0, .max = 1048576.0, .doc = "largest ring message"});
  s.check("max_message_words", h.max_message_words >= h.words_per_command,
          "must hold at least one command (words_per_command)");
  s.duration("copy_us_per_region", h.copy_time_per_region,
             {.unit = "us", .min = 0.0, .above_min = true, .doc = "renderer to frame buffer, one 128 × 128 region"});
  s.duration("render_us_per_command", h.render_time_per_command,
             {.unit = "us", .doc = "one triangle command into one region"});
}

void bind_pxpl5_common(scenario::Section& s, const sections::SharedParams& shared, const pxpl5::HardwareParams& hw,
                       Pxpl5Common& common) {
  common.stereo = shared.host.stereo;
  s.check("frame_buffers", !(common.stereo && hw.frame_buffers < 2), "stereo needs one frame buffer per eye (2)");
  s.choice("workload", common.workload,
           {{"synthetic", Pxpl5WorkloadKind::synthetic}, {"view", Pxpl5WorkloadKind::view}},
           {.doc = "synthetic: /scene's triangles and regions_per_triangle, the same every image; view: /scene's "
                   "geometry inside each eye's view at the pose used, binned by screen bounding box"});
  s.flag("cull_back_faces", common.cull_back_faces,
         {.doc = "workload view: the application culls back faces (PHIGS PLUS face culling); a triangle facing away "
                 "costs what one outside the view does"});
  s.check_pointer("/scene", shared.scene.has_value(), "Pixel-Planes 5 needs a scene (its triangles)");
  // Every triangle is dealt to a bin one by one.
  s.check_pointer("/scene/triangles", !shared.scene || shared.scene->triangles <= 100'000'000,
                  "Pixel-Planes 5 simulates each triangle: at most 1e8");
  if (!shared.scene) return;
  common.synthetic.triangles = shared.scene->triangles;
  common.synthetic.regions_per_triangle = shared.scene->regions_per_triangle;
}

}  // namespace latsim::pipelines
