// Time warp of rendered frames: re-projecting an image rendered from one eye
// pose to another, as a compositor does just before scanout.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "latsim/renderer/camera.hpp"
#include "latsim/renderer/image.hpp"

namespace latsim::renderer {

/// Whether the ray through pixel (x, y), seen with orientation `shown`, lies
/// inside the image a camera of the same kind rendered with orientation
/// `source`. A rotation-only warp has nothing to show where it does not: the
/// undefined edge that appears on the side the head turns towards.
bool inside_rotated_source(const Camera& camera, const glm::dquat& source, const glm::dquat& shown, int x, int y);

/// A frame re-projected to another pose; `defined` is 0 where no source pixel landed.
struct WarpedFrame {
  Frame frame;
  std::vector<uint8_t> defined;  ///< row-major, one flag per pixel
  int64_t undefined_px = 0;
};

/// Forward warp with depth. The source pixels' centres, each moved to where
/// its surface point (at its depth; points that hit nothing at infinity, by
/// direction only) appears from `shown`, form a grid of quads that is
/// rasterised into the destination with a depth test, each destination pixel
/// taking the colour of the nearest quad corner. A quad whose corners' depths
/// differ by more than `break_ratio` (or mix surface and sky) spans an
/// occlusion edge and is not drawn, so the surfaces a translation uncovers
/// stay `undefined` (disocclusion gaps), as do the edges no source pixel
/// reaches; a pixel no quad covers takes the source pixel whose centre lands
/// in it, if any. With `shown` == `source` the result equals the source exactly.
WarpedFrame warp_with_depth(const Frame& source, const Camera& camera, const tracker::Pose& source_pose,
                            const tracker::Pose& shown_pose, const glm::vec3& undefined, double break_ratio = 1.1);

}  // namespace latsim::renderer
