#include "warped_spans.hpp"

#include <cstring>
#include <optional>
#include <vector>

#include "latsim/renderer/image_warp.hpp"

namespace latsim::results {

namespace {

bool same_pose(const tracker::Pose& a, const tracker::Pose& b) {
  return a.position_m == b.position_m && a.orientation == b.orientation;
}

/// Spans sharing one (source, shown, kind): one source cast, one warp.
struct Group {
  ImageRecord::Warp warp;
  tracker::Pose source, shown;
  std::vector<const WarpedSpan*> spans;
};

std::vector<Group> group(std::span<const WarpedSpan> spans) {
  std::vector<Group> groups;
  for (const WarpedSpan& s : spans) {
    Group* g = nullptr;
    for (Group& c : groups)
      if (c.warp == s.warp && same_pose(c.source, s.source) && same_pose(c.shown, s.shown)) g = &c;
    if (!g) g = &groups.emplace_back(Group{s.warp, s.source, s.shown, {}});
    g->spans.push_back(&s);
  }
  return groups;
}

void copy_pixel(const renderer::Frame& from, renderer::Frame& to, int x, int y) {
  to.colour.at(x, y) = from.colour.at(x, y);
  to.depth.at(x, y) = from.depth.at(x, y);
}

}  // namespace

int64_t draw_warped_spans(const renderer::RayCaster& caster, const renderer::Camera& camera,
                          std::span<const WarpedSpan> spans, renderer::Frame& displayed, renderer::Frame& unwarped,
                          const renderer::RenderOptions& options, const glm::vec3& undefined) {
  int64_t undefined_px = 0;
  // Source images are cast once each, whole (a warp with depth needs them whole).
  std::vector<std::pair<tracker::Pose, renderer::Frame>> sources;
  const auto source_frame = [&](const tracker::Pose& pose) -> const renderer::Frame& {
    for (const auto& [p, f] : sources)
      if (same_pose(p, pose)) return f;
    return sources.emplace_back(pose, caster.render_frame(camera, pose, options)).second;
  };
  for (const Group& g : group(spans)) {
    const renderer::Frame& src = source_frame(g.source);
    std::optional<renderer::Frame> rotated;
    std::optional<renderer::WarpedFrame> moved;
    if (g.warp == ImageRecord::Warp::positional)
      moved = renderer::warp_with_depth(src, camera, g.source, g.shown, undefined);
    else
      rotated = caster.render_frame(camera, g.shown, options);
    for (const WarpedSpan* s : g.spans)
      for (int x = s->x_begin; x < s->x_end; ++x) {
        copy_pixel(src, unwarped, x, s->row);
        bool defined = true;
        if (moved) {
          defined = moved->defined[static_cast<size_t>(s->row) * static_cast<size_t>(camera.width_px()) +
                                   static_cast<size_t>(x)] != 0;
          copy_pixel(moved->frame, displayed, x, s->row);
        } else {
          defined = renderer::inside_rotated_source(camera, g.source.orientation, g.shown.orientation, x, s->row);
          if (defined) copy_pixel(*rotated, displayed, x, s->row);
          else displayed.colour.at(x, s->row) = undefined;
        }
        if (!defined) ++undefined_px;
      }
  }
  return undefined_px;
}

}  // namespace latsim::results
