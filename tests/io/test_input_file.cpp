// Input files are read only when they are regular files of bounded size.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "latsim/io/input_file.hpp"

namespace fs = std::filesystem;
using latsim::io::InputFileError;
using latsim::io::read_input_file;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("latsim_input_file_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

}  // namespace

TEST_CASE("a regular file is read whole, up to its limit", "[input_file]") {
  const fs::path f = scratch("ten.txt");
  std::ofstream(f) << "0123456789";
  CHECK(read_input_file(f, 10) == "0123456789");
  CHECK_THROWS_WITH(read_input_file(f, 9), "it is too large (10 bytes; at most 9)");
  std::ofstream(scratch("empty.txt")).close();
  CHECK(read_input_file(scratch("empty.txt"), 0).empty());
  fs::remove_all(f.parent_path());
}

TEST_CASE("FIFOs, devices and directories are refused at once", "[input_file]") {
  const fs::path fifo = scratch("fifo");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  // No writer ever opens it: a blocking open or read would never return.
  const auto t0 = std::chrono::steady_clock::now();
  CHECK_THROWS_WITH(read_input_file(fifo, 1 << 20), "it is not a regular file (a device, pipe or socket)");
  CHECK(std::chrono::steady_clock::now() - t0 < std::chrono::seconds(1));
  CHECK_THROWS_WITH(read_input_file("/dev/zero", 1 << 20), "it is not a regular file (a device, pipe or socket)");
  CHECK_THROWS_WITH(read_input_file(fifo.parent_path(), 1 << 20), "it is a directory");
  CHECK_THROWS_AS(read_input_file(fifo.parent_path() / "missing", 1 << 20), InputFileError);
  fs::remove_all(fifo.parent_path());
}
