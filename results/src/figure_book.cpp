#include "latsim/results/figure_book.hpp"

#include <algorithm>
#include <stdexcept>

#include "latsim/results/figure_writer.hpp"

namespace latsim::results {

namespace {

// Relative accuracy of every distribution's quantiles.
constexpr double kRelativeError = 0.005;

std::string kinds_text(std::initializer_list<std::string_view> kinds) {
  std::string out;
  for (std::string_view k : kinds) out += (out.empty() ? "" : " or ") + std::string(k);
  return out;
}

}  // namespace

FigureBook::FigureBook(const des::Simulator& sim, bool keep_samples, const FigureRegistry& registry)
    : sim_(sim), keep_samples_(keep_samples), registry_(registry) {}

FigureWriter FigureBook::writer(std::string_view family) {
  if (!registry_.has_family(family))
    throw std::logic_error("figure family \"" + std::string(family) + "\" is not declared in results/figure_registry.json");
  return FigureWriter(*this, std::string(family));
}

const FigureDecl& FigureBook::check(const std::string& name, std::string_view family,
                                    std::initializer_list<std::string_view> kinds) const {
  const FigureDecl* d = registry_.find(name);
  if (d == nullptr)
    throw std::logic_error("figure \"" + name + "\" is not declared in results/figure_registry.json: declare it "
                           "there, once, with its kind, unit, family and meaning (docs/adding-a-figure.md)");
  if (d->family != family) {
    if (family == "pipeline")
      throw std::logic_error("figure \"" + name + "\" is computed by the recorder for every pipeline (docs/figures.md, "
                             "family \"" + d->family + "\"); report a pipeline-specific variant under a name of its own");
    throw std::logic_error("figure \"" + name + "\" belongs to family \"" + d->family + "\", not \"" +
                           std::string(family) + "\" (results/figure_registry.json)");
  }
  if (std::find(kinds.begin(), kinds.end(), d->kind) == kinds.end())
    throw std::logic_error("figure \"" + name + "\" is declared a " + d->kind + ", not a " + kinds_text(kinds) +
                           " (results/figure_registry.json)");
  return *d;
}

const stats::Distribution* FigureBook::distribution(const std::string& name) const {
  const auto& all = distributions();
  const auto it = all.find(name);
  return it == all.end() ? nullptr : &it->second;
}

int64_t FigureBook::counter(const std::string& name) const {
  const auto it = counters_.find(name);
  return it == counters_.end() ? 0 : it->second;
}

void FigureBook::use_headline(std::string set) {
  if (!registry_.has_headline(set))
    throw std::logic_error("headline \"" + set + "\" is not declared in results/figure_registry.json");
  headline_set_ = std::move(set);
}

std::vector<std::string> FigureBook::headline(const nlohmann::json& all) const {
  std::vector<std::string> present;
  for (const std::string& name : registry_.headline(headline_set_)) {
    const auto it = all.find(name);
    // A distribution without a sample says nothing: it is no headline.
    if (it == all.end() || (it->is_object() && it->contains("count") && it->at("count").get<int64_t>() == 0)) continue;
    present.push_back(name);
  }
  return present;
}

std::vector<std::string> FigureBook::headline(const FigureTree& all) const {
  std::vector<std::string> present;
  for (const std::string& name : registry_.headline(headline_set_)) {
    const FigureTree::Top top = all.top(name);
    if (!top.present || (top.count && *top.count == 0)) continue;
    present.push_back(name);
  }
  return present;
}

// ---- FigureWriter ------------------------------------------------------------

void FigureWriter::add(const std::string& name, double value) {
  distribution(name).add(value);
  log(name.c_str(), value);
}

void FigureWriter::add(const std::string& name, des::Time value) {
  distribution(name).add(value);
  log(name.c_str(), value.to_ms());
}

stats::Distribution& FigureWriter::distribution(const std::string& name) {
  auto& dists = book_->dists_;
  auto it = dists.find(name);
  if (it == dists.end()) {
    book_->check(name, family_, {"distribution"});
    it = dists.emplace(name, stats::Distribution(kRelativeError, book_->keep_samples_)).first;
  }
  return it->second;
}

int64_t& FigureWriter::counter(const std::string& name) {
  auto& counters = book_->counters_;
  auto it = counters.find(name);
  if (it == counters.end()) {
    book_->check("counts." + name, family_, {"count"});
    it = counters.emplace(name, 0).first;
  }
  return it->second;
}

void FigureWriter::count(const std::string& name, int64_t n) { counter(name) += n; }

void FigureWriter::set(const std::string& name, FigureValue value) {
  book_->check(name, family_, {"count", "number", "flag", "word"});
  if (book_->dists_.count(name) != 0) throw std::logic_error("figure \"" + name + "\" is already a distribution");
  book_->table_.set(name, std::move(value));
}

void FigureWriter::list(const std::string& name) {
  book_->check(name, family_, {"list"});
  book_->table_.list(name);
}

void FigureWriter::object(const std::string& name) {
  book_->check(name, family_, {"object"});
  book_->table_.object(name);
}

void FigureWriter::publish(const std::string& name, const stats::Distribution& d) {
  book_->check(name, family_, {"distribution"});
  if (book_->dists_.count(name) != 0) throw std::logic_error("figure \"" + name + "\" is already a distribution");
  book_->table_.publish(name, d);
}

bool FigureWriter::logging() const { return book_->sample_log_.on(); }

void FigureWriter::log(const char* name, double value) const {
  if (book_->sample_log_.on()) book_->sample_log_.add(book_->sim_.now().to_ms(), name, value);
}

void FigureWriter::warn(std::string text) { book_->warn(std::move(text)); }

void FigureWriter::add_capture(nlohmann::json entry) { book_->captures_.push_back(std::move(entry)); }

void FigureWriter::use_headline(std::string set) { book_->use_headline(std::move(set)); }

}  // namespace latsim::results
