// Fuzz target: a Wavefront OBJ scene file. Bad input must end as a
// SceneError; anything else escaping, a crash or a hang is a finding. A scene
// that loads has only finite vertices.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "latsim/renderer/obj_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const latsim::renderer::Scene scene = latsim::renderer::parse_obj(in, "input.obj");
    for (const auto& t : scene.triangles())
      for (const auto& v : t.position_m)
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) std::abort();
  } catch (const latsim::renderer::SceneError&) {
  }
  return 0;
}
