// The figure registry: every figure a run reports, declared once in
// results/figure_registry.json with its name, kind, unit, family, the
// pipelines that produce it, its meaning, its headline ranks and its table
// columns. The recorders refuse a figure it does not declare; the glossary,
// the headlines, the results tables and the Python analysis come from it.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace latsim::results {

/// A column of the results tables (results.csv, the report's latency table).
struct FigureColumn {
  int order = 0;             ///< place among all columns, from 1
  std::string name;          ///< e.g. "mtp_p99_ms"
  std::string figure;        ///< dotted path, e.g. "motion_to_photon_ms.p99"
  std::string label;         ///< table and plot label, e.g. "MTP p99 (ms)"
  std::string shown;         ///< "always", "where present" or "when leading" (the report's default tables)
  bool report = true;        ///< in the report's latency table (false: results.csv only)
};

/// A headline: the pipelines that use it and why their readers look there first.
struct HeadlineSet {
  std::string used_by;
  std::string why;
};

/// One declared figure. A name may hold placeholders: <n> an index, any
/// other <word> one of the registry's words of that name.
struct FigureDecl {
  std::string name;
  std::string kind;    ///< distribution, count, number, flag, word, list, object, group, summary
  std::string unit;
  std::string family;  ///< the listeners that compute it, or "pipeline"
  std::vector<std::string> pipelines;  ///< the pipelines that produce it; empty: any
  std::string meaning;
  std::map<std::string, int> headline;  ///< headline set -> rank (1 first)
  std::vector<FigureColumn> columns;

  bool any_pipeline() const { return pipelines.empty(); }
  bool produced_by(std::string_view pipeline) const;
};

/// The declared figures, looked up by the names figures.json nests them under.
class FigureRegistry {
 public:
  /// The registry built into latsim (results/figure_registry.json).
  static const FigureRegistry& builtin();
  /// The text of results/figure_registry.json as latsim was built with it.
  static std::string_view builtin_text();
  /// A registry from its JSON text; throws std::invalid_argument naming the
  /// figure and field that is wrong.
  static FigureRegistry parse(std::string_view json_text);

  const std::vector<FigureDecl>& figures() const { return figures_; }
  /// The headline sets by name.
  const std::map<std::string, HeadlineSet>& headlines() const { return headlines_; }
  /// The declaration of figure `name` ("memories.0.renders", "counts.fields",
  /// "variants.1.render_load"), or nullptr when none declares it. A name
  /// under a group is its member's declaration.
  const FigureDecl* find(std::string_view name) const;
  /// The headline of `set`: its figures in rank order. Throws
  /// std::logic_error for a set the registry does not declare.
  std::vector<std::string> headline(std::string_view set) const;
  bool has_headline(std::string_view set) const { return headlines_.count(std::string(set)) != 0; }
  /// Every column, in order.
  const std::vector<FigureColumn>& columns() const { return columns_; }
  /// The words placeholder <name> stands for.
  const std::vector<std::string>& placeholder(std::string_view name) const;
  /// Whether `name` matches the declared name `pattern` (placeholders filled in).
  bool matches(std::string_view pattern, std::string_view name) const;
  /// Whether `family` is declared.
  bool has_family(std::string_view family) const { return families_.count(std::string(family)) != 0; }
  /// Whether `d` is a glossary figure: computed by the recorders alike for
  /// every pipeline, and defined in docs/figures.md's glossary.
  bool in_glossary(const FigureDecl& d) const;

 private:
  const FigureDecl* find_in(std::string_view name, int depth) const;

  std::vector<FigureDecl> figures_;
  std::unordered_map<std::string, size_t> exact_;  // names without placeholders -> index
  std::vector<size_t> patterns_;                   // figures whose names hold placeholders
  std::map<std::string, std::vector<std::string>> placeholders_;
  std::map<std::string, bool> families_;  // family -> in the glossary
  std::map<std::string, HeadlineSet> headlines_;
  std::vector<FigureColumn> columns_;
};

}  // namespace latsim::results
