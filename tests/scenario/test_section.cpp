// Declaring parameters once: the same binding reads a scenario object into a
// struct and describes it for the schema.
#include <catch2/catch.hpp>

#include "latsim/run/runner.hpp"
#include "latsim/scenario/section.hpp"

using namespace latsim;
using scenario::KeySpec;
using scenario::ObjectSchema;
using scenario::ScenarioDocument;
using scenario::ScenarioError;
using scenario::Section;
using Json = nlohmann::json;

namespace {

/// A small struct with one key of each kind and two modes.
struct Lamp {
  double power_w = 60.0;
  int64_t bulbs = 1;
  des::Time warmup = des::Time::ms(20);
  des::RationalSeconds flicker{1001, 60000};
  std::string kind = "filament";
  double filament_mm = 10.0;
  double led_count = 4.0;
};

void bind(Section& s, Lamp& p) {
  s.number("power_w", p.power_w, {.unit = "W", .min = 0.0, .above_min = true, .doc = "electric power"});
  s.integer("bulbs", p.bulbs, {.min = 1.0, .max = 8.0, .doc = "how many"});
  s.duration("warmup_ms", p.warmup, {.unit = "ms", .doc = "until full brightness"});
  s.rate("flicker_hz", p.flicker, {.unit = "Hz", .doc = "mains flicker"});
  p.kind = s.modes("kind", "filament",
                   {{"filament", "a hot wire", [&p](Section& m) { m.number("length_mm", p.filament_mm, {.unit = "mm"}); }},
                    {"led", "diodes", [&p](Section& m) { m.number("count", p.led_count, {.min = 1.0}); }}},
                   {.doc = "which light"});
  s.check("bulbs", p.bulbs <= 4 || p.power_w <= 100.0, "more than 4 bulbs need at most 100 W");
}

Lamp read(const ScenarioDocument& doc) {
  Lamp lamp;
  Section s(doc.root());
  bind(s, lamp);
  return lamp;
}

std::string error_pointer(const Json& j) {
  try {
    const auto doc = ScenarioDocument::from_json(j, ".");
    read(doc);
    doc.check_unknown_keys();
  } catch (const ScenarioError& e) {
    return e.pointer();
  }
  return "<no error>";
}

}  // namespace

TEST_CASE("one binding describes each key: type, default, range, unit, meaning, mode", "[params]") {
  ObjectSchema schema;
  Section s(schema);
  Lamp lamp;
  bind(s, lamp);
  const auto* power = schema.find("power_w");
  REQUIRE(power != nullptr);
  CHECK(power->type == "number");
  CHECK(power->default_value == 60.0);
  CHECK(power->min == 0.0);
  CHECK(power->above_min);
  CHECK(power->unit == "W");
  CHECK(power->doc == "electric power");
  CHECK(schema.find("warmup_ms")->default_value == 20.0);
  CHECK(schema.find("flicker_hz")->default_value == "60000/1001");
  CHECK(schema.find("length_mm")->modes == std::vector<std::string>{"kind=filament"});
  CHECK(schema.find("count")->modes == std::vector<std::string>{"kind=led"});
  REQUIRE(schema.discriminators.size() == 1);
  CHECK(schema.discriminators[0].values.size() == 2);
  REQUIRE(schema.rules.size() == 1);
  CHECK(schema.rules[0].second == "bulbs: more than 4 bulbs need at most 100 W");
  // Describing changes nothing and checks nothing.
  CHECK(lamp.power_w == 60.0);
}

TEST_CASE("reading applies defaults, records them, and converts units exactly", "[params]") {
  const auto doc = ScenarioDocument::from_json(Json{{"warmup_ms", 1.5}, {"kind", "led"}, {"count", 12}}, ".");
  const Lamp lamp = read(doc);
  CHECK(lamp.power_w == 60.0);
  CHECK(lamp.warmup == des::Time::us(1500));
  CHECK(lamp.flicker.num == 1001);
  CHECK(lamp.flicker.den == 60000);
  CHECK(lamp.kind == "led");
  CHECK(lamp.led_count == 12.0);
  CHECK(doc.resolved()["power_w"] == 60.0);
  CHECK(doc.resolved()["flicker_hz"] == "60000/1001");
  CHECK(doc.resolved()["kind"] == "led");
  // The other mode's key is neither read nor recorded.
  CHECK_FALSE(doc.resolved().contains("length_mm"));
}

TEST_CASE("bad values are errors at their JSON pointer", "[params]") {
  CHECK(error_pointer(Json::object()) == "<no error>");
  CHECK(error_pointer({{"power_w", 0}}) == "/power_w");
  CHECK(error_pointer({{"power_w", "bright"}}) == "/power_w");
  CHECK(error_pointer({{"bulbs", 9}}) == "/bulbs");
  CHECK(error_pointer({{"bulbs", 2.5}}) == "/bulbs");
  CHECK(error_pointer({{"warmup_ms", -1}}) == "/warmup_ms");
  CHECK(error_pointer({{"flicker_hz", "sixty"}}) == "/flicker_hz");
  CHECK(error_pointer({{"kind", "candle"}}) == "/kind");
  CHECK(error_pointer({{"bulbs", 5}, {"power_w", 200}}) == "/bulbs");
  CHECK(error_pointer({{"colour", "red"}}) == "/colour");
}

