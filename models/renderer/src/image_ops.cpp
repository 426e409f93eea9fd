#include "latsim/renderer/image_ops.hpp"

#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace latsim::renderer {
namespace {

void check_same_size(const ImageRGB& a, const ImageRGB& b, const char* what) {
  if (a.width != b.width || a.height != b.height) {
    throw std::invalid_argument(std::string(what) + ": images differ in size (" + std::to_string(a.width) +
                                " x " + std::to_string(a.height) + " vs " + std::to_string(b.width) +
                                " x " + std::to_string(b.height) + ")");
  }
}

}  // namespace

ImageRGB difference_image(const ImageRGB& a, const ImageRGB& b, float gain) {
  check_same_size(a, b, "difference_image");
  ImageRGB out = ImageRGB::filled(a.width, a.height, glm::vec3(0.5f));
  for (size_t i = 0; i < out.pixels.size(); ++i) {
    out.pixels[i] = glm::clamp(glm::vec3(0.5f) + gain * (a.pixels[i] - b.pixels[i]), 0.0f, 1.0f);
  }
  return out;
}

glm::vec3 heat_colour(float value, float max_value) {
  static constexpr std::array<glm::vec3, 5> kRamp = {
      glm::vec3(0.0f, 0.0f, 0.35f), glm::vec3(0.0f, 0.8f, 0.9f), glm::vec3(0.1f, 0.85f, 0.1f),
      glm::vec3(0.95f, 0.9f, 0.0f), glm::vec3(0.9f, 0.05f, 0.0f)};
  float s = (max_value > 0.0f && value > 0.0f) ? value / max_value : 0.0f;
  s = std::min(s, 1.0f) * static_cast<float>(kRamp.size() - 1);
  const size_t k = std::min(static_cast<size_t>(s), kRamp.size() - 2);
  const float f = s - static_cast<float>(k);
  return kRamp[k] * (1.0f - f) + kRamp[k + 1] * f;
}

ImageRGB heat_map(std::span<const float> values, int width, int height, float max_value) {
  ImageRGB out = ImageRGB::filled(width, height, glm::vec3(0.0f));
  if (values.size() != out.pixels.size()) {
    throw std::invalid_argument("heat_map: " + std::to_string(values.size()) + " values for a " +
                                std::to_string(width) + " x " + std::to_string(height) + " image");
  }
  for (size_t i = 0; i < values.size(); ++i) out.pixels[i] = heat_colour(values[i], max_value);
  return out;
}

ImageRGB heat_map(const DepthImage& depth, float max_depth_m) {
  ImageRGB out = heat_map(depth.depth_m, depth.width, depth.height, max_depth_m);
  for (size_t i = 0; i < depth.depth_m.size(); ++i) {
    if (std::isinf(depth.depth_m[i])) out.pixels[i] = glm::vec3(0.0f);
  }
  return out;
}

ImageRGB horizontal_strip(std::span<const ImageRGB> images, int separator_px, const glm::vec3& separator) {
  if (separator_px < 0) throw std::invalid_argument("horizontal_strip: separator_px must be >= 0");
  int width = 0;
  int height = 0;
  for (size_t k = 0; k < images.size(); ++k) {
    width += images[k].width + (k > 0 ? separator_px : 0);
    height = std::max(height, images[k].height);
  }
  ImageRGB out = ImageRGB::filled(width, height, separator);
  int left = 0;
  for (const ImageRGB& image : images) {
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) out.at(left + x, y) = image.at(x, y);
    }
    left += image.width + separator_px;
  }
  return out;
}

double image_error(const ImageRGB& a, const ImageRGB& b) {
  check_same_size(a, b, "image_error");
  if (a.pixels.empty()) return 0.0;
  double sum = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) sum += std::fabs(static_cast<double>(a.pixels[i][c]) - b.pixels[i][c]);
  }
  return sum / (3.0 * static_cast<double>(a.pixels.size()));
}

ImageRGB upscale_nearest(const ImageRGB& image, int factor) {
  if (factor < 1) throw std::invalid_argument("upscale_nearest: factor must be >= 1, got " + std::to_string(factor));
  ImageRGB out = ImageRGB::filled(image.width * factor, image.height * factor, glm::vec3(0.0f));
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) out.at(x, y) = image.at(x / factor, y / factor);
  }
  return out;
}

uint64_t fnv1a_64(std::span<const uint8_t> bytes) {
  uint64_t hash = 0xcbf29ce484222325ull;
  for (uint8_t b : bytes) {
    hash ^= b;
    hash *= 0x100000001b3ull;
  }
  return hash;
}

}  // namespace latsim::renderer
