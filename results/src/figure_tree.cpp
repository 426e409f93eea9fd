#include "latsim/results/figure_tree.hpp"

#include <cctype>
#include <charconv>
#include <string_view>

#include "latsim/results/json_text.hpp"

namespace latsim::results {

namespace {

// Buckets of a distribution's histogram, as FigureTable::distribution_json makes it.
constexpr int kHistogramBuckets = 50;

bool is_index(std::string_view part) {
  if (part.empty()) return false;
  for (char c : part)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

void write_value(std::string& out, const FigureValue& value) {
  if (const auto* i = std::get_if<int64_t>(&value)) json_text::append_integer(out, *i);
  else if (const auto* x = std::get_if<double>(&value)) json_text::append_real(out, *x);
  else if (const auto* b = std::get_if<bool>(&value)) out += *b ? "true" : "false";
  else json_text::append_string(out, std::get<std::string>(value));
}

}  // namespace

std::optional<FigureTree> FigureTree::of(const FigureTable& table,
                                         const std::map<std::string, stats::Distribution>& distributions,
                                         const std::map<std::string, int64_t>& counters) {
  // The same steps, in the same order, as FigureTable::to_json.
  FigureTree tree;
  for (const auto& [name, d] : distributions) set_distribution(tree.root_.children[name], d);
  if (!counters.empty()) {
    Node& counts = tree.root_.children["counts"];
    if (counts.kind == Node::Kind::null) counts.kind = Node::Kind::object;
    if (counts.kind != Node::Kind::object || counters.count("count") != 0) return std::nullopt;
    for (const auto& [name, v] : counters) {
      Node& n = counts.children[name];
      n = Node{};
      n.kind = Node::Kind::value;
      n.value = v;
    }
  }
  for (const auto& [name, is_list] : table.containers_) {
    Node* c = tree.at_name(name);
    if (c == nullptr) return std::nullopt;
    if (c->kind == Node::Kind::null) c->kind = is_list ? Node::Kind::array : Node::Kind::object;
  }
  for (const auto& [name, d] : table.published_) {
    Node* n = tree.at_name(name);
    if (n == nullptr) return std::nullopt;
    *n = Node{};
    set_distribution(*n, d);
  }
  for (const auto& [name, value] : table.values_) {
    Node* n = tree.at_name(name);
    if (n == nullptr) return std::nullopt;
    *n = Node{};
    n->kind = Node::Kind::value;
    n->value = value;
  }
  return tree;
}

FigureTree::Node* FigureTree::at_name(const std::string& name) {
  // As nlohmann::json's operator[] nests: a null becomes an array for an
  // index, an object for a key; an array grows to the index.
  Node* node = &root_;
  size_t begin = 0;
  while (true) {
    const size_t dot = name.find('.', begin);
    const std::string_view part =
        std::string_view(name).substr(begin, dot == std::string::npos ? std::string_view::npos : dot - begin);
    if (is_index(part) && node->kind != Node::Kind::object) {
      if (node->kind == Node::Kind::null) node->kind = Node::Kind::array;
      size_t index = 0;
      const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), index);
      if (node->kind != Node::Kind::array || error != std::errc{} || index > (size_t{1} << 20)) return nullptr;
      if (index >= node->elements.size()) node->elements.resize(index + 1);
      node = &node->elements[index];
    } else {
      if (node->kind == Node::Kind::null) node->kind = Node::Kind::object;
      // A "count" below the top level would say something to the headline.
      if (node->kind != Node::Kind::object || (node != &root_ && part == "count")) return nullptr;
      node = &node->children[std::string(part)];
    }
    if (dot == std::string::npos) return node;
    begin = dot + 1;
  }
}

void FigureTree::set_distribution(Node& node, const stats::Distribution& d) {
  node.kind = Node::Kind::distribution;
  node.distribution = &d;
  node.summary = d.summary();
}

FigureTree::Top FigureTree::top(const std::string& name) const {
  const auto it = root_.children.find(name);
  if (it == root_.children.end()) return {};
  const Node& n = it->second;
  Top t;
  t.present = true;
  t.object = n.kind == Node::Kind::object || n.kind == Node::Kind::distribution;
  if (n.kind == Node::Kind::distribution) t.count = static_cast<int64_t>(n.summary.count);
  return t;
}

void FigureTree::write(std::string& out) const { write(out, root_); }

void FigureTree::write(std::string& out, const Node& node) {
  switch (node.kind) {
    case Node::Kind::object: {
      out += '{';
      bool first = true;
      for (const auto& [key, child] : node.children) {
        if (!first) out += ',';
        first = false;
        json_text::append_string(out, key);
        out += ':';
        write(out, child);
      }
      out += '}';
      return;
    }
    case Node::Kind::array:
      out += '[';
      for (size_t i = 0; i < node.elements.size(); ++i) {
        if (i) out += ',';
        write(out, node.elements[i]);
      }
      out += ']';
      return;
    case Node::Kind::distribution: write_distribution(out, node); return;
    case Node::Kind::value: write_value(out, node.value); return;
    case Node::Kind::null: out += "null"; return;
  }
}

void FigureTree::write_distribution(std::string& out, const Node& node) {
  // Keys in order: count, histogram, max, mean, min, p50, p90, p99, p999, stddev.
  const stats::Distribution::Summary& s = node.summary;
  out += "{\"count\":";
  json_text::append_integer(out, s.count);
  std::vector<std::pair<double, uint64_t>> buckets;
  if (s.count > 0) buckets = node.distribution->plot_histogram(kHistogramBuckets);
  // Edges that follow from min and max (edge b = min + (max - min) / n * b): the counts alone.
  bool regular = !buckets.empty();
  const double width = (s.max - s.min) / static_cast<double>(buckets.size());
  for (size_t b = 0; regular && b < buckets.size(); ++b)
    regular = buckets[b].first == s.min + width * static_cast<double>(b);
  out += regular ? ",\"histogram_counts\":[" : ",\"histogram\":[";
  for (size_t b = 0; b < buckets.size(); ++b) {
    if (b) out += ',';
    if (regular) {
      json_text::append_integer(out, buckets[b].second);
      continue;
    }
    out += '[';
    json_text::append_real(out, buckets[b].first);
    out += ',';
    json_text::append_integer(out, buckets[b].second);
    out += ']';
  }
  out += ']';
  const std::pair<const char*, double> reals[] = {{",\"max\":", s.max},   {",\"mean\":", s.mean}, {",\"min\":", s.min},
                                                  {",\"p50\":", s.p50},   {",\"p90\":", s.p90},   {",\"p99\":", s.p99},
                                                  {",\"p999\":", s.p999}, {",\"stddev\":", s.stddev}};
  for (const auto& [key, x] : reals) {
    out += key;
    json_text::append_real(out, x);
  }
  out += '}';
}

}  // namespace latsim::results
