#include "latsim/renderer/image.hpp"

#include <stdexcept>
#include <string>

namespace latsim::renderer {
namespace {

size_t checked_pixel_count(int width, int height) {
  if (width < 0 || height < 0) {
    throw std::invalid_argument("image: size must be non-negative, got " + std::to_string(width) +
                                " x " + std::to_string(height));
  }
  return static_cast<size_t>(width) * static_cast<size_t>(height);
}

}  // namespace

ImageRGB ImageRGB::filled(int width, int height, const glm::vec3& colour) {
  ImageRGB image;
  image.width = width;
  image.height = height;
  image.pixels.assign(checked_pixel_count(width, height), colour);
  return image;
}

DepthImage DepthImage::cleared(int width, int height) {
  DepthImage image;
  image.width = width;
  image.height = height;
  image.depth_m.assign(checked_pixel_count(width, height), std::numeric_limits<float>::infinity());
  return image;
}

Frame Frame::cleared(int width, int height, const glm::vec3& background) {
  return Frame{ImageRGB::filled(width, height, background), DepthImage::cleared(width, height)};
}

}  // namespace latsim::renderer
