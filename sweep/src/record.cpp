#include "latsim/sweep/record.hpp"

#include <stdexcept>

namespace latsim::sweep {

namespace {

using Json = nlohmann::json;

bool is_number(const Json& object, const char* key) {
  const auto it = object.find(key);
  return it != object.end() && it->is_number_float();
}

// Replaces, below `node`, every histogram whose edges follow from its
// distribution's min and max by its counts.
void compact_histograms(Json& node) {
  if (!node.is_object()) return;
  const auto it = node.find("histogram");
  if (it != node.end() && it->is_array() && !it->empty() && is_number(node, "min") && is_number(node, "max")) {
    const double lo = node["min"].get<double>(), hi = node["max"].get<double>();
    const Json& buckets = *it;
    const double width = (hi - lo) / static_cast<double>(buckets.size());
    Json counts = Json::array();
    bool regular = true;
    for (size_t b = 0; b < buckets.size() && regular; ++b) {
      const Json& bucket = buckets[b];
      regular = bucket.is_array() && bucket.size() == 2 && bucket[0].is_number_float() &&
                bucket[0].get<double>() == lo + width * static_cast<double>(b) && bucket[1].is_number_unsigned();
      if (regular) counts.push_back(bucket[1]);
    }
    if (regular) {
      node.erase(it);
      node["histogram_counts"] = std::move(counts);
    }
    return;
  }
  for (auto& child : node) compact_histograms(child);
}

void expand_histograms(Json& node) {
  if (!node.is_object()) return;
  const auto it = node.find("histogram_counts");
  if (it != node.end()) {
    const double lo = node.at("min").get<double>(), hi = node.at("max").get<double>();
    const Json counts = std::move(*it);
    node.erase("histogram_counts");
    const double width = (hi - lo) / static_cast<double>(counts.size());
    Json buckets = Json::array();
    for (size_t b = 0; b < counts.size(); ++b) buckets.push_back({lo + width * static_cast<double>(b), counts[b]});
    node["histogram"] = std::move(buckets);
    return;
  }
  for (auto& child : node) expand_histograms(child);
}

}  // namespace

std::string encode_record(Json&& summary) {
  Json scenario;
  if (const auto it = summary.find("scenario"); it != summary.end()) {
    scenario = std::move(*it);
    summary.erase(it);
  }
  if (const auto it = summary.find("figures"); it != summary.end()) compact_histograms(*it);
  // Text a result file would replace (not UTF-8) is replaced here too.
  std::string text = summary.dump(-1, ' ', false, Json::error_handler_t::replace);
  text += '\n';
  text += scenario.dump(-1, ' ', false, Json::error_handler_t::replace);
  return text;
}

Json decode_record(std::string_view record, RecordRead read) {
  const size_t line = record.find('\n');
  if (line == std::string_view::npos) throw std::runtime_error("not a run record (no scenario line)");
  Json summary = Json::parse(record.substr(0, line));
  if (!summary.is_object()) throw std::runtime_error("not a run record (not a JSON object)");
  if (read == RecordRead::tables) return summary;
  if (const auto it = summary.find("figures"); it != summary.end()) expand_histograms(*it);
  summary["scenario"] = Json::parse(record.substr(line + 1));
  return summary;
}

}  // namespace latsim::sweep
