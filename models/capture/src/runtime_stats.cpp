#include "latsim/capture/runtime_stats.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "cell_units.hpp"
#include "row_source.hpp"

namespace latsim::capture {

namespace {


/// A reader of one kind: the columns it needs, then every row.
class StatsReader {
 public:
  explicit StatsReader(const std::filesystem::path& file) : rows_(file) {}

  RuntimeStats read() {
    out_.source = rows_.file();
    out_.generation = rows_.vrapi() ? Generation::vrapi : detect_generation(rows_.header());
    switch (out_.generation) {
      case Generation::ovr_metrics: ovr(); break;
      case Generation::vrapi: vrapi(); break;
      case Generation::steamvr: steamvr(); break;
      default:
        throw CaptureError(rows_.file(), 0,
                           std::string("not a runtime's statistics (OVR Metrics Tool, VrApi or SteamVR frame "
                                       "timing): its header is of a ") + generation_name(out_.generation) + " file");
    }
    return std::move(out_);
  }

 private:
  std::optional<size_t> column(std::string_view name, bool required = true) {
    const auto at = rows_.column(name);
    if (!at && required)
      throw CaptureError(rows_.file(), 1, "no column \"" + shown(name) + "\" in this " +
                                              generation_name(out_.generation) + " file");
    return at;
  }

  // The cell as a number (none when not available); bad text is an error.
  std::optional<double> number(std::optional<size_t> c) {
    if (!c) return std::nullopt;
    if (*c >= rows_.size()) rows_.fail("a row of " + std::to_string(rows_.size()) + " fields; the header has " +
                                       std::to_string(rows_.header().size()));
    const std::string_view v = rows_[*c];
    if (not_available(out_.generation, v)) return std::nullopt;
    std::optional<double> x = out_.generation == Generation::vrapi ? vrapi_number(v) : parse_number(v);
    if (!x || !std::isfinite(*x))
      rows_.fail("column " + shown(rows_.header()[*c]) + " holds '" + shown(v) + "', not a number");
    return x;
  }

  // A VrApi value: the number before its unit ("28ms", "1171/490MHz": 28, 1171).
  static std::optional<double> vrapi_number(std::string_view v) {
    size_t end = 0;
    while (end < v.size() && (std::isdigit(static_cast<unsigned char>(v[end])) || v[end] == '.' || v[end] == '-')) ++end;
    if (end == 0) return std::nullopt;
    return parse_number(v.substr(0, end));
  }

  void put(const char* key, std::optional<double> v, double scale = 1.0) {
    if (v) out_.series[key].add(*v * scale, rows_.line());
  }

  void ovr() {
    const auto stamp = column("Time Stamp");
    const auto rate = column("average_frame_rate"), refresh = column("display_refresh_rate");
    const auto prd = column("average_prediction_milliseconds"), tears = column("screen_tear_count");
    const auto early = column("early_frame_count"), stale = column("stale_frame_count");
    const auto app = column("app_gpu_time_microseconds"), tw = column("timewarp_gpu_time_microseconds");
    // The tool's first row counts from its start, part of a second; its last
    // row, written when the recording stops, repeats the one before less
    // than a second later. Rows between are a second's figures (their Time
    // Stamps jitter by a few hundred ms, the counts are still per second).
    struct Row {
      int64_t line = 0;
      double stamp_ms = 0.0;
      std::optional<double> rate, refresh, prd, tears, early, stale, app, tw;
    };
    std::vector<Row> rows;
    while (rows_.next()) {
      ++out_.rows_read;
      rows.push_back(Row{rows_.line(), number(stamp).value_or(0.0), number(rate), number(refresh), number(prd),
                         number(tears), number(early), number(stale), number(app), number(tw)});
    }
    size_t first = rows.empty() ? 0 : 1, end = rows.size();
    if (end > first + 1 && rows[end - 1].stamp_ms - rows[end - 2].stamp_ms < 950.0) --end;
    out_.partial_rows = static_cast<int64_t>(rows.size() - (end > first ? end - first : 0));
    for (size_t i = first; i < end; ++i) {
      const Row& r = rows[i];
      auto put_row = [&](const char* key, std::optional<double> v, double scale = 1.0) {
        if (v) out_.series[key].add(*v * scale, r.line);
      };
      put_row("frame_rate_hz", r.rate);
      put_row("refresh_hz", r.refresh);
      put_row("prediction_ms", r.prd);
      put_row("tears_per_s", r.tears);
      put_row("early_per_s", r.early);
      put_row("stale_per_s", r.stale);
      put_row("app_gpu_ms", r.app, 1e-3);
      put_row("timewarp_gpu_ms", r.tw, 1e-3);
    }
  }

