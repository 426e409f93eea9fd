#include "latsim/results/figures.hpp"

#include <cctype>
#include <stdexcept>

namespace latsim::results {

namespace {

using Json = nlohmann::json;

bool is_index(const std::string& part) {
  if (part.empty()) return false;
  for (char c : part)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

// The JSON value at a dotted name, created (objects and arrays) on the way.
Json& at_name(Json& root, const std::string& name) {
  Json* node = &root;
  size_t begin = 0;
  while (true) {
    const size_t dot = name.find('.', begin);
    const std::string part = name.substr(begin, dot == std::string::npos ? std::string::npos : dot - begin);
    node = is_index(part) && !node->is_object() ? &(*node)[std::stoul(part)] : &(*node)[part];
    if (dot == std::string::npos) return *node;
    begin = dot + 1;
  }
}

}  // namespace

void FigureTable::set(const std::string& name, FigureValue value) {
  if (values_.count(name) != 0 || published_.count(name) != 0)
    throw std::logic_error("figure \"" + name + "\" is set twice; a figure has one value");
  values_.emplace(name, std::move(value));
}

void FigureTable::publish(const std::string& name, const stats::Distribution& d) {
  if (values_.count(name) != 0 || published_.count(name) != 0)
    throw std::logic_error("figure \"" + name + "\" is published twice; a figure has one value");
  published_.emplace(name, d);
}

Json FigureTable::distribution_json(const stats::Distribution& d) {
  const auto s = d.summary();
  Json j{{"count", s.count}, {"mean", s.mean}, {"stddev", s.stddev}, {"min", s.min}, {"p50", s.p50},
         {"p90", s.p90},     {"p99", s.p99},   {"p999", s.p999},     {"max", s.max}};
  Json h = Json::array();
  if (s.count > 0)
    for (const auto& [edge, count] : d.plot_histogram(50)) h.push_back({edge, count});
  j["histogram"] = h;
  return j;
}

Json FigureTable::to_json(const std::map<std::string, stats::Distribution>& distributions,
                          const std::map<std::string, int64_t>& counters) const {
  Json f = Json::object();
  for (const auto& [name, d] : distributions) f[name] = distribution_json(d);
  for (const auto& [name, v] : counters) f["counts"][name] = v;
  for (const auto& [name, is_list] : containers_) {
    Json& c = at_name(f, name);
    if (c.is_null()) c = is_list ? Json::array() : Json::object();
  }
  for (const auto& [name, d] : published_) at_name(f, name) = distribution_json(d);
  // A named pair, not a structured binding: clang before 16 cannot capture bindings in a lambda.
  for (const auto& entry : values_) std::visit([&](const auto& x) { at_name(f, entry.first) = x; }, entry.second);
  return f;
}

}  // namespace latsim::results
