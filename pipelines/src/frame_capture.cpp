#include "latsim/pipelines/frame_capture.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "latsim/pipelines/latency_recorder.hpp"
#include "latsim/renderer/camera.hpp"
#include "latsim/renderer/image_ops.hpp"
#include "latsim/renderer/obj_loader.hpp"
#include "latsim/renderer/png_writer.hpp"
#include "latsim/renderer/ray_caster.hpp"
#include "latsim/renderer/scene_generators.hpp"

namespace latsim::pipelines {

namespace {

/// What /scene asks to be ray-cast: read while the run is built (so unknown
/// keys are caught up front), loaded only when the first field is cast.
struct SceneSpec {
  std::string type = "gallery";
  std::filesystem::path file;
  renderer::GalleryParams gallery;
};

SceneSpec read_scene(const scenario::ConfigNode* node) {
  SceneSpec s;
  if (node == nullptr) return s;
  // The same default and the same gallery keys as the address recalculation
  // pipelines, because /scene is one object shared by every reader.
  s.type = node->choice("type", "gallery", {"gallery", "room", "test_pattern", "obj"});
  if (s.type == "obj") {
    s.file = node->has("path") && !node->has("file") ? node->path("path") : node->path("file");
  } else if (s.type == "gallery") {
    renderer::GalleryParams& p = s.gallery;
    p.size_x_m = node->positive("size_x_m", p.size_x_m);
    p.size_z_m = node->positive("size_z_m", p.size_z_m);
    p.height_m = node->positive("height_m", p.height_m);
    p.partition_count = static_cast<int>(node->integer("partition_count", p.partition_count, 0, 64));
    p.frames_per_wall = static_cast<int>(node->integer("frames_per_wall", p.frames_per_wall, 0, 64));
    p.tile_m = node->positive("tile_m", p.tile_m);
  }
  return s;
}

renderer::Scene load_scene(const SceneSpec& s) {
  if (s.type == "test_pattern") return renderer::make_test_pattern();
  if (s.type == "room") return renderer::make_room();
  if (s.type == "obj") return renderer::load_obj(s.file);
  return renderer::make_gallery(s.gallery);
}

renderer::EyePose to_eye(const tracker::Pose& p) { return renderer::EyePose{p.position_m, p.orientation}; }

/// One stretch of a row showing one image, as collected during scanout.
struct ShownSpan {
  int x_begin = 0;
  int x_end = 0;
  bool lit = false;
  tracker::Pose eye_pose;
  des::Time measured_at;
};

/// Everything one field of the captured eye showed, kept until the field ends.
struct Collection {
  int64_t field = -1;
  bool capture = false;                     ///< false: only primes the persistent buffers
  int64_t capture_index = -1;
  bool pixel_mode = false;                  ///< pixels from a PixelSource instead of images
  std::vector<std::vector<ShownSpan>> lines;  ///< image mode: spans per field line
  std::vector<ShownPixel> pixels;           ///< pixel mode: lines x width
};

std::string capture_name(int64_t index, const char* what) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%04lld_%s.png", static_cast<long long>(index), what);
  return buf;
}

}  // namespace

struct FrameCapture::Impl {
  FrameCaptureInputs in;
  SceneSpec scene_spec;
  std::set<int64_t> at_fields;
  int64_t every_nth = 0;
  int64_t max_captures = 20;
  int eye = 0;
  int threads = 1;
  glm::vec3 background{0.0f};
  float diff_gain = 4.0f;
  float age_scale_ms = 100.0f;

  const PixelSource* source = nullptr;
  std::optional<Collection> current;
  int64_t captures_begun = 0;
  std::optional<renderer::RayCaster> caster;
  int64_t casters_built = 0;
  std::optional<renderer::Camera> camera;
  // Persistent across fields: an interlaced field replaces only its own rows.
  renderer::Frame displayed;
  renderer::Frame truth;
  std::vector<float> age_ms;
  nlohmann::json entries = nlohmann::json::array();
  double error_sum = 0.0;

  explicit Impl(FrameCaptureInputs inputs) : in(std::move(inputs)) {}

  int width() const { return in.timing.params().width_px; }
  int height() const { return in.timing.params().height_px; }

  bool qualifies(int64_t field) const {
    if (field < 0) return false;
    if (at_fields.count(field) != 0) return true;
    return every_nth > 0 && field % every_nth == every_nth - 1;
  }

