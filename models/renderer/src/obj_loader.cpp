#include "latsim/renderer/obj_loader.hpp"

#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <string_view>
#include <vector>

#include "latsim/io/input_file.hpp"

namespace latsim::renderer {
namespace {

// Farthest vertex coordinate accepted, in metres (Embree refuses about 1.8e18).
constexpr double kFarthestVertexM = 1e18;

// Reads one OBJ line at a time and turns it into scene objects; knows where it is so
// every error can name the file and line.
class ObjParser {
 public:
  ObjParser(std::string source_name, const glm::vec3& default_colour)
      : source_name_(std::move(source_name)), default_colour_(default_colour) {}

  void parse_line(std::string_view line, int line_number) {
    line_number_ = line_number;
    if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    std::vector<std::string_view> tokens = split(line);
    if (tokens.empty()) return;
    const std::string_view keyword = tokens.front();
    if (keyword == "v") {
      parse_vertex(tokens);
    } else if (keyword == "f") {
      parse_face(tokens);
    } else if (keyword == "o" || keyword == "g") {
      pending_name_ = tokens.size() > 1 ? join_rest(tokens) : std::string("unnamed");
      object_open_ = false;
    } else if (keyword == "vt" || keyword == "vn" || keyword == "usemtl" || keyword == "mtllib" ||
               keyword == "s") {
      return;
    } else {
      fail("unsupported statement '" + std::string(keyword) + "'");
    }
  }

  Scene take_scene() { return std::move(scene_); }

 private:
  [[noreturn]] void fail(const std::string& reason) const {
    throw SceneError(source_name_ + ":" + std::to_string(line_number_) + ": " + reason);
  }

  static std::vector<std::string_view> split(std::string_view line) {
    std::vector<std::string_view> tokens;
    size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      const size_t start = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
      if (i > start) tokens.push_back(line.substr(start, i - start));
    }
    return tokens;
  }

  static std::string join_rest(const std::vector<std::string_view>& tokens) {
    std::string name(tokens[1]);
    for (size_t i = 2; i < tokens.size(); ++i) {
      name += ' ';
      name += tokens[i];
    }
    return name;
  }

  double number(std::string_view token) const {
    // from_chars rejects a leading '+', which some exporters write.
    const std::string_view digits = (token.size() > 1 && token[0] == '+') ? token.substr(1) : token;
    double value = 0.0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (error != std::errc() || end != digits.data() + digits.size() || !std::isfinite(value)) {
      fail("non-numeric value '" + std::string(token) + "'");
    }
    return value;
  }

  void parse_vertex(const std::vector<std::string_view>& tokens) {
    const size_t count = tokens.size() - 1;
    if (count != 3 && count != 4 && count != 6) {
      fail("vertex needs 3 coordinates (optionally w, or r g b), got " + std::to_string(count) +
           " values");
    }
    std::vector<double> values;
    for (size_t i = 1; i < tokens.size(); ++i) values.push_back(number(tokens[i]));
    // Stored in single precision and traced by Embree, which takes nothing beyond about 1.8e18.
    for (size_t i = 0; i < 3; ++i)
      if (std::fabs(values[i]) > kFarthestVertexM)
        fail("vertex coordinate '" + std::string(tokens[i + 1]) + "' is beyond 1e18 m, which ray casting cannot reach");
    positions_.emplace_back(values[0], values[1], values[2]);
    colours_.push_back(count == 6 ? glm::vec3(values[3], values[4], values[5]) : default_colour_);
  }

  uint32_t vertex_index(std::string_view token) const {
    const std::string_view index_text = token.substr(0, token.find('/'));
    long long index = 0;
    const auto [end, error] =
        std::from_chars(index_text.data(), index_text.data() + index_text.size(), index);
    if (error != std::errc() || end != index_text.data() + index_text.size()) {
      fail("non-numeric value '" + std::string(token) + "'");
    }
    const long long count = static_cast<long long>(positions_.size());
    // OBJ indices are 1-based; negative ones count back from the newest vertex.
    const long long resolved = index > 0 ? index - 1 : count + index;
    if (index == 0 || resolved < 0 || resolved >= count) {
      fail("bad vertex index " + std::to_string(index) + " (" + std::to_string(count) +
           " vertices defined so far)");
    }
    return static_cast<uint32_t>(resolved);
  }

  void parse_face(const std::vector<std::string_view>& tokens) {
    if (tokens.size() < 4) {
      fail("too few vertices in face: " + std::to_string(tokens.size() - 1) + ", need at least 3");
    }
    std::vector<uint32_t> corners;
    for (size_t i = 1; i < tokens.size(); ++i) corners.push_back(vertex_index(tokens[i]));
    if (!object_open_) {
      scene_.begin_object(pending_name_);
      object_open_ = true;
    }
    for (size_t i = 1; i + 1 < corners.size(); ++i) {
      const uint32_t a = corners[0];
      const uint32_t b = corners[i];
      const uint32_t c = corners[i + 1];
      scene_.add_triangle(Triangle{{positions_[a], positions_[b], positions_[c]},
                                   {colours_[a], colours_[b], colours_[c]}});
    }
  }

  std::string source_name_;
  glm::vec3 default_colour_;
  Scene scene_;
  std::vector<glm::vec3> positions_;
  std::vector<glm::vec3> colours_;
  std::string pending_name_ = "default";
  bool object_open_ = false;
  int line_number_ = 0;
};

}  // namespace

Scene parse_obj(std::istream& input, const std::string& source_name,
                const glm::vec3& default_colour) {
  ObjParser parser(source_name, default_colour);
  std::string line;
  int line_number = 0;
  while (std::getline(input, line)) parser.parse_line(line, ++line_number);
  if (input.bad()) throw SceneError(source_name + ":" + std::to_string(line_number) + ": read error");
  return parser.take_scene();
}

Scene load_obj(const std::filesystem::path& path, const glm::vec3& default_colour) {
  std::istringstream file;
  try {
    file.str(io::read_input_file(path, kMaxObjBytes));
  } catch (const io::InputFileError& e) {
    throw SceneError(path.string() + ": cannot read the mesh: " + e.what());
  }
  return parse_obj(file, path.string(), default_colour);
}

}  // namespace latsim::renderer
