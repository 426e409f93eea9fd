// Covered texels, the fill cost of a segment: solid angles against closed
// forms, and texel counts against a ray-cast cube memory (a second method).
#include <catch2/catch.hpp>

#include <cmath>

#include "latsim/arp/covered_texels.hpp"
#include "latsim/renderer/cube_map.hpp"
#include "latsim/renderer/ray_caster.hpp"
#include "latsim/units/units.hpp"

using namespace latsim;

TEST_CASE("solid angles of triangles with known closed forms") {
  const glm::dvec3 o(0.0);
  // The octant triangle: a spherical triangle with three right angles, 4 pi / 8.
  CHECK(arp::solid_angle_sr(o, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}) == Approx(units::kPi / 2).epsilon(1e-12));
  // Half of a cube face seen from the centre: 4 pi / 12.
  CHECK(arp::solid_angle_sr(o, {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}) ==
        Approx(4 * units::kPi / 12).epsilon(1e-12));
  // More than a hemisphere's worth is impossible for one flat triangle, but a
  // triangle nearly containing the eye's foot approaches 2 pi.
  CHECK(arp::solid_angle_sr({0, 1e-6, 0}, {-1000, 0, -1000}, {1000, 0, -1000}, {0, 0, 1000}) ==
        Approx(2 * units::kPi).epsilon(1e-5));
  // A tiny far triangle: area / distance^2 (legs 1 mm at 100 m, facing the eye).
  CHECK(arp::solid_angle_sr(o, {0, 0, -100}, {0.001, 0, -100}, {0, 0.001, -100}) ==
        Approx(0.5e-6 / 1e4).epsilon(1e-6));
  // Seen edge-on it covers nothing, and the eye's position does not matter, only the offsets.
  CHECK(arp::solid_angle_sr(o, {1, 0, -1}, {2, 0, -1}, {1, 0, -2}) == 0.0);
  CHECK(arp::solid_angle_sr({5, 5, 5}, {6, 5, 5}, {5, 6, 5}, {5, 5, 6}) ==
        Approx(units::kPi / 2).epsilon(1e-12));
}

TEST_CASE("a cube face seen from the centre covers exactly one face of texels") {
  const glm::dvec3 o(0.0);
  for (int face_px : {16, 256}) {
    const double texels = arp::triangle_texels(o, {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, face_px) +
                          arp::triangle_texels(o, {-1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, face_px);
    CHECK(texels == Approx(static_cast<double>(face_px) * face_px).epsilon(0.01));
  }
  // The density at a face centre is (face_px/2)^2 per steradian, at a corner 3^1.5 times that.
  CHECK(arp::cube_texels_per_sr({0, 0, -1}, 256) == Approx(128.0 * 128.0));
  CHECK(arp::cube_texels_per_sr({1, 1, -1}, 256) == Approx(128.0 * 128.0 * std::pow(3.0, 1.5)));
}

TEST_CASE("covered texels agree with a ray-cast cube memory of the triangle alone") {
  struct Case {
    glm::dvec3 eye;
    glm::vec3 a, b, c;
  };
  // A floor tile under the eye, a wall panel across a cube edge, a far picture frame
  // (about 550 texels: big enough that texels cut by its edges stay within 3 %).
  const Case cases[] = {{{0.3, 1.6, 0.2}, {-0.5f, 0, -0.5f}, {0.5f, 0, -0.5f}, {0.5f, 0, 0.5f}},
                        {{0.0, 1.6, 0.0}, {-2.0f, 0, -1.0f}, {2.0f, 0, -1.0f}, {2.0f, 2.5f, -1.0f}},
                        {{0.0, 1.6, 0.0}, {3.0f, 1.0f, -5.0f}, {4.2f, 1.0f, -5.0f}, {4.2f, 2.4f, -5.0f}}};
  const int face_px = 256;
  for (const Case& k : cases) {
    renderer::Scene scene;
    scene.begin_object("triangle");
    scene.add_triangle(k.a, k.b, k.c, glm::vec3(1.0f));
    const renderer::RayCaster caster(scene);
    const renderer::CubeMap cube = renderer::render_cube(caster, k.eye, face_px, renderer::RenderOptions{});
    int64_t hit = 0;
    for (int f = 0; f < renderer::CubeMap::kFaceCount; ++f)
      for (int j = 0; j < face_px; ++j)
        for (int i = 0; i < face_px; ++i) hit += std::isfinite(cube.texel(f, i, j).depth_m) ? 1 : 0;
    const double estimate = arp::triangle_texels(k.eye, glm::dvec3(k.a), glm::dvec3(k.b), glm::dvec3(k.c), face_px);
    // Texels cut by the edges are counted whole or not at all by the rays: allow 3 %.
    CHECK(estimate == Approx(static_cast<double>(hit)).epsilon(0.03));
    CHECK(hit > 200);
  }
}
