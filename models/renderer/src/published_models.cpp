#include "latsim/renderer/published_models.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace latsim::renderer {
namespace {

constexpr double kPi = std::numbers::pi;

void check_size(double size_m, const char* what) {
  if (!(size_m > 0.0) || !std::isfinite(size_m)) throw std::invalid_argument(std::string(what) + ": size must be above 0");
}

glm::vec3 v3(const glm::dvec3& p) { return glm::vec3(p); }

void add_quad(Scene& s, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d,
              const glm::vec3& colour) {
  s.add_triangle(v3(a), v3(b), v3(c), colour);
  s.add_triangle(v3(a), v3(c), v3(d), colour);
}

/// A thin plate round a planform (root leading, root trailing, tip trailing,
/// tip leading), `half_thickness` either side along `normal`: both faces, the
/// leading and trailing edges and, when `tip`, the tip (10 or 8 triangles).
void add_plate(Scene& s, const std::array<glm::dvec3, 4>& planform, const glm::dvec3& normal, double half_thickness,
               bool tip, const glm::vec3& colour) {
  const glm::dvec3 h = normal * half_thickness;
  const auto& [rl, rt, tt, tl] = planform;
  add_quad(s, rl + h, tl + h, tt + h, rt + h, colour);  // upper face
  add_quad(s, rl - h, rt - h, tt - h, tl - h, colour);  // lower face
  add_quad(s, rl + h, rl - h, tl - h, tl + h, colour);  // leading edge
  add_quad(s, rt + h, tt + h, tt - h, rt - h, colour);  // trailing edge
  if (tip) add_quad(s, tl + h, tl - h, tt - h, tt + h, colour);
}

/// A number in [0, 1) from an index (splitmix64): fixed geometry, not a random stream.
double unit_hash(uint64_t i) {
  uint64_t z = i + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

}  // namespace

Scene make_mig(double length_m) {
  check_size(length_m, "mig");
  const double L = length_m;
  Scene s;
  s.begin_object("mig");
  const glm::vec3 grey(0.55f, 0.6f, 0.62f), dark(0.3f, 0.33f, 0.36f), glass(0.2f, 0.35f, 0.5f);
  constexpr int kSides = 12, kStations = 15;
  const double r_max = 0.055 * L, z_first = -0.38 * L, z_last = 0.5 * L;
  const auto radius = [&](int k) {
    const double t = static_cast<double>(k) / (kStations - 1);
    return r_max * (t < 0.35 ? 0.45 + 0.55 * std::sin(t / 0.35 * kPi / 2) : 1.0 - 0.25 * (t - 0.35) / 0.65);
  };
  const auto point = [&](int k, int j) {
    const double a = 2.0 * kPi * j / kSides, z = z_first + (z_last - z_first) * k / (kStations - 1);
    return glm::dvec3(1.1 * radius(k) * std::cos(a), radius(k) * std::sin(a), z);
  };
  for (int k = 0; k + 1 < kStations; ++k)  // 14 segments x 12 sides x 2 = 336
    for (int j = 0; j < kSides; ++j) add_quad(s, point(k, j), point(k, j + 1), point(k + 1, j + 1), point(k + 1, j), grey);
  const glm::dvec3 nose(0.0, 0.0, -0.5 * L), exhaust(0.0, 0.0, z_last);
  for (int j = 0; j < kSides; ++j) {  // nose cone and exhaust cap: 12 + 12
    s.add_triangle(v3(nose), v3(point(0, j + 1)), v3(point(0, j)), grey);
    s.add_triangle(v3(exhaust), v3(point(kStations - 1, j)), v3(point(kStations - 1, j + 1)), dark);
  }
  const glm::dvec3 up(0, 1, 0), side(1, 0, 0);
  for (double sign : {-1.0, 1.0}) {
    const double root = sign * r_max;
    add_plate(s, {glm::dvec3(root, 0, -0.05 * L), glm::dvec3(root, 0, 0.2 * L), glm::dvec3(sign * 0.33 * L, 0, 0.2 * L),
                  glm::dvec3(sign * 0.33 * L, 0, 0.12 * L)},
              up, 0.006 * L, true, grey);  // wing: 10
    add_plate(s, {glm::dvec3(0.7 * root, 0, 0.36 * L), glm::dvec3(0.7 * root, 0, 0.48 * L),
                  glm::dvec3(sign * 0.17 * L, 0, 0.49 * L), glm::dvec3(sign * 0.17 * L, 0, 0.44 * L)},
              up, 0.004 * L, false, grey);  // tailplane: 8
  }
  add_plate(s, {glm::dvec3(0, 0.9 * r_max, 0.3 * L), glm::dvec3(0, 0.9 * r_max, 0.48 * L), glm::dvec3(0, 0.2 * L, 0.48 * L),
                glm::dvec3(0, 0.2 * L, 0.42 * L)},
            side, 0.004 * L, true, grey);  // fin: 10
  const glm::dvec3 apex(0.0, 1.55 * r_max, -0.2 * L);
  for (int j = 0; j < 11; ++j) {  // canopy: a fan of 11 over the front half of the cockpit rim
    const auto rim = [&](int q) {
      const double a = kPi * q / 11.0;
      return glm::dvec3(0.6 * r_max * std::cos(a), 0.8 * r_max, -0.2 * L - 0.09 * L * std::sin(a));
    };
    s.add_triangle(v3(apex), v3(rim(j)), v3(rim(j + 1)), glass);
  }
  return s;
}

Scene make_molecules(double size_m) {
  check_size(size_m, "molecules");
  const double S = size_m;
  Scene s;
  s.begin_object("ribbon");
  // The backbone: a sum of slow and fast sines per axis, scaled so that it
  // reaches 0.35 S from the centre at most, with a helical wiggle of 0.03 S
  // and 40 turns along it; atoms (below) reach at most 0.095 S further, so
  // everything lies inside the ball of diameter S.
  constexpr int kSegments = kMoleculesTriangles / 2;  // 1310 ribbon quads
  constexpr int kFine = 16 * kSegments;                // samples for the coil's reach
  const auto coil = [](double t) {
    glm::dvec3 p(0.0);
    for (int k = 1; k <= 9; ++k) {
      const double w = 2.0 * kPi * k * t;
      p += glm::dvec3(std::sin(w + 1.3 * k), std::sin(1.1 * w + 0.7 * k), std::cos(0.9 * w + 2.1 * k)) / (0.6 * k + 1.0);
    }
    return p;
  };
  double reach = 0.0;
  for (int i = 0; i <= kFine; ++i) reach = std::max(reach, glm::length(coil(static_cast<double>(i) / kFine)));
  const auto backbone = [&](double t) {
    const double a = 2.0 * kPi * 40.0 * t;
    const glm::dvec3 wiggle(std::cos(a), std::sin(a), std::cos(a + 1.0));
    return coil(t) * (0.35 * S / reach) + 0.03 * S * wiggle / glm::length(wiggle);
  };
  std::vector<glm::dvec3> spine(kSegments + 1);
  for (int i = 0; i <= kSegments; ++i) spine[i] = backbone(static_cast<double>(i) / kSegments);
  for (int i = 0; i < kSegments; ++i) {
    const glm::dvec3 tangent = spine[i + 1] - spine[i];
    glm::dvec3 across = glm::cross(tangent, glm::dvec3(0.3, 1.0, 0.2));
    const double n = glm::length(across);
    across = n > 0.0 ? across / n * (0.012 * S) : glm::dvec3(0.012 * S, 0, 0);
    add_quad(s, spine[i] - across, spine[i + 1] - across, spine[i + 1] + across, spine[i] + across,
             glm::vec3(0.9f, 0.75f, 0.2f));
  }
  // The atoms, strung along the backbone with side chains reaching out.
  const std::array<glm::vec3, 4> element{glm::vec3(0.5f), glm::vec3(0.2f, 0.3f, 0.9f), glm::vec3(0.9f, 0.15f, 0.1f),
                                         glm::vec3(0.9f, 0.85f, 0.2f)};
  for (int j = 0; j < kMoleculesSpheres; ++j) {
    const double t = (j + 0.5) / kMoleculesSpheres;
    const double u = unit_hash(3 * j), v = unit_hash(3 * j + 1), w = unit_hash(3 * j + 2);
    const double z = 2.0 * u - 1.0, a = 2.0 * kPi * v, ring = std::sqrt(1.0 - z * z);
    const glm::dvec3 out(ring * std::cos(a), ring * std::sin(a), z);
    const glm::dvec3 centre = backbone(t) + out * (0.02 + 0.04 * w) * S;
    s.add_sphere(Sphere{glm::vec3(centre), static_cast<float>((0.025 + 0.01 * w) * S), element[j % 4]});
  }
  return s;
}

Scene make_head(double height_m) {
  check_size(height_m, "head");
  const double H = height_m;
  constexpr int kColumns = 191, kRows = 156;
  static_assert(2 * kColumns * kRows == kHeadTriangles);
  Scene s;
  s.begin_object("head");
  // Ring k of kRows + 1: the neck (a cylinder) below, then an ellipsoid from
  // under the jaw to just short of the crown. Column j faces +z at j = 0.
  const auto point = [&](int k, int j) {
    const double theta = 2.0 * kPi * j / kColumns;
    const double u = static_cast<double>(k) / kRows;
    const double front = std::cos(theta);  // +1 facing forward
    glm::dvec3 p;
    if (u < 0.2) {
      const double r = 0.17 * H;
      p = glm::dvec3(r * std::sin(theta), -0.5 * H + u / 0.2 * 0.2 * H, r * front);
    } else {
      const double phi = -1.05 + (u - 0.2) / 0.8 * (1.05 + 1.52);  // latitude, -60 to +87 degrees
      const double c = std::cos(phi);
      p = glm::dvec3(0.3 * H * c * std::sin(theta), 0.12 * H + 0.38 * H * std::sin(phi), 0.36 * H * c * front);
      // The nose: a bump forward on the face's centre line; ears: bumps to either side.
      const double dtheta = std::remainder(theta, 2.0 * kPi);
      p.z += 0.07 * H * std::exp(-(dtheta * dtheta) / 0.02 - (phi - 0.05) * (phi - 0.05) / 0.04);
      const double ear = std::remainder(theta - kPi / 2, kPi);
      p.x += (std::sin(theta) > 0 ? 1 : -1) * 0.03 * H * std::exp(-(ear * ear) / 0.03 - phi * phi / 0.05);
    }
    return p;
  };
  const glm::vec3 skin(0.85f, 0.65f, 0.55f);
  for (int k = 0; k < kRows; ++k)
    for (int j = 0; j < kColumns; ++j) add_quad(s, point(k, j), point(k, j + 1), point(k + 1, j + 1), point(k + 1, j), skin);
  return s;
}

}  // namespace latsim::renderer
