#include "compare_run.hpp"

#include <algorithm>
#include <fstream>
#include <map>

#include "latsim/io/input_file.hpp"
#include "latsim/sweep/compare.hpp"

namespace latsim::sweep {

namespace {

nlohmann::json read_json(const std::filesystem::path& file) {
  std::string text;
  try {
    text = io::read_input_file(file, size_t{256} << 20);
  } catch (const io::InputFileError& e) {
    throw CompareError(file.string() + ": " + e.what());
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw CompareError(file.string() + ": not JSON (" + std::string(e.what()) + ")");
  }
}

bool iequal(const std::string& a, const std::string& b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) { return (x | 0x20) == (y | 0x20); });
}

// `recorded` is the path the run read (relative to where it ran): when it
// no longer leads to a file from here, the file's name decides.
bool same_file(const std::filesystem::path& recorded, const std::filesystem::path& given) {
  std::error_code ec;
  if (std::filesystem::equivalent(recorded, given, ec)) return true;
  return !std::filesystem::exists(recorded, ec) && recorded.filename() == given.filename();
}

}  // namespace

std::optional<double> RunSide::figure(const std::string& name, const char* stat) const {
  const auto it = figures.find(name);
  if (it == figures.end()) return std::nullopt;
  const nlohmann::json& v = stat ? it->value(stat, nlohmann::json()) : *it;
  if (!v.is_number()) return std::nullopt;
  return v.get<double>();
}

RunSide read_run(const std::filesystem::path& dir) {
  RunSide r;
  r.dir = dir;
  const nlohmann::json figures = read_json(dir / "figures.json");
  r.figures = figures.value("figures", nlohmann::json::object());
  const nlohmann::json& scenario = figures.value("scenario", nlohmann::json::object());
  r.pipeline = scenario.value("pipeline", nlohmann::json::object()).value("type", std::string());
  r.refresh_hz = scenario.value("display", nlohmann::json::object()).value("refresh_hz", 0.0);
  // The figures cover the time simulated (shorter when a capture ran out).
  const auto frames = r.figure("frames_rendered"), rate = r.figure("application_frame_rate_hz");
  r.seconds = frames && rate && *rate > 0.0 ? *frames / *rate : scenario.value("duration_s", 0.0);
  std::error_code ec;
  if (std::filesystem::is_regular_file(dir / "summary.json", ec)) {
    const nlohmann::json summary = read_json(dir / "summary.json");
    for (const nlohmann::json& c : summary.value("captures", nlohmann::json::array())) {
      RunSide::Replayed x;
      x.file = c.value("file", std::string());
      x.column = c.value("column", std::string());
      x.quantity = c.value("quantity", replayed_quantity(x.column));
      x.application = c.value("application", std::string());
      if (c.contains("process_id") && c["process_id"].is_number_integer()) x.process_id = c["process_id"].get<int64_t>();
      r.replayed.push_back(std::move(x));
    }
  }
  if (std::filesystem::is_regular_file(dir / "presentmon.csv", ec))
    r.frames = capture::read_presentmon(dir / "presentmon.csv", {});
  return r;
}

std::string replayed_quantity(const std::string& column) {
  static const std::map<std::string, std::string> kByColumn{
      {"MsCPUBusy", "cpu_busy"},
      {"CPUBusy", "cpu_busy"},
      {"MsCPUWait", "cpu_wait"},
      {"CPUWait", "cpu_wait"},
      {"MsInPresentAPI", "cpu_wait"},
      {"msInPresentAPI", "cpu_wait"},
      {"MsGPUBusy", "gpu_busy"},
      {"GPUBusy", "gpu_busy"},
      {"msGPUActive", "gpu_busy"},
      {"app_gpu_time_microseconds", "app_gpu"},
      {"App", "app_gpu"},
      {"timewarp_gpu_time_microseconds", "timewarp_gpu"},
      {"TW", "timewarp_gpu"},
      {"m_flCompositorRenderGpuMs", "timewarp_gpu"},
  };
  const auto it = kByColumn.find(column);
  return it == kByColumn.end() ? std::string() : it->second;
}

bool replays(const RunSide& run, const std::filesystem::path& file, const std::string& quantity,
             const std::string& application, std::optional<int64_t> process_id) {
  for (const RunSide::Replayed& x : run.replayed) {
    if (x.quantity != quantity || !same_file(x.file, file)) continue;
    if (!x.application.empty() && !application.empty() && !iequal(x.application, application)) continue;
    if (x.process_id && process_id && *x.process_id != *process_id) continue;
    return true;
  }
  return false;
}

}  // namespace latsim::sweep
