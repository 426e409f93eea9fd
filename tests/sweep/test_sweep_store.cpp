// Tests for the results store: a run's record reads back to the same
// summary, segments keep every whole frame and drop a frame cut short, and a
// run recorded twice is read from its first record.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "latsim/stats/stats.hpp"
#include "latsim/sweep/record.hpp"
#include "latsim/sweep/segment.hpp"
#include "scratch_dir.hpp"

using latsim::sweep::decode_record;
using latsim::sweep::encode_record;
using latsim::sweep::record_scenario;
using latsim::sweep::RecordRead;
using latsim::sweep::SegmentWriter;
using latsim::sweep::StoreIndex;
using latsim::test::scratch_dir;
using Json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

// A distribution figure as a run writes it (results::FigureTable): its
// histogram made by stats::Distribution::plot_histogram, the code every figure uses.
Json distribution(const std::vector<double>& samples) {
  latsim::stats::Distribution d(0.005, true);
  for (double x : samples) d.add(x);
  const auto s = d.summary();
  Json h = Json::array();
  for (const auto& [edge, count] : d.plot_histogram(50)) h.push_back({edge, count});
  return {{"count", s.count}, {"mean", s.mean}, {"stddev", s.stddev}, {"min", s.min}, {"p50", s.p50},
          {"p90", s.p90},     {"p99", s.p99},   {"p999", s.p999},     {"max", s.max}, {"histogram", h}};
}

Json summary(double scale) {
  std::vector<double> samples;
  for (int i = 0; i < 997; ++i) samples.push_back(scale * (1.0 + (i * 37 % 101) / 7.0));
  Json hand_made = {{"count", 2}, {"mean", 1.5}, {"min", 1.0}, {"max", 2.0},
                    {"histogram", {{0.5, 1u}, {1.75, 1u}}}};  // edges not those of min and max: kept whole
  return {{"events", 1234u},
          {"wall_s", 0.001},
          {"fingerprint", "00ff"},
          {"warnings", {"a warning\nover two lines"}},
          {"figures",
           {{"motion_to_photon_ms", distribution(samples)},
            {"one_value_ms", distribution({4.25, 4.25})},
            {"hand_made", hand_made},
            {"empty_ms", {{"count", 0}, {"histogram", Json::array()}}},
            {"analytic", {{"method", "integrated"}, {"complete", true}}},
            {"frame_rate_hz", 60.0}}},
          {"scenario", {{"display", {{"refresh_hz", "60000/1001"}, {"phase_ms", 3.25 * scale}}}}}};
}

std::string text_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("a run's record reads back to the same summary, and the tables read it without the scenario",
          "[sweep][store]") {
  const Json original = summary(1.0);
  const auto encoded = encode_record(Json(original));
  const std::string& record = encoded.text;
  CHECK(encoded.scenario == original["scenario"]);
  const Json back = decode_record(record);
  CHECK(back == original);
  // Written as nlohmann::json writes it, value for value: the text reads back to the same text.
  CHECK(back.dump() == original.dump());
  // The regular histograms are their counts alone, the others whole.
  CHECK(record.find("histogram_counts") != std::string::npos);
  CHECK(record.find("[[0.5,1],[1.75,1]]") != std::string::npos);
  const Json tables = decode_record(record, nullptr, RecordRead::tables);
  CHECK_FALSE(tables.contains("scenario"));
  CHECK(tables["figures"]["motion_to_photon_ms"]["mean"] == original["figures"]["motion_to_photon_ms"]["mean"]);
  CHECK(tables["figures"]["motion_to_photon_ms"]["histogram_counts"].size() == 50);
  CHECK_THROWS(decode_record("{}"));
}

