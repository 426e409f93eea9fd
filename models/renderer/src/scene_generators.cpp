#include "latsim/renderer/scene_generators.hpp"

#include "latsim/renderer/mesh_builder.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace latsim::renderer {
namespace {

TileColour checker(const glm::vec3& a, const glm::vec3& b) {
  return [a, b](int u, int v) { return ((u + v) % 2 == 0) ? a : b; };
}

// Walls alternate their tile brightness slightly so that tears and sliding stay visible
// on otherwise uniform surfaces.
TileColour banded(const glm::vec3& c) {
  return [c](int u, int v) { return ((u + v) % 2 == 0) ? c : c * 0.85f; };
}

}  // namespace

Scene make_test_pattern() {
  Scene scene;
  scene.begin_object("backdrop");
  add_tiled_quad(scene, {-16.0, -10.0, -12.0}, {32.0, 0.0, 0.0}, {0.0, 24.0, 0.0}, 1.0,
                 checker({0.65f, 0.65f, 0.65f}, {0.3f, 0.3f, 0.3f}));
  scene.begin_object("floor");
  add_tiled_quad(scene, {-16.0, -1.5, 2.0}, {32.0, 0.0, 0.0}, {0.0, 0.0, -14.0}, 1.0,
                 checker({0.35f, 0.4f, 0.6f}, {0.15f, 0.2f, 0.35f}));
  struct BoxSpec {
    const char* name;
    glm::dvec3 centre_m;
    double size_m;
    glm::vec3 colour;
  };
  const BoxSpec boxes[] = {
      {"box_2m", {-0.6, 0.3, -2.0}, 0.4, {0.9f, 0.15f, 0.15f}},
      {"box_3m", {0.9, -0.2, -3.0}, 0.6, {0.15f, 0.8f, 0.2f}},
      {"box_4m", {0.0, 0.0, -4.0}, 0.5, {0.95f, 0.85f, 0.1f}},
      {"box_6m", {-1.8, -0.6, -6.0}, 1.0, {0.2f, 0.3f, 0.95f}},
      {"box_9m", {2.6, 1.0, -9.0}, 1.4, {0.85f, 0.2f, 0.85f}},
  };
  for (const BoxSpec& box : boxes) {
    scene.begin_object(box.name);
    const glm::dvec3 half(0.5 * box.size_m);
    add_box(scene, box.centre_m - half, box.centre_m + half, box.colour);
  }
  return scene;
}

Scene make_room() {
  constexpr double kTile = 0.5;
  Scene scene;
  scene.begin_object("floor");
  add_tiled_quad(scene, {-3.0, 0.0, -4.0}, {6.0, 0.0, 0.0}, {0.0, 0.0, 8.0}, kTile,
                 checker({0.55f, 0.38f, 0.2f}, {0.4f, 0.26f, 0.12f}));
  scene.begin_object("ceiling");
  add_tiled_quad(scene, {-3.0, 2.7, -4.0}, {6.0, 0.0, 0.0}, {0.0, 0.0, 8.0}, kTile,
                 banded({0.9f, 0.9f, 0.88f}));
  scene.begin_object("wall_north");
  add_tiled_quad(scene, {-3.0, 0.0, -4.0}, {6.0, 0.0, 0.0}, {0.0, 2.7, 0.0}, kTile,
                 banded({0.75f, 0.8f, 0.7f}));
  scene.begin_object("wall_south");
  add_tiled_quad(scene, {-3.0, 0.0, 4.0}, {6.0, 0.0, 0.0}, {0.0, 2.7, 0.0}, kTile,
                 banded({0.7f, 0.75f, 0.8f}));
  scene.begin_object("wall_west");
  add_tiled_quad(scene, {-3.0, 0.0, -4.0}, {0.0, 0.0, 8.0}, {0.0, 2.7, 0.0}, kTile,
                 banded({0.8f, 0.72f, 0.65f}));
  scene.begin_object("wall_east");
  add_tiled_quad(scene, {3.0, 0.0, -4.0}, {0.0, 0.0, 8.0}, {0.0, 2.7, 0.0}, kTile,
                 banded({0.8f, 0.78f, 0.6f}));

  const glm::vec3 wood(0.45f, 0.28f, 0.15f);
  scene.begin_object("table");
  add_box(scene, {-0.8, 0.72, -2.0}, {0.8, 0.77, -1.1}, wood);
  for (double x : {-0.75, 0.7}) {
    for (double z : {-1.95, -1.2}) add_box(scene, {x, 0.0, z}, {x + 0.05, 0.72, z + 0.05}, wood);
  }
  const glm::vec3 chair_colour(0.7f, 0.2f, 0.15f);
  for (int k = 0; k < 2; ++k) {
    const double x = -0.45 + 0.7 * k;
    scene.begin_object("chair_" + std::to_string(k));
    add_box(scene, {x, 0.42, -0.95}, {x + 0.42, 0.46, -0.55}, chair_colour);
    add_box(scene, {x, 0.46, -0.57}, {x + 0.42, 0.95, -0.53}, chair_colour);
    for (double dx : {0.0, 0.38}) {
      for (double dz : {-0.95, -0.59}) {
        add_box(scene, {x + dx, 0.0, dz}, {x + dx + 0.04, 0.42, dz + 0.04}, chair_colour);
      }
    }
  }
  scene.begin_object("shelf");
  add_box(scene, {-2.9, 0.0, -3.95}, {-1.7, 0.05, -3.6}, wood);
  for (int k = 1; k <= 4; ++k) {
    const double y = 0.45 * k;
    add_box(scene, {-2.9, y, -3.95}, {-1.7, y + 0.03, -3.6}, wood);
  }
  add_box(scene, {-2.92, 0.0, -3.95}, {-2.88, 1.83, -3.6}, wood);
  add_box(scene, {-1.72, 0.0, -3.95}, {-1.68, 1.83, -3.6}, wood);
  for (int k = 0; k < 6; ++k) {
    scene.begin_object("book_" + std::to_string(k));
    const double x = -2.8 + 0.17 * k;
    const double y = 0.05 + 0.45 * (k % 3);
    add_box(scene, {x, y, -3.9}, {x + 0.12, y + 0.3, -3.65}, distinct_colour(k));
  }
  scene.begin_object("sofa");
  const glm::vec3 fabric(0.2f, 0.35f, 0.6f);
  add_box(scene, {2.1, 0.0, -1.0}, {2.9, 0.45, 1.2}, fabric);
  add_box(scene, {2.7, 0.45, -1.0}, {2.9, 0.9, 1.2}, fabric);
  add_box(scene, {2.1, 0.45, -1.0}, {2.7, 0.65, -0.8}, fabric);
  add_box(scene, {2.1, 0.45, 1.0}, {2.7, 0.65, 1.2}, fabric);
  scene.begin_object("cabinet");
  add_box(scene, {1.2, 0.0, -3.95}, {2.6, 0.9, -3.45}, {0.85f, 0.85f, 0.8f});
  scene.begin_object("lamp");
  add_box(scene, {2.35, 0.9, -3.8}, {2.45, 1.3, -3.7}, {0.2f, 0.2f, 0.2f});
  add_box(scene, {2.25, 1.3, -3.9}, {2.55, 1.5, -3.6}, {0.95f, 0.9f, 0.5f});
  scene.begin_object("picture");
  add_box(scene, {-1.0, 1.2, 3.95}, {1.0, 2.2, 3.99}, {0.15f, 0.1f, 0.05f});
  add_tiled_quad(scene, {-0.9, 1.3, 3.94}, {1.8, 0.0, 0.0}, {0.0, 0.8, 0.0}, 0.3,
                 [](int u, int v) { return distinct_colour(u * 3 + v); });
  return scene;
}

