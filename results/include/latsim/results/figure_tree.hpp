// A run's figures arranged as figures.json arranges them, its distributions
// kept as distributions: written straight to the results store's text
// without building (and freeing) a JSON tree of every histogram bucket.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "latsim/results/figures.hpp"
#include "latsim/stats/stats.hpp"

namespace latsim::results {

/// The figures object of FigureTable::to_json as a light tree: objects,
/// arrays, values and distributions (each summarised once). Its text is
/// what sweep::encode_record writes for that JSON tree, byte for byte:
/// compact, keys in order, and a histogram whose bucket edges are those of
/// its distribution's min and max kept as its counts ("histogram_counts").
class FigureTree {
 public:
  /// The tree of `table`'s figures beside `distributions` and `counters`;
  /// nullopt where the JSON tree's rules would do something a well-formed
  /// registry never asks for (a name nesting into a distribution, a value
  /// or a list's element by name, a "count" below the top level): the JSON
  /// tree is then the one to ask.
  static std::optional<FigureTree> of(const FigureTable& table,
                                      const std::map<std::string, stats::Distribution>& distributions,
                                      const std::map<std::string, int64_t>& counters);

  /// What the figures hold at a top-level name: whether it is there, whether
  /// it is an object and, for a distribution, its count.
  struct Top {
    bool present = false;
    bool object = false;
    std::optional<int64_t> count;
  };
  Top top(const std::string& name) const;

  /// Appends the figures object's text.
  void write(std::string& out) const;

 private:
  struct Node {
    enum class Kind : uint8_t { null, object, array, distribution, value };
    Kind kind = Kind::null;
    std::map<std::string, Node> children;  // an object's
    std::vector<Node> elements;            // an array's
    const stats::Distribution* distribution = nullptr;
    stats::Distribution::Summary summary;
    FigureValue value;
  };

  /// The node at a dotted name, made on the way; null where the JSON tree
  /// would nest differently (see of()).
  Node* at_name(const std::string& name);
  static void set_distribution(Node& node, const stats::Distribution& d);
  static void write(std::string& out, const Node& node);
  static void write_distribution(std::string& out, const Node& node);

  Node root_{Node::Kind::object, {}, {}, nullptr, {}, {}};
};

}  // namespace latsim::results
