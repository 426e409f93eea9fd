#include "latsim/arp/covered_texels.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace latsim::arp {
namespace {

constexpr double kMaxPartSr = 0.05;
constexpr int kMaxDepth = 6;

double split_texels(const glm::dvec3& eye, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, int face_px,
                    int depth) {
  const double omega = solid_angle_sr(eye, a, b, c);
  if (omega <= kMaxPartSr || depth >= kMaxDepth) {
    const glm::dvec3 centre = (a + b + c) / 3.0 - eye;
    if (!(glm::dot(centre, centre) > 0.0)) return 0.0;
    return omega * cube_texels_per_sr(centre, face_px);
  }
  // The four parts' solid angles add up to the whole's: their projections tile it.
  const glm::dvec3 ab = 0.5 * (a + b);
  const glm::dvec3 bc = 0.5 * (b + c);
  const glm::dvec3 ca = 0.5 * (c + a);
  return split_texels(eye, a, ab, ca, face_px, depth + 1) + split_texels(eye, ab, b, bc, face_px, depth + 1) +
         split_texels(eye, ca, bc, c, face_px, depth + 1) + split_texels(eye, ab, bc, ca, face_px, depth + 1);
}

}  // namespace

double solid_angle_sr(const glm::dvec3& eye_m, const glm::dvec3& a_m, const glm::dvec3& b_m, const glm::dvec3& c_m) {
  const glm::dvec3 a = a_m - eye_m;
  const glm::dvec3 b = b_m - eye_m;
  const glm::dvec3 c = c_m - eye_m;
  const double la = glm::length(a);
  const double lb = glm::length(b);
  const double lc = glm::length(c);
  const double numerator = std::abs(glm::dot(a, glm::cross(b, c)));
  const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
  // atan2 keeps the branch right when the denominator is negative (more than a hemisphere's worth).
  return 2.0 * std::atan2(numerator, denominator);
}

double cube_texels_per_sr(const glm::dvec3& d, int face_px) {
  const double ax = std::abs(d.x);
  const double ay = std::abs(d.y);
  const double az = std::abs(d.z);
  const double major = std::max({ax, ay, az});
  // u^2 + v^2 = (sum of squares - major^2) / major^2.
  const double uv2 = (ax * ax + ay * ay + az * az) / (major * major) - 1.0;
  const double half = 0.5 * face_px;
  return half * half * std::pow(1.0 + uv2, 1.5);
}

double triangle_texels(const glm::dvec3& eye_m, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                       int face_px) {
  return split_texels(eye_m, a, b, c, face_px, 0);
}

double object_texels(const renderer::Scene& scene, uint32_t object, const glm::dvec3& eye_m, int face_px) {
  const renderer::SceneObject& obj = scene.objects().at(object);
  double texels = 0.0;
  for (uint32_t t = obj.first_triangle; t < obj.first_triangle + obj.triangle_count; ++t) {
    const auto& p = scene.triangles()[t].position_m;
    texels += triangle_texels(eye_m, glm::dvec3(p[0]), glm::dvec3(p[1]), glm::dvec3(p[2]), face_px);
  }
  return texels;
}

}  // namespace latsim::arp