namespace {

// One picture: a dark border box standing off the wall and a 3 x 3 tiled canvas in front.
void add_frame(Scene& scene, const std::string& name, const glm::dvec3& centre_m,
               const glm::dvec3& along, const glm::dvec3& normal, double width_m,
               double height_m, int index) {
  constexpr double kDepth = 0.04;
  constexpr double kMargin = 0.06;
  const glm::dvec3 up(0.0, 1.0, 0.0);
  scene.begin_object(name);
  const glm::dvec3 p0 = centre_m - along * (0.5 * width_m) - up * (0.5 * height_m);
  const glm::dvec3 p1 = centre_m + along * (0.5 * width_m) + up * (0.5 * height_m) + normal * kDepth;
  add_box(scene, glm::min(p0, p1), glm::max(p0, p1), {0.12f, 0.08f, 0.05f});
  const glm::dvec3 canvas_origin = centre_m - along * (0.5 * width_m - kMargin) -
                                   up * (0.5 * height_m - kMargin) + normal * (kDepth + 0.005);
  const double canvas_w = width_m - 2.0 * kMargin;
  const double canvas_h = height_m - 2.0 * kMargin;
  const glm::vec3 base = distinct_colour(index);
  add_tiled_quad(scene, canvas_origin, along * canvas_w, up * canvas_h,
                 std::max(canvas_w, canvas_h) / 3.0, [base](int u, int v) {
                   return base * (0.55f + 0.15f * static_cast<float>((u + 2 * v) % 4));
                 });
}

// Pictures evenly spaced along a wall segment of the given length, centred at eye height.
void add_frames_on_wall(Scene& scene, const std::string& wall, const glm::dvec3& start_m,
                        const glm::dvec3& along, const glm::dvec3& normal, double length_m,
                        const GalleryParams& p, int& frame_index) {
  if (p.frames_per_wall <= 0) return;
  const double slot_m = length_m / p.frames_per_wall;
  const double width_m = std::min(1.6, 0.7 * slot_m);
  const double height_m = std::min(0.65 * width_m, 0.4 * p.height_m);
  const double centre_y = std::min(1.6, p.height_m - 0.5 * height_m - 0.1);
  for (int k = 0; k < p.frames_per_wall; ++k) {
    glm::dvec3 centre = start_m + along * (slot_m * (k + 0.5));
    centre.y = centre_y;
    add_frame(scene, "frame_" + wall + "_" + std::to_string(k), centre, along, normal, width_m,
              height_m, frame_index++);
  }
}

}  // namespace

