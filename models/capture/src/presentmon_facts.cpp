// What a PresentMon capture says as a whole: its processes, its display's
// refresh period, and what a replay of one of its processes should warn of.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>

#include "cell_units.hpp"
#include "latsim/capture/presentmon.hpp"
#include "row_source.hpp"

namespace latsim::capture {

namespace {

// A ProcessID as the readers take it: an integer (the whole text), or none
// (a number no int64_t holds, 1e19 say, is none rather than wrapped).
std::optional<int64_t> process_id_of(std::string_view text) {
  int64_t id = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
  if (ec != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return id;
}


double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string fmt(double v, const char* format) {
  char buf[48];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

}  // namespace

std::vector<ProcessCount> presentmon_processes(const std::filesystem::path& file) {
  RowSource rows(file);
  const auto app = rows.column("Application"), pid = rows.column("ProcessID");
  std::vector<ProcessCount> out;
  std::map<std::pair<std::string, int64_t>, size_t> at;
  while (rows.next()) {
    ProcessCount key;
    if (app && *app < rows.size()) key.application = std::string(rows[*app]);
    if (pid && *pid < rows.size())
      if (const auto id = process_id_of(rows[*pid])) key.process_id = *id;
    const auto [it, added] = at.try_emplace({key.application, key.process_id}, out.size());
    if (added) out.push_back(key);
    ++out[it->second].frames;
  }
  std::stable_sort(out.begin(), out.end(), [](const ProcessCount& a, const ProcessCount& b) { return a.frames > b.frames; });
  return out;
}

std::optional<double> refresh_period_ms(const std::filesystem::path& file) {
  RowSource rows(file);
  const std::vector<std::string>& h = rows.header();
  const Generation g = detect_generation(h);
  if (!is_presentmon(g)) return std::nullopt;
  // v2 writes how long each frame stayed on screen instead of the change interval.
  const auto change = g == Generation::v2 ? rows.column("DisplayedTime")
                                          : rows.column(g == Generation::v1 ? "msBetweenDisplayChange" : "MsBetweenDisplayChange");
  const auto sync = rows.column("SyncInterval"), tearing = rows.column("AllowsTearing");
  if (!change || !sync) return std::nullopt;
  std::vector<double> intervals;
  while (rows.next()) {
    if (*change >= rows.size() || *sync >= rows.size()) continue;
    const auto s = parse_number(rows[*sync]);
    const bool tears = tearing && *tearing < rows.size() && rows[*tearing] == "1";
    const auto v = parse_number(rows[*change]);
    if (s && *s >= 1 && !tears && v && *v > 0.0) intervals.push_back(*v);
  }
  std::vector<double> short_ones;
  for (double v : intervals)
    if (v < 50.0) short_ones.push_back(v);
  if (short_ones.empty()) return std::nullopt;
  const double guess = median(short_ones);
  // Each interval is a whole number of periods; those that are not (within
  // 10 % of the guess) are left out.
  double sum = 0.0, periods = 0.0;
  for (double v : intervals) {
    const double k = std::round(v / guess);
    if (k < 1.0 || k > 16.0 || std::fabs(v / k - guess) > 0.1 * guess) continue;
    sum += v;
    periods += k;
  }
  // The median of an even count is the mean of two intervals, which need not
  // be a period itself: none may then fit it (1 and 2 ms: 1.5 ms).
  if (periods == 0.0) return std::nullopt;
  return sum / periods;
}

std::vector<std::string> presentmon_warnings(const PresentMonProcess& p, std::optional<double> capture_period_ms,
                                             double refresh_hz, bool cpu_busy_as_work) {
  std::vector<std::string> out;
  std::string who = p.source.string();
  who.append(" (").append(p.application);
  if (p.process_id) who.append(" ").append(std::to_string(*p.process_id));
  who.append(")");
  if (p.sync_interval() == 0)
    out.push_back(who + " is uncapped: it presented with SyncInterval 0, not waiting for the display's refresh" +
                  (p.allows_tearing() ? " (and may tear)" : std::string()) +
                  ", so its frame rate is its own, not one a display paced");
  const PresentMode mode = p.mode();
  if (is_composed(mode))
    out.push_back(who + " was composed by the desktop compositor (PresentMode \"" + present_mode_text(mode) +
                  "\"): its display times include the compositor's own frame, which an HMD's compositor replaces");
  if (capture_period_ms) {
    const double capture_hz = 1000.0 / *capture_period_ms;
    if (std::fabs(capture_hz - refresh_hz) > 0.005 * refresh_hz)
      out.push_back(who + " was taken on a display refreshing at " + fmt(capture_hz, "%.2f") +
                    " Hz; the scenario's display refreshes at " + fmt(refresh_hz, "%.2f") +
                    " Hz, so waits the capture's display imposed are replayed against another");
  }
  if (!cpu_busy_as_work) return out;
  std::vector<double> busy, between;
  for (const PresentMonFrame& f : p.frames) {
    if (f.cpu_busy_ms) busy.push_back(*f.cpu_busy_ms);
    if (f.between_presents_ms) between.push_back(*f.between_presents_ms);
  }
  if (!busy.empty() && !between.empty() && median(busy) >= 0.9 * median(between))
    out.push_back(who + ": its CPU busy time (PresentMon: from the previous Present()'s return to this one's call, "
                        "the application's own waiting included) is " + fmt(median(busy), "%.2f") +
                  " ms at the median against a frame interval of " + fmt(median(between), "%.2f") +
                  " ms: it holds waiting, not only work, so a stage costing it waits twice");
  return out;
}

}  // namespace latsim::capture
