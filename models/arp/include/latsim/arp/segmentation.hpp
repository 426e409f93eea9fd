// Segmentation of a scene along region boundaries, and the vertices that
// neighbouring segments share (where tears open).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "latsim/renderer/region_grid.hpp"
#include "latsim/renderer/scene.hpp"

namespace latsim::arp {

/// One unit that region priority rendering assigns to a memory: a whole
/// object, or the part of a large object inside one region.
struct Segment {
  uint32_t source_object = 0;   ///< object of the input scene
  uint32_t scene_object = 0;    ///< object of SegmentedScene::scene holding its triangles
  std::vector<int> regions;     ///< linear indices of the regions it reaches into (one when cut)
  bool animated = false;
  /// Object segments it stands for, the unit in which renders are counted: 1
  /// for a cut segment; for a whole object, the parts segmentation would cut
  /// it into (one per region it has triangles in), so that the same
  /// geometry counts the same with and without segmentation.
  int64_t object_segments = 1;
};

/// A vertex position used by two segments whose regions differ, so the two
/// may be drawn by different memories from different viewpoints.
struct SharedVertex {
  glm::dvec3 position_m{0.0};
  uint32_t segment_a = 0;
  uint32_t segment_b = 0;
};

/// The scene as region priority rendering draws it.
struct SegmentedScene {
  renderer::Scene scene;            ///< one object per segment, in segment order
  std::vector<Segment> segments;
  std::vector<SharedVertex> shared_vertices;
  bool segmented = false;
};

/// Cuts every static object along the grid's region boundaries (animated
/// objects stay whole: they always live in the fastest memory). Triangles
/// crossing a boundary are clipped to each region's column and fanned; a cut
/// vertex lies exactly on the boundary and is computed from the edge's
/// endpoints in a fixed order, so both sides get bit-identical coordinates.
SegmentedScene segment_scene(const renderer::Scene& scene, const renderer::RegionGrid& grid);

/// The scene without cutting: one segment per object, reaching into every
/// region its bounds overlap, counting the object segments it would be cut into.
SegmentedScene whole_objects(const renderer::Scene& scene, const renderer::RegionGrid& grid);

}  // namespace latsim::arp
