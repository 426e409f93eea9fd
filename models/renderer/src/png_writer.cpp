#include "latsim/renderer/png_writer.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

namespace latsim::renderer {
namespace {

// libpng reports errors through a callback that must not return. Throwing unwinds through
// libpng's C frames, which works where C code carries unwind tables (the default on x86-64
// Linux); encode_png validates its input first, so this path means a libpng fault.
[[noreturn]] void throw_png_error(png_structp, png_const_charp message) {
  throw std::runtime_error(std::string("png: ") + message);
}

void ignore_png_warning(png_structp, png_const_charp) {}

void append_bytes(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::vector<uint8_t>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + length);
}

void flush_nothing(png_structp) {}

// Owns the libpng write structs so they are released even when an error throws.
class PngWriteStruct {
 public:
  PngWriteStruct() {
    png_ = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, throw_png_error, ignore_png_warning);
    if (png_ == nullptr) throw std::runtime_error("png: cannot create write struct");
    info_ = png_create_info_struct(png_);
    if (info_ == nullptr) {
      png_destroy_write_struct(&png_, nullptr);
      throw std::runtime_error("png: cannot create info struct");
    }
  }
  ~PngWriteStruct() { png_destroy_write_struct(&png_, &info_); }
  PngWriteStruct(const PngWriteStruct&) = delete;
  PngWriteStruct& operator=(const PngWriteStruct&) = delete;
  png_structp png() const { return png_; }
  png_infop info() const { return info_; }

 private:
  png_structp png_ = nullptr;
  png_infop info_ = nullptr;
};

}  // namespace

uint8_t linear_to_srgb8(float linear) {
  const double c = std::isnan(linear) ? 0.0 : std::clamp(static_cast<double>(linear), 0.0, 1.0);
  const double encoded = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return static_cast<uint8_t>(std::floor(encoded * 255.0 + 0.5));
}

std::vector<uint8_t> to_srgb8(const ImageRGB& image) {
  std::vector<uint8_t> bytes;
  bytes.reserve(image.pixels.size() * 3);
  for (const glm::vec3& p : image.pixels) {
    bytes.push_back(linear_to_srgb8(p.r));
    bytes.push_back(linear_to_srgb8(p.g));
    bytes.push_back(linear_to_srgb8(p.b));
  }
  return bytes;
}

std::vector<uint8_t> encode_png(const ImageRGB& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<size_t>(image.width) * static_cast<size_t>(image.height)) {
    throw std::invalid_argument("png: image is empty or its pixel count does not match " +
                                std::to_string(image.width) + " x " + std::to_string(image.height));
  }
  std::vector<uint8_t> rgb = to_srgb8(image);
  std::vector<uint8_t> out;
  PngWriteStruct writer;
  png_set_write_fn(writer.png(), &out, append_bytes, flush_nothing);
  png_set_compression_level(writer.png(), 6);
  png_set_filter(writer.png(), PNG_FILTER_TYPE_BASE, PNG_ALL_FILTERS);
  png_set_IHDR(writer.png(), writer.info(), static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB(writer.png(), writer.info(), PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(writer.png(), writer.info());
  const size_t stride = static_cast<size_t>(image.width) * 3;
  for (int y = 0; y < image.height; ++y) {
    png_write_row(writer.png(), rgb.data() + static_cast<size_t>(y) * stride);
  }
  png_write_end(writer.png(), nullptr);
  return out;
}

void write_png(const std::filesystem::path& path, const ImageRGB& image) {
  const std::vector<uint8_t> bytes = encode_png(image);
  std::filesystem::path temporary = path;
  temporary += ".tmp";
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    if (!file) throw std::runtime_error("png: cannot open '" + temporary.string() + "' for writing");
    file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!file) throw std::runtime_error("png: write to '" + temporary.string() + "' failed");
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    throw std::runtime_error("png: cannot rename '" + temporary.string() + "' to '" + path.string() +
                             "': " + error.message());
  }
}

}  // namespace latsim::renderer
