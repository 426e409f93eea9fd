#include "latsim/results/frame_capture.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "latsim/renderer/camera.hpp"
#include "latsim/renderer/image_ops.hpp"
#include "latsim/renderer/ray_caster.hpp"
#include "latsim/results/latency_recorder.hpp"
#include "latsim/results/run_files.hpp"
#include "warped_spans.hpp"

namespace latsim::results {

namespace {

/// One stretch of a row showing one image, as collected during scanout.
struct ShownSpan {
  int x_begin = 0;
  int x_end = 0;
  bool lit = false;
  tracker::Pose eye_pose;
  des::Time measured_at;
  ImageRecord::Warp warp = ImageRecord::Warp::none;
  tracker::Pose source_pose;  ///< warped: the pose the application rendered from
  /// Address recalculation: the orientation is the newest when the span was
  /// written, looked up when the field has been scanned (samples measured
  /// during a field do not exist yet when field-level scanout hands over its lines).
  bool orientation_at_scanout = false;
  int eye = 0;
  des::Time written_at;
  des::Time photon_time;  ///< the instant the host predicts the looked-up orientation for
};

/// Everything one field of the captured eye showed, kept until the field ends.
struct Collection {
  int64_t field = -1;
  bool capture = false;                     ///< false: only primes the persistent buffers
  int64_t capture_index = -1;
  bool pixel_mode = false;                  ///< pixels from a PixelSource instead of images
  std::vector<std::vector<ShownSpan>> lines;  ///< image mode: spans per field line
  std::vector<ShownPixel> pixels;           ///< pixel mode: lines x width
  bool warped = false;                      ///< some span showed a time-warped image
  int64_t undefined_px = 0;                 ///< pixels a warp had nothing for
};

std::string capture_name(int64_t index, const char* what) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%04lld_%s.png", static_cast<long long>(index), what);
  return buf;
}

}  // namespace

