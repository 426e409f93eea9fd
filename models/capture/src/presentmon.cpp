// read_presentmon: a PresentMon capture's frames of one process in
// PresentMon's own definitions, whatever the generation of its columns.
#include "latsim/capture/presentmon.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <set>
#include <string_view>

#include "cell_units.hpp"
#include "row_source.hpp"

namespace latsim::capture {

namespace {

constexpr std::array<std::pair<PresentMode, std::string_view>, 7> kModes{{
    {PresentMode::hardware_legacy_flip, "Hardware: Legacy Flip"},
    {PresentMode::hardware_legacy_copy, "Hardware: Legacy Copy to front buffer"},
    {PresentMode::hardware_independent_flip, "Hardware: Independent Flip"},
    {PresentMode::hardware_composed_independent_flip, "Hardware Composed: Independent Flip"},
    {PresentMode::composed_flip, "Composed: Flip"},
    {PresentMode::composed_copy_gpu_gdi, "Composed: Copy with GPU GDI"},
    {PresentMode::composed_copy_cpu_gdi, "Composed: Copy with CPU GDI"},
}};

bool iequal(std::string_view a, std::string_view b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) { return (x | 0x20) == (y | 0x20); });
}

/// Where each column of interest is (absent: the generation has none).
struct Columns {
  std::optional<size_t> application, process_id, sync, mode, tearing, runtime, frame_type, dropped;
  std::optional<size_t> between, in_present, cpu_busy, gpu_busy, gpu_time, until_displayed, display_change;
  // v1 and v2 only.
  std::optional<size_t> render_start, render_complete, display_latency, displayed_time;
  std::optional<size_t> time_s, scanout;  // TimeInSeconds; a latsim run's MsUntilScanout
};


Columns layout(const RowSource& h, Generation g) {
  Columns c;
  c.application = h.column("Application");
  c.process_id = h.column("ProcessID");
  c.sync = h.column("SyncInterval");
  c.mode = h.column("PresentMode");
  c.tearing = h.column("AllowsTearing");
  c.frame_type = h.column("FrameType");
  c.time_s = h.column("TimeInSeconds");
  c.scanout = h.column("MsUntilScanout");
  switch (g) {
    case Generation::current:
      c.runtime = h.column("PresentRuntime");
      c.between = h.column("MsBetweenPresents");
      c.in_present = h.column("MsInPresentAPI");
      if (!c.in_present) c.in_present = h.column("MsCPUWait");
      c.cpu_busy = h.column("MsCPUBusy");
      c.gpu_busy = h.column("MsGPUBusy");
      c.gpu_time = h.column("MsGPUTime");
      c.until_displayed = h.column("MsUntilDisplayed");
      c.display_change = h.column("MsBetweenDisplayChange");
      break;
    case Generation::v2:
      c.runtime = h.column("PresentRuntime");
      c.in_present = h.column("CPUWait");
      c.cpu_busy = h.column("CPUBusy");
      c.gpu_busy = h.column("GPUBusy");
      c.gpu_time = h.column("GPUTime");
      c.display_latency = h.column("DisplayLatency");
      c.displayed_time = h.column("DisplayedTime");
      break;
    case Generation::v1:
      c.runtime = h.column("Runtime");
      c.dropped = h.column("Dropped");
      c.between = h.column("msBetweenPresents");
      c.in_present = h.column("msInPresentAPI");
      c.gpu_busy = h.column("msGPUActive");
      c.render_start = h.column("msUntilRenderStart");
      c.render_complete = h.column("msUntilRenderComplete");
      c.until_displayed = h.column("msUntilDisplayed");
      c.display_change = h.column("msBetweenDisplayChange");
      break;
    default: break;
  }
  return c;
}

/// One pass over the rows, keeping the frames of the chosen process.
class FrameReader {
 public:
  FrameReader(const std::filesystem::path& file, const ProcessSelect& select) : rows_(file), select_(select) {}

