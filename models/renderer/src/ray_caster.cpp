#include "latsim/renderer/ray_caster.hpp"

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace latsim::renderer {
namespace {

// Shading is a fixed light in world space, not tied to the eye, so that a surface looks
// the same from every viewpoint; image-based strategies (cube memories, reused frames)
// then differ from direct rendering only by geometry, which is what latsim measures.
const glm::vec3 kLightDirection = glm::normalize(glm::vec3(0.4f, 1.0f, 0.6f));
constexpr float kAmbient = 0.35f;
constexpr float kDiffuse = 0.65f;
// Rays handed to Embree in one stream call by the ray-set paths.
constexpr size_t kChunkRays = 64;

// An intersection context that also carries the object mask, so the filter callback can
// reach it from the context pointer Embree hands back.
struct MaskedContext {
  RTCIntersectContext context;
  const uint8_t* mask;
};

void reject_masked_objects(const RTCFilterFunctionNArguments* args) {
  const auto* masked = reinterpret_cast<const MaskedContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    if (masked->mask[RTCHitN_geomID(args->hit, args->N, i)] == 0) args->valid[i] = 0;
  }
}

// Embree traces a ray only when its origin and direction are finite and below
// about 1.8e18 in every component (its ray.valid(), an assertion that ends the
// process); poses and directions outside that are refused here instead.
constexpr double kLargestTraceable = 1e18;

bool traceable(const glm::dvec3& v) {
  return std::fabs(v.x) <= kLargestTraceable && std::fabs(v.y) <= kLargestTraceable &&
         std::fabs(v.z) <= kLargestTraceable;  // false for NaN too
}

std::string vec_text(const glm::dvec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", v.x, v.y, v.z);
  return buf;
}

RTCRayHit make_ray(const glm::dvec3& origin_m, const glm::dvec3& dir) {
  const glm::dvec3 unit = glm::normalize(dir);
  if (!traceable(origin_m) || !traceable(unit) || !(glm::dot(unit, unit) > 0.5)) [[unlikely]]
    throw std::invalid_argument("ray caster: cannot trace a ray from " + vec_text(origin_m) + " along " +
                                vec_text(dir) + ": the origin must be finite and within 1e18 m, the direction "
                                "finite and not zero");
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(origin_m.x);
  rh.ray.org_y = static_cast<float>(origin_m.y);
  rh.ray.org_z = static_cast<float>(origin_m.z);
  rh.ray.dir_x = static_cast<float>(unit.x);
  rh.ray.dir_y = static_cast<float>(unit.y);
  rh.ray.dir_z = static_cast<float>(unit.z);
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

// Runs body(i) for i in [0, count) on thread_count workers. Each index is independent
// and writes only its own outputs, so the result does not depend on the schedule.
template <typename Body>
void parallel_indices(int thread_count, size_t count, const Body& body) {
  if (thread_count <= 1 || count <= 1) {
    for (size_t i = 0; i < count; ++i) body(i);
    return;
  }
  tbb::task_arena arena(thread_count);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i) body(i);
    });
  });
}

void check_frame(const Camera& camera, const Frame& frame) {
  if (frame.colour.width != camera.width_px() || frame.colour.height != camera.height_px() ||
      frame.depth.width != camera.width_px() || frame.depth.height != camera.height_px() ||
      frame.colour.pixels.size() != frame.depth.depth_m.size()) {
    throw std::invalid_argument("ray caster: frame is " + std::to_string(frame.colour.width) + " x " +
                                std::to_string(frame.colour.height) + " but the camera is " +
                                std::to_string(camera.width_px()) + " x " +
                                std::to_string(camera.height_px()) +
                                "; create it with Frame::cleared(camera size)");
  }
}

void check_rows(const Camera& camera, const RowSet& rows) {
  if (rows.step < 1 || rows.first < 0 || rows.end > camera.height_px()) {
    throw std::invalid_argument("ray caster: row set [" + std::to_string(rows.first) + ", " +
                                std::to_string(rows.end) + ") step " + std::to_string(rows.step) +
                                " does not fit an image of " + std::to_string(camera.height_px()) +
                                " rows");
  }
}

}  // namespace

struct RayCaster::Impl {
  Scene scene;
  std::vector<glm::vec3> normals;
  RTCDevice device = nullptr;
  RTCScene rtc_scene = nullptr;

  ~Impl() {
    if (rtc_scene != nullptr) rtcReleaseScene(rtc_scene);
    if (device != nullptr) rtcReleaseDevice(device);
  }

  void check(const char* what) const {
    const RTCError error = rtcGetDeviceError(device);
    if (error != RTC_ERROR_NONE) {
      throw std::runtime_error(std::string("ray caster: Embree error ") + std::to_string(error) +
                               " while " + what);
    }
  }

