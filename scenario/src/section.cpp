// scenario::Section itself and its single-value keys: numbers, integers, flags, text, choices, rates, durations, paths.
#include "latsim/scenario/section.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "latsim/scenario/choice_list.hpp"
#include "section_internal.hpp"
#include "latsim/scenario/readable.hpp"

namespace latsim::scenario {

using Json = nlohmann::json;

namespace {

// The exact rational period as the frequency a scenario would write: 60, or "60000/1001".
Json hz_of_period(des::RationalSeconds period) {
  if (period.num == 1) return Json(period.den);
  return Json(std::to_string(period.den) + "/" + std::to_string(period.num));
}

double ticks_per_unit(std::string_view unit) {
  if (unit == "s") return 1e12;
  if (unit == "ms") return 1e9;
  if (unit == "us") return 1e6;
  throw std::logic_error("a duration's unit must be s, ms or us, not \"" + std::string(unit) + "\"");
}

// Every number a scenario gives is finite and at most this large in
// magnitude unless its declaration says otherwise: beyond it no quantity of a
// head-mounted display means anything, and products of two such numbers stay
// far inside a double.
constexpr double kLargestNumber = 1e12;
// A rate's period must be a whole number of picoseconds or more (the time unit).
constexpr double kHighestRateHz = 1e6;

KeySpec bounded_duration(const KeySpec& spec, double ticks_per_unit) {
  KeySpec b = spec;
  if (!b.min) b.min = 0.0;
  if (!b.max) b.max = kLongestSpanSeconds * 1e12 / ticks_per_unit;
  return b;
}

KeySpec bounded_rate(const KeySpec& spec) {
  KeySpec b = spec;
  if (!b.min) {
    b.min = 1.0 / kLongestSpanSeconds;
    b.above_min = false;
  }
  if (!b.max) b.max = kHighestRateHz;
  return b;
}

}  // namespace

KeySpec bounded_number(const KeySpec& spec) {
  KeySpec b = spec;
  if (!b.min) b.min = -kLargestNumber;
  if (!b.max) b.max = kLargestNumber;
  return b;
}

Section::Section(ConfigNode node) : node_(std::move(node)) {}

Section::Section(ObjectSchema& schema) : schema_(&schema) {}

const std::string& Section::pointer() const {
  static const std::string kNone;
  return node_ ? node_->pointer() : kNone;
}

bool Section::has(std::string_view key) const { return node_ && node_->has(key); }

void Section::doc(std::string_view text) {
  if (schema_) schema_->doc = text;
}

void Section::fail(std::string_view key, const std::string& message) const {
  if (!node_) throw std::logic_error("Section::fail while describing: " + message);
  node_->fail(key, message);
}

KeySchema& Section::declare(std::string_view key, const char* type, const KeySpec& spec) {
  KeySchema k;
  k.name = key;
  k.type = type;
  k.required = spec.required;
  k.min = spec.min;
  k.max = spec.max;
  k.above_min = spec.above_min;
  k.unit = spec.unit;
  k.doc = spec.doc;
  k.default_doc = spec.default_doc;
  if (!mode_.empty()) k.modes.push_back(mode_);
  schema_->keys.push_back(std::move(k));
  return schema_->keys.back();
}

std::optional<std::string> range_problem(double x, const KeySpec& spec) {
  const bool below = spec.min && (spec.above_min ? !(x > *spec.min) : x < *spec.min);
  const bool above = spec.max && x > *spec.max;
  if (!below && !above) return std::nullopt;
  const std::string got = ", got " + number_text(x);
  if (spec.min && spec.max)
    return "must lie in " + std::string(spec.above_min ? "(" : "[") + number_text(*spec.min) + ", " +
           number_text(*spec.max) + "]" + got;
  if (spec.min && *spec.min == 0.0)
    return std::string(spec.above_min ? "must be greater than zero" : "must not be negative") + got;
  if (spec.min)
    return std::string(spec.above_min ? "must be greater than " : "must be at least ") + number_text(*spec.min) + got;
  return "must be at most " + number_text(*spec.max) + got;
}

void Section::check_range(std::string_view key, double x, const KeySpec& spec) const {
  if (const auto problem = range_problem(x, spec)) fail(key, *problem);
}

void Section::number(std::string_view key, double& v, const KeySpec& declared) {
  const KeySpec spec = bounded_number(declared);
  if (schema_) {
    KeySchema& k = declare(key, "number", spec);
    if (!spec.required) k.default_value = v;
    return;
  }
  v = spec.required ? node_->number(key) : node_->number(key, v);
  check_range(key, v, spec);
}

void Section::number(std::string_view key, std::optional<double>& v, const KeySpec& declared) {
  const KeySpec spec = bounded_number(declared);
  if (schema_) {
    declare(key, "number", spec);
    return;
  }
  if (!has(key)) return;
  v = node_->number(key);
  check_range(key, *v, spec);
}

void Section::integer64(std::string_view key, int64_t& v, const KeySpec& spec, int64_t type_min, int64_t type_max) {
  if (schema_) {
    KeySchema& k = declare(key, "integer", spec);
    if (!spec.required) k.default_value = v;
    return;
  }
  const int64_t lo = spec.min ? static_cast<int64_t>(std::ceil(*spec.min)) : type_min;
  const int64_t hi = spec.max ? static_cast<int64_t>(std::floor(*spec.max)) : type_max;
  v = spec.required ? node_->integer(key, lo, hi) : node_->integer(key, v, lo, hi);
}

void Section::flag(std::string_view key, bool& v, const KeySpec& spec) {
  if (schema_) {
    declare(key, "boolean", spec).default_value = v;
    return;
  }
  v = node_->boolean(key, v);
}

void Section::text(std::string_view key, std::string& v, const KeySpec& spec) {
  if (schema_) {
    KeySchema& k = declare(key, "string", spec);
    if (!spec.required) k.default_value = v;
    return;
  }
  v = spec.required ? node_->string(key) : node_->string(key, v);
}

std::string Section::choice_name(std::string_view key, const std::string& current,
                                 const std::vector<std::string>& names, const KeySpec& spec) {
  if (schema_) {
    KeySchema& k = declare(key, "choice", spec);
    k.choices = names;
    if (!spec.required) k.default_value = current;
    return current;
  }
  const std::string v = spec.required ? node_->string(key) : node_->string(key, current);
  for (const auto& n : names)
    if (v == n) return v;
  fail(key, "unknown value " + quote_value(v) + "; expected one of " + choice_list(names));
}

void Section::choices(std::string_view key, std::vector<std::string>& v, const std::vector<std::string>& names,
                      const KeySpec& spec) {
  if (schema_) {
    KeySchema& k = declare(key, "choices", spec);
    k.choices = names;
    if (!spec.required) k.default_value = v;
    return;
  }
  v = node_->strings(key, v);
  for (size_t i = 0; i < v.size(); ++i) {
    if (std::find(names.begin(), names.end(), v[i]) != names.end()) continue;
    throw ScenarioError(join_pointer(join_pointer(pointer(), key), std::to_string(i)),
                        "unknown value " + quote_value(v[i]) + "; expected one of " + choice_list(names));
  }
}

void Section::rate(std::string_view key, des::RationalSeconds& period, const KeySpec& declared) {
  const KeySpec spec = bounded_rate(declared);
  const Json def = hz_of_period(period);
  if (schema_) {
    KeySchema& k = declare(key, "rate", spec);
    if (!spec.required) k.default_value = def;
    return;
  }
  period = node_->rate_as_period(key, def.is_string() ? def.get<std::string>() : std::to_string(def.get<int64_t>()));
  // The frequency is den/num Hz; its range in exact arithmetic first, so that
  // a fraction like "9223372036854775807/1" is judged, not rounded.
  const __int128 ticks_num = static_cast<__int128>(period.num) * des::Time::kTicksPerSecond;
  const double hz = static_cast<double>(period.den) / static_cast<double>(period.num);
  check_range(key, hz, spec);
  if (ticks_num < static_cast<__int128>(period.den))
    fail(key, "the period of " + number_text(hz) + " Hz is shorter than the time unit, 1 ps");
}

void Section::duration(std::string_view key, des::Time& v, const KeySpec& spec) {
  const double scale = ticks_per_unit(spec.unit);
  const KeySpec bounded = bounded_duration(spec, scale);
  const double def = static_cast<double>(v.ticks()) / scale;
  if (schema_) {
    KeySchema& k = declare(key, "duration", bounded);
    if (!spec.required) k.default_value = def;
    return;
  }
  const double x = spec.required ? node_->number(key) : node_->number(key, def);
  if (!spec.min && x < 0) fail(key, "duration must not be negative, got " + number_text(x));
  check_range(key, x, bounded);
  try {
    if (spec.unit == "s") v = des::Time::from_seconds(x);
    else if (spec.unit == "ms") v = des::Time::from_ms(x);
    else v = des::Time::from_us(x);
  } catch (const des::TimeOverflow&) {
    fail(key, "duration out of range");
  }
  // A positive value shorter than the time unit rounds to 0 ps, out of a
  // range that excludes 0 (a step of 1e-308 ms passed the range check, then
  // never advanced; a window of it failed with no pointer).
  if (x > 0 && v == des::Time::zero() && bounded.min && (*bounded.min > 0 || bounded.above_min))
    fail(key, "rounds to 0 in the time unit, 1 ps (" + number_text(1.0 / scale) + " " + std::string(spec.unit) + "), got " +
                  number_text(x));
}

void Section::duration(std::string_view key, std::optional<des::Time>& v, const KeySpec& spec) {
  if (schema_) {
    declare(key, "duration", bounded_duration(spec, ticks_per_unit(spec.unit)));
    return;
  }
  if (!has(key)) return;
  des::Time t;
  KeySpec required = spec;
  required.required = true;
  duration(key, t, required);
  v = t;
}

void Section::path(std::string_view key, std::filesystem::path& v, const KeySpec& spec) {
  if (schema_) {
    KeySchema& k = declare(key, "path", spec);
    if (!spec.required && !v.empty()) k.default_value = v.string();
    return;
  }
  if (!spec.required && !has(key)) return;
  v = node_->path(key);
}

}  // namespace latsim::scenario
