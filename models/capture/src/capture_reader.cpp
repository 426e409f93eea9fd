// read_capture: one pass over the file, keeping only the asked-for columns of
// the rows of the chosen process.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <string_view>

#include "cell_units.hpp"
#include "latsim/capture/capture.hpp"
#include "row_source.hpp"

namespace latsim::capture {

namespace {

/// Names of one quantity across the generations, for the hint of a missing column.
constexpr std::array<std::array<std::string_view, 3>, 14> kAliases{{
    {"MsBetweenPresents", "msBetweenPresents", ""},
    {"MsBetweenAppStart", "FrameTime", ""},
    {"MsCPUBusy", "CPUBusy", ""},
    {"MsCPUWait", "CPUWait", ""},
    {"MsGPULatency", "GPULatency", ""},
    {"MsGPUTime", "GPUTime", ""},
    {"MsGPUBusy", "GPUBusy", "msGPUActive"},
    {"MsGPUWait", "GPUWait", ""},
    {"MsVideoBusy", "VideoBusy", "msGPUVideoActive"},
    {"MsUntilDisplayed", "msUntilDisplayed", ""},
    {"MsBetweenDisplayChange", "msBetweenDisplayChange", ""},
    {"MsInPresentAPI", "msInPresentAPI", ""},
    {"MsRenderPresentLatency", "msUntilRenderComplete", ""},
    {"MsFlipDelay", "msFlipDelay", ""},
}};

bool iequal(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return (x | 0x20) == (y | 0x20) && ((x >= 'A' && x <= 'Z') || (x >= 'a' && x <= 'z') || x == y);
         });
}

/// A process as the capture names it, with its rows.
struct ProcessRows {
  std::string application;
  std::string process_id;
  int64_t rows = 0;
};

/// A column's smallest and largest values so far, and their lines.
struct Extremes {
  des::Time min, max;
  int64_t min_line = 0, max_line = 0;
};

/// Where the columns of interest are in the header.
struct Layout {
  std::vector<size_t> wanted;  // by request order
  std::optional<size_t> application, process_id, dropped;
  size_t needed = 0;  // fields a row must have
};


std::string missing_column(const std::vector<std::string>& header, Generation g, const std::string& name) {
  std::string text = "no column \"" + shown(name) + "\" in this " + generation_name(g) + " capture";
  // The same quantity under another generation's name. The groups are padded
  // with empty names, which no column request is an alias of.
  std::vector<std::string> here;
  for (const auto& group : kAliases)
    if (!name.empty() && std::find(group.begin(), group.end(), name) != group.end())
      for (std::string_view alias : group)
        if (!alias.empty() && alias != name && find_column(header, alias))
          here.push_back(std::string(1, '"').append(alias).append(1, '"'));
  if (!here.empty()) text += " (here it is " + name_list(here) + ")";
  return text + "; its columns: " + name_list(header);
}

/// The reading itself: the header, then every row.
class Reader {
 public:
  Reader(const std::filesystem::path& file, const CaptureRequest& request) : file_(file), request_(request), rows_(file) {}

  Capture read() {
    capture_.source = file_;
    read_header();
    // The fields after the last one read are not even split.
    while (rows_.next(layout_.needed)) {
      ++capture_.rows_read;
      take_row();
    }
    return finish();
  }

 private:
  [[noreturn]] void fail(const std::string& reason) const { rows_.fail(reason); }

  void read_header() {
    header_ = rows_.header();
    capture_.generation = rows_.vrapi() ? Generation::vrapi : detect_generation(header_);
    for (const std::string& name : request_.columns) {
      const auto at = rows_.column(name);
      if (!at) fail(missing_column(header_, capture_.generation, name));
      if (const auto why = not_a_duration(capture_.generation, name)) fail(*why);
      layout_.wanted.push_back(*at);
      layout_.needed = std::max(layout_.needed, *at + 1);
      capture_.columns.push_back(CaptureColumn{.name = name});
      display_.push_back(is_display_column(name));
      extremes_.emplace_back();
    }
    layout_.application = rows_.column("Application");
    layout_.process_id = rows_.column("ProcessID");
    if (capture_.generation == Generation::v1) layout_.dropped = rows_.column("Dropped");
    const ProcessSelect& sel = request_.select;
    if (!sel.application.empty() && !layout_.application)
      fail("an application is chosen but the capture has no Application column");
    if (sel.process_id && !layout_.process_id) fail("a process_id is chosen but the capture has no ProcessID column");
    for (const auto& c : {layout_.application, layout_.process_id, layout_.dropped})
      if (c) layout_.needed = std::max(layout_.needed, *c + 1);
  }

