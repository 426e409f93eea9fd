#include "latsim/arp/scene_config.hpp"

#include "latsim/renderer/obj_loader.hpp"
#include "latsim/renderer/scene_generators.hpp"

namespace latsim::arp {

renderer::Scene scene_from_config(const scenario::ConfigNode& node) {
  const std::string type = node.choice("type", "gallery", {"gallery", "room", "test_pattern", "obj"});
  if (type == "room") return renderer::make_room();
  if (type == "test_pattern") return renderer::make_test_pattern();
  if (type == "obj") return renderer::load_obj(node.path("path"));
  renderer::GalleryParams p;
  p.size_x_m = node.positive("size_x_m", p.size_x_m);
  p.size_z_m = node.positive("size_z_m", p.size_z_m);
  p.height_m = node.positive("height_m", p.height_m);
  p.partition_count = static_cast<int>(node.integer("partition_count", p.partition_count, 0, 64));
  p.frames_per_wall = static_cast<int>(node.integer("frames_per_wall", p.frames_per_wall, 0, 64));
  p.tile_m = node.positive("tile_m", p.tile_m);
  return renderer::make_gallery(p);
}

}  // namespace latsim::arp
