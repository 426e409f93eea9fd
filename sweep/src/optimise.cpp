#include "latsim/sweep/optimise.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "latsim/scenario/readable.hpp"

namespace latsim::sweep {

std::optional<FigureBound> parse_bound(const std::string& text) {
  for (const char* op : {"<=", ">="}) {
    const size_t at = text.find(op);
    if (at == std::string::npos || at == 0) continue;
    FigureBound b;
    b.figure = text.substr(0, at);
    b.at_most = op[0] == '<';
    const std::string value = text.substr(at + 2);
    char* end = nullptr;
    b.bound = std::strtod(value.c_str(), &end);
    if (value.empty() || end != value.c_str() + value.size() || !std::isfinite(b.bound)) return std::nullopt;
    return b;
  }
  return std::nullopt;
}

std::optional<int> setting_decimals(const scenario::KeySchema* key) {
  if (key && key->type == "rate") return 6;
  if (key && key->type == "integer") return 0;
  return std::nullopt;
}

std::optional<double> setting_in_steps(double x, double lo, double hi, std::optional<int> decimals) {
  if (!decimals) return x;
  // Dividing the whole number of steps by 10^decimals gives the double
  // nearest the decimal (multiplying by 10^-decimals, inexact, would not).
  const double scale = std::pow(10.0, *decimals);
  const auto at = [scale](double k) { return k / scale; };
  double k = std::nearbyint(x * scale);
  if (at(k) < lo) k += 1;
  if (at(k) > hi) k -= 1;
  if (at(k) < lo || at(k) > hi) return std::nullopt;
  return at(k);
}

bool better(const Trial& a, const Trial& b) {
  if (a.violation != b.violation) return a.violation < b.violation;
  if (a.objective != b.objective) return a.objective < b.objective;
  return a.x < b.x;
}

SearchResult golden_section(const std::function<Trial(double)>& evaluate, double lo, double hi, double tolerance) {
  if (!(hi > lo) || !(tolerance > 0)) throw std::invalid_argument("golden_section: needs lo < hi and tolerance > 0");
  // 1/phi: each step keeps 0.618 of the interval and reuses one probe.
  const double r = (std::sqrt(5.0) - 1.0) / 2.0;
  SearchResult out;
  auto eval = [&](double x) {
    out.tried.push_back(evaluate(x));
    return out.tried.back();
  };
  double a = lo, b = hi;
  double c = b - r * (b - a), d = a + r * (b - a);
  Trial fc = eval(c), fd = eval(d);
  while (b - a > tolerance) {
    if (better(fc, fd)) {  // the best lies in [a, d]
      b = d;
      d = c;
      fd = fc;
      c = b - r * (b - a);
      fc = eval(c);
    } else {  // in [c, b]
      a = c;
      c = d;
      fc = fd;
      d = a + r * (b - a);
      fd = eval(d);
    }
  }
  // The ends are tried too: the best of a monotone merit lies at one.
  eval(lo);
  eval(hi);
  out.best = *std::min_element(out.tried.begin(), out.tried.end(), better);
  return out;
}

std::optional<int64_t> largest_fitting(const std::function<bool(int64_t)>& fits, int64_t lo, int64_t hi) {
  if (!fits(lo)) return std::nullopt;
  if (fits(hi)) return hi;
  // Invariant: lo fits, hi does not.
  while (hi - lo > 1) {
    const int64_t mid = lo + (hi - lo) / 2;
    (fits(mid) ? lo : hi) = mid;
  }
  return lo;
}

std::string missing_figure_message(const std::string& figure, const nlohmann::json& summary, size_t max_names) {
  std::vector<std::string> names;
  if (summary.contains("headline"))
    for (const auto& n : summary["headline"]) names.push_back(n.get<std::string>());
  if (summary.contains("figures"))
    for (auto it = summary["figures"].begin(); it != summary["figures"].end(); ++it)
      if ((it->is_number() || (it->is_object() && it->contains("mean"))) &&
          std::find(names.begin(), names.end(), it.key()) == names.end())
        names.push_back(it.key());
  std::string text = "this run reports no figure " + scenario::quote_value(figure) + "; it reports ";
  for (size_t i = 0; i < names.size() && i < max_names; ++i) text += (i ? ", " : "") + names[i];
  if (names.size() > max_names) text += ", ...";
  return text + " (every figure: figures.json)";
}

}  // namespace latsim::sweep