  void build(const std::string& embree_config) {
    device = rtcNewDevice(embree_config.c_str());
    if (device == nullptr) {
      throw std::runtime_error("ray caster: rtcNewDevice(\"" + embree_config + "\") failed with error " +
                               std::to_string(rtcGetDeviceError(nullptr)));
    }
    if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED) == 0) {
      throw std::runtime_error("ray caster: this Embree build lacks filter functions, needed for object masks");
    }
    rtc_scene = rtcNewScene(device);
    // ROBUST keeps shared edges watertight, so tiled surfaces show no cracks.
    rtcSetSceneFlags(rtc_scene, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    const auto& triangles = scene.triangles();
    normals.reserve(triangles.size());
    for (const Triangle& t : triangles) {
      const glm::vec3 n = glm::cross(t.position_m[1] - t.position_m[0], t.position_m[2] - t.position_m[0]);
      const float length = glm::length(n);
      normals.push_back(length > 0.0f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f));
    }
    // One Embree geometry per object with geomID = object id, so hits name their object
    // and the mask filter is one table lookup.
    for (uint32_t id = 0; id < scene.object_count(); ++id) {
      const SceneObject& object = scene.objects()[id];
      if (object.triangle_count == 0) continue;
      RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
          geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * object.triangle_count));
      auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
          geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), object.triangle_count));
      check("allocating geometry buffers");
      for (uint32_t k = 0; k < object.triangle_count; ++k) {
        const Triangle& t = triangles[object.first_triangle + k];
        for (int c = 0; c < 3; ++c) {
          const size_t v = 3 * static_cast<size_t>(k) + static_cast<size_t>(c);
          vertices[3 * v + 0] = t.position_m[c].x;
          vertices[3 * v + 1] = t.position_m[c].y;
          vertices[3 * v + 2] = t.position_m[c].z;
          indices[v] = static_cast<unsigned>(v);
        }
      }
      rtcCommitGeometry(geometry);
      rtcAttachGeometryByID(rtc_scene, geometry, id);
      rtcReleaseGeometry(geometry);
    }
    rtcCommitScene(rtc_scene);
    check("building the scene");
  }

  void check_mask(const ObjectMask& mask) const {
    if (!mask.empty() && mask.size() != scene.object_count()) {
      throw std::invalid_argument("ray caster: object mask has " + std::to_string(mask.size()) +
                                  " entries but the scene has " + std::to_string(scene.object_count()) +
                                  " objects");
    }
  }

  MaskedContext context(const ObjectMask& mask, bool coherent) const {
    MaskedContext masked{};
    rtcInitIntersectContext(&masked.context);
    masked.context.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    masked.mask = mask.empty() ? nullptr : mask.data();
    if (masked.mask != nullptr) masked.context.filter = reject_masked_objects;
    return masked;
  }

  void trace(RTCRayHit* rays, size_t count, const ObjectMask& mask, bool coherent) const {
    MaskedContext masked = context(mask, coherent);
    rtcIntersect1M(rtc_scene, &masked.context, rays, static_cast<unsigned>(count), sizeof(RTCRayHit));
  }

  Hit resolve(const RTCRayHit& rh, const glm::vec3& background) const {
    Hit hit;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
      hit.colour = background;
      return hit;
    }
    const SceneObject& object = scene.objects()[rh.hit.geomID];
    const uint32_t triangle_id = object.first_triangle + rh.hit.primID;
    const Triangle& t = scene.triangles()[triangle_id];
    const float u = rh.hit.u;
    const float v = rh.hit.v;
    const glm::vec3 base = (1.0f - u - v) * t.colour[0] + u * t.colour[1] + v * t.colour[2];
    // Two-sided lighting: walls are seen from inside and boxes from outside alike.
    const float light = kAmbient + kDiffuse * std::fabs(glm::dot(normals[triangle_id], kLightDirection));
    hit.hit = true;
    hit.distance_m = rh.ray.tfar;
    hit.colour = base * light;
    hit.object_id = rh.hit.geomID;
    hit.primitive_id = triangle_id;
    return hit;
  }

  // Casts the pixels (x, row) for x in [0, width) from one pose as one coherent stream.
  void cast_row(const Camera& camera, const tracker::Pose& pose, int row, Frame& frame,
                const RenderOptions& options) const {
    const int width = camera.width_px();
    std::vector<RTCRayHit> rays(static_cast<size_t>(width));
    for (int x = 0; x < width; ++x) {
      rays[static_cast<size_t>(x)] = make_ray(pose.position_m, camera.pixel_ray(x, row, pose.orientation));
    }
    trace(rays.data(), rays.size(), options.object_mask, true);
    for (int x = 0; x < width; ++x) {
      const Hit hit = resolve(rays[static_cast<size_t>(x)], options.background);
      frame.colour.at(x, row) = hit.colour;
      frame.depth.at(x, row) = hit.distance_m;
    }
  }
};