TEST_CASE("a later record's scenario is what it changes in its segment's first one", "[sweep][store]") {
  const Json base = summary(1.0)["scenario"];
  Json later = summary(2.0);
  later["scenario"]["display"]["interlaced"] = true;  // added
  later["scenario"]["tracker"] = {{"rate_hz", 120}};  // added as a whole object
  Json gone = summary(3.0);
  gone["scenario"].erase("display");                  // removed
  for (const Json& original : {later, gone}) {
    const auto encoded = encode_record(Json(original), &base);
    const std::string line = encoded.text.substr(encoded.text.find('\n') + 1);
    CHECK(line.front() == '[');
    CHECK(line.size() < 100);
    CHECK(decode_record(encoded.text, &base) == original);
    CHECK(record_scenario(encoded.text, &base) == original["scenario"]);
    CHECK_THROWS(decode_record(encoded.text));  // a patch without what it patches
  }
  // The same scenario: an empty patch.
  CHECK(encode_record(summary(1.0), &base).text.substr(encode_record(summary(1.0), &base).text.find('\n') + 1) == "[]");
}

TEST_CASE("segments keep every whole record, drop one cut short, and a run's first record wins", "[sweep][store]") {
  const fs::path dir = scratch_dir("latsim_sweep_segments");
  const std::string a = encode_record(summary(1.0)).text, b = encode_record(summary(2.0)).text,
                    c = encode_record(summary(3.0)).text;
  uintmax_t first_bytes = 0, both_bytes = 0;
  {
    SegmentWriter one(dir, "host.1.0-0"), two(dir, "host.1.0-1");
    one.append("00000000000000aa", a);
    first_bytes = fs::file_size(dir / "host.1.0-0.0.seg");
    one.append("00000000000000bb", b);
    both_bytes = fs::file_size(dir / "host.1.0-0.0.seg");
    two.append("00000000000000cc", c);
    two.append("00000000000000aa", c);  // the same run again, in a later segment: not read
    CHECK_THROWS(one.append("not-a-run-id", a));
  }
  {
    const StoreIndex index(dir);
    StoreIndex::Reader reader(index);
    CHECK(index.size() == 3);
    CHECK(reader.read(*index.find("00000000000000aa")) == a);
    CHECK(reader.read(*index.find("00000000000000bb")) == b);
    CHECK(reader.read(*index.find("00000000000000cc")) == c);
    CHECK(index.segment_first_record(*index.find("00000000000000bb")) == a);
    // The tables read the first line alone: the first record of a segment, and a later one.
    CHECK(reader.read_first_line(*index.find("00000000000000aa")) == a.substr(0, a.find('\n')));
    CHECK(reader.read_first_line(*index.find("00000000000000bb")) == b.substr(0, b.find('\n')));
    CHECK_FALSE(index.find("00000000000000dd"));
    CHECK(index.damaged_bytes() == 0);
  }
  // Later records are deflated against the first of their segment: a fraction of their text.
  CHECK(both_bytes - first_bytes < b.size() / 4);
  // A writer killed in the middle of its third frame: the first two stay whole.
  {
    SegmentWriter one(dir, "host.2.0-0");
    one.append("00000000000000d1", a);
    one.append("00000000000000d2", b);
    one.append("00000000000000d3", c);
  }
  const fs::path torn = dir / "host.2.0-0.0.seg";
  const std::string bytes = text_of(torn);
  fs::resize_file(torn, bytes.size() - 7);
  {
    const StoreIndex index(dir);
    CHECK(StoreIndex::Reader(index).read(*index.find("00000000000000d2")) == b);
    CHECK_FALSE(index.find("00000000000000d3"));
    CHECK(index.damaged_bytes() > 0);
  }
  // A damaged byte inside a frame: its CRC fails and the segment is read up to there.
  std::string damaged = bytes;
  damaged[damaged.size() - 100] ^= 0x55;
  std::ofstream(torn, std::ios::binary | std::ios::trunc) << damaged;
  {
    const StoreIndex index(dir);
    CHECK(index.find("00000000000000d2"));
    CHECK_FALSE(index.find("00000000000000d3"));
  }
  fs::remove_all(dir);
}
