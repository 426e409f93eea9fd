// The stand-ins for the models of the Pixel-Planes 5 latency measurements:
// the published primitive counts, and surfaces that face outwards (so that an
// application culling back faces keeps the side the viewer sees).
#include <catch2/catch.hpp>

#include <glm/geometric.hpp>

#include "latsim/renderer/mesh_builder.hpp"
#include "latsim/renderer/published_models.hpp"
#include "latsim/renderer/scene_spec.hpp"

using namespace latsim::renderer;

namespace {

/// Triangles whose normal (counter-clockwise corners) points away from the
/// line x = z = 0 through the model, among those of non-zero area.
double outward_fraction(const Scene& scene) {
  int outward = 0, counted = 0;
  for (const Triangle& t : scene.triangles()) {
    const glm::dvec3 a(t.position_m[0]), b(t.position_m[1]), c(t.position_m[2]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    if (glm::length(n) < 1e-12) continue;
    const glm::dvec3 centroid = (a + b + c) / 3.0;
    ++counted;
    if (glm::dot(n, glm::dvec3(centroid.x, 0.0, centroid.z)) > 0.0) ++outward;
  }
  return static_cast<double>(outward) / counted;
}

}  // namespace

TEST_CASE("the published models have the published primitive counts", "[renderer][models]") {
  // SPEC.md section 4: Mig 417 triangles; Molecules 2,620 triangles and 1,219 spheres; head 59,592 triangles.
  CHECK(make_mig(2.0).triangle_count() == 417);
  CHECK(make_mig(2.0).spheres().empty());
  const Scene molecules = make_molecules(2.0);
  CHECK(molecules.triangle_count() == 2620);
  CHECK(molecules.spheres().size() == 1219);
  CHECK(make_head(2.0).triangle_count() == 59592);
}

TEST_CASE("the published models fill the size asked for, centred on the origin", "[renderer][models]") {
  const Aabb mig = make_mig(2.0).bounds();
  CHECK(mig.size_m().z == Approx(2.0).margin(1e-6));  // nose at z = -1, exhaust at z = +1
  CHECK(mig.min_m.z == Approx(-1.0).margin(1e-6));
  const Aabb head = make_head(2.0).bounds();
  CHECK(head.min_m.y == Approx(-1.0).margin(1e-6));  // the neck's open end
  CHECK(head.max_m.y < 1.0);                           // the crown, a little under
  CHECK(head.max_m.y > 0.45);
  const Aabb molecules = make_molecules(2.0).bounds();
  for (int axis = 0; axis < 3; ++axis) {
    CHECK(molecules.max_m[axis] < 1.0);
    CHECK(molecules.min_m[axis] > -1.0);
  }
}

TEST_CASE("the head's and the fuselage's triangles face outwards", "[renderer][models]") {
  // A closed range-scan surface round the vertical axis: every cell faces away from it.
  CHECK(outward_fraction(make_head(2.0)) > 0.99);
  // The Mig along z: its fuselage (336 of 417) faces away from the z axis.
  const Scene mig = make_mig(2.0);
  int outward = 0;
  for (int t = 0; t < 336; ++t) {
    const Triangle& tri = mig.triangles()[static_cast<std::size_t>(t)];
    const glm::dvec3 a(tri.position_m[0]), b(tri.position_m[1]), c(tri.position_m[2]);
    const glm::dvec3 centroid = (a + b + c) / 3.0;
    if (glm::dot(glm::cross(b - a, c - a), glm::dvec3(centroid.x, centroid.y, 0.0)) > 0.0) ++outward;
  }
  CHECK(outward == 336);
}

TEST_CASE("spheres reach triangle-only users tessellated, 72 triangles each", "[renderer][models]") {
  const SceneSpec spec{.type = SceneSpec::Type::Molecules, .model_size_m = 2.0};
  const Scene native = make_scene(spec, SphereForm::native);
  CHECK(native.spheres().size() == 1219);
  const Scene drawn = make_scene(spec);
  CHECK(drawn.spheres().empty());
  CHECK(drawn.triangle_count() == 2620 + 1219 * 72);
  // Every corner of a tessellated sphere lies on it.
  Scene one;
  one.begin_object("ball");
  add_sphere_mesh(one, Sphere{glm::vec3(1.0f, 2.0f, 3.0f), 0.5f, glm::vec3(1.0f)}, 3);
  CHECK(one.triangle_count() == 72);
  for (const Triangle& t : one.triangles())
    for (const glm::vec3& p : t.position_m) CHECK(glm::length(p - glm::vec3(1.0f, 2.0f, 3.0f)) == Approx(0.5).epsilon(1e-5));
}
