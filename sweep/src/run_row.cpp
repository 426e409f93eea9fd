#include "latsim/sweep/run_row.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <stdexcept>

namespace latsim::sweep {

namespace {

/// Reads JSON text token by token, keeping nothing but what it is asked for.
class Scanner {
 public:
  explicit Scanner(std::string_view text) : t_(text) {}

  enum class Kind { object, array, string, number, boolean, null };

  Kind kind() {
    ws();
    if (i_ >= t_.size()) fail("unexpected end");
    switch (t_[i_]) {
      case '{': return Kind::object;
      case '[': return Kind::array;
      case '"': return Kind::string;
      case 't':
      case 'f': return Kind::boolean;
      case 'n': return Kind::null;
      default: return Kind::number;
    }
  }
  void expect(char c) {
    if (!eat(c)) fail("malformed JSON");
  }
  bool eat(char c) {
    ws();
    if (i_ < t_.size() && t_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  double number() {
    ws();
    const size_t start = i_;
    while (i_ < t_.size() && (std::isdigit(static_cast<unsigned char>(t_[i_])) || t_[i_] == '-' || t_[i_] == '+' ||
                              t_[i_] == '.' || t_[i_] == 'e' || t_[i_] == 'E'))
      ++i_;
    double v = 0.0;
    const auto [end, error] = std::from_chars(t_.data() + start, t_.data() + i_, v);
    if (error != std::errc() || end != t_.data() + i_) fail("a malformed number");
    return v;
  }
  bool boolean() {
    if (literal("true")) return true;
    if (literal("false")) return false;
    fail("malformed JSON");
  }
  std::string string() {
    expect('"');
    std::string out;
    while (i_ < t_.size() && t_[i_] != '"') {
      const char c = t_[i_++];
      if (c != '\\') {
        out += c;
        continue;
      }
      if (i_ >= t_.size()) break;
      const char e = t_[i_++];
      switch (e) {
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': unicode(out); break;
        default: out += e;  // \" \\ \/
      }
    }
    expect('"');
    return out;
  }
  void skip_value() {
    switch (kind()) {
      case Kind::string: (void)string(); return;
      case Kind::number: (void)number(); return;
      case Kind::boolean: (void)boolean(); return;
      case Kind::null:
        if (!literal("null")) fail("malformed JSON");
        return;
      case Kind::array:
        if (skip_flat_array()) return;
        [[fallthrough]];
      case Kind::object: {
        const char open = t_[i_], close = open == '{' ? '}' : ']';
        expect(open);
        if (eat(close)) return;
        do {
          if (open == '{') {
            (void)string();
            expect(':');
          }
          skip_value();
        } while (eat(','));
        expect(close);
        return;
      }
    }
  }

 private:
  // An array of numbers (a histogram's counts), skipped in one pass to its
  // bracket; false, and nothing consumed, when it holds anything else.
  bool skip_flat_array() {
    size_t j = i_ + 1;
    while (j < t_.size() && t_[j] != ']') {
      const char c = t_[j];
      if (c == '[' || c == '{' || c == '"') return false;
      ++j;
    }
    if (j >= t_.size()) return false;
    i_ = j + 1;
    return true;
  }
  void ws() {
    while (i_ < t_.size() && (t_[i_] == ' ' || t_[i_] == '\n' || t_[i_] == '\r' || t_[i_] == '\t')) ++i_;
  }
  bool literal(std::string_view word) {
    ws();
    if (t_.substr(i_, word.size()) != word) return false;
    i_ += word.size();
    return true;
  }
  unsigned hex4() {
    if (i_ + 4 > t_.size()) fail("a malformed \\u escape");
    unsigned v = 0;
    const auto [end, error] = std::from_chars(t_.data() + i_, t_.data() + i_ + 4, v, 16);
    if (error != std::errc() || end != t_.data() + i_ + 4) fail("a malformed \\u escape");
    i_ += 4;
    return v;
  }
  // A \u escape (a surrogate pair as one code point) in UTF-8.
  void unicode(std::string& out) {
    unsigned cp = hex4();
    if (cp >= 0xD800 && cp < 0xDC00 && t_.substr(i_, 2) == "\\u") {
      i_ += 2;
      cp = 0x10000 + ((cp - 0xD800) << 10) + (hex4() - 0xDC00);
    }
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xC0 | cp >> 6);
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xE0 | cp >> 12);
      out += static_cast<char>(0x80 | (cp >> 6 & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | cp >> 18);
      out += static_cast<char>(0x80 | (cp >> 12 & 0x3F));
      out += static_cast<char>(0x80 | (cp >> 6 & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }
  [[noreturn]] void fail(const char* what) const {
    throw std::runtime_error(std::string("not a run summary: ") + what + " at byte " + std::to_string(i_));
  }

  std::string_view t_;
  size_t i_ = 0;
};

struct Flat {
  std::vector<RowScalar> scalars;
  std::vector<RowDistribution> distributions;
};

// The figures below one object, by dotted name from `prefix`: an object with
// "count" and "mean" is a distribution (its numbers its statistics, anything
// else in it ignored); any other object's numbers and booleans are scalars,
// its objects looked into, its strings, arrays and nulls ignored.
void scan_figures(Scanner& s, const std::string& prefix, Flat& out) {
  s.expect('{');
  std::vector<std::pair<std::string, double>> numbers;
  Flat mine;
  bool has_count = false, has_mean = false;
  if (!s.eat('}')) {
    do {
      std::string key = s.string();
      s.expect(':');
      has_count = has_count || key == "count";
      has_mean = has_mean || key == "mean";
      std::string name = prefix.empty() ? key : prefix + "." + key;
      switch (s.kind()) {
        case Scanner::Kind::number: {
          const double v = s.number();
          mine.scalars.push_back({std::move(name), v, false});
          numbers.emplace_back(std::move(key), v);
          break;
        }
        case Scanner::Kind::boolean: mine.scalars.push_back({std::move(name), s.boolean() ? 1.0 : 0.0, true}); break;
        case Scanner::Kind::object: scan_figures(s, name, mine); break;
        default: s.skip_value();
      }
    } while (s.eat(','));
    s.expect('}');
  }
  if (has_count && has_mean) {
    RowDistribution d;
    d.name = prefix;
    for (auto& [key, v] : numbers) {
      const auto it = std::find(kDistributionStats.begin(), kDistributionStats.end(), key);
      if (it != kDistributionStats.end()) d.stats[static_cast<size_t>(it - kDistributionStats.begin())] = v;
      else d.extra.emplace_back(std::move(key), v);
    }
    out.distributions.push_back(std::move(d));
    return;
  }
  for (auto& x : mine.scalars) out.scalars.push_back(std::move(x));
  for (auto& x : mine.distributions) out.distributions.push_back(std::move(x));
}

void scan_models(Scanner& s, RunRow& row) {
  s.expect('{');
  if (s.eat('}')) return;
  do {
    RowModel m;
    m.name = s.string();
    s.expect(':');
    if (s.kind() != Scanner::Kind::object) {
      s.skip_value();
      continue;
    }
    s.expect('{');
    if (!s.eat('}')) {
      do {
        const std::string key = s.string();
        s.expect(':');
        const bool number = s.kind() == Scanner::Kind::number;
        if (number && key == "events") m.events = s.number();
        else if (number && key == "wall_s") m.wall_s = s.number();
        else s.skip_value();
      } while (s.eat(','));
      s.expect('}');
    }
    row.models.push_back(std::move(m));
  } while (s.eat(','));
  s.expect('}');
}

}  // namespace

void scan_summary(std::string_view text, RunRow& row) {
  Scanner s(text);
  if (s.kind() != Scanner::Kind::object) throw std::runtime_error("not a run summary: not a JSON object");
  s.expect('{');
  if (s.eat('}')) return;
  do {
    const std::string key = s.string();
    s.expect(':');
    const Scanner::Kind kind = s.kind();
    if (key == "figures" && kind == Scanner::Kind::object) {
      Flat flat;
      scan_figures(s, "", flat);
      row.scalars = std::move(flat.scalars);
      row.distributions = std::move(flat.distributions);
    } else if (key == "models" && kind == Scanner::Kind::object) {
      scan_models(s, row);
    } else if (key == "fingerprint" && kind == Scanner::Kind::string) {
      row.fingerprint = s.string();
    } else if (kind == Scanner::Kind::number) {
      const double v = s.number();
      if (key == "events") row.events = v;
      else if (key == "wall_s") row.wall_s = v;
      else if (key == "peak_rss_mb") row.peak_rss_mb = v;
      row.root.emplace_back(key, v);
    } else {
      s.skip_value();
    }
  } while (s.eat(','));
  s.expect('}');
}

void scan_summary_json(const nlohmann::json& summary, RunRow& row) { scan_summary(std::string_view(summary.dump()), row); }

std::optional<double> RunRow::figure(const std::string& path) const {
  for (const auto& s : scalars)
    if (!s.boolean && s.name == path) return s.value;
  for (const auto& d : distributions) {
    if (d.name == path) return d.stats[1];  // a distribution alone stands for its mean
    if (path.size() <= d.name.size() + 1 || path.compare(0, d.name.size(), d.name) != 0 || path[d.name.size()] != '.')
      continue;
    const std::string stat = path.substr(d.name.size() + 1);
    for (size_t i = 0; i < kDistributionStats.size(); ++i)
      if (stat == kDistributionStats[i]) return d.stats[i];
    for (const auto& [name, v] : d.extra)
      if (name == stat) return v;
  }
  // Any other object with a mean stands for it too.
  for (const auto& s : scalars)
    if (!s.boolean && s.name == path + ".mean") return s.value;
  for (const auto& [name, v] : root)
    if (name == path) return v;
  return std::nullopt;
}

}  // namespace latsim::sweep