  void begin_field(int64_t field) {
    const bool capture = qualifies(field) && captures_begun < max_captures;
    const int64_t after = captures_begun + (capture ? 1 : 0);
    // An interlaced capture also needs the rows the previous field left on screen.
    const bool prime = in.timing.params().interlaced && qualifies(field + 1) && after < max_captures;
    if (!capture && !prime) return;
    Collection c;
    c.field = field;
    c.capture = capture;
    if (capture) c.capture_index = captures_begun++;
    c.pixel_mode = source != nullptr;
    const size_t lines = static_cast<size_t>(in.timing.lines_per_field());
    if (c.pixel_mode) c.pixels.assign(lines * static_cast<size_t>(width()), ShownPixel{});
    else c.lines.assign(lines, {});
    current = std::move(c);
  }

  void collect(const display::ScanoutSpan& span) {
    Collection& c = *current;
    if (c.pixel_mode) {
      const size_t offset = static_cast<size_t>(span.line) * static_cast<size_t>(width()) +
                            static_cast<size_t>(span.x_begin);
      source->shown_pixels(span.eye, span.row, span.x_begin,
                           std::span<ShownPixel>(c.pixels).subspan(offset, static_cast<size_t>(span.x_end - span.x_begin)));
      return;
    }
    ShownSpan s{span.x_begin, span.x_end, false, {}, {}};
    if (const ImageRecord* img = in.recorder.image(span.image_id)) {
      s.lit = true;
      s.eye_pose = img->eye_pose;
      s.measured_at = img->sample.measured_at;
      if (img->orientation_at_scanout) {
        // Address recalculation: the orientation is looked up as the pixel is fetched.
        if (const auto newest = in.host.newest_at(span.photon_time)) {
          s.eye_pose.orientation = eye_pose_of(newest->pose, span.eye, in.ipd_m, in.stereo).orientation;
        }
      }
    }
    c.lines[static_cast<size_t>(span.line)].push_back(s);
  }

  void ensure_renderer() {
    if (caster) return;
    caster.emplace(load_scene(scene_spec));
    ++casters_built;
    camera.emplace(in.hfov_deg, width(), height());
    displayed = renderer::Frame::cleared(width(), height(), background);
    truth = renderer::Frame::cleared(width(), height(), background);
    age_ms.assign(static_cast<size_t>(width()) * static_cast<size_t>(height()), std::numeric_limits<float>::quiet_NaN());
  }

  renderer::RenderOptions options() const {
    renderer::RenderOptions o;
    o.background = background;
    o.thread_count = threads;
    return o;
  }

  renderer::RowSet field_rows(int64_t field) const {
    return in.timing.params().interlaced ? renderer::RowSet::field(in.timing.row_of(field, 0), height())
                                         : renderer::RowSet::all(height());
  }

  /// One ray per listed pixel, each from its own pose and through its source pixel.
  struct PixelRay {
    int x, row;
    renderer::Ray ray;
  };
  void cast_pixel_rays(const std::vector<PixelRay>& list, renderer::Frame& frame) {
    std::vector<renderer::Ray> rays;
    rays.reserve(list.size());
    for (const PixelRay& p : list) rays.push_back(p.ray);
    std::vector<renderer::Hit> hits(rays.size());
    caster->cast_rays(rays, hits, options());
    for (size_t i = 0; i < list.size(); ++i) {
      frame.colour.at(list[i].x, list[i].row) = hits[i].colour;
      frame.depth.at(list[i].x, list[i].row) = hits[i].distance_m;
    }
  }

  /// The truth: one true pose per row, at the instant the row's first pixel is
  /// lit. Per pixel it is cast through the same ray path, in the same order,
  /// as a per-pixel displayed image, so that equal poses give equal pixels.
  void cast_truth(int64_t field, bool per_pixel) {
    std::vector<renderer::EyePose> row_poses(static_cast<size_t>(height()));
    std::vector<PixelRay> list;
    for (int j = 0; j < in.timing.lines_per_field(); ++j) {
      const tracker::Pose head = in.motion.pose_at(in.timing.line_time(field, j));
      const renderer::EyePose pose = to_eye(eye_pose_of(head, eye, in.ipd_m, in.stereo));
      const int row = in.timing.row_of(field, j);
      row_poses[static_cast<size_t>(row)] = pose;
      if (per_pixel)
        for (int x = 0; x < width(); ++x)
          list.push_back({x, row, renderer::Ray{pose.position_m, camera->pixel_ray(x, row, pose.orientation)}});
    }
    if (per_pixel) cast_pixel_rays(list, truth);
    else caster->render_scanlines(*camera, row_poses, field_rows(field), truth, options());
  }

