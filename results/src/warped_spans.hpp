// What time-warped images look like on screen, for frame capture: the warped
// pixels, the undefined edge and disocclusion gaps, and the image as the
// application rendered it before the warp.
#pragma once

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "latsim/renderer/camera.hpp"
#include "latsim/renderer/image.hpp"
#include "latsim/renderer/ray_caster.hpp"
#include "latsim/results/image_record.hpp"

namespace latsim::results {

/// A stretch of a row that showed a warped image.
struct WarpedSpan {
  int row = 0;
  int x_begin = 0;
  int x_end = 0;
  ImageRecord::Warp warp = ImageRecord::Warp::rotation;
  tracker::Pose source;  ///< the eye pose the application rendered from
  tracker::Pose shown;   ///< the eye pose the warp re-projected to
};

/// Draws each span into `displayed` as the compositor made it: a
/// rotation-only warp is the scene from the shown pose wherever the source
/// image has pixels (the rest is `undefined`); a warp with depth is the
/// source image (cast from its pose, with depth) forward-warped to the shown
/// pose, its gaps `undefined`. Into `unwarped` goes the source image itself.
/// Returns the number of undefined pixels.
int64_t draw_warped_spans(const renderer::RayCaster& caster, const renderer::Camera& camera,
                          std::span<const WarpedSpan> spans, renderer::Frame& displayed, renderer::Frame& unwarped,
                          const renderer::RenderOptions& options, const glm::vec3& undefined);

}  // namespace latsim::results
