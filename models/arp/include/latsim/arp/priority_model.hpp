// Priority rendering: objects sorted by validity period into display memories
// updated at harmonic rates, each memory redrawn only when one of its images
// would become invalid before its next slot.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "latsim/arp/harmonic_memories.hpp"
#include "latsim/des/time.hpp"
#include "latsim/renderer/aabb.hpp"

namespace latsim::arp {

/// One object as priority rendering sees it.
struct PriorityObject {
  renderer::Aabb bounds;
  double animation_validity_s = 0.0;  ///< user-defined period; <= 0 means static
  glm::dvec3 velocity_m_s{0.0};       ///< the object's own motion (animated objects)
};

/// Settings of the priority model.
struct PriorityParams {
  double threshold_rad = 0.003;
  des::RationalSeconds base_period{1, 60};
  int memory_count = 4;
};

/// What one tick decided.
struct PriorityTick {
  std::vector<int> updated_memories;  ///< ascending
  std::vector<int> changed_memories;  ///< updated because objects moved in or out (ascending)
  int promotions = 0;
  int demotions = 0;
  int64_t objects_rendered = 0;
};

/// Counters of one display memory's decided updates (the renderer may still skip some).
struct MemoryCounters {
  int64_t updates = 0;
  int64_t objects = 0;
  des::Time last_update;
};

/// The assignment of objects to harmonic memories and the on-demand updates.
class PriorityModel {
 public:
  PriorityModel(std::vector<PriorityObject> objects, PriorityParams params);

  /// One tick k of the fastest rate at time `now`: estimates every object's
  /// validity from the eye position and velocity; an object whose memory
  /// should change moves at the next slot of the slower of its two memories
  /// (a slot of the faster one too), where both are redrawn, so it is never
  /// missing from both or drawn by both; then redraws each memory that has a
  /// slot at k and either changed contents or holds an image that would
  /// expire before its next slot.
  PriorityTick tick(int64_t k, des::Time now, const glm::dvec3& eye_m, const glm::dvec3& eye_velocity_m_s);

  const HarmonicMemories& memories() const { return memories_; }
  int memory_of(size_t object) const { return memory_of_.at(object); }
  const std::vector<int>& assignment() const { return memory_of_; }
  std::vector<std::vector<uint32_t>> objects_per_memory() const;
  const std::vector<MemoryCounters>& counters() const { return counters_; }
  int64_t promotions() const { return promotions_; }
  int64_t demotions() const { return demotions_; }

 private:
  // The viewpoint an object's image was drawn from.
  struct Drawn {
    bool valid = false;
    des::Time at;
    glm::dvec3 eye_m{0.0};
    double nearest_distance_m = 0.0;
    double centre_distance_m = 0.0;
  };

  bool expires_before_next_slot(size_t object, int memory, des::Time now, const glm::dvec3& eye_m,
                                const glm::dvec3& eye_velocity_m_s) const;

  std::vector<PriorityObject> objects_;
  PriorityParams params_;
  HarmonicMemories memories_;
  std::vector<int> memory_of_;
  std::vector<int> pending_;
  std::vector<Drawn> drawn_;
  std::vector<bool> dirty_;
  std::vector<MemoryCounters> counters_;
  int64_t promotions_ = 0;
  int64_t demotions_ = 0;
};

}  // namespace latsim::arp
