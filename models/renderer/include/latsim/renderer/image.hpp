// Linear-light colour images and per-pixel depth.
#pragma once

#include <glm/vec3.hpp>

#include <limits>
#include <vector>

namespace latsim::renderer {

/// Linear RGB floats, row-major, row 0 at the top.
struct ImageRGB {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> pixels;

  /// A width x height image filled with one colour; throws for negative sizes.
  static ImageRGB filled(int width, int height, const glm::vec3& colour);
  glm::vec3& at(int x, int y) { return pixels[index(x, y)]; }
  const glm::vec3& at(int x, int y) const { return pixels[index(x, y)]; }

 private:
  size_t index(int x, int y) const { return static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x); }
};

/// Per-pixel distance in metres from the eye to the visible surface along the pixel's
/// ray; +infinity where the ray hit nothing, so nearest-wins composition needs no flag.
struct DepthImage {
  int width = 0;
  int height = 0;
  std::vector<float> depth_m;

  static DepthImage cleared(int width, int height);
  float& at(int x, int y) { return depth_m[index(x, y)]; }
  float at(int x, int y) const { return depth_m[index(x, y)]; }

 private:
  size_t index(int x, int y) const { return static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x); }
};

/// What a frame path writes: colour and depth of the same pixels.
struct Frame {
  ImageRGB colour;
  DepthImage depth;

  /// A frame with every pixel at the background colour and infinite depth.
  static Frame cleared(int width, int height, const glm::vec3& background);
};

}  // namespace latsim::renderer