  void clear_pixel(int x, int row) {
    displayed.colour.at(x, row) = background;
    displayed.depth.at(x, row) = std::numeric_limits<float>::infinity();
  }

  void set_age(int64_t field, int line, int x, bool lit, des::Time measured_at) {
    const int row = in.timing.row_of(field, line);
    const size_t i = static_cast<size_t>(row) * static_cast<size_t>(width()) + static_cast<size_t>(x);
    age_ms[i] = lit ? static_cast<float>((in.timing.pixel_time(field, line, x) - measured_at).to_ms())
                    : std::numeric_limits<float>::quiet_NaN();
  }

  void cast_displayed_pixels(const Collection& c) {
    std::vector<PixelRay> list;
    list.reserve(c.pixels.size());
    for (int j = 0; j < in.timing.lines_per_field(); ++j) {
      const int row = in.timing.row_of(c.field, j);
      for (int x = 0; x < width(); ++x) {
        const ShownPixel& p = c.pixels[static_cast<size_t>(j) * static_cast<size_t>(width()) + static_cast<size_t>(x)];
        set_age(c.field, j, x, p.lit, p.measured_at);
        // Unlit pixels get a ray too, so that the batches line up with the truth's.
        const glm::dvec3 dir = camera->pixel_ray(p.source_x, p.source_y, p.eye_pose.orientation);
        list.push_back({x, row, renderer::Ray{p.eye_pose.position_m, dir}});
      }
    }
    cast_pixel_rays(list, displayed);
    for (int j = 0; j < in.timing.lines_per_field(); ++j)
      for (int x = 0; x < width(); ++x)
        if (!c.pixels[static_cast<size_t>(j) * static_cast<size_t>(width()) + static_cast<size_t>(x)].lit)
          clear_pixel(x, in.timing.row_of(c.field, j));
  }

  void cast_displayed_images(const Collection& c) {
    // Rows showing one image across the whole width are cast as scanlines
    // from that image's pose; rows split by a swap during the line (pixel
    // scanout) or left unlit are filled span by span afterwards.
    const int lines = in.timing.lines_per_field();
    std::vector<renderer::EyePose> row_poses(static_cast<size_t>(height()));
    std::vector<char> whole(static_cast<size_t>(lines), 0);
    std::vector<PixelRay> split;
    for (int j = 0; j < lines; ++j) {
      const int row = in.timing.row_of(c.field, j);
      const auto& spans = c.lines[static_cast<size_t>(j)];
      whole[static_cast<size_t>(j)] =
          spans.size() == 1 && spans[0].lit && spans[0].x_begin == 0 && spans[0].x_end == width();
      if (whole[static_cast<size_t>(j)]) row_poses[static_cast<size_t>(row)] = to_eye(spans[0].eye_pose);
      for (int x = 0; x < width(); ++x) set_age(c.field, j, x, false, {});
      for (const ShownSpan& s : spans)
        for (int x = s.x_begin; x < s.x_end; ++x) {
          set_age(c.field, j, x, s.lit, s.measured_at);
          if (!whole[static_cast<size_t>(j)] && s.lit)
            split.push_back({x, row, renderer::Ray{s.eye_pose.position_m, camera->pixel_ray(x, row, s.eye_pose.orientation)}});
        }
    }
    caster->render_scanlines(*camera, row_poses, field_rows(c.field), displayed, options());
    for (int j = 0; j < lines; ++j) {
      if (whole[static_cast<size_t>(j)]) continue;
      const int row = in.timing.row_of(c.field, j);
      for (int x = 0; x < width(); ++x) clear_pixel(x, row);
    }
    cast_pixel_rays(split, displayed);
  }

  void process(const Collection& c) {
    ensure_renderer();
    cast_truth(c.field, c.pixel_mode);
    if (c.pixel_mode) cast_displayed_pixels(c);
    else cast_displayed_images(c);
    if (c.capture) write_capture(c);
  }