struct FrameCapture::Impl {
  FrameCaptureInputs in;
  renderer::SceneSpec scene_spec;
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
  std::optional<renderer::Camera> camera;
  // Persistent across fields: an interlaced field replaces only its own rows.
  renderer::Frame displayed;
  renderer::Frame unwarped;  ///< the application's images before time warp
  renderer::Frame truth;
  std::vector<float> age_ms;
  int64_t entries = 0;
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
    // Spans of several lines (field fidelity) carry one write and photon time per line.
    for (int line = span.line; line < span.line_end; ++line) {
      const auto i = static_cast<uint64_t>(line - span.line);
      const des::Time written = i == 0 ? span.written_at : des::Time::ps(span.written.at(i));
      const des::Time photon = i == 0 ? span.photon_time : des::Time::ps(span.photons.at(i));
      collect_line(span, line, written, photon);
    }
  }

  void collect_line(const display::ScanoutSpan& span, int line, des::Time written, des::Time photon) {
    Collection& c = *current;
    if (c.pixel_mode) {
      const size_t offset = static_cast<size_t>(line) * static_cast<size_t>(width()) + static_cast<size_t>(span.x_begin);
      source->shown_pixels(span.eye, in.timing.row_of(span.field, line), span.x_begin,
                           std::span<ShownPixel>(c.pixels).subspan(offset, static_cast<size_t>(span.x_end - span.x_begin)));
      return;
    }
    ShownSpan s{span.x_begin, span.x_end, false, {}, {}, ImageRecord::Warp::none, {}, false, 0, {}};
    if (const ImageRecord* img = in.recorder.images().find(span.image_id)) {
      s.lit = true;
      s.eye_pose = img->eye_pose;
      s.measured_at = img->sample.measured_at;
      s.warp = img->warp;
      s.source_pose = img->source_pose;
      s.orientation_at_scanout = img->orientation_at_scanout;
      s.eye = span.eye;
      s.written_at = written;
      s.photon_time = photon;
    }
    c.lines[static_cast<size_t>(line)].push_back(s);
  }

  void ensure_renderer() {
    if (caster) return;
    caster.emplace(renderer::make_scene(scene_spec));
    camera.emplace(in.hfov_deg, width(), height());
    displayed = renderer::Frame::cleared(width(), height(), background);
    unwarped = renderer::Frame::cleared(width(), height(), background);
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
    std::vector<tracker::Pose> row_poses(static_cast<size_t>(height()));
    std::vector<PixelRay> list;
    for (int j = 0; j < in.timing.lines_per_field(); ++j) {
      const tracker::Pose head = in.motion.pose_at(photon(field, in.timing.line_time(field, j)));
      const tracker::Pose pose = tracker::eye_pose(head, eye, in.ipd_m, in.stereo);
      const int row = in.timing.row_of(field, j);
      row_poses[static_cast<size_t>(row)] = pose;
      if (per_pixel)
        for (int x = 0; x < width(); ++x)
          list.push_back({x, row, renderer::Ray{pose.position_m, camera->pixel_ray(x, row, pose.orientation)}});
    }
    if (per_pixel) cast_pixel_rays(list, truth);
    else caster->render_scanlines(*camera, row_poses, field_rows(field), truth, options());
  }

  /// When a pixel written at `written` is seen: the middle of its lit interval.
  des::Time photon(int64_t field, des::Time written) const {
    return in.persistence ? in.persistence->lit(field, written).middle() : written;
  }

  void clear_pixel(int x, int row) {
    displayed.colour.at(x, row) = background;
    displayed.depth.at(x, row) = std::numeric_limits<float>::infinity();
  }

  void set_age(int64_t field, int line, int x, bool lit, des::Time measured_at) {
    const int row = in.timing.row_of(field, line);
    const size_t i = static_cast<size_t>(row) * static_cast<size_t>(width()) + static_cast<size_t>(x);
    age_ms[i] = lit ? static_cast<float>((photon(field, in.timing.pixel_time(field, line, x)) - measured_at).to_ms())
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

  void cast_displayed_images(Collection& c) {
    // Rows showing one image across the whole width are cast as scanlines
    // from that image's pose; rows split by a swap during the line (pixel
    // scanout) or left unlit are filled span by span afterwards, and
    // time-warped spans are drawn as the compositor made them.
    const int lines = in.timing.lines_per_field();
    std::vector<tracker::Pose> row_poses(static_cast<size_t>(height()));
    std::vector<char> whole(static_cast<size_t>(lines), 0);
    std::vector<PixelRay> split;
    std::vector<WarpedSpan> warped;
    for (int j = 0; j < lines; ++j) {
      const int row = in.timing.row_of(c.field, j);
      const auto& spans = c.lines[static_cast<size_t>(j)];
      whole[static_cast<size_t>(j)] = spans.size() == 1 && spans[0].lit && spans[0].x_begin == 0 &&
                                      spans[0].x_end == width() && spans[0].warp == ImageRecord::Warp::none;
      if (whole[static_cast<size_t>(j)]) row_poses[static_cast<size_t>(row)] = spans[0].eye_pose;
      for (int x = 0; x < width(); ++x) set_age(c.field, j, x, false, {});
      for (const ShownSpan& s : spans) {
        if (s.lit && s.warp != ImageRecord::Warp::none)
          warped.push_back(WarpedSpan{row, s.x_begin, s.x_end, s.warp, s.source_pose, s.eye_pose});
        for (int x = s.x_begin; x < s.x_end; ++x) {
          set_age(c.field, j, x, s.lit, s.measured_at);
          if (!whole[static_cast<size_t>(j)] && s.lit && s.warp == ImageRecord::Warp::none)
            split.push_back({x, row, renderer::Ray{s.eye_pose.position_m, camera->pixel_ray(x, row, s.eye_pose.orientation)}});
        }
      }
    }
    caster->render_scanlines(*camera, row_poses, field_rows(c.field), displayed, options());
    for (int j = 0; j < lines; ++j) {
      if (whole[static_cast<size_t>(j)]) continue;
      const int row = in.timing.row_of(c.field, j);
      for (int x = 0; x < width(); ++x) clear_pixel(x, row);
    }
    cast_pixel_rays(split, displayed);
    if (warped.empty()) return;
    c.warped = true;
    unwarped = displayed;
    c.undefined_px = draw_warped_spans(*caster, *camera, warped, displayed, unwarped, options(), background);
  }

  // Address recalculation looks the orientation up as each pixel is fetched,
  // predicted by the host to the instant the pixel is seen.
  void resolve_orientations(Collection& c) const {
    for (auto& line : c.lines)
      for (ShownSpan& s : line)
        if (s.lit && s.orientation_at_scanout)
          if (const auto newest = in.host.pose_for(s.written_at, s.photon_time))
            s.eye_pose.orientation = tracker::eye_pose(newest->pose, s.eye, in.ipd_m, in.stereo).orientation;
  }

  void process(Collection& c) {
    resolve_orientations(c);
    ensure_renderer();
    cast_truth(c.field, c.pixel_mode);
    if (c.pixel_mode) cast_displayed_pixels(c);
    else cast_displayed_images(c);
    if (c.capture) write_capture(c);
  }

  void write_capture(const Collection& c) {
    const double error = renderer::image_error(displayed.colour, truth.colour);
    error_sum += error;
    LatencyRecorder& r = in.recorder;
    const std::string at = "frames." + std::to_string(entries++) + ".";
    r.list(at + "files");
    if (in.files.enabled()) {
      int file = 0;
      const auto write = [&](const char* what, const renderer::ImageRGB& image) {
        const std::string name = "frames/" + capture_name(c.capture_index, what);
        in.files.write_png(name, image);
        r.set(at + "files." + std::to_string(file++), name);
      };
      write("displayed", displayed.colour);
      write("truth", truth.colour);
      write("diff", renderer::difference_image(displayed.colour, truth.colour, diff_gain));
      write("age", renderer::heat_map(age_ms, width(), height(), age_scale_ms));
      if (c.warped) write("unwarped", unwarped.colour);
    }
    if (c.warped) r.set(at + "undefined_px", c.undefined_px);
    float max_age = 0.0f;
    for (float a : age_ms)
      if (!std::isnan(a) && a > max_age) max_age = a;
    r.set(at + "index", c.capture_index);
    r.set(at + "field", c.field);
    r.set(at + "t_ms", in.timing.field_start(c.field).to_ms());
    r.set(at + "image_error", error);
    r.set(at + "max_pixel_age_ms", static_cast<double>(max_age));
  }
};

