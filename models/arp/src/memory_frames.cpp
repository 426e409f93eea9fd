#include "latsim/arp/memory_frames.hpp"

#include <algorithm>
#include <limits>

#include "latsim/renderer/image_ops.hpp"

namespace latsim::arp {

renderer::Frame view_through_cubes(std::span<const renderer::CubeMap* const> cubes, const renderer::Camera& camera,
                                   const glm::dquat& orientation, const glm::vec3& background) {
  renderer::Frame frame = renderer::Frame::cleared(camera.width_px(), camera.height_px(), background);
  for (int y = 0; y < camera.height_px(); ++y) {
    for (int x = 0; x < camera.width_px(); ++x) {
      const glm::dvec3 dir = camera.pixel_ray(x, y, orientation);
      float best = std::numeric_limits<float>::infinity();
      for (const renderer::CubeMap* cube : cubes) {
        const renderer::CubeTexel t = cube->lookup(dir);
        if (t.depth_m < best) {
          best = t.depth_m;
          frame.colour.at(x, y) = t.colour;
        }
      }
      frame.depth.at(x, y) = best;
    }
  }
  return frame;
}

MemoryRenderer::MemoryRenderer(const SegmentedScene& scene, int face_px, glm::vec3 background, int thread_count)
    : scene_(scene),
      face_px_(face_px),
      background_(background),
      thread_count_(thread_count),
      caster_(std::make_unique<renderer::RayCaster>(scene.scene)) {}

renderer::CubeMap MemoryRenderer::render_all(const glm::dvec3& eye_m) const {
  renderer::RenderOptions options;
  options.background = background_;
  options.thread_count = thread_count_;
  return renderer::render_cube(*caster_, eye_m, face_px_, options);
}

renderer::CubeMap MemoryRenderer::render_memory(const RegionPriorityModel& model, const MemoryImage& image) const {
  renderer::RenderOptions options;
  options.background = background_;
  options.thread_count = thread_count_;
  if (!model.params().warping) {
    options.object_mask.assign(scene_.scene.object_count(), 0);
    for (uint32_t s : image.contents) options.object_mask[scene_.segments[s].scene_object] = 1;
    return renderer::render_cube(*caster_, image.eye_m, face_px_, options);
  }
  // Warping moves vertices, so the memory gets its own copy of its segments.
  renderer::Scene warped;
  for (uint32_t s : image.contents) {
    const renderer::SceneObject& obj = scene_.scene.objects()[scene_.segments[s].scene_object];
    warped.begin_object(obj.name, obj.animated);
    for (uint32_t t = obj.first_triangle; t < obj.first_triangle + obj.triangle_count; ++t) {
      renderer::Triangle tri = scene_.scene.triangles()[t];
      for (auto& p : tri.position_m)
        p = glm::vec3(glm::dvec3(p) + model.warp_offset_m(image.memory, glm::dvec3(p), *image.view));
      warped.add_triangle(tri);
    }
  }
  if (warped.triangle_count() == 0) return renderer::CubeMap(image.eye_m, face_px_, background_);
  const renderer::RayCaster caster(std::move(warped));
  return renderer::render_cube(caster, image.eye_m, face_px_, options);
}

std::vector<renderer::CubeMap> MemoryRenderer::render(const RegionPriorityModel& model,
                                                      const std::vector<const MemoryImage*>& shown) const {
  std::vector<renderer::CubeMap> cubes;
  for (const MemoryImage* image : shown) {
    if (image) cubes.push_back(render_memory(model, *image));
    else cubes.emplace_back(glm::dvec3(0.0), face_px_, background_);
  }
  return cubes;
}

renderer::ImageRGB close_up(const renderer::ImageRGB& image, int centre_x, int centre_y, int half_size_px, int factor) {
  const int size = 2 * half_size_px;
  renderer::ImageRGB crop = renderer::ImageRGB::filled(size, size, glm::vec3(0.0f));
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const int sx = std::clamp(centre_x - half_size_px + x, 0, image.width - 1);
      const int sy = std::clamp(centre_y - half_size_px + y, 0, image.height - 1);
      crop.at(x, y) = image.at(sx, sy);
    }
  }
  return renderer::upscale_nearest(crop, factor);
}

}  // namespace latsim::arp
