// The named figures of one run, each declared in the figure registry and
// written by its own family, and the one serialisation of them into
// figures.json.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/des/simulator.hpp"
#include "latsim/results/figure_registry.hpp"
#include "latsim/results/figure_tree.hpp"
#include "latsim/results/figures.hpp"
#include "latsim/results/ledger.hpp"
#include "latsim/stats/stats.hpp"

namespace latsim::results {

class FigureWriter;

/// The distributions, counters and values of a run by name, its warnings,
/// the captures its measured costs read, and its headline. Listeners and the
/// pipeline write through a FigureWriter of their family, which refuses a
/// name the registry does not declare or declares for another family; a
/// figure is never written twice.
class FigureBook {
 public:
  FigureBook(const des::Simulator& sim, bool keep_samples, const FigureRegistry& registry = FigureRegistry::builtin());
  FigureBook(const FigureBook&) = delete;
  FigureBook& operator=(const FigureBook&) = delete;

  /// The writer of `family` (a family of the registry, or "pipeline").
  FigureWriter writer(std::string_view family);
  const FigureRegistry& registry() const { return registry_; }

  /// Raw samples go here too when it is on (samples.csv).
  SampleLog& sample_log() { return sample_log_; }
  const SampleLog& sample_log() const { return sample_log_; }
  /// Called before any distribution is read: a listener that gathers runs of
  /// samples adds what it holds.
  void before_reading(std::function<void()> complete) { before_reading_ = std::move(complete); }

  const stats::Distribution* distribution(const std::string& name) const;
  int64_t counter(const std::string& name) const;
  const std::map<std::string, stats::Distribution>& distributions() const {
    if (before_reading_) before_reading_();
    return dists_;
  }
  const std::map<std::string, int64_t>& counters() const { return counters_; }
  /// Every figure in the one serialisation of figures.json.
  nlohmann::json figures() const { return table_.to_json(distributions(), counters_); }
  /// The same figures as a FigureTree, to be written as text (nullopt: ask figures()).
  std::optional<FigureTree> figure_tree() const { return FigureTree::of(table_, distributions(), counters_); }

  /// The headline set the pipeline's reader means first (the registry ranks
  /// its figures); "default" unless the pipeline names one.
  void use_headline(std::string set);
  /// The headline's figures that the run has, in rank order (after finish).
  std::vector<std::string> headline() const { return headline(figures()); }
  /// The same, from the run's figures() already in hand (they take a while to make).
  std::vector<std::string> headline(const nlohmann::json& figures) const;
  std::vector<std::string> headline(const FigureTree& figures) const;
  /// Legal but doubtful: reported on stderr and in summary.json's "warnings".
  void warn(std::string text) { table_.warn(std::move(text)); }
  const std::vector<std::string>& warnings() const { return table_.warnings(); }
  const nlohmann::json& captures() const { return captures_; }

 private:
  friend class FigureWriter;

  /// The declaration of `name` for a write by `family` of a figure of one of
  /// `kinds`; throws std::logic_error saying what to do otherwise.
  const FigureDecl& check(const std::string& name, std::string_view family, std::initializer_list<std::string_view> kinds) const;

  const des::Simulator& sim_;
  bool keep_samples_;
  const FigureRegistry& registry_;
  std::map<std::string, stats::Distribution> dists_;
  std::map<std::string, int64_t> counters_;
  FigureTable table_;
  nlohmann::json captures_ = nlohmann::json::array();
  std::string headline_set_ = "default";
  SampleLog sample_log_;
  std::function<void()> before_reading_;
};

}  // namespace latsim::results