  void write_capture(const Collection& c) {
    const double error = renderer::image_error(displayed.colour, truth.colour);
    error_sum += error;
    nlohmann::json files = nlohmann::json::array();
    if (!in.out_dir.empty()) {
      const std::filesystem::path dir = in.out_dir / "frames";
      std::filesystem::create_directories(dir);
      const auto write = [&](const char* what, const renderer::ImageRGB& image) {
        const std::string name = capture_name(c.capture_index, what);
        renderer::write_png(dir / name, image);
        files.push_back("frames/" + name);
      };
      write("displayed", displayed.colour);
      write("truth", truth.colour);
      write("diff", renderer::difference_image(displayed.colour, truth.colour, diff_gain));
      write("age", renderer::heat_map(age_ms, width(), height(), age_scale_ms));
    }
    float max_age = 0.0f;
    for (float a : age_ms)
      if (!std::isnan(a) && a > max_age) max_age = a;
    entries.push_back({{"index", c.capture_index},
                       {"field", c.field},
                       {"t_ms", in.timing.field_start(c.field).to_ms()},
                       {"image_error", error},
                       {"max_pixel_age_ms", max_age},
                       {"files", files}});
  }
};

FrameCapture::FrameCapture(const scenario::ConfigNode& frames, const scenario::ConfigNode* scene,
                           FrameCaptureInputs inputs)
    : impl_(std::make_unique<Impl>(std::move(inputs))) {
  Impl& m = *impl_;
  for (double t : frames.numbers("at_s", {})) {
    if (!(t >= 0.0) || t > 1e6) frames.fail("at_s", "capture times must lie in [0, 1e6] seconds");
    m.at_fields.insert(m.in.timing.field_at_or_after(des::Time::from_seconds(t)));
  }
  m.every_nth = frames.integer("every_nth_refresh", 0, 0, int64_t{1} << 40);
  m.max_captures = frames.integer("max_captures", 20, 0, 100000);
  m.eye = static_cast<int>(frames.integer("eye", 0, 0, 1));
  if (m.eye == 1 && !m.in.stereo) frames.fail("eye", "eye 1 exists only on a stereo display (/host/stereo)");
  m.threads = static_cast<int>(frames.integer("threads", 1, 1, 256));
  const std::vector<double> bg = frames.numbers("background", {0.0, 0.0, 0.0});
  if (bg.size() != 3) frames.fail("background", "expected a linear colour [r, g, b]");
  m.background = glm::vec3(static_cast<float>(bg[0]), static_cast<float>(bg[1]), static_cast<float>(bg[2]));
  m.diff_gain = static_cast<float>(frames.positive("diff_gain", 4.0));
  m.age_scale_ms = static_cast<float>(frames.positive("age_scale_ms", 100.0));
  if (m.at_fields.empty() && m.every_nth == 0)
    frames.fail("at_s", "say which fields to capture: \"at_s\": [seconds, ...] and/or \"every_nth_refresh\": N");
  m.scene_spec = read_scene(scene);
}

FrameCapture::~FrameCapture() = default;

void FrameCapture::set_pixel_source(const PixelSource* source) { impl_->source = source; }

void FrameCapture::on_field_start(int eye, int64_t field, des::Time) {
  Impl& m = *impl_;
  if (eye != m.eye) return;
  if (m.current && m.current->field != field) {
    const Collection done = std::move(*m.current);
    m.current.reset();
    m.process(done);
  }
  m.begin_field(field);
}

void FrameCapture::on_scanout(const display::ScanoutSpan& span) {
  Impl& m = *impl_;
  if (span.eye != m.eye || !m.current || span.field != m.current->field) return;
  m.collect(span);
}

void FrameCapture::finish(nlohmann::json& figures) {
  Impl& m = *impl_;
  if (m.current) {
    const Collection done = std::move(*m.current);
    m.current.reset();
    m.process(done);
  }
  figures["frames"] = m.entries;
  figures["frames_mean_image_error"] = m.entries.empty() ? 0.0 : m.error_sum / static_cast<double>(m.entries.size());
}

int64_t FrameCapture::renderers_built() const { return impl_->casters_built; }

std::unique_ptr<FrameCapture> make_frame_capture(const scenario::ConfigNode& frames, const scenario::ConfigNode& root,
                                                 FrameCaptureInputs inputs) {
  // "enabled": false keeps a scenario's capture settings but casts nothing
  // (the speed of a run without frames is measured that way).
  const std::optional<scenario::ConfigNode> scene = root.optional_child("scene");
  if (!frames.boolean("enabled", true)) {
    frames.mark_all_read();
    (void)read_scene(scene ? &*scene : nullptr);  // its keys stay known, nothing is loaded
    return nullptr;
  }
  return std::make_unique<FrameCapture>(frames, scene ? &*scene : nullptr, std::move(inputs));
}

}  // namespace latsim::pipelines
