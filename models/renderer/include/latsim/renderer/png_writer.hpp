// 8-bit sRGB PNG encoding of linear images, byte-for-byte reproducible.
#pragma once

#include "latsim/renderer/image.hpp"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace latsim::renderer {

/// The sRGB transfer function of one linear value, clamped to [0, 1] and rounded to 8 bits.
uint8_t linear_to_srgb8(float linear);

/// Interleaved 8-bit sRGB RGB bytes of the image, row 0 first.
std::vector<uint8_t> to_srgb8(const ImageRGB& image);

/// PNG file bytes: 8-bit RGB, sRGB chunk, no time or text chunks, fixed zlib level and
/// filter, so equal images give equal bytes (for a given zlib build).
std::vector<uint8_t> encode_png(const ImageRGB& image);

/// Writes encode_png(image) to "<path>.tmp" and renames it over path, so readers never see
/// a half-written file. Throws std::runtime_error naming the path on failure.
void write_png(const std::filesystem::path& path, const ImageRGB& image);

}  // namespace latsim::renderer
