#include "latsim/renderer/image_ops.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string_view>

using namespace latsim::renderer;

namespace {

ImageRGB ramp(int w, int h) {
  ImageRGB image = ImageRGB::filled(w, h, glm::vec3(0.0f));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) image.at(x, y) = glm::vec3(0.1f * x, 0.1f * y, 0.5f);
  }
  return image;
}

}  // namespace

TEST_CASE("Difference image is mid grey where equal and signed elsewhere") {
  const ImageRGB a = ramp(4, 3);
  ImageRGB b = a;
  const ImageRGB same = difference_image(a, b, 4.0f);
  for (const glm::vec3& p : same.pixels) CHECK(p == glm::vec3(0.5f));
  b.at(1, 1) += glm::vec3(0.05f, -0.05f, 0.5f);
  const ImageRGB diff = difference_image(a, b, 4.0f);
  CHECK(diff.at(1, 1).r == Approx(0.3f));
  CHECK(diff.at(1, 1).g == Approx(0.7f));
  CHECK(diff.at(1, 1).b == 0.0f);
  CHECK(diff.at(0, 0) == glm::vec3(0.5f));
  CHECK_THROWS_AS(difference_image(a, ramp(3, 3), 1.0f), std::invalid_argument);
}

TEST_CASE("Image error is the mean absolute channel difference") {
  const ImageRGB a = ImageRGB::filled(2, 2, glm::vec3(0.5f));
  ImageRGB b = a;
  CHECK(image_error(a, b) == 0.0);
  b.at(0, 0).r = 0.8f;
  b.at(1, 1) = glm::vec3(0.2f);
  CHECK(image_error(a, b) == Approx((0.3 + 0.9) / 12.0));
  CHECK_THROWS_AS(image_error(a, ramp(2, 3)), std::invalid_argument);
}

TEST_CASE("Heat map ramps from dark blue to red and clamps") {
  CHECK(heat_colour(0.0f, 10.0f) == glm::vec3(0.0f, 0.0f, 0.35f));
  CHECK(heat_colour(-3.0f, 10.0f) == glm::vec3(0.0f, 0.0f, 0.35f));
  CHECK(heat_colour(5.0f, 10.0f) == glm::vec3(0.1f, 0.85f, 0.1f));
  CHECK(heat_colour(10.0f, 10.0f) == glm::vec3(0.9f, 0.05f, 0.0f));
  CHECK(heat_colour(99.0f, 10.0f) == glm::vec3(0.9f, 0.05f, 0.0f));
  CHECK(heat_colour(std::nanf(""), 10.0f) == glm::vec3(0.0f, 0.0f, 0.35f));
  const glm::vec3 mid = heat_colour(3.75f, 10.0f);
  CHECK(mid.g == Approx(0.825f));
  DepthImage depth = DepthImage::cleared(2, 1);
  depth.at(0, 0) = 20.0f;
  const ImageRGB heat = heat_map(depth, 20.0f);
  CHECK(heat.at(0, 0) == glm::vec3(0.9f, 0.05f, 0.0f));
  CHECK(heat.at(1, 0) == glm::vec3(0.0f));
  const std::vector<float> values{0.0f, 1.0f};
  CHECK_THROWS_AS(heat_map(values, 3, 1, 1.0f), std::invalid_argument);
}

TEST_CASE("Horizontal strip places images side by side with separators") {
  const ImageRGB a = ramp(3, 2);
  const ImageRGB b = ImageRGB::filled(2, 4, glm::vec3(0.9f));
  const std::vector<ImageRGB> images{a, b};
  const glm::vec3 sep(1, 0, 1);
  const ImageRGB strip = horizontal_strip(images, 2, sep);
  CHECK(strip.width == 3 + 2 + 2);
  CHECK(strip.height == 4);
  CHECK(strip.at(2, 1) == a.at(2, 1));
  CHECK(strip.at(3, 0) == sep);
  CHECK(strip.at(4, 3) == sep);
  CHECK(strip.at(5, 3) == glm::vec3(0.9f));
  CHECK(strip.at(0, 3) == sep);
}

TEST_CASE("Nearest-neighbour upscale repeats pixels in blocks") {
  const ImageRGB a = ramp(2, 2);
  const ImageRGB big = upscale_nearest(a, 3);
  CHECK(big.width == 6);
  CHECK(big.height == 6);
  for (int y = 0; y < 6; ++y) {
    for (int x = 0; x < 6; ++x) CHECK(big.at(x, y) == a.at(x / 3, y / 3));
  }
  CHECK(upscale_nearest(a, 1).pixels == a.pixels);
  CHECK_THROWS_AS(upscale_nearest(a, 0), std::invalid_argument);
}

TEST_CASE("FNV-1a matches its published test vectors") {
  const std::string_view letter = "a";
  const std::string_view word = "foobar";
  CHECK(fnv1a_64({}) == 0xcbf29ce484222325ull);
  CHECK(fnv1a_64({reinterpret_cast<const uint8_t*>(letter.data()), letter.size()}) == 0xaf63dc4c8601ec8cull);
  CHECK(fnv1a_64({reinterpret_cast<const uint8_t*>(word.data()), word.size()}) == 0x85944171f73967e8ull);
}
