#include "latsim/renderer/png_writer.hpp"

#include <catch2/catch.hpp>

#include <png.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

using namespace latsim::renderer;

namespace {

ImageRGB pattern() {
  ImageRGB image = ImageRGB::filled(7, 5, glm::vec3(0.0f));
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 7; ++x) image.at(x, y) = glm::vec3(x / 6.0f, y / 4.0f, (x + y) % 2 ? 0.18f : 1.0f);
  }
  return image;
}

std::vector<uint8_t> read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool contains(const std::vector<uint8_t>& bytes, const std::string& tag) {
  return std::search(bytes.begin(), bytes.end(), tag.begin(), tag.end()) != bytes.end();
}

}  // namespace

TEST_CASE("sRGB encoding follows the standard transfer curve") {
  CHECK(linear_to_srgb8(0.0f) == 0);
  CHECK(linear_to_srgb8(1.0f) == 255);
  CHECK(linear_to_srgb8(0.5f) == 188);
  CHECK(linear_to_srgb8(0.18f) == 118);
  CHECK(linear_to_srgb8(0.002f) == 7);  // linear segment: 12.92 * 0.002 * 255 = 6.6
  CHECK(linear_to_srgb8(-1.0f) == 0);
  CHECK(linear_to_srgb8(7.0f) == 255);
  CHECK(linear_to_srgb8(std::numeric_limits<float>::quiet_NaN()) == 0);
}

TEST_CASE("PNG bytes decode to the sRGB pixels and carry no time chunk") {
  const ImageRGB image = pattern();
  const std::vector<uint8_t> png = encode_png(image);
  REQUIRE(png.size() > 8);
  CHECK(png_sig_cmp(png.data(), 0, 8) == 0);
  CHECK(contains(png, "sRGB"));
  CHECK_FALSE(contains(png, "tIME"));
  CHECK_FALSE(contains(png, "tEXt"));

  png_image decoded{};
  decoded.version = PNG_IMAGE_VERSION;
  REQUIRE(png_image_begin_read_from_memory(&decoded, png.data(), png.size()) != 0);
  decoded.format = PNG_FORMAT_RGB;
  std::vector<uint8_t> rgb(PNG_IMAGE_SIZE(decoded));
  REQUIRE(png_image_finish_read(&decoded, nullptr, rgb.data(), 0, nullptr) != 0);
  CHECK(decoded.width == 7);
  CHECK(decoded.height == 5);
  CHECK(rgb == to_srgb8(image));
}

TEST_CASE("PNG files are byte-identical across writes and written atomically") {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "latsim_renderer_png_test";
  std::filesystem::create_directories(dir);
  const std::filesystem::path first = dir / "first.png";
  const std::filesystem::path second = dir / "second.png";
  write_png(first, pattern());
  write_png(second, pattern());
  CHECK(read_file(first) == read_file(second));
  CHECK(read_file(first) == encode_png(pattern()));
  CHECK_FALSE(std::filesystem::exists(dir / "first.png.tmp"));
  // Rewriting replaces the file rather than appending to it.
  write_png(first, ImageRGB::filled(2, 2, glm::vec3(1.0f)));
  CHECK(read_file(first) == encode_png(ImageRGB::filled(2, 2, glm::vec3(1.0f))));
  CHECK_THROWS_AS(write_png(dir / "missing_dir" / "x.png", pattern()), std::runtime_error);
  CHECK_THROWS_AS(encode_png(ImageRGB{}), std::invalid_argument);
  std::filesystem::remove_all(dir);
}