  PresentMonProcess read() {
    out_.source = rows_.file();
    out_.generation = rows_.vrapi() ? Generation::vrapi : detect_generation(rows_.header());
    if (!is_presentmon(out_.generation))
      throw CaptureError(rows_.file(), 0,
                         std::string("not a PresentMon capture (its header is of a ") +
                             generation_name(out_.generation) + " file)");
    cols_ = layout(rows_, out_.generation);
    if (!select_.application.empty() && !cols_.application)
      rows_.fail("an application is chosen but the capture has no Application column");
    if (select_.process_id && !cols_.process_id) rows_.fail("a process_id is chosen but the capture has no ProcessID column");
    while (rows_.next()) {
      ++out_.rows_read;
      take_row();
    }
    if (keys_.size() > 1) {
      const std::vector<std::string> names(keys_.begin(), keys_.end());
      throw CaptureError(rows_.file(), 0,
                         std::to_string(keys_.size()) + " processes match: choose one with application and process_id: " +
                             name_list(names));
    }
    if (out_.frames.empty()) throw CaptureError(rows_.file(), 0, "no frames of the process asked for");
    derive();
    return std::move(out_);
  }

 private:
  std::string_view cell(const std::optional<size_t>& c) const {
    return c && *c < rows_.size() ? rows_[*c] : std::string_view();
  }

  std::optional<double> number(const std::optional<size_t>& c) {
    const std::string_view v = cell(c);
    if (not_available(out_.generation, v)) return std::nullopt;
    const std::optional<double> x = parse_number(v);
    if (!x) rows_.fail("column " + rows_.header()[*c] + " holds '" + std::string(v.substr(0, 40)) + "', not a number");
    // The bound of the capture reader (capture_reader.cpp), so that both
    // readers give one verdict on one file: 1e9 ms is eleven days a frame.
    if (!std::isfinite(*x) || std::fabs(*x) > 1e9)
      rows_.fail("column " + rows_.header()[*c] + " holds '" + std::string(v.substr(0, 40)) + "', out of range (|x| <= 1e9)");
    return x;
  }

  bool chosen() {
    const std::string_view app = cell(cols_.application), pid = cell(cols_.process_id);
    if (!select_.application.empty() && !iequal(app, select_.application)) return false;
    if (select_.process_id) {
      int64_t id = 0;
      const auto [end, ec] = std::from_chars(pid.data(), pid.data() + pid.size(), id);
      if (ec != std::errc{} || end != pid.data() + pid.size() || id != *select_.process_id) return false;
    }
    const std::string key = std::string(app) + " " + std::string(pid);
    if (keys_.empty()) {
      out_.application = std::string(app);
      int64_t id = 0;
      const auto [end, ec] = std::from_chars(pid.data(), pid.data() + pid.size(), id);
      if (cols_.process_id && ec == std::errc{} && end == pid.data() + pid.size()) out_.process_id = id;
    }
    keys_.insert(key);
    return keys_.size() == 1;
  }

  void take_row() {
    if (!chosen()) return;
    PresentMonFrame f;
    f.line = rows_.line();
    const std::string_view sync = cell(cols_.sync);
    // D3D's sync intervals are 0 to 4; a number no int holds stays "not said".
    if (const auto s = parse_number(sync); s && std::fabs(*s) <= 1e9) f.sync_interval = static_cast<int>(*s);
    f.mode = parse_present_mode(cell(cols_.mode));
    f.allows_tearing = cell(cols_.tearing) == "1";
    f.runtime = std::string(cell(cols_.runtime));
    f.application_frame = !cols_.frame_type || cell(cols_.frame_type) == "Application";
    f.between_presents_ms = number(cols_.between);
    f.in_present_ms = number(cols_.in_present);
    f.cpu_busy_ms = number(cols_.cpu_busy);
    f.gpu_busy_ms = number(cols_.gpu_busy);
    f.gpu_time_ms = number(cols_.gpu_time);
    const bool dropped = cell(cols_.dropped) == "1";
    if (out_.generation == Generation::v1) {
      const auto start = number(cols_.render_start), complete = number(cols_.render_complete);
      if (start && complete) f.gpu_time_ms = std::round((*complete - *start) * 1e9) / 1e9;
    }
    if (out_.generation == Generation::v2) {
      const auto latency = number(cols_.display_latency);
      if (latency && f.cpu_busy_ms) f.until_displayed_ms = std::round((*latency - *f.cpu_busy_ms) * 1e9) / 1e9;
      displayed_time_.push_back(number(cols_.displayed_time));
    } else if (!dropped) {
      f.until_displayed_ms = number(cols_.until_displayed);
      if (f.until_displayed_ms) f.between_display_change_ms = number(cols_.display_change);
    }
    f.displayed = f.until_displayed_ms.has_value();
    f.present_time_s = number(cols_.time_s);
    f.until_scanout_ms = number(cols_.scanout);
    out_.frames.push_back(std::move(f));
  }