  void vrapi() {
    const auto fps = column("FPS"), prd = column("Prd"), tear = column("Tear"), early = column("Early");
    const auto stale = column("Stale"), tw = column("TW", false), app = column("App", false);
    while (rows_.next()) {
      ++out_.rows_read;
      put("frame_rate_hz", number(fps));
      // "FPS=72/72": frames shown / the display's refresh rate (newer runtimes).
      const std::string_view f = rows_[*fps];
      if (const size_t slash = f.find('/'); slash != std::string_view::npos) {
        const auto r = parse_number(f.substr(slash + 1));
        if (!r) rows_.fail("field FPS holds '" + std::string(f.substr(0, 40)) + "', not frames/refresh");
        put("refresh_hz", r);
      }
      put("prediction_ms", number(prd));
      put("tears_per_s", number(tear));
      put("early_per_s", number(early));
      put("stale_per_s", number(stale));
      put("app_gpu_ms", number(app));
      put("timewarp_gpu_ms", number(tw));
    }
  }

  void steamvr() {
    const auto time = column("m_flSystemTimeInSeconds"), interval = column("m_flClientFrameIntervalMs");
    const auto pre = column("m_flPreSubmitGpuMs"), post = column("m_flPostSubmitGpuMs");
    const auto comp = column("m_flCompositorRenderGpuMs"), dropped = column("m_nNumDroppedFrames");
    const auto mis = column("m_nNumMisPresented");
    out_.per_frame = true;
    std::vector<double> vsyncs;
    double dropped_sum = 0.0, mis_sum = 0.0;
    while (rows_.next()) {
      ++out_.rows_read;
      put("frame_interval_ms", number(interval));
      const auto a = number(pre), b = number(post);
      if (a && b) put("app_gpu_ms", *a + *b);
      put("timewarp_gpu_ms", number(comp));
      if (const auto t = number(time)) vsyncs.push_back(*t);
      dropped_sum += number(dropped).value_or(0.0);
      mis_sum += number(mis).value_or(0.0);
    }
    // Frames follow vsyncs: the shortest step between them is one refresh (or a few).
    std::sort(vsyncs.begin(), vsyncs.end());
    std::vector<double> steps;
    for (size_t i = 1; i < vsyncs.size(); ++i)
      if (vsyncs[i] > vsyncs[i - 1]) steps.push_back(vsyncs[i] - vsyncs[i - 1]);
    if (steps.empty()) return;
    const double period_s = *std::min_element(steps.begin(), steps.end());
    out_.series["refresh_hz"].add(1.0 / period_s, 0);
    const double seconds = vsyncs.back() - vsyncs.front() + period_s;
    out_.series["stale_per_s"].add(dropped_sum / seconds, 0);
    out_.series["mispresented_per_s"].add(mis_sum / seconds, 0);
  }

  RowSource rows_;
  RuntimeStats out_;
};

}  // namespace

const StatSeries* RuntimeStats::find(const std::string& key) const {
  const auto it = series.find(key);
  return it == series.end() ? nullptr : &it->second;
}

RuntimeStats read_runtime_stats(const std::filesystem::path& file) { return StatsReader(file).read(); }

}  // namespace latsim::capture
