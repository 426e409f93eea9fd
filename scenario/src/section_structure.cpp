// scenario::Section's arrays, nested objects and modes, and its cross-field rules.
#include "latsim/scenario/section.hpp"

#include <stdexcept>

#include "latsim/des/stop_token.hpp"
#include "latsim/des/time.hpp"
#include "latsim/scenario/readable.hpp"
#include "section_internal.hpp"

namespace latsim::scenario {

using Json = nlohmann::json;

namespace {

const Json& empty_object() {
  static const Json kEmpty = Json::object();
  return kEmpty;
}

bool same_declaration(const KeySchema& a, const KeySchema& b) {
  const bool same_object = (!a.object && !b.object) ||
                           (a.object && b.object && json_schema(*a.object) == json_schema(*b.object));
  return a.type == b.type && a.default_value == b.default_value && a.default_doc == b.default_doc &&
         a.required == b.required && a.min == b.min && a.max == b.max && a.above_min == b.above_min &&
         a.count == b.count && a.row_count == b.row_count && a.choices == b.choices && a.unit == b.unit &&
         a.doc == b.doc && same_object;
}

}  // namespace

void Section::value(std::string_view key, Json& v, const KeySpec& spec) {
  if (schema_) {
    KeySchema& k = declare(key, "value", spec);
    if (!spec.required) k.default_value = v;
    return;
  }
  if (const Json* given = node_->value(key)) v = *given;
  else if (spec.required) fail(key, "required key is missing");
}

void Section::numbers(std::string_view key, std::vector<double>& v, const KeySpec& declared) {
  const KeySpec spec = bounded_number(declared);
  if (schema_) {
    KeySchema& k = declare(key, "numbers", spec);
    k.count = spec.count;
    if (!spec.required) k.default_value = v;
    return;
  }
  v = spec.required ? node_->numbers(key) : node_->numbers(key, v);
  if (spec.count > 0 && static_cast<int>(v.size()) != spec.count)
    fail(key, "expected " + std::to_string(spec.count) + " numbers, found " + std::to_string(v.size()));
  for (size_t i = 0; i < v.size(); ++i)
    if (const auto problem = range_problem(v[i], spec))
      throw ScenarioError(join_pointer(join_pointer(pointer(), key), std::to_string(i)), *problem);
}

void Section::number_rows(std::string_view key, std::vector<std::vector<double>>& v, const KeySpec& declared) {
  const KeySpec spec = bounded_number(declared);
  if (schema_) {
    KeySchema& k = declare(key, "number_rows", spec);
    k.row_count = spec.count;
    if (!spec.required) k.default_value = v;
    return;
  }
  if (!spec.required && !has(key)) return;
  v = node_->number_rows(key);
  const std::string base = join_pointer(pointer(), key);
  for (size_t i = 0; i < v.size(); ++i) {
    const std::string row = join_pointer(base, std::to_string(i));
    if (spec.count > 0 && static_cast<int>(v[i].size()) != spec.count)
      throw ScenarioError(row, "expected " + std::to_string(spec.count) + " numbers, found " + std::to_string(v[i].size()));
    for (size_t j = 0; j < v[i].size(); ++j)
      if (const auto problem = range_problem(v[i][j], spec)) throw ScenarioError(join_pointer(row, std::to_string(j)), *problem);
  }
}

void Section::number_rows(std::string_view key, std::optional<std::vector<std::vector<double>>>& v,
                          const KeySpec& spec) {
  std::vector<std::vector<double>> rows;
  if (schema_) {
    KeySpec optional = bounded_number(spec);
    optional.required = false;
    declare(key, "number_rows", optional).row_count = spec.count;
    return;
  }
  if (!has(key)) return;
  KeySpec given = spec;
  given.required = true;
  number_rows(key, rows, given);
  v = std::move(rows);
}

void Section::nested(std::string_view key, const char* type, const KeySpec& spec,
                     const std::function<void(Section&)>& bind) {
  if (schema_) {
    auto object = std::make_shared<ObjectSchema>();
    Section s(*object);
    bind(s);
    declare(key, type, spec).object = std::move(object);
    return;
  }
  if (!has(key) && spec.required) fail(key, "required key is missing");
  // Absent: every key takes its default, recorded as if the object were empty.
  Section s(has(key) ? node_->child(key) : ConfigNode(&empty_object(), join_pointer(node_->pointer(), key), node_->log()));
  try {
    bind(s);
  } catch (const des::TimeOverflow& e) {
    // A time its keys imply but no key holds (a cost summed from several):
    // the object's error, not the whole scenario's.
    fail(key, e.what());
  }
}

std::vector<ConfigNode> Section::array_of_objects(std::string_view key) const {
  if (!has(key)) return {};
  return node_->objects(key);
}

std::string Section::modes(std::string_view key, std::string_view default_mode, const std::vector<ModeDecl>& modes,
                           const KeySpec& spec) {
  std::vector<std::string> names;
  for (const auto& m : modes) names.push_back(m.name);
  KeySpec chosen_spec = spec;
  chosen_spec.required = default_mode.empty();
  if (schema_) {
    choice_name(key, std::string(default_mode), names, chosen_spec);
    ObjectSchema::Discriminator d{std::string(key), {}};
    for (const auto& m : modes) d.values.emplace_back(m.name, m.doc);
    schema_->discriminators.push_back(std::move(d));
    const std::string outer = mode_;
    for (const auto& m : modes) {
      mode_ = (outer.empty() ? "" : outer + ", ") + std::string(key) + "=" + m.name;
      const size_t before = schema_->keys.size();
      m.bind(*this);
      // A key several modes declare alike is one key read by all of them.
      for (size_t i = before; i < schema_->keys.size();) {
        KeySchema& k = schema_->keys[i];
        KeySchema* earlier = nullptr;
        for (size_t j = 0; j < before && !earlier; ++j)
          if (schema_->keys[j].name == k.name && (schema_->keys[j].modes.empty() || same_declaration(schema_->keys[j], k)))
            earlier = &schema_->keys[j];
        for (size_t j = 0; j < before && !earlier; ++j)
          if (schema_->keys[j].name == k.name) earlier = &schema_->keys[j];
        if (!earlier) {
          ++i;
          continue;
        }
        if (earlier->modes.empty())
          throw std::logic_error("scenario key \"" + k.name + "\" is declared for every mode and again for one");
        if (!same_declaration(*earlier, k)) {
          ++i;  // the same name means something else in this mode: its own declaration
          continue;
        }
        earlier->modes.push_back(mode_);
        schema_->keys.erase(schema_->keys.begin() + static_cast<std::ptrdiff_t>(i));
      }
    }
    mode_ = outer;
    return std::string(default_mode);
  }
  const std::string chosen = choice_name(key, std::string(default_mode), names, chosen_spec);
  for (const auto& m : modes)
    if (m.name == chosen) m.bind(*this);
  return chosen;
}

void Section::check(std::string_view key, bool ok, std::string_view message) {
  if (schema_) {
    add_rule(std::string(key) + ": " + std::string(message));
    return;
  }
  if (!ok) fail(key, std::string(message));
}

void Section::check_pointer(std::string_view pointer, bool ok, std::string_view message) {
  if (schema_) {
    add_rule(std::string(pointer) + ": " + std::string(message));
    return;
  }
  if (!ok) throw ScenarioError(std::string(pointer), std::string(message));
}

void check_span_at(std::string_view pointer, double per_item_s, double items, std::string_view items_text) {
  const double total_s = per_item_s * items;
  if (total_s <= kLongestSpanSeconds) return;
  throw ScenarioError(std::string(pointer), number_text(per_item_s) + " s × " + std::string(items_text) + " (" +
                                                number_text(items) + ") = " + number_text(total_s) +
                                                " s, more than the 1e6 s a run may last");
}

void Section::check_span(std::string_view key, double per_item_s, double items, std::string_view items_text) {
  if (schema_) {
    add_rule(std::string(key) + " × " + std::string(items_text) + ": at most 1e6 s");
    return;
  }
  check_span_at(join_pointer(pointer(), key), per_item_s, items, items_text);
}

void Section::add_rule(std::string text) {
  for (const auto& [mode, rule] : schema_->rules)
    if (mode == mode_ && rule == text) return;
  schema_->rules.emplace_back(mode_, std::move(text));
}

void Section::guard(std::string_view key, const std::function<void()>& fn) {
  if (schema_) return;
  try {
    fn();
  } catch (const ScenarioError&) {
    throw;
  } catch (const des::StopRequested&) {
    throw;  // a signal while reading a file the key names: no problem of the key
  } catch (const std::exception& e) {
    fail(key, e.what());
  }
}

}  // namespace latsim::scenario
