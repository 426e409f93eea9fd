// latsim compare on a capture whose timing cells are all NA: legal, compared
// (only the share never displayed has values), and said in one warning.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "latsim/sweep/compare.hpp"

using namespace latsim::sweep;

namespace {

const std::string kHeader =
    "Application,ProcessID,SwapChainAddress,PresentRuntime,SyncInterval,PresentFlags,AllowsTearing,PresentMode,"
    "CPUStartQPC,MsBetweenPresents,MsInPresentAPI,MsCPUBusy,MsCPUWait,MsGPUBusy,MsGPUTime,MsUntilDisplayed,"
    "MsBetweenDisplayChange\n";

std::filesystem::path write(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::temp_directory_path() / ("latsim-compare-" + std::to_string(::getpid()) + "-" + name);
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

}  // namespace

TEST_CASE("compare: a capture of NA timing cells is compared and warned of; a timed one is not warned of") {
  std::string na = kHeader, timed = kHeader;
  for (int i = 0; i < 3; ++i) {
    na += "a.exe,7,0x1,DXGI,1,0,0,Hardware: Independent Flip," + std::to_string(1000 + i) + ",NA,NA,NA,NA,NA,NA,NA,NA\n";
    timed += "a.exe,7,0x1,DXGI,1,0,0,Hardware: Independent Flip," + std::to_string(1000 + i) +
             ",11.1,0.1,5.0,6.1,4.0,4.2,20.0,11.1\n";
  }
  const auto na_file = write("na.csv", na), timed_file = write("timed.csv", timed);
  CompareRequest q;
  q.run = timed_file;
  q.capture = na_file;
  const Comparison c = compare_capture(q);
  REQUIRE(c.warnings.size() == 1);
  CHECK(c.warnings[0].find("3 frames and not one timing value") != std::string::npos);
  q.capture = timed_file;
  CHECK(compare_capture(q).warnings.empty());
  std::filesystem::remove(na_file);
  std::filesystem::remove(timed_file);
}
