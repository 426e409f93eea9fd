// Priority rendering as a running system: the model's decisions, renders on a
// limited number of renderers, and what the display memories show.
#pragma once

#include <cstdint>
#include <vector>

#include "latsim/arp/display_memories.hpp"
#include "latsim/arp/memory_render_cost.hpp"
#include "latsim/arp/priority_model.hpp"
#include "latsim/renderer/scene.hpp"

namespace latsim::arp {

/// Settings of a priority rendering system.
struct PrioritySystemParams {
  PriorityParams model;
  MemoryRenderCost cost;
  int renderers = 1;
  int face_px = 256;  ///< cube memory resolution (covered texels)
};

/// Ticks a PriorityModel and renders the updates it decides on a
/// DisplayMemories. Memories that exchange objects at a tick are presented
/// together, so every object is in exactly one shown image at every instant.
class PrioritySystem {
 public:
  /// Object i of `scene` is object i of the model.
  PrioritySystem(des::Simulator& sim, des::KindId render_kind, const renderer::Scene& scene,
                 std::vector<PriorityObject> objects, PrioritySystemParams params);

  /// Tick k: the model decides with the user at eye_m moving at velocity, and
  /// the decided images, drawn from eye_m (tracker sample tag `sample`), are requested.
  const PriorityTick& tick(int64_t k, des::Time now, const glm::dvec3& eye_m, const glm::dvec3& velocity_m_s,
                           int64_t sample);

  const PriorityModel& model() const { return model_; }
  DisplayMemories& memories() { return memories_; }
  const DisplayMemories& memories() const { return memories_; }

 private:
  const renderer::Scene& scene_;
  PrioritySystemParams params_;
  PriorityModel model_;
  DisplayMemories memories_;
  PriorityTick last_tick_;
};

}  // namespace latsim::arp
