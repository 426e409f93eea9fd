// A run's figures written straight to a record's text (results::FigureTree)
// against the second method, their JSON tree written by sweep::encode_record:
// the same bytes, the same headline and warnings.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "../run/run_helpers.hpp"
#include "latsim/results/figure_tree.hpp"
#include "latsim/results/figures.hpp"
#include "latsim/sweep/record.hpp"

namespace {

using latsim::results::FigureTable;
using latsim::results::FigureTree;
using latsim::stats::Distribution;
using latsim::sweep::encode_record;
using Json = nlohmann::json;

// The record text the JSON tree makes of `figures`, and the one the tree's text makes.
std::string by_json(const Json& figures) { return encode_record(Json{{"figures", figures}}).text; }
std::string by_text(const std::string& text) { return "{\"figures\":" + text + "}\nnull"; }

// What a run puts in its summary that differs from run to run: the times and the memory.
Json without_times(Json summary) {
  for (const char* key : {"wall_s", "command_wall_s", "peak_rss_mb"}) summary.erase(key);
  return summary;
}

}  // namespace

TEST_CASE("a run's figures as text are the bytes of their JSON tree's record, on shipped scenarios",
          "[sweep][record][figures]") {
  // Double-buffered (the serial poll and direct HMDs with their analytic
  // figure, the frameless comparison, NTSC stereo) and others: frameless,
  // timewarp, pacing, passthrough, PixelPlanes 5, address recalculation.
  const std::vector<std::string> files = {
      "hmd_60hz_serial_poll.json",      "hmd_60hz_direct.json",        "frameless/double_buffered.json",
      "ntsc_stereo_interlaced.json",    "frameless/side_by_side.json", "modern/timewarp.json",
      "pacing/fixed.json",              "passthrough/quest3_passthrough.json", "pxpl5/rc_head.json",
      "arp/arp_basic.json"};
  for (const std::string& file : files) {
    INFO(file);
    const auto doc = latsim::run::load_scenario(LATSIM_SOURCE_DIR "/scenarios/" + file, {"/duration_s=0.3"});
    latsim::run::RunOptions options;
    options.seed = 11;
    options.replication = 3;
    const Json tree = latsim::run::run_scenario(doc, options);
    std::string text;
    options.figures_text = &text;
    const Json direct = latsim::run::run_scenario(doc, options);
    REQUIRE(!text.empty());
    CHECK(direct.at("figures").is_null());
    CHECK(by_text(text) == by_json(tree.at("figures")));
    CHECK(direct.at("headline") == tree.at("headline"));
    CHECK(direct.at("warnings") == tree.at("warnings"));
    // The whole record, the figures spliced in at their key.
    CHECK(encode_record(without_times(direct), nullptr, text).text == encode_record(without_times(tree)).text);
  }
}

TEST_CASE("figures nested by dotted names, lists, counters and odd distributions: the same text both ways",
          "[sweep][record][figures]") {
  std::map<std::string, Distribution> dists;
  dists.emplace("empty_ms", Distribution());
  Distribution one;
  one.add(2.5);
  dists.emplace("one_ms", one);
  Distribution spread(0.005, true);
  for (int i = 0; i < 1000; ++i) spread.add(std::sqrt(static_cast<double>(i)) * 1.7 - 3.0);
  dists.emplace("spread_ms", spread);
  const std::map<std::string, int64_t> counters = {{"frames", 120}, {"missed.fields", -1}};
  FigureTable table;
  table.list("memories");
  table.list("empty_list");
  table.object("empty_object");
  table.set("memories.1.renders", int64_t{4});
  table.set("memories.0.name", std::string("z-buffer \xc3\xa9 \"quoted\"\n"));
  table.set("utilisation.gp", 0.25);
  table.set("utilisation.whole", 1.0);
  table.set("flag", true);
  table.set("huge", 1e300);
  table.publish("analytic.motion_to_photon_ms", spread);
  table.publish("analytic.none_ms", Distribution());
  const auto tree = FigureTree::of(table, dists, counters);
  REQUIRE(tree);
  std::string text;
  tree->write(text);
  CHECK(by_text(text) == by_json(table.to_json(dists, counters)));
  // Read back by the top level as the headline reads it.
  CHECK(tree->top("one_ms").count == 1);
  CHECK(tree->top("empty_ms").count == 0);
  CHECK(tree->top("utilisation").present);
  CHECK_FALSE(tree->top("utilisation").count);
  CHECK_FALSE(tree->top("absent").present);
}

TEST_CASE("names a registry never declares leave the figures to their JSON tree", "[sweep][record][figures]") {
  std::map<std::string, Distribution> dists;
  dists.emplace("d", Distribution());
  const std::map<std::string, int64_t> none;
  FigureTable into_distribution;
  into_distribution.set("d.extra", 1.0);  // would become a key inside the distribution's object
  CHECK_FALSE(FigureTree::of(into_distribution, dists, none));
  FigureTable nested_count;
  nested_count.set("x.count", int64_t{0});  // the headline would read it as an empty distribution's count
  CHECK_FALSE(FigureTree::of(nested_count, dists, none));
  FigureTable by_name_into_list;
  by_name_into_list.list("l");
  by_name_into_list.set("l.name", 1.0);  // the JSON tree throws
  CHECK_FALSE(FigureTree::of(by_name_into_list, dists, none));
  CHECK_FALSE(FigureTree::of(FigureTable(), dists, {{"count", 0}}));
}
