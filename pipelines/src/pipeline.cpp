#include "latsim/pipelines/pipeline.hpp"

#include <stdexcept>

namespace latsim::pipelines {

void PipelineRegistry::add(PipelineEntry entry) {
  const std::string name = entry.name;
  if (!entries_.emplace(name, std::move(entry)).second)
    throw std::logic_error("pipeline \"" + name + "\" registered twice");
}

const PipelineEntry* PipelineRegistry::find(const std::string& name) const {
  auto it = entries_.find(name);
  return it == entries_.end() ? nullptr : &it->second;
}

std::vector<std::string> PipelineRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& [name, e] : entries_) out.push_back(name);
  return out;
}

}  // namespace latsim::pipelines