  // Whether this row belongs to the chosen process; counts every process seen.
  bool chosen() {
    const std::string_view app = layout_.application ? rows_[*layout_.application] : std::string_view();
    const std::string_view pid = layout_.process_id ? rows_[*layout_.process_id] : std::string_view();
    const ProcessSelect& sel = request_.select;
    if (!sel.application.empty() && !iequal(app, sel.application)) return other();
    if (sel.process_id) {
      int64_t id = 0;
      const auto [end, ec] = std::from_chars(pid.data(), pid.data() + pid.size(), id);
      if (ec != std::errc{} || end != pid.data() + pid.size() || id != *sel.process_id) return other();
    }
    // The matching rows must be of one process.
    if (processes_.size() == 1 && app == first_app_ && pid == first_pid_) {
      ++processes_.begin()->second.rows;
      return true;
    }
    std::string key = std::string(app) + '\n' + std::string(pid);
    auto [it, added] = processes_.try_emplace(std::move(key), ProcessRows{std::string(app), std::string(pid), 0});
    ++it->second.rows;
    if (added && processes_.size() == 1) {
      first_app_ = app;
      first_pid_ = pid;
    }
    return processes_.size() == 1;
  }
  bool other() {
    ++capture_.rows_of_other_processes;
    return false;
  }

  void take_row() {
    if (rows_.size() < layout_.needed)
      fail("a row of " + std::to_string(rows_.size()) + " fields; the columns read need " + std::to_string(layout_.needed));
    if (!chosen()) return;
    const bool dropped = layout_.dropped && rows_[*layout_.dropped] == "1";
    for (size_t k = 0; k < layout_.wanted.size(); ++k) {
      CaptureColumn& col = capture_.columns[k];
      const std::string_view cell = rows_[layout_.wanted[k]];
      const bool unknown = not_available(capture_.generation, cell);
      if (display_[k] && (dropped || unknown)) {
        ++col.skipped_not_displayed;
        continue;
      }
      if (unknown) {
        ++col.skipped_na;
        continue;
      }
      add(col, layout_.wanted[k], cell);
    }
  }

  void add(CaptureColumn& col, size_t index, std::string_view cell) {
    const std::string where = "column " + std::to_string(index + 1) + " (" + col.name + ") ";
    const std::optional<double> parsed = cell_ms(capture_.generation, col.name, cell);
    if (!parsed) fail(where + "holds '" + shown(cell) + "', not a number of " + unit_name(capture_.generation, col.name));
    const double ms = *parsed;
    if (!std::isfinite(ms) || std::fabs(ms) > 1e9) fail(where + "holds '" + shown(cell) + "', out of range (|ms| <= 1e9)");
    const des::Time v = des::Time::from_ms(ms);
    Extremes& x = extremes_[static_cast<size_t>(&col - capture_.columns.data())];
    if (col.values.empty() || v < x.min) x = Extremes{v, x.max, rows_.line(), x.max_line};
    if (col.values.empty() || v > x.max) x = Extremes{x.min, v, x.min_line, rows_.line()};
    col.values.push_back(v);
  }

  Capture finish() {
    if (processes_.size() > 1) fail_several();
    if (processes_.empty()) fail_none();
    const ProcessRows& p = processes_.begin()->second;
    capture_.application = p.application;
    int64_t id = 0;
    const auto [end, ec] = std::from_chars(p.process_id.data(), p.process_id.data() + p.process_id.size(), id);
    if (layout_.process_id && ec == std::errc{} && end == p.process_id.data() + p.process_id.size())
      capture_.process_id = id;  // (a ProcessID that is no integer stays unnamed)
    capture_.rows_selected = p.rows;
    for (size_t k = 0; k < capture_.columns.size(); ++k) {
      CaptureColumn& col = capture_.columns[k];
      if (col.values.empty())
        throw CaptureError(file_, 0,
                           "column " + col.name + " has no values for " + who() + " (" +
                               std::to_string(col.skipped_na) + " NA, " + std::to_string(col.skipped_not_displayed) +
                               " not displayed)");
      col.values.shrink_to_fit();  // 8 bytes a value kept, not the growth's slack
      col.min_line = extremes_[k].min_line;
      col.max_line = extremes_[k].max_line;
    }
    return std::move(capture_);
  }

  std::string who() const {
    const ProcessSelect& sel = request_.select;
    if (sel.application.empty() && !sel.process_id) return "the capture";
    std::string text = sel.application.empty() ? "process" : shown(sel.application);
    if (sel.process_id) text += " " + std::to_string(*sel.process_id);
    return text;
  }

  [[noreturn]] void fail_several() const {
    std::vector<std::string> names;
    for (const auto& [key, p] : processes_) names.push_back(shown(p.application) + " " + shown(p.process_id));
    throw CaptureError(file_, 0,
                       std::to_string(processes_.size()) + " processes match " + who() +
                           ": choose one with application and process_id: " + name_list(names));
  }
  [[noreturn]] void fail_none() const {
    throw CaptureError(file_, 0, "no rows of " + who() + " among " + std::to_string(capture_.rows_read) + " rows");
  }

  const std::filesystem::path& file_;
  const CaptureRequest& request_;
  RowSource rows_;
  std::vector<std::string> header_;
  Layout layout_;
  std::vector<bool> display_;
  std::map<std::string, ProcessRows> processes_;
  std::string first_app_, first_pid_;  // of the first process seen (the fast path)
  std::vector<Extremes> extremes_;  // by column
  Capture capture_;
};

}  // namespace

Generation file_generation(const std::filesystem::path& file) {
  const RowSource rows(file);
  return rows.vrapi() ? Generation::vrapi : detect_generation(rows.header());
}

Capture read_capture(const std::filesystem::path& file, const CaptureRequest& request) {
  return Reader(file, request).read();
}

}  // namespace latsim::capture
