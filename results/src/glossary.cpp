#include "latsim/results/glossary.hpp"

namespace latsim::results {

bool is_glossary_figure(std::string_view name, const FigureRegistry& registry) {
  const FigureDecl* d = registry.find(name.substr(0, name.find('.')));
  return d != nullptr && registry.in_glossary(*d);
}

}  // namespace latsim::results
