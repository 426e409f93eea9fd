#include "latsim/sweep/record.hpp"

#include <stdexcept>

#include "latsim/results/json_text.hpp"
#include "latsim/scenario/config.hpp"

namespace latsim::sweep {

namespace {

using Json = nlohmann::json;

/// Writes JSON as nlohmann::json::dump(-1) reads it back (text that is not
/// UTF-8 replaced as dump's error_handler_t::replace does), compacting
/// histograms on the way: a run's summary is written once and never copied.
class Writer {
 public:
  /// `figures`, when not empty, is written as the value of the top-level
  /// object's "figures" (a FigureTree's text).
  explicit Writer(std::string& out, std::string_view figures = {}) : out_(out), figures_(figures) {}

  void value(const Json& v) {
    switch (v.type()) {
      case Json::value_t::object: object(v); return;
      case Json::value_t::array:
        out_ += '[';
        for (size_t i = 0; i < v.size(); ++i) {
          if (i) out_ += ',';
          value(v[i]);
        }
        out_ += ']';
        return;
      case Json::value_t::string: string(v.get_ref<const std::string&>()); return;
      case Json::value_t::number_float: real(v.get<double>()); return;
      case Json::value_t::number_integer: integer(v.get<int64_t>()); return;
      case Json::value_t::number_unsigned: integer(v.get<uint64_t>()); return;
      case Json::value_t::boolean: out_ += v.get<bool>() ? "true" : "false"; return;
      default: out_ += "null";
    }
  }

 private:
  void object(const Json& v) {
    // A histogram whose edges follow from its distribution's min and max: its counts.
    const Json* counts_of = regular_histogram(v);
    out_ += '{';
    bool first = true;
    for (auto it = v.begin(); it != v.end(); ++it) {
      if (!first) out_ += ',';
      first = false;
      if (counts_of && it.key() == "histogram") {
        out_ += "\"histogram_counts\":[";
        for (size_t b = 0; b < counts_of->size(); ++b) {
          if (b) out_ += ',';
          value((*counts_of)[b][1]);
        }
        out_ += ']';
        continue;
      }
      string(it.key());
      out_ += ':';
      if (!figures_.empty() && depth_ == 0 && it.key() == "figures") {
        out_ += figures_;
        continue;
      }
      ++depth_;
      value(it.value());
      --depth_;
    }
    out_ += '}';
  }
  static const Json* regular_histogram(const Json& node) {
    const auto h = node.find("histogram"), lo = node.find("min"), hi = node.find("max");
    if (h == node.end() || lo == node.end() || hi == node.end() || !h->is_array() || h->empty() ||
        !lo->is_number_float() || !hi->is_number_float())
      return nullptr;
    const double min = lo->get<double>(), width = (hi->get<double>() - min) / static_cast<double>(h->size());
    for (size_t b = 0; b < h->size(); ++b) {
      const Json& bucket = (*h)[b];
      if (!bucket.is_array() || bucket.size() != 2 || !bucket[0].is_number_float() || !bucket[1].is_number_unsigned() ||
          bucket[0].get<double>() != min + width * static_cast<double>(b))
        return nullptr;
    }
    return &*h;
  }
  void string(const std::string& s) { results::json_text::append_string(out_, s); }
  void real(double x) { results::json_text::append_real(out_, x); }
  template <class I>
  void integer(I x) {
    results::json_text::append_integer(out_, x);
  }

  std::string& out_;
  std::string_view figures_;
  int depth_ = 0;  // objects entered below the top level's
};

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

// What `now` changes in `base`, as ["=", pointer, value] and ["-", pointer].
void diff(const Json& base, const Json& now, const std::string& pointer, Json& ops) {
  if (!base.is_object() || !now.is_object()) {
    if (base != now) ops.push_back({"=", pointer, now});
    return;
  }
  for (auto it = base.begin(); it != base.end(); ++it)
    if (!now.contains(it.key())) ops.push_back({"-", scenario::join_pointer(pointer, it.key())});
  for (auto it = now.begin(); it != now.end(); ++it) {
    const auto b = base.find(it.key());
    if (b == base.end()) ops.push_back({"=", scenario::join_pointer(pointer, it.key()), it.value()});
    else diff(*b, it.value(), scenario::join_pointer(pointer, it.key()), ops);
  }
}

Json patched(const Json& base, const Json& ops) {
  Json doc = base;
  for (const Json& op : ops) {
    const Json::json_pointer at(op.at(1).get<std::string>());
    if (op.at(0) == "=") {
      doc[at] = op.at(2);
    } else {
      Json& parent = doc.at(at.parent_pointer());
      parent.erase(at.back());
    }
  }
  return doc;
}

std::string_view first_line(std::string_view record) {
  const size_t line = record.find('\n');
  if (line == std::string_view::npos) throw std::runtime_error("not a run record (no scenario line)");
  return record.substr(0, line);
}

}  // namespace

EncodedRecord encode_record(Json&& summary, const Json* base, std::string_view figures) {
  EncodedRecord out;
  if (const auto it = summary.find("scenario"); it != summary.end()) {
    out.scenario = std::move(*it);
    summary.erase(it);
  }
  out.text.reserve(8192);
  Writer(out.text, figures).value(summary);
  out.text += '\n';
  Writer w(out.text);
  if (base && base->is_object()) {
    Json ops = Json::array();
    diff(*base, out.scenario, "", ops);
    w.value(ops);
  } else {
    w.value(out.scenario);
  }
  return out;
}

Json record_scenario(std::string_view record, const Json* base) {
  Json scenario = Json::parse(record.substr(first_line(record).size() + 1));
  if (scenario.is_array()) {
    if (!base) throw std::runtime_error("a run record's scenario is a patch, and its segment's first is missing");
    return patched(*base, scenario);
  }
  return scenario;
}

Json decode_record(std::string_view record, const Json* base, RecordRead read) {
  Json summary = Json::parse(first_line(record));
  if (!summary.is_object()) throw std::runtime_error("not a run record (not a JSON object)");
  if (read == RecordRead::tables) return summary;
  if (const auto it = summary.find("figures"); it != summary.end()) expand_histograms(*it);
  summary["scenario"] = record_scenario(record, base);
  return summary;
}

}  // namespace latsim::sweep