TEST_CASE("a key of another mode is a warning when the schema knows it, an error otherwise", "[params]") {
  ObjectSchema schema;
  Section describe(schema);
  Lamp dummy;
  bind(describe, dummy);
  const auto doc = ScenarioDocument::from_json(Json{{"kind", "led"}, {"length_mm", 3}}, ".");
  read(doc);
  std::vector<std::string> warnings;
  doc.check_unknown_keys(&schema, &warnings);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0] == "/length_mm: ignored: read only when kind=filament");
  const auto typo = ScenarioDocument::from_json(Json{{"kind", "led"}, {"lenght_mm", 3}}, ".");
  read(typo);
  CHECK_THROWS_AS(typo.check_unknown_keys(&schema, &warnings), ScenarioError);
}

TEST_CASE("a key of another mode must still fit its declaration", "[params]") {
  ObjectSchema schema;
  Section describe(schema);
  Lamp dummy;
  bind(describe, dummy);
  // The led mode reads "count" (at least 1); the filament mode "length_mm" (a number).
  const auto pointer_of = [&schema](const Json& j) -> std::string {
    const auto doc = ScenarioDocument::from_json(j, ".");
    read(doc);
    std::vector<std::string> warnings;
    try {
      doc.check_unknown_keys(&schema, &warnings);
    } catch (const ScenarioError& e) {
      return e.pointer() + ": " + e.message();
    }
    return warnings.empty() ? "<nothing>" : warnings[0];
  };
  CHECK(pointer_of({{"kind", "led"}, {"length_mm", "long"}}).rfind("/length_mm: expected a number", 0) == 0);
  CHECK(pointer_of({{"kind", "led"}, {"length_mm", 1e13}}).rfind("/length_mm: must lie in", 0) == 0);
  CHECK(pointer_of({{"count", 0}}).rfind("/count: must lie in [1, ", 0) == 0);
  CHECK(pointer_of({{"count", 2}}) == "/count: ignored: read only when kind=led");
}

TEST_CASE("an unread file name is not opened, and an unread key is checked as its mode would", "[params]") {
  // The first warning, or the error: "pointer: message".
  auto validate = [](const Json& motion) -> std::string {
    const Json j = {{"motion", motion},
                    {"tracker", {{"rate_hz", 60}}},
                    {"display", {{"refresh_hz", 60}}},
                    {"pipeline", {{"type", "double_buffer"}, {"render", {{"fixed_ms", 1}}}}}};
    try {
      const std::vector<std::string> warnings = run::validate_scenario(ScenarioDocument::from_json(j, "."));
      return warnings.empty() ? "<nothing>" : "warning " + warnings[0];
    } catch (const ScenarioError& e) {
      return e.pointer() + ": " + e.message();
    }
  };
  // A trace's file on a still head: a well-typed name, never looked at.
  CHECK(validate({{"type", "still"}, {"file", "/nonexistent/trace.csv"}}) ==
        "warning /motion/file: ignored: read only when type=trace");
  CHECK(validate({{"type", "still"}, {"file", 3}}).rfind("/motion/file: expected a string", 0) == 0);
  CHECK(validate({{"type", "still"}, {"points", "garbage"}}).rfind("/motion/points: ", 0) == 0);
  CHECK(validate({{"type", "still"}, {"points", {{0, 1.6, 0}, {1, 1.6}}}}).rfind("/motion/points/1: expected 3", 0) == 0);
}

TEST_CASE("an override creates an optional section the schema declares, and nothing else", "[params]") {
  const ObjectSchema schema = run::scenario_schema();
  Json doc = {{"display", Json::object()}};
  scenario::apply_override(doc, "/output/timeline=false", &schema);
  CHECK(doc["output"]["timeline"] == false);
  scenario::apply_override(doc, "/transport/host=\"interrupt\"", &schema);
  CHECK(doc["transport"]["host"] == "interrupt");
  try {
    scenario::apply_override(doc, "/nothing/here=1", &schema);
    FAIL("an undeclared section was created");
  } catch (const ScenarioError& e) {
    CHECK(e.pointer() == "/nothing/here");
  }
  CHECK_THROWS_AS(scenario::apply_override(doc, "/output2/timeline=false"), ScenarioError);
}

TEST_CASE("a key declared for every mode and again for one is a declaration error", "[params]") {
  ObjectSchema schema;
  Section s(schema);
  double x = 1.0;
  s.number("x", x, {.doc = "everywhere"});
  const std::vector<scenario::ModeDecl> modes{{"a", "", [&x](Section& m) { m.number("x", x, {.doc = "in a"}); }}};
  CHECK_THROWS_AS(s.modes("type", "a", modes, {}), std::logic_error);
}