RayCaster::RayCaster(Scene scene, const std::string& embree_config) : impl_(std::make_unique<Impl>()) {
  impl_->scene = std::move(scene);
  impl_->build(embree_config);
}

RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;

const Scene& RayCaster::scene() const { return impl_->scene; }

Hit RayCaster::cast(const glm::dvec3& origin_m, const glm::dvec3& dir) const {
  return cast(origin_m, dir, ObjectMask{});
}

Hit RayCaster::cast(const glm::dvec3& origin_m, const glm::dvec3& dir, const ObjectMask& mask) const {
  impl_->check_mask(mask);
  RTCRayHit rh = make_ray(origin_m, dir);
  MaskedContext masked = impl_->context(mask, false);
  rtcIntersect1(impl_->rtc_scene, &masked.context, &rh);
  return impl_->resolve(rh, glm::vec3(0.0f));
}

void RayCaster::cast_rays(std::span<const Ray> rays, std::span<Hit> hits, const RenderOptions& options) const {
  if (rays.size() != hits.size()) {
    throw std::invalid_argument("ray caster: cast_rays needs as many hits as rays");
  }
  impl_->check_mask(options.object_mask);
  const size_t chunks = (rays.size() + kChunkRays - 1) / kChunkRays;
  parallel_indices(options.thread_count, chunks, [&](size_t chunk) {
    const size_t begin = chunk * kChunkRays;
    const size_t end = std::min(rays.size(), begin + kChunkRays);
    std::vector<RTCRayHit> batch;
    batch.reserve(end - begin);
    for (size_t i = begin; i < end; ++i) batch.push_back(make_ray(rays[i].origin_m, rays[i].direction));
    impl_->trace(batch.data(), batch.size(), options.object_mask, false);
    for (size_t i = begin; i < end; ++i) hits[i] = impl_->resolve(batch[i - begin], options.background);
  });
}

Frame RayCaster::render_frame(const Camera& camera, const tracker::Pose& pose, const RenderOptions& options) const {
  Frame frame = Frame::cleared(camera.width_px(), camera.height_px(), options.background);
  render_rows(camera, pose, RowSet::all(camera.height_px()), frame, options);
  return frame;
}

void RayCaster::render_rows(const Camera& camera, const tracker::Pose& pose, const RowSet& rows, Frame& frame,
                            const RenderOptions& options) const {
  check_frame(camera, frame);
  check_rows(camera, rows);
  impl_->check_mask(options.object_mask);
  parallel_indices(options.thread_count, static_cast<size_t>(rows.count()), [&](size_t k) {
    impl_->cast_row(camera, pose, rows.row(static_cast<int>(k)), frame, options);
  });
}

void RayCaster::render_scanlines(const Camera& camera, std::span<const tracker::Pose> row_poses, const RowSet& rows,
                                 Frame& frame, const RenderOptions& options) const {
  check_frame(camera, frame);
  check_rows(camera, rows);
  impl_->check_mask(options.object_mask);
  if (row_poses.size() != static_cast<size_t>(camera.height_px())) {
    throw std::invalid_argument("ray caster: render_scanlines needs one pose per row (" +
                                std::to_string(camera.height_px()) + "), got " +
                                std::to_string(row_poses.size()));
  }
  parallel_indices(options.thread_count, static_cast<size_t>(rows.count()), [&](size_t k) {
    const int row = rows.row(static_cast<int>(k));
    impl_->cast_row(camera, row_poses[static_cast<size_t>(row)], row, frame, options);
  });
}

void RayCaster::render_pixels(const Camera& camera, std::span<const PixelRequest> requests, Frame& frame,
                              const RenderOptions& options) const {
  check_frame(camera, frame);
  std::vector<Ray> rays;
  rays.reserve(requests.size());
  for (const PixelRequest& r : requests) {
    if (r.x < 0 || r.y < 0 || r.x >= camera.width_px() || r.y >= camera.height_px()) {
      throw std::invalid_argument("ray caster: pixel (" + std::to_string(r.x) + ", " + std::to_string(r.y) +
                                  ") is outside the " + std::to_string(camera.width_px()) + " x " +
                                  std::to_string(camera.height_px()) + " image");
    }
    rays.push_back({r.pose.position_m, camera.pixel_ray(r.x, r.y, r.pose.orientation)});
  }
  std::vector<Hit> hits(rays.size());
  cast_rays(rays, hits, options);
  for (size_t i = 0; i < requests.size(); ++i) {
    frame.colour.at(requests[i].x, requests[i].y) = hits[i].colour;
    frame.depth.at(requests[i].x, requests[i].y) = hits[i].distance_m;
  }
}

}  // namespace latsim::renderer
