// The "trace" key of a cost: a capture column as the cost of each frame.
#include <cstdio>

#include "latsim/capture/capture.hpp"
#include "latsim/capture/presentmon.hpp"
#include "latsim/sections/render_cost.hpp"

namespace latsim::sections {

namespace {

using scenario::Section;

/// The trace keys as the scenario writes them.
struct TraceKeys {
  std::filesystem::path file;
  std::string column;
  std::string application;
  int64_t process_id = 0;
  capture::ReplayParams replay;
};

std::string ms_text(double ms) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g ms", ms);
  return buf;
}

// The smallest value must stay a duration after scale and offset.
void check_smallest(Section& t, const TraceKeys& k, const capture::CaptureColumn& col) {
  const double lowest_ms = col.min().to_ms() * k.replay.scale + k.replay.offset_ms;
  t.check("offset_ms", lowest_ms >= 0.0,
          "the smallest value, " + ms_text(col.min().to_ms()) + " at line " + std::to_string(col.min_line) +
              " of the capture, becomes " + ms_text(lowest_ms) + ": a duration below zero");
}

void bind_keys(Section& t, TraceKeys& k, std::shared_ptr<const renderer::TraceCost>& out) {
  t.doc("A measured cost: the values of one column of a PresentMon capture (current, v1 or v2 columns, told "
        "apart by the header) or of any CSV with a header, in milliseconds, one per frame. See docs/measured.md.");
  t.path("file", k.file, {.required = true, .doc = "the capture (CSV), relative to the file that names it; at most 1 GiB"});
  t.text("column", k.column,
         {.required = true, .doc = "the header name, exactly (MsGPUBusy, msGPUActive, GPUBusy, ...)"});
  t.text("application", k.application,
         {.doc = "keep the rows of this Application (any ASCII case); empty: any"});
  t.integer("process_id", k.process_id,
            {.min = 0.0, .doc = "keep the rows of this ProcessID; 0: any (the rows kept must be of one process)"});
  using Order = capture::ReplayParams::Order;
  using AtEnd = capture::ReplayParams::AtEnd;
  t.choice("order", k.replay.order, {{"in_order", Order::in_order}, {"bootstrap", Order::bootstrap}},
           {.doc = "in_order: as captured; bootstrap: blocks of block_length consecutive values from random "
                   "starts (circular), drawn from the run's random stream, so replications differ"});
  t.choice("at_end", k.replay.at_end, {{"wrap", AtEnd::wrap}, {"stop", AtEnd::stop}},
           {.doc = "in_order, after the last value: wrap: the first again; stop: the run ends there (with a warning)"});
  t.integer("block_length", k.replay.block_length,
            {.min = 1.0, .max = 1e9, .doc = "bootstrap: values per block (at most the column's values)"});
  t.number("scale", k.replay.scale, {.min = 0.0, .max = 1000.0, .doc = "each value × scale + offset_ms"});
  t.number("offset_ms", k.replay.offset_ms, {.unit = "ms", .min = -1e6, .max = 1e6, .doc = "added after scaling"});
  t.number("max_ms", k.replay.max_ms,
           {.unit = "ms", .min = 0.0, .max = 1e9, .doc = "values above it (after scale and offset) are clipped to it; absent: none"});
  if (t.describing()) return;
  std::shared_ptr<const capture::Capture> capture;
  t.guard("file", [&] {
    capture::CaptureRequest request{{k.column}, {k.application, std::nullopt}};
    if (k.process_id != 0) request.select.process_id = k.process_id;
    capture = std::make_shared<const capture::Capture>(capture::read_capture(k.file, request));
  });
  const capture::CaptureColumn& col = capture->columns.front();
  const auto n = static_cast<int64_t>(col.values.size());
  t.check("block_length", k.replay.order == Order::in_order || k.replay.block_length <= n,
          "block_length " + std::to_string(k.replay.block_length) + " is longer than the column's " +
              std::to_string(n) + " values");
  check_smallest(t, k, col);
  out = std::make_shared<const renderer::TraceCost>(renderer::TraceCost{capture, k.replay, t.pointer()});
}

}  // namespace

void bind_trace(Section& s, renderer::RenderCost::Params& p) {
  std::optional<TraceKeys> keys;
  std::shared_ptr<const renderer::TraceCost> trace;
  s.optional_object("trace", keys, [&trace](Section& t, TraceKeys& k) { bind_keys(t, k, trace); },
                    {.doc = "a measured cost instead of the terms above: a capture column, one value per frame"});
  s.rule("trace", "a trace is the whole cost: no fixed_ms, per_primitive_us, per_pixel_ns or variation beside it");
  if (!keys) return;
  for (const char* key : {"fixed_ms", "per_primitive_us", "per_pixel_ns", "variation", "variation_fraction",
                          "variation_correlation_frames"})
    s.check(key, !s.has(key), "a trace is the whole cost: leave this key out");
  p.trace = std::move(trace);
}

nlohmann::json trace_summary(const renderer::RenderCost& cost) {
  const renderer::TraceCost* t = cost.trace();
  const capture::Replay* r = cost.replay();
  if (!t || !r) return nlohmann::json();
  const capture::Capture& c = *t->capture;
  const capture::CaptureColumn& col = c.columns.front();
  nlohmann::json j{{"pointer", t->label},
                   {"file", c.source.string()},
                   {"generation", capture::generation_name(c.generation)},
                   {"column", col.name},
                   {"rows_read", c.rows_read},
                   {"rows_of_other_processes", c.rows_of_other_processes},
                   {"rows_selected", c.rows_selected},
                   {"values", col.values.size()},
                   {"skipped", {{"na", col.skipped_na}, {"not_displayed", col.skipped_not_displayed}}},
                   {"clipped_values", r->clipped_values()},
                   {"mean_ms", r->mean().to_ms()},
                   {"values_played", r->played()},
                   {"wraps", r->wraps()},
                   {"exhausted", r->exhausted()}};
  if (!c.application.empty()) j["application"] = c.application;
  if (c.process_id) j["process_id"] = *c.process_id;
  return j;
}

std::vector<std::string> trace_warnings(const renderer::RenderCost& cost, double refresh_hz) {
  const renderer::TraceCost* t = cost.trace();
  if (!t || !capture::is_presentmon(t->capture->generation)) return {};
  const capture::Capture& c = *t->capture;
  const std::string& column = c.columns.front().name;
  const bool busy = column == "MsCPUBusy" || column == "CPUBusy";
  std::vector<std::string> out;
  try {
    const capture::PresentMonProcess p = capture::read_presentmon(c.source, {c.application, c.process_id});
    for (std::string& w : capture::presentmon_warnings(p, capture::refresh_period_ms(c.source), refresh_hz, busy))
      out.push_back(t->label + ": " + w);
  } catch (const capture::CaptureError&) {
    // The column was read; a capture whose other PresentMon columns are not whole says nothing more.
  }
  return out;
}

std::string trace_ran_out(const renderer::RenderCost& cost, des::Time now) {
  const renderer::TraceCost* t = cost.trace();
  const capture::Replay* r = cost.replay();
  char at[40];
  std::snprintf(at, sizeof at, "%.6g s", now.to_seconds());
  return "the capture of " + (t ? t->label : std::string("a cost")) + " ran out after its " +
         std::to_string(r ? r->played() : 0) + " values at simulated t = " + at +
         " (at_end: stop): the figures cover the run until then";
}

}  // namespace latsim::sections
