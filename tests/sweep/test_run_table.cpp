// Tests for the result tables: results.csv rows and results.sqlite contents,
// and the sweep directory's resume bookkeeping (temporary files, lock).
#include <catch2/catch.hpp>

#include <sqlite3.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>

#include "latsim/results/csv_text.hpp"
#include "latsim/scenario/readable.hpp"
#include "latsim/sweep/results_db.hpp"
#include "scratch_dir.hpp"
#include "latsim/sweep/run_table.hpp"
#include "latsim/sweep/store.hpp"

using latsim::results::csv_field;
using latsim::scenario::number_text;
using latsim::sweep::find_figure;
using latsim::sweep::is_temporary_name;
using latsim::sweep::results_csv;
using latsim::sweep::RunRow;
using latsim::sweep::SweepStore;
using latsim::test::scratch_dir;
using Json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

Json summary_with(double mtp_mean_ms) {
  return {{"events", 1234},
          {"wall_s", 0.5},
          {"fingerprint", "abc"},
          {"figures",
           {{"motion_to_photon_ms",
             {{"count", 10}, {"mean", mtp_mean_ms}, {"p50", 20.0}, {"p99", 30.5}, {"max", 31.0},
              {"histogram", {{10.0, 4}, {20.0, 6}}}}},
            {"render_latency_ms", 16.5},
            {"frame_rate_hz", 60},
            {"missed_refreshes", 0},
            {"pxpl5", {{"gp_utilisation", 0.75}}}}},
          {"models", {{"tracker", {{"events", 600}, {"wall_s", 0.01}}}}}};
}

RunRow row_of(std::string run_id, size_t point, Json value, const Json& summary) {
  RunRow row{std::move(run_id), point, 1, 0, {std::move(value)}};
  latsim::sweep::scan_summary_json(summary, row);
  return row;
}

std::vector<RunRow> two_records() {
  return {row_of("00000000000000aa", 0, 60, summary_with(25.25)),
          row_of("00000000000000bb", 1, "60000/1001", summary_with(26.0))};
}

int64_t count_rows(sqlite3* db, const std::string& sql) {
  sqlite3_stmt* stmt = nullptr;
  REQUIRE(sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt, nullptr) == SQLITE_OK);
  REQUIRE(sqlite3_step(stmt) == SQLITE_ROW);
  const int64_t n = sqlite3_column_int64(stmt, 0);
  sqlite3_finalize(stmt);
  return n;
}

}  // namespace

TEST_CASE("find_figure looks under figures, then at the root, and a bare distribution is its mean", "[sweep]") {
  const Json s = summary_with(25.25);
  CHECK(*find_figure(s, "motion_to_photon_ms.p99") == 30.5);
  CHECK(*find_figure(s, "motion_to_photon_ms") == 25.25);
  CHECK(*find_figure(s, "events") == 1234);
  CHECK(*find_figure(s, "pxpl5.gp_utilisation") == 0.75);
  CHECK_FALSE(find_figure(s, "registration_error_arcmin.mean"));
  CHECK_FALSE(find_figure(s, "fingerprint"));
}

TEST_CASE("a run's row, read from its summary's text, finds every figure find_figure finds", "[sweep]") {
  Json s = summary_with(25.25);
  s["figures"]["flags"] = {{"torn", true}, {"mean_like", {{"mean", 4.5}}}};
  s["figures"]["names"] = "not a number";
  s["figures"]["list"] = {1, 2};
  s["figures"]["odd \"key\"\n"] = 7;
  RunRow row;
  latsim::sweep::scan_summary(std::string_view(s.dump(2)), row);  // indented text reads the same
  for (const std::string path : {"motion_to_photon_ms.p99", "motion_to_photon_ms", "motion_to_photon_ms.count",
                                 "events", "wall_s", "pxpl5.gp_utilisation", "registration_error_arcmin.mean",
                                 "fingerprint", "flags.torn", "flags.mean_like", "names", "list", "odd \"key\"\n",
                                 "render_latency_ms", "missed_refreshes", "no_such_figure"}) {
    INFO(path);
    CHECK(row.figure(path) == find_figure(s, path));
  }
  CHECK(row.fingerprint == "abc");
  REQUIRE(row.models.size() == 1);
  CHECK(row.models[0].events == 600.0);
  // The booleans are in the database as 1 and 0, as before.
  CHECK(std::count_if(row.scalars.begin(), row.scalars.end(), [](const auto& x) { return x.boolean && x.value == 1.0; }) == 1);
  CHECK_THROWS(latsim::sweep::scan_summary(std::string_view("[1, 2]"), row));
  CHECK_THROWS(latsim::sweep::scan_summary(std::string_view("{\"figures\": {\"x\": 1"), row));
}