FrameCapture::FrameCapture(const sections::FramesParams& frames, renderer::SceneSpec scene, FrameCaptureInputs inputs)
    : impl_(std::make_unique<Impl>(std::move(inputs))) {
  Impl& m = *impl_;
  for (double t : frames.at_s) m.at_fields.insert(m.in.timing.field_at_or_after(des::Time::from_seconds(t)));
  m.every_nth = frames.every_nth_refresh;
  m.max_captures = frames.max_captures;
  m.eye = frames.eye;
  m.threads = frames.threads;
  m.background = frames.background;
  m.diff_gain = static_cast<float>(frames.diff_gain);
  m.age_scale_ms = static_cast<float>(frames.age_scale_ms);
  m.scene_spec = std::move(scene);
}

FrameCapture::~FrameCapture() = default;

void FrameCapture::set_pixel_source(const PixelSource* source) { impl_->source = source; }

void FrameCapture::on_field_start(int eye, int64_t field, des::Time) {
  Impl& m = *impl_;
  if (eye != m.eye) return;
  if (m.current && m.current->field != field) {
    Collection done = std::move(*m.current);
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

void FrameCapture::finish() {
  Impl& m = *impl_;
  if (m.current) {
    Collection done = std::move(*m.current);
    m.current.reset();
    m.process(done);
  }
  m.in.recorder.list("frames");
  m.in.recorder.set("frames_mean_image_error", m.entries == 0 ? 0.0 : m.error_sum / static_cast<double>(m.entries));
}

}  // namespace latsim::results