  // What a generation gives only across frames, to the picosecond (latsim's
  // time unit), so that a sum of two cells equals the same time written whole.
  void derive() {
    auto ps = [](double ms) { return std::round(ms * 1e9) / 1e9; };
    std::vector<PresentMonFrame>& fr = out_.frames;
    for (size_t j = 1; j < fr.size(); ++j) {
      if (out_.generation == Generation::v1 && fr[j].between_presents_ms && fr[j - 1].in_present_ms)
        fr[j].cpu_busy_ms = ps(*fr[j].between_presents_ms - *fr[j - 1].in_present_ms);
      if (out_.generation == Generation::v2 && fr[j].cpu_busy_ms && fr[j - 1].in_present_ms)
        fr[j].between_presents_ms = ps(*fr[j - 1].in_present_ms + *fr[j].cpu_busy_ms);
    }
    if (out_.generation != Generation::v2) return;
    std::optional<double> shown_before;  // DisplayedTime of the last displayed frame
    for (size_t j = 0; j < fr.size(); ++j) {
      if (!fr[j].displayed) continue;
      fr[j].between_display_change_ms = shown_before;
      shown_before = displayed_time_[j];
    }
  }

  RowSource rows_;
  const ProcessSelect& select_;
  Columns cols_;
  PresentMonProcess out_;
  std::set<std::string> keys_;
  std::vector<std::optional<double>> displayed_time_;
};

template <class T, class F>
T most_common(const std::vector<PresentMonFrame>& frames, F get, T fallback) {
  std::map<T, int64_t> count;
  for (const PresentMonFrame& f : frames) ++count[get(f)];
  T best = fallback;
  int64_t n = -1;
  for (const auto& [value, c] : count)
    if (c > n) {
      best = value;
      n = c;
    }
  return best;
}

}  // namespace

const char* present_mode_text(PresentMode m) {
  for (const auto& [mode, text] : kModes)
    if (mode == m) return text.data();
  return "Other";
}

PresentMode parse_present_mode(std::string_view text) {
  for (const auto& [mode, name] : kModes)
    if (name == text) return mode;
  return PresentMode::unknown;
}

bool is_composed(PresentMode m) {
  return m == PresentMode::composed_flip || m == PresentMode::composed_copy_gpu_gdi ||
         m == PresentMode::composed_copy_cpu_gdi;
}

PresentMode PresentMonProcess::mode() const {
  return most_common<PresentMode>(frames, [](const PresentMonFrame& f) { return f.mode; }, PresentMode::unknown);
}

int PresentMonProcess::sync_interval() const {
  return most_common<int>(frames, [](const PresentMonFrame& f) { return f.sync_interval; }, -1);
}

bool PresentMonProcess::allows_tearing() const {
  return most_common<bool>(frames, [](const PresentMonFrame& f) { return f.allows_tearing; }, false);
}

PresentMonProcess read_presentmon(const std::filesystem::path& file, const ProcessSelect& select) {
  return FrameReader(file, select).read();
}

}  // namespace latsim::capture