Scene make_gallery(const GalleryParams& p) {
  if (!(p.size_x_m > 0.0 && p.size_z_m > 0.0 && p.height_m > 0.0)) {
    throw std::invalid_argument("gallery: size_x_m, size_z_m and height_m must be positive");
  }
  if (p.partition_count < 0 || p.frames_per_wall < 0) {
    throw std::invalid_argument("gallery: partition_count and frames_per_wall must be >= 0");
  }
  const double hx = 0.5 * p.size_x_m;
  const double hz = 0.5 * p.size_z_m;
  const double h = p.height_m;
  Scene scene;
  scene.begin_object("floor");
  add_tiled_quad(scene, {-hx, 0.0, -hz}, {p.size_x_m, 0.0, 0.0}, {0.0, 0.0, p.size_z_m}, p.tile_m,
                 checker({0.6f, 0.55f, 0.45f}, {0.35f, 0.3f, 0.25f}));
  scene.begin_object("ceiling");
  add_tiled_quad(scene, {-hx, h, -hz}, {p.size_x_m, 0.0, 0.0}, {0.0, 0.0, p.size_z_m}, p.tile_m,
                 banded({0.92f, 0.92f, 0.9f}));
  const glm::dvec3 ux(1.0, 0.0, 0.0);
  const glm::dvec3 uz(0.0, 0.0, 1.0);
  const glm::dvec3 uy(0.0, h, 0.0);
  scene.begin_object("wall_north");
  add_tiled_quad(scene, {-hx, 0.0, -hz}, ux * p.size_x_m, uy, p.tile_m, banded({0.8f, 0.78f, 0.72f}));
  scene.begin_object("wall_south");
  add_tiled_quad(scene, {-hx, 0.0, hz}, ux * p.size_x_m, uy, p.tile_m, banded({0.72f, 0.76f, 0.8f}));
  scene.begin_object("wall_west");
  add_tiled_quad(scene, {-hx, 0.0, -hz}, uz * p.size_z_m, uy, p.tile_m, banded({0.8f, 0.74f, 0.7f}));
  scene.begin_object("wall_east");
  add_tiled_quad(scene, {hx, 0.0, -hz}, uz * p.size_z_m, uy, p.tile_m, banded({0.74f, 0.8f, 0.72f}));

  int frame_index = 0;
  add_frames_on_wall(scene, "north", {-hx, 0.0, -hz}, ux, uz, p.size_x_m, p, frame_index);
  add_frames_on_wall(scene, "south", {-hx, 0.0, hz}, ux, -uz, p.size_x_m, p, frame_index);
  add_frames_on_wall(scene, "west", {-hx, 0.0, -hz}, uz, ux, p.size_z_m, p, frame_index);
  add_frames_on_wall(scene, "east", {hx, 0.0, -hz}, uz, -ux, p.size_z_m, p, frame_index);

  // Partitions alternate orientation; those of one orientation are spread evenly across
  // the gallery and shifted alternately off-centre so that they form bays, not a grid.
  constexpr double kThickness_m = 0.2;
  const double partition_h = 0.8 * h;
  const int along_z_count = (p.partition_count + 1) / 2;
  const int along_x_count = p.partition_count / 2;
  for (int k = 0; k < p.partition_count; ++k) {
    const bool runs_along_z = (k % 2 == 0);
    const int i = k / 2;
    const int n = runs_along_z ? along_z_count : along_x_count;
    const double shift_sign = (i % 2 == 0) ? -1.0 : 1.0;
    const std::string name = "partition_" + std::to_string(k);
    scene.begin_object(name);
    glm::dvec3 lo;
    glm::dvec3 hi;
    if (runs_along_z) {
      const double x = -hx + p.size_x_m * (i + 1) / (n + 1);
      const double zc = shift_sign * 0.15 * p.size_z_m;
      lo = {x - 0.5 * kThickness_m, 0.0, zc - 0.25 * p.size_z_m};
      hi = {x + 0.5 * kThickness_m, partition_h, zc + 0.25 * p.size_z_m};
    } else {
      const double z = -hz + p.size_z_m * (i + 1) / (n + 1);
      const double xc = shift_sign * 0.15 * p.size_x_m;
      lo = {xc - 0.25 * p.size_x_m, 0.0, z - 0.5 * kThickness_m};
      hi = {xc + 0.25 * p.size_x_m, partition_h, z + 0.5 * kThickness_m};
    }
    add_tiled_box(scene, lo, hi, p.tile_m, banded({0.88f, 0.86f, 0.82f}));
    const glm::dvec3 along = runs_along_z ? uz : ux;
    const glm::dvec3 normal = runs_along_z ? ux : uz;
    const double length = runs_along_z ? hi.z - lo.z : hi.x - lo.x;
    add_frames_on_wall(scene, name + "_a", hi * normal + lo * along, along, normal, length, p,
                       frame_index);
    add_frames_on_wall(scene, name + "_b", lo, along, -normal, length, p, frame_index);
  }
  return scene;
}

}  // namespace latsim::renderer
