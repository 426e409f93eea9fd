// How one family of listeners, or the pipeline, writes its figures into the
// run's figure book.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "latsim/des/time.hpp"
#include "latsim/results/figures.hpp"
#include "latsim/stats/stats.hpp"

namespace latsim::results {

class FigureBook;

/// Writes the figures of one family (docs/adding-a-figure.md): every name
/// must be declared in results/figure_registry.json for that family, and
/// every figure is written once. A distribution is created on first use and
/// its reference stays valid for the run (hot paths keep it).
class FigureWriter {
 public:
  FigureWriter(FigureBook& book, std::string family) : book_(&book), family_(std::move(family)) {}

  /// Adds one sample to the named distribution (and to samples.csv when kept).
  void add(const std::string& name, double value);
  /// A duration, kept exactly.
  void add(const std::string& name, des::Time value);
  stats::Distribution& distribution(const std::string& name);
  /// add() through a handle the caller keeps, set on first use: no lookup
  /// by name on a hot path.
  void add(stats::Distribution*& handle, const char* name, double value) {
    if (!handle) handle = &distribution(name);
    handle->add(value);
    log(name, value);
  }
  /// Adds to the counter counts.<name>.
  void count(const std::string& name, int64_t n = 1);
  /// The counter counts.<name> itself, created at 0 (hot paths keep it).
  int64_t& counter(const std::string& name);
  /// A named value: "frames_rendered", "utilisation.gp", "memories.0.renders".
  void set(const std::string& name, FigureValue value);
  /// An empty list or object at `name` unless something is set there.
  void list(const std::string& name);
  void object(const std::string& name);
  /// A distribution a model kept itself, reported under `name` like the others.
  void publish(const std::string& name, const stats::Distribution& d);
  /// Logs a sample of `name` to samples.csv when the run keeps it.
  void log(const char* name, double value) const;
  bool logging() const;

  /// Legal but doubtful: reported on stderr and in summary.json's "warnings".
  void warn(std::string text);
  /// What a measured cost read and played (summary.json's "captures").
  void add_capture(nlohmann::json entry);
  /// The headline set of the registry the pipeline's reader means first.
  void use_headline(std::string set);

  const std::string& family() const { return family_; }
  FigureBook& book() const { return *book_; }

 private:
  FigureBook* book_;
  std::string family_;
};

}  // namespace latsim::results
