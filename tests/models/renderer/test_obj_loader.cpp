#include "latsim/renderer/obj_loader.hpp"

#include <catch2/catch.hpp>

#include <sstream>
#include <string>

using namespace latsim::renderer;

namespace {

Scene parse(const std::string& text) {
  std::istringstream in(text);
  return parse_obj(in, "test.obj", glm::vec3(0.5f));
}

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "no error";
}

const char* kSquare =
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 1 1 0\n"
    "v 0 1 0\n";

}  // namespace

TEST_CASE("OBJ polygons are triangulated as fans from the first corner") {
  const Scene quad = parse(std::string(kSquare) + "f 1 2 3 4\n");
  REQUIRE(quad.triangle_count() == 2);
  const auto& t = quad.triangles();
  CHECK(t[0].position_m == std::array<glm::vec3, 3>{glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0)});
  CHECK(t[1].position_m == std::array<glm::vec3, 3>{glm::vec3(0, 0, 0), glm::vec3(1, 1, 0), glm::vec3(0, 1, 0)});

  const Scene pentagon = parse(std::string(kSquare) + "v 0.5 2 0\nf 1 2 3 5 4\n");
  REQUIRE(pentagon.triangle_count() == 3);
  for (const Triangle& tri : pentagon.triangles()) CHECK(tri.position_m[0] == glm::vec3(0, 0, 0));
  CHECK(pentagon.triangles()[2].position_m[1] == glm::vec3(0.5f, 2.0f, 0.0f));
  CHECK(pentagon.triangles()[2].position_m[2] == glm::vec3(0, 1, 0));
}

TEST_CASE("OBJ negative indices count back from the newest vertex") {
  const Scene absolute = parse(std::string(kSquare) + "f 2 3 4\n");
  const Scene relative = parse(std::string(kSquare) + "f -3 -2 -1\n");
  REQUIRE(relative.triangle_count() == 1);
  CHECK(relative.triangles()[0].position_m == absolute.triangles()[0].position_m);
}

TEST_CASE("OBJ index forms with texture and normal indices use the vertex index") {
  const Scene plain = parse(std::string(kSquare) + "f 1 2 3\n");
  const Scene with_vt = parse(std::string(kSquare) + "vt 0 0\nf 1/1 2/1 3/1\n");
  const Scene with_both = parse(std::string(kSquare) + "vn 0 0 1\nvt 0 0\nf 1/1/1 2/1/1 3/1/1\n");
  const Scene with_vn = parse(std::string(kSquare) + "vn 0 0 1\nf 1//1 2//1 3//1\n");
  for (const Scene* s : {&with_vt, &with_both, &with_vn}) {
    REQUIRE(s->triangle_count() == 1);
    CHECK(s->triangles()[0].position_m == plain.triangles()[0].position_m);
  }
}

TEST_CASE("OBJ vertex colours and default colour and objects and ignored statements") {
  const Scene scene = parse(
      "# comment line\n"
      "mtllib x.mtl\n"
      "v 0 0 0 1 0 0\n"
      "v 1 0 0 0 1 0\n"
      "v 0 1 0 0 0 1   # trailing comment\n"
      "v 0 0 1\n"
      "f 1 2 3\n"
      "o second thing\n"
      "usemtl red\n"
      "s 1\n"
      "f 1 2 4\n"
      "g third\n"
      "f 2 3 4\n");
  REQUIRE(scene.object_count() == 3);
  CHECK(scene.objects()[0].name == "default");
  CHECK(scene.objects()[1].name == "second thing");
  CHECK(scene.objects()[2].name == "third");
  CHECK(scene.objects()[2].first_triangle == 2);
  const Triangle& first = scene.triangles()[0];
  CHECK(first.colour[0] == glm::vec3(1, 0, 0));
  CHECK(first.colour[2] == glm::vec3(0, 0, 1));
  CHECK(scene.triangles()[1].colour[2] == glm::vec3(0.5f));
}

TEST_CASE("Malformed OBJ input names file and line and reason") {
  CHECK(error_of(std::string(kSquare) + "f 1 2 7\n") == "test.obj:5: bad vertex index 7 (4 vertices defined so far)");
  CHECK(error_of(std::string(kSquare) + "f 1 2 -5\n") == "test.obj:5: bad vertex index -5 (4 vertices defined so far)");
  CHECK(error_of(std::string(kSquare) + "f 0 1 2\n") == "test.obj:5: bad vertex index 0 (4 vertices defined so far)");
  CHECK(error_of(std::string(kSquare) + "\nf 1 2\n") == "test.obj:6: too few vertices in face: 2, need at least 3");
  CHECK(error_of("v 0 0 0\nv 1 abc 0\n") == "test.obj:2: non-numeric value 'abc'");
  CHECK(error_of(std::string(kSquare) + "f 1 x 3\n") == "test.obj:5: non-numeric value 'x'");
  CHECK(error_of("v 1 2\n") == "test.obj:1: vertex needs 3 coordinates (optionally w, or r g b), got 2 values");
  CHECK(error_of("l 1 2\n") == "test.obj:1: unsupported statement 'l'");
}

TEST_CASE("The example OBJ file loads with its objects and colours") {
  const std::string path = std::string(LATSIM_SOURCE_DIR) + "/scenarios/objects/pyramid.obj";
  const Scene pyramid = load_obj(path);
  REQUIRE(pyramid.object_count() == 2);
  CHECK(pyramid.objects()[0].name == "base");
  CHECK(pyramid.objects()[0].triangle_count == 2);
  CHECK(pyramid.objects()[1].triangle_count == 4);
  CHECK(pyramid.bounds().max_m.y == Approx(1.0));
  CHECK(pyramid.triangles()[2].position_m[2] == glm::vec3(0, 1, 0));
  CHECK(pyramid.triangles()[0].colour[0] == glm::vec3(0.9f, 0.1f, 0.1f));
  CHECK_THROWS_WITH(load_obj("/nonexistent/x.obj"), "/nonexistent/x.obj: cannot read the mesh: No such file or directory");
}
