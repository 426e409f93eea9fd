#include "latsim/tracker/trace.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <string_view>

#include <glm/geometric.hpp>

#include "latsim/io/input_file.hpp"

namespace latsim::tracker {

namespace {

enum class TraceFormat { LatsimCsv, Corbillon };

constexpr std::string_view kCsvHeader = "t_s,px,py,pz,qw,qx,qy,qz";

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

std::vector<std::string_view> split_csv(std::string_view line) {
  std::vector<std::string_view> fields;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma == std::string_view::npos ? comma : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

std::vector<std::string_view> split_whitespace(std::string_view line) {
  std::vector<std::string_view> fields;
  size_t pos = 0;
  while (true) {
    const size_t begin = line.find_first_not_of(" \t\r", pos);
    if (begin == std::string_view::npos) break;
    const size_t end = line.find_first_of(" \t\r", begin);
    fields.push_back(line.substr(begin, end == std::string_view::npos ? end : end - begin));
    if (end == std::string_view::npos) break;
    pos = end;
  }
  return fields;
}

std::optional<TraceFormat> recognise_header(std::string_view header) {
  const std::string_view h = trim(header);
  std::string compact;
  for (char c : h)
    if (c != ' ' && c != '\t') compact.push_back(c);
  if (compact == kCsvHeader) return TraceFormat::LatsimCsv;
  const auto words = split_whitespace(h);
  const std::vector<std::string_view> corbillon{"timestamp", "viewpoint", "w", "x", "y", "z"};
  if (words == corbillon) return TraceFormat::Corbillon;
  return std::nullopt;
}

// Parses every field as a finite double, naming the first bad one.
class RowParser {
 public:
  RowParser(const std::filesystem::path& file, int64_t line) : file_(file), line_(line) {}

  std::vector<double> numbers(const std::vector<std::string_view>& fields,
                              const std::vector<std::string_view>& names) const {
    if (fields.size() != names.size())
      fail("expected " + std::to_string(names.size()) + " columns, found " + std::to_string(fields.size()));
    std::vector<double> values(fields.size());
    for (size_t i = 0; i < fields.size(); ++i) {
      const std::string_view f = fields[i];
      double v = 0.0;
      const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
      if (f.empty() || ec != std::errc{} || end != f.data() + f.size())
        fail("column " + std::string(names[i]) + " is not a number: '" + std::string(f) + "'");
      if (!std::isfinite(v)) fail("column " + std::string(names[i]) + " is not finite: '" + std::string(f) + "'");
      values[i] = v;
    }
    return values;
  }

  [[noreturn]] void fail(const std::string& reason) const { throw TraceError(file_, line_, reason); }

 private:
  const std::filesystem::path& file_;
  int64_t line_;
};

// Unity is left-handed with +z forward; latsim is right-handed with -z
// forward. Mirroring z on both sides of the rotation (R' = M R M with
// M = diag(1, 1, -1)) keeps w and z and negates x and y.
glm::dquat from_unity(double w, double x, double y, double z) { return glm::dquat{w, -x, -y, z}; }

des::Time timestamp(double seconds, const RowParser& parser) {
  // Time holds about +-106 days; a trace beyond that is certainly corrupt.
  if (std::abs(seconds) > 9.0e6) parser.fail("timestamp out of range: " + std::to_string(seconds) + " s");
  return des::Time::from_seconds(seconds);
}

TraceSample parse_row(TraceFormat format, std::string_view line, const RowParser& parser, bool& has_position) {
  TraceSample s;
  glm::dquat q;
  if (format == TraceFormat::LatsimCsv) {
    const auto v = parser.numbers(split_csv(line), {"t_s", "px", "py", "pz", "qw", "qx", "qy", "qz"});
    s.t = timestamp(v[0], parser);
    s.pose.position_m = glm::dvec3{v[1], v[2], v[3]};
    q = glm::dquat{v[4], v[5], v[6], v[7]};
    has_position = true;
  } else {
    const auto v = parser.numbers(split_whitespace(line), {"timestamp", "viewpoint", "w", "x", "y", "z"});
    s.t = timestamp(v[0], parser);
    q = from_unity(v[2], v[3], v[4], v[5]);
  }
  // Normalised through its largest component, so that components near the
  // largest double (whose squares overflow) still give a unit quaternion.
  const double largest = std::max(std::max(std::fabs(q.w), std::fabs(q.x)), std::max(std::fabs(q.y), std::fabs(q.z)));
  if (!(largest > 1e-12)) parser.fail("zero quaternion (it describes no orientation)");
  const glm::dquat scaled = q / largest;
  s.pose.orientation = scaled / std::sqrt(glm::dot(scaled, scaled));
  return s;
}

}  // namespace

Trace load_trace(const std::filesystem::path& file) {
  std::istringstream in;
  try {
    in.str(io::read_input_file(file, kMaxTraceBytes));
  } catch (const io::InputFileError& e) {
    throw TraceError(file, 0, std::string("cannot read the trace file: ") + e.what());
  }

  Trace trace;
  trace.source = file;
  std::string line;
  int64_t line_no = 0;
  std::optional<TraceFormat> format;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string_view content = trim(line);
    if (content.empty() || content.front() == '#') continue;
    if (!format) {
      format = recognise_header(content);
      if (!format)
        throw TraceError(file, line_no,
                         "unrecognised header; expected 't_s,px,py,pz,qw,qx,qy,qz' or "
                         "'timestamp viewpoint w x y z'");
      continue;
    }
    const RowParser parser(file, line_no);
    TraceSample s = parse_row(*format, content, parser, trace.has_position);
    if (!trace.samples.empty()) {
      const des::Time prev = trace.samples.back().t;
      if (s.t < prev)
        parser.fail("timestamp " + s.t.str() + " is earlier than the previous row's " + prev.str() +
                    "; timestamps must not decrease");
      if (s.t == prev) {
        // Keep the later row (the newer report for that instant).
        trace.samples.pop_back();
        ++trace.repeated_timestamps_dropped;
      }
    }
    if (!trace.samples.empty()) {
      const glm::dquat& reference = trace.samples.back().pose.orientation;
      if (glm::dot(s.pose.orientation, reference) < 0.0) {
        s.pose.orientation = -s.pose.orientation;
        ++trace.sign_flips_removed;
      }
    }
    trace.samples.push_back(s);
  }
  if (!format) throw TraceError(file, line_no, "empty trace file: no header");
  if (trace.samples.empty()) throw TraceError(file, line_no, "trace has a header but no data rows");
  return trace;
}

}  // namespace latsim::tracker