TEST_CASE("numbers print in their shortest exact form and CSV fields are quoted when needed", "[sweep]") {
  CHECK(number_text(0.1) == "0.1");
  CHECK(number_text(60) == "60");
  CHECK(std::stod(number_text(1.0 / 3.0)) == 1.0 / 3.0);
  CHECK(csv_field("60000/1001") == "60000/1001");
  CHECK(csv_field("a,b") == "\"a,b\"");
  CHECK(csv_field("say \"hi\"") == "\"say \"\"hi\"\"\"");
  // RFC 4180: a field holding a line break, CR or LF, is quoted.
  CHECK(csv_field("a\rb") == "\"a\rb\"");
  CHECK(csv_field("a\nb") == "\"a\nb\"");
}

TEST_CASE("results.csv has one row per run in the given order with the headline figures", "[sweep]") {
  const std::string csv = results_csv({"/display/refresh_hz"}, two_records());
  std::istringstream lines(csv);
  std::string header, first, second, extra;
  std::getline(lines, header);
  std::getline(lines, first);
  std::getline(lines, second);
  CHECK_FALSE(std::getline(lines, extra));
  CHECK(header.rfind("run_id,point,/display/refresh_hz,seed,replication,mtp_mean_ms,mtp_p50_ms,mtp_p99_ms,mtp_max_ms,", 0) == 0);
  CHECK_THAT(header, Catch::EndsWith(",events,wall_s"));
  CHECK(first.rfind("00000000000000aa,0,60,1,0,25.25,20,30.5,31,16.5,", 0) == 0);
  CHECK(second.rfind("00000000000000bb,1,60000/1001,1,0,26,", 0) == 0);
  // Registration error (2 columns), rotation latency (2), the six figures of
  // what a viewer or camera sees, the nine counts and rates of application
  // frames, compositors, Slats and streaming, the streaming tool's total and
  // photon-to-photon latency are absent from these summaries: their 21 cells
  // stay empty.
  CHECK_THAT(first, Catch::Contains(",60,0" + std::string(21, ',') + ",1234,0.5"));
}

