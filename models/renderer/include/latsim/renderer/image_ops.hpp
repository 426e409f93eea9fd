// Image utilities for looking at and comparing rendered frames.
#pragma once

#include "latsim/renderer/image.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>

namespace latsim::renderer {

/// Enhanced difference: 0.5 grey where the images agree, 0.5 + gain * (a - b) per channel
/// elsewhere (clamped to [0, 1]), so small errors become visible in both directions.
/// Throws std::invalid_argument if the sizes differ.
ImageRGB difference_image(const ImageRGB& a, const ImageRGB& b, float gain);

/// Colour for value / max_value on a dark-blue, cyan, green, yellow, red ramp; values at or
/// above max_value are red, NaN and values at or below zero dark blue.
glm::vec3 heat_colour(float value, float max_value);

/// One heat colour per value (row-major width x height); no legend or colour bar.
ImageRGB heat_map(std::span<const float> values, int width, int height, float max_value);
/// Depth as heat; pixels that hit nothing (infinite depth) are black.
ImageRGB heat_map(const DepthImage& depth, float max_depth_m);

/// Images side by side, top-aligned, separated by separator_px columns of separator colour
/// (which also fills below shorter images).
ImageRGB horizontal_strip(std::span<const ImageRGB> images, int separator_px,
                          const glm::vec3& separator);

/// Mean absolute difference over all pixels and channels; throws if sizes differ.
double image_error(const ImageRGB& a, const ImageRGB& b);

/// Each pixel repeated factor x factor times; throws for factor < 1.
ImageRGB upscale_nearest(const ImageRGB& image, int factor);

/// 64-bit FNV-1a of a byte sequence, for pinning images in regression tests.
uint64_t fnv1a_64(std::span<const uint8_t> bytes);

}  // namespace latsim::renderer
