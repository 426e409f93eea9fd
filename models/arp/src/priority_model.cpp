#include "latsim/arp/priority_model.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "latsim/arp/validity.hpp"

namespace latsim::arp {

PriorityModel::PriorityModel(std::vector<PriorityObject> objects, PriorityParams params)
    : objects_(std::move(objects)),
      params_(params),
      memories_(params.base_period, params.memory_count),
      // Until the first tick every object waits in the slowest memory; the
      // first tick assigns them properly and draws every memory.
      memory_of_(objects_.size(), params.memory_count - 1),
      pending_(objects_.size(), -1),
      drawn_(objects_.size()),
      dirty_(static_cast<size_t>(params.memory_count), true),
      counters_(static_cast<size_t>(params.memory_count)) {}

std::vector<std::vector<uint32_t>> PriorityModel::objects_per_memory() const {
  std::vector<std::vector<uint32_t>> lists(static_cast<size_t>(memories_.count()));
  for (size_t o = 0; o < memory_of_.size(); ++o) lists[static_cast<size_t>(memory_of_[o])].push_back(static_cast<uint32_t>(o));
  return lists;
}

bool PriorityModel::expires_before_next_slot(size_t object, int memory, des::Time now, const glm::dvec3& eye_m,
                                             const glm::dvec3& eye_velocity_m_s) const {
  const Drawn& d = drawn_[object];
  if (!d.valid) return true;
  const PriorityObject& obj = objects_[object];
  const double period_s = memories_.period_s(memory);
  const double elapsed_s = (now - d.at).to_seconds();
  const ObjectView view = view_of(obj.bounds, eye_m, obj.velocity_m_s - eye_velocity_m_s, obj.animation_validity_s);
  // Displacement so far is measured; only the part until the next slot is predicted,
  // so accelerations are caught at the next tick.
  const glm::dvec3 moved = (eye_m - d.eye_m) - obj.velocity_m_s * elapsed_s;
  const double speed = glm::length(view.relative_velocity_m_s);
  const double x = translational_validity_distance_m(std::min(d.nearest_distance_m, view.nearest_distance_m),
                                                      params_.threshold_rad);
  if (glm::length(moved) + speed * period_s > x) return true;
  const double radial_speed = std::abs(glm::dot(view.relative_velocity_m_s, view.to_centre_unit));
  const double size_x = size_validity_distance_m(std::min(d.centre_distance_m, view.centre_distance_m), view.radius_m,
                                                 params_.threshold_rad);
  if (std::abs(view.centre_distance_m - d.centre_distance_m) + radial_speed * period_s > size_x) return true;
  return obj.animation_validity_s > 0.0 && elapsed_s + period_s > obj.animation_validity_s;
}

PriorityTick PriorityModel::tick(int64_t k, des::Time now, const glm::dvec3& eye_m, const glm::dvec3& eye_velocity_m_s) {
  PriorityTick result;
  // A memory's first drawing changes what it holds (from nothing).
  std::vector<bool> changed(static_cast<size_t>(memories_.count()), false);
  for (int m = 0; m < memories_.count(); ++m) {
    changed[static_cast<size_t>(m)] = counters_[static_cast<size_t>(m)].updates == 0;
  }
  for (size_t o = 0; o < objects_.size(); ++o) {
    const PriorityObject& obj = objects_[o];
    const ObjectView view = view_of(obj.bounds, eye_m, obj.velocity_m_s - eye_velocity_m_s, obj.animation_validity_s);
    const int target = memories_.memory_for_validity(validity_periods(view, params_.threshold_rad).min_s());
    const int current = memory_of_[o];
    pending_[o] = target == current ? -1 : target;
    if (target == current || !memories_.has_slot(std::max(current, target), k)) continue;
    // Both memories are redrawn at this slot: one gains the object, the other loses it.
    dirty_[static_cast<size_t>(current)] = true;
    dirty_[static_cast<size_t>(target)] = true;
    changed[static_cast<size_t>(current)] = true;
    changed[static_cast<size_t>(target)] = true;
    if (drawn_[o].valid) (target < current ? result.promotions : result.demotions) += 1;
    memory_of_[o] = target;
    pending_[o] = -1;
  }
  promotions_ += result.promotions;
  demotions_ += result.demotions;

  const auto lists = objects_per_memory();
  for (int m = 0; m < memories_.count(); ++m) {
    if (!memories_.has_slot(m, k)) continue;
    const auto& members = lists[static_cast<size_t>(m)];
    bool needed = dirty_[static_cast<size_t>(m)];
    for (size_t i = 0; i < members.size() && !needed; ++i) {
      needed = expires_before_next_slot(members[i], m, now, eye_m, eye_velocity_m_s);
    }
    if (!needed) continue;
    for (uint32_t o : members) {
      const ObjectView view = view_of(objects_[o].bounds, eye_m, glm::dvec3(0.0), 0.0);
      drawn_[o] = Drawn{true, now, eye_m, view.nearest_distance_m, view.centre_distance_m};
    }
    dirty_[static_cast<size_t>(m)] = false;
    MemoryCounters& c = counters_[static_cast<size_t>(m)];
    ++c.updates;
    c.objects += static_cast<int64_t>(members.size());
    c.last_update = now;
    result.updated_memories.push_back(m);
    if (changed[static_cast<size_t>(m)]) result.changed_memories.push_back(m);
    result.objects_rendered += static_cast<int64_t>(members.size());
  }
  return result;
}

}  // namespace latsim::arp
