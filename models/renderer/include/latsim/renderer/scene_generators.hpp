// Built-in deterministic scenes: a test pattern, a furnished room and the gallery.
#pragma once

#include "latsim/renderer/scene.hpp"

namespace latsim::renderer {

/// Coloured boxes at 2 to 9 m in front of a checkered backdrop (z = -12 m) over a checkered
/// floor (y = -1.5 m), seen best from the origin looking down -z; misregistration shows
/// as boxes sliding against the backdrop by an amount that depends on their depth.
Scene make_test_pattern();

/// A 6 x 2.7 x 8 m room (x in [-3, 3], y in [0, 2.7], z in [-4, 4]) with tiled walls, floor
/// and ceiling and about a dozen furniture boxes; under two thousand triangles.
Scene make_room();

/// Parameters of the art gallery used by the address-recalculation experiment.
struct GalleryParams {
  double size_x_m = 20.0;
  double size_z_m = 20.0;
  double height_m = 3.0;
  int partition_count = 4;
  /// Pictures on each outer wall and on each side of each partition.
  int frames_per_wall = 3;
  /// Tessellation step of floor, ceiling, walls and partitions; choose a divisor of the
  /// region size so that segments of a large object align with region boundaries.
  double tile_m = 1.0;
};

/// The gallery: x in [-size_x/2, size_x/2], z likewise, y in [0, height]. Floor, ceiling
/// and the four outer walls are each one object spanning many regions; free-standing
/// partitions alternate between running along z and along x; every picture frame is its
/// own object. Throws std::invalid_argument for non-positive sizes or negative counts.
Scene make_gallery(const GalleryParams& params);

}  // namespace latsim::renderer
