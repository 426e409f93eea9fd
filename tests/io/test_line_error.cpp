// An input file's error is located as compilers locate theirs: "file:line: reason".
#include <catch2/catch.hpp>

#include <string>

#include "latsim/io/line_error.hpp"

using latsim::io::LineError;

TEST_CASE("a line error names the file and the line, or only the file at line 0", "[io]") {
  const LineError at_line("traces/head.csv", 12, "expected 8 columns, got 7");
  CHECK(std::string(at_line.what()) == "traces/head.csv:12: expected 8 columns, got 7");
  CHECK(at_line.line() == 12);
  const LineError whole_file("captures/empty.csv", 0, "no header");
  CHECK(std::string(whole_file.what()) == "captures/empty.csv: no header");
  CHECK(whole_file.line() == 0);
}
