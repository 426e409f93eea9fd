// The shipped PresentMon captures: what the reader keeps equals what a second,
// deliberately simple parse of the same file finds (these files have no
// quotes, so splitting at commas is enough here).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "latsim/capture/capture.hpp"

using namespace latsim::capture;
using latsim::des::Time;

namespace {

const std::string kDir = std::string(LATSIM_SOURCE_DIR) + "/scenarios/measured/captures/";

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string f;
  while (std::getline(in, f, ',')) out.push_back(f);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

/// What the simple parse finds: the cells of `column` of the rows of one
/// process that are numbers, as milliseconds, and how many are "NA".
struct Expected {
  std::vector<double> ms;
  int64_t na = 0;
};

Expected simple_parse(const std::string& file, const std::string& column, const std::string& app, const std::string& pid) {
  std::ifstream in(kDir + file);
  std::string line;
  std::getline(in, line);
  if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
  const std::vector<std::string> header = split(line);
  size_t c = 0;
  while (header.at(c) != column) ++c;
  Expected e;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = split(line);
    if (f.size() < header.size() || f[0] != app || f[1] != pid) continue;
    if (f[c] == "NA") ++e.na;
    else e.ms.push_back(std::strtod(f[c].c_str(), nullptr));
  }
  return e;
}

void check_column(const std::string& file, const std::string& column, int64_t process_id, int64_t rows) {
  INFO(file << " " << column);
  const Capture c = read_capture(kDir + file, CaptureRequest{{column}, {.application = "dwm.exe", .process_id = process_id}});
  const Expected e = simple_parse(file, column, "dwm.exe", std::to_string(process_id));
  CHECK(c.rows_selected == rows);
  const CaptureColumn& col = c.column(column);
  REQUIRE(col.values.size() == e.ms.size());
  for (size_t i = 0; i < e.ms.size(); ++i) CHECK(col.values[i] == Time::from_ms(e.ms[i]));
  CHECK(col.skipped_na + col.skipped_not_displayed == e.na);
  CHECK(c.rows_read == c.rows_selected + c.rows_of_other_processes);
}

}  // namespace

TEST_CASE("shipped captures: dwm.exe's columns in every generation equal a simple parse") {
  // Row counts by `grep -c '^dwm.exe,1268,'` on each file.
  check_column("test_case_0.csv", "MsGPUBusy", 1268, 197);
  check_column("test_case_0.csv", "MsCPUBusy", 1268, 197);
  check_column("test_case_0.csv", "MsUntilDisplayed", 1268, 197);
  check_column("test_case_0_v1.csv", "msBetweenPresents", 1268, 199);
  check_column("test_case_0_v1.csv", "msGPUActive", 1268, 199);
  check_column("test_case_0_v2.csv", "GPUBusy", 1268, 197);
  check_column("test_case_0_v2.csv", "CPUBusy", 1268, 197);
  check_column("test_case_2.csv", "MsGPUBusy", 1300, 56);
}

TEST_CASE("shipped captures: generations recognised; ten processes named when none is chosen") {
  CHECK(read_capture(kDir + "test_case_0.csv", {{"MsGPUBusy"}, {.process_id = 1268}}).generation == Generation::current);
  CHECK(read_capture(kDir + "test_case_0_v1.csv", {{"msGPUActive"}, {.process_id = 1268}}).generation == Generation::v1);
  CHECK(read_capture(kDir + "test_case_0_v2.csv", {{"GPUBusy"}, {.process_id = 1268}}).generation == Generation::v2);
  try {
    (void)read_capture(kDir + "test_case_0.csv", {{"MsGPUBusy"}, {}});
    FAIL("several processes were accepted");
  } catch (const CaptureError& e) {
    CHECK(std::string(e.what()).find("10 processes match the capture") != std::string::npos);
  }
}
