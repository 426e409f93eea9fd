#include "latsim/des/run_clocks.hpp"

#include <stdexcept>

namespace latsim::des {

const des::Clock& RunClocks::resolve(const std::string& name, const std::string& phase_pointer,
                                     des::RationalSeconds nominal, const des::ClockSettings& settings) {
  if (find(name) != nullptr) throw std::logic_error("clock \"" + name + "\" resolved twice");
  des::RandomStream stream(seed_, "clock." + name, replication_);
  clocks_.push_back(des::resolve_clock(name, nominal, settings, stream));
  const des::Clock& c = clocks_.back();
  // Whole picoseconds divided by 1e9 read back to the same tick (a double
  // carries 15 significant digits; a phase is far below 1e6 ms).
  phases_ms_.emplace_back(phase_pointer, static_cast<double>(c.phase.ticks()) / 1e9);
  return c;
}

const des::Clock* RunClocks::find(const std::string& name) const {
  for (const auto& c : clocks_)
    if (c.name == name) return &c;
  return nullptr;
}

}  // namespace latsim::des