TEST_CASE("results.sqlite holds runs, figures, distributions, histograms and models", "[sweep]") {
  const fs::path dir = scratch_dir("latsim_results_db");
  const fs::path file = dir / "results.sqlite";
  latsim::sweep::write_results_db(file, {"/display/refresh_hz"}, two_records());
  REQUIRE(fs::exists(file));
  for (const auto& entry : fs::directory_iterator(dir)) CHECK_FALSE(is_temporary_name(entry.path().filename().string()));
  sqlite3* db = nullptr;
  REQUIRE(sqlite3_open_v2(file.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK);
  CHECK(count_rows(db, "SELECT COUNT(*) FROM runs") == 2);
  CHECK(count_rows(db, "SELECT COUNT(*) FROM runs WHERE \"/display/refresh_hz\" = 60") == 1);
  CHECK(count_rows(db, "SELECT COUNT(*) FROM runs WHERE \"/display/refresh_hz\" = '60000/1001'") == 1);
  CHECK(count_rows(db, "SELECT COUNT(*) FROM figures WHERE name = 'pxpl5.gp_utilisation' AND value = 0.75") == 2);
  CHECK(count_rows(db, "SELECT COUNT(*) FROM distributions WHERE name = 'motion_to_photon_ms' AND stat = 'p99'") == 2);
  CHECK(count_rows(db, "SELECT COUNT(*) FROM distributions WHERE run_id = '00000000000000bb' AND name = "
                       "'motion_to_photon_ms' AND stat = 'mean' AND value = 26.0") == 1);
  // The summaries give five statistics of the distribution (no stddev, min, p90 or p999): five rows a run.
  CHECK(count_rows(db, "SELECT COUNT(*) FROM distributions") == 10);
  CHECK(count_rows(db, "SELECT COUNT(*) FROM models WHERE model = 'tracker' AND events = 600") == 2);
  // Histograms stay in the results store, where the report reads them.
  CHECK(count_rows(db, "SELECT COUNT(*) FROM sqlite_master WHERE name = 'histograms'") == 0);
  sqlite3_close(db);
  // Writing again replaces the file whole.
  latsim::sweep::write_results_db(file, {"/display/refresh_hz"}, {two_records()[0]});
  REQUIRE(sqlite3_open_v2(file.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK);
  CHECK(count_rows(db, "SELECT COUNT(*) FROM runs") == 1);
  sqlite3_close(db);
  fs::remove_all(dir);
}

TEST_CASE("results.sqlite written in more parts than SQLite attaches at once holds every run in order", "[sweep]") {
  const fs::path dir = scratch_dir("latsim_results_db_parts");
  const fs::path file = dir / "results.sqlite";
  constexpr unsigned kParts = 12;  // SQLite attaches at most ten databases to one connection
  {
    latsim::sweep::ResultsDbWriter db(file, {"/display/refresh_hz"}, kParts);
    int64_t position = 0;
    for (int chunk = 0; chunk < 2; ++chunk) {
      for (unsigned k = 0; k < kParts; ++k) {
        db.begin_part(k);
        const std::string id = "00000000000000" + std::to_string(10 + chunk * kParts + k);
        db.add_to_part(k, row_of(id, position, 60, summary_with(static_cast<double>(position))), position);
        ++position;
        db.end_part(k);
      }
      db.merge_parts();
    }
    db.commit();
  }
  for (const auto& entry : fs::directory_iterator(dir)) CHECK(entry.path().filename() == "results.sqlite");
  sqlite3* db = nullptr;
  REQUIRE(sqlite3_open_v2(file.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK);
  CHECK(count_rows(db, "SELECT COUNT(*) FROM runs") == 2 * kParts);
  // In the order the parts were merged, part 0 first, chunk after chunk.
  CHECK(count_rows(db, "SELECT COUNT(*) FROM runs WHERE plan_index = rowid - 1") == 2 * kParts);
  CHECK(count_rows(db, "SELECT COUNT(*) FROM distributions d JOIN runs r USING (run_id) WHERE d.name = "
                       "'motion_to_photon_ms' AND d.stat = 'mean' AND d.value = r.plan_index") == 2 * kParts);
  CHECK(count_rows(db, "SELECT COUNT(*) FROM names WHERE name = 'motion_to_photon_ms'") == 1);
  sqlite3_close(db);
  fs::remove_all(dir);
}

TEST_CASE("temporary file names are recognised", "[sweep]") {
  CHECK(is_temporary_name("summary.json.tmp.12345"));
  CHECK(is_temporary_name("results.csv.tmp"));
  CHECK_FALSE(is_temporary_name("summary.json"));
  CHECK_FALSE(is_temporary_name("timeline.tmp.csv"));
  CHECK_FALSE(is_temporary_name("x.tmp.12a"));
  CHECK_FALSE(is_temporary_name(".tmp"));
}

TEST_CASE("a sweep directory: finished means marked done, stray temporaries are removed per run", "[sweep]") {
  const fs::path dir = scratch_dir("latsim_sweep_store");
  SweepStore store(dir);
  const fs::path mark = store.new_mark("test");
  CHECK(store.mark_finished("r1", mark));
  CHECK(store.mark_finished("r1", mark));  // a second mark of the same run is no error
  fs::create_directories(store.run_dir("r2") / "frames");
  // r2 was killed while writing its kept files: only temporary files and its staging directory.
  std::ofstream(store.run_dir("r2") / "summary.json.tmp.4242") << R"({"eve)";
  std::ofstream(store.run_dir("r2") / "frames" / "f0.png.tmp.4242") << "png";
  std::ofstream(store.run_dir("r2") / "timeline.csv") << "stage,frame,eye,unit,start_ms,end_ms\n";
  fs::create_directories(store.staging_dir("r2"));
  fs::create_directories(store.run_dir("r1"));
  std::ofstream(store.run_dir("r1") / "figures.json.tmp.77") << "{";
  std::ofstream(dir / "results.csv.tmp.4242") << "run_id";
  std::ofstream(dir / "plan.json.tmp.4242") << "{";
  std::ofstream(dir / "notes.txt.tmp") << "someone else's file";
  CHECK(store.is_finished("r1"));
  CHECK_FALSE(store.is_finished("r2"));
  // The marks are names of one empty file: no file of their own, no data.
  CHECK(fs::hard_link_count(mark) == 2);
  CHECK(fs::file_size(dir / "done" / "r1") == 0);
  CHECK(store.finished_runs() == std::set<std::string>{"r1"});
  CHECK(latsim::sweep::finished_runs_in(dir) == std::set<std::string>{"r1"});
  CHECK(latsim::sweep::finished_runs_in(dir / "nowhere").empty());
  // Two processes may share the directory: opening it again is fine.
  CHECK_NOTHROW(SweepStore(dir));
  // Only the named run's temporaries go (another process may be writing r1's).
  CHECK(store.remove_run_temporaries("r2") == 3);
  CHECK_FALSE(fs::exists(store.run_dir("r2") / "summary.json.tmp.4242"));
  CHECK_FALSE(fs::exists(store.staging_dir("r2")));
  CHECK(fs::exists(store.run_dir("r2") / "timeline.csv"));
  CHECK(fs::exists(store.run_dir("r1") / "figures.json.tmp.77"));
  CHECK(store.remove_run_temporaries("no_such_run") == 0);
  CHECK(store.remove_table_temporaries() == 2);
  CHECK(fs::exists(dir / "notes.txt.tmp"));
  fs::remove_all(dir);
}

TEST_CASE("plan.json is rewritten only when its content changes", "[sweep]") {
  const fs::path dir = scratch_dir("latsim_write_if_changed");
  const fs::path file = dir / "plan.json";
  latsim::sweep::write_file_if_changed(file, "{}\n");
  const auto first = fs::last_write_time(file);
  // Set the time back by hand: the test must not depend on the clock's resolution.
  fs::last_write_time(file, first - std::chrono::hours(1));
  latsim::sweep::write_file_if_changed(file, "{}\n");
  CHECK(fs::last_write_time(file) == first - std::chrono::hours(1));
  latsim::sweep::write_file_if_changed(file, "{\"runs\": []}\n");
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(text == "{\"runs\": []}\n");
  fs::remove_all(dir);
}
