// Embree 3 ray casting of a Scene: single rays, ray sets and the frame paths.
#pragma once

#include "latsim/renderer/camera.hpp"
#include "latsim/renderer/image.hpp"
#include "latsim/renderer/scene.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace latsim::renderer {

/// One flag per scene object (non-zero = visible); an empty mask shows every object.
using ObjectMask = std::vector<uint8_t>;

/// The result of one ray: the nearest surface, its shaded colour and what it belongs to.
struct Hit {
  static constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
  bool hit = false;
  /// Distance from the ray origin in metres; +infinity on a miss.
  float distance_m = std::numeric_limits<float>::infinity();
  /// Interpolated vertex colour times a fixed world-space light; background on a miss.
  glm::vec3 colour{0.0f};
  uint32_t object_id = kNone;
  /// Index into Scene::triangles().
  uint32_t primitive_id = kNone;
};

/// A ray in world space; the direction need not be unit length.
struct Ray {
  glm::dvec3 origin_m{0.0};
  glm::dvec3 direction{0.0, 0.0, -1.0};
};

/// How a batch of rays is cast.
struct RenderOptions {
  glm::vec3 background{0.0f};
  /// Worker threads for this call (>= 1); results are identical for every value.
  int thread_count = 1;
  /// Objects to render; empty = all. Its size must equal the scene's object count.
  ObjectMask object_mask;
};

/// A set of image rows: first, first + step, ... while < end.
struct RowSet {
  int first = 0;
  int end = 0;
  int step = 1;

  static RowSet all(int height) { return {0, height, 1}; }
  /// Rows with row % 2 == parity (0: rows 0, 2, 4 ...; 1: rows 1, 3, 5 ...), one
  /// interlaced field; which parity a display calls "odd" is the display model's choice.
  static RowSet field(int parity, int height) { return {parity, height, 2}; }
  static RowSet range(int first_row, int end_row) { return {first_row, end_row, 1}; }
  int count() const { return end > first ? (end - first + step - 1) / step : 0; }
  int row(int k) const { return first + k * step; }
};

/// One pixel to cast from its own pose (frameless rendering).
struct PixelRequest {
  int x = 0;
  int y = 0;
  tracker::Pose pose;
};

/// Owns an Embree device and scene built from a copy of a Scene, and casts rays into it.
/// Const member functions may be called concurrently from several threads.
class RayCaster {
 public:
  /// Builds the acceleration structure. embree_config is passed to rtcNewDevice; the
  /// default limits Embree's own build threads to one so that it does not compete with
  /// the caller's thread budget. Throws std::runtime_error if Embree reports an error.
  explicit RayCaster(Scene scene, const std::string& embree_config = "threads=1");
  ~RayCaster();
  RayCaster(RayCaster&&) noexcept;
  RayCaster& operator=(RayCaster&&) noexcept;
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  const Scene& scene() const;

  /// One rtcIntersect1 query from origin along dir (normalised internally); a miss has
  /// black colour (the batch paths use RenderOptions::background instead).
  Hit cast(const glm::dvec3& origin_m, const glm::dvec3& dir) const;
  Hit cast(const glm::dvec3& origin_m, const glm::dvec3& dir, const ObjectMask& mask) const;
  /// Casts rays[i] into hits[i] in parallel chunks; spans must have equal sizes.
  void cast_rays(std::span<const Ray> rays, std::span<Hit> hits, const RenderOptions& options) const;

  /// (a) A whole frame from one pose, sized to the camera.
  Frame render_frame(const Camera& camera, const tracker::Pose& pose, const RenderOptions& options) const;
  /// (b) Only the given rows, from one pose, into an existing frame; other rows keep
  /// their contents. The frame must match the camera's size.
  void render_rows(const Camera& camera, const tracker::Pose& pose, const RowSet& rows, Frame& frame,
                   const RenderOptions& options) const;
  /// (c) Just-in-time scanline: row y is cast from row_poses[y]; only rows in the set are
  /// touched. row_poses must hold one pose per camera row.
  void render_scanlines(const Camera& camera, std::span<const tracker::Pose> row_poses, const RowSet& rows,
                        Frame& frame, const RenderOptions& options) const;
  /// (d) Individual pixels, each from its own pose. Requests are cast in parallel and
  /// written in request order, so a pixel requested twice keeps the later result.
  void render_pixels(const Camera& camera, std::span<const PixelRequest> requests, Frame& frame,
                     const RenderOptions& options) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace latsim::renderer
