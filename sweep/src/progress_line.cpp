#include "latsim/sweep/progress_line.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace latsim::sweep {

namespace {

// Redrawing more often than this only costs terminal bandwidth.
constexpr auto kRedrawInterval = std::chrono::milliseconds(200);
// A run shorter than this needs no progress line.
constexpr auto kQuietStart = std::chrono::seconds(2);

int64_t ns_of(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
}

constexpr int64_t kRedrawNs = std::chrono::duration_cast<std::chrono::nanoseconds>(kRedrawInterval).count();

std::string duration_text(double s) {
  char buf[48];
  if (s < 100) std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 6000) std::snprintf(buf, sizeof buf, "%.0f min %02.0f s", std::floor(s / 60), std::fmod(s, 60));
  else std::snprintf(buf, sizeof buf, "%.0f h %02.0f min", std::floor(s / 3600), std::floor(std::fmod(s, 3600) / 60));
  return buf;
}

}  // namespace

ProgressLine::ProgressLine(std::string label, size_t total, size_t already_done)
    : label_(std::move(label)),
      total_(total),
      resumed_(already_done),
      done_(already_done),
      enabled_(::isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()),
      next_draw_ns_(0) {
  if (enabled_) draw(false);
}

void ProgressLine::resume(size_t already_done) {
  resumed_ = already_done;
  done_ = already_done;
  if (enabled_) draw(false);
}

void ProgressLine::advance() {
  done_.fetch_add(1, std::memory_order_relaxed);
  if (!enabled_) return;
  const int64_t now = ns_of(std::chrono::steady_clock::now());
  int64_t due = next_draw_ns_.load(std::memory_order_relaxed);
  // One worker wins the redraw; the others carry on.
  if (now < due || !next_draw_ns_.compare_exchange_strong(due, now + kRedrawNs)) return;
  const std::unique_lock lock(draw_mutex_, std::try_to_lock);
  if (lock.owns_lock()) draw(false);
}

void ProgressLine::finish() {
  const std::lock_guard lock(draw_mutex_);
  if (enabled_) draw(true);
}

void ProgressLine::draw(bool final_line) {
  const auto now = std::chrono::steady_clock::now();
  next_draw_ns_ = ns_of(now) + kRedrawNs;
  const double elapsed_s = std::chrono::duration<double>(now - start_).count();
  // The rate counts only runs done by this process; resumed ones cost nothing.
  const size_t done = done_.load();
  const size_t fresh = done - resumed_;
  const double rate_per_s = elapsed_s > 0.0 ? static_cast<double>(fresh) / elapsed_s : 0.0;
  char eta[32] = "ETA --";
  if (rate_per_s > 0.0) std::snprintf(eta, sizeof eta, "ETA %.0f s", static_cast<double>(total_ - done) / rate_per_s);
  std::fprintf(stderr, "\r%s: %zu/%zu runs (%zu resumed), %.1f runs/s, %s, %.0f s elapsed\033[K%s", label_.c_str(),
               done, total_, resumed_, rate_per_s, final_line ? "done" : eta, elapsed_s, final_line ? "\n" : "");
  std::fflush(stderr);
}

}  // namespace latsim::sweep

namespace latsim::sweep {

SimulationProgress::SimulationProgress(bool forced)
    : terminal_(::isatty(STDERR_FILENO) == 1),
      enabled_(forced || terminal_),
      forced_(forced),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

std::string SimulationProgress::line(const run::RunProgress& p, double elapsed_s) {
  const double now_s = p.now.to_seconds(), end_s = p.end.to_seconds();
  const double fraction = end_s > 0 ? now_s / end_s : 1.0;
  const double events_per_s = elapsed_s > 0 ? static_cast<double>(p.events) / elapsed_s : 0.0;
  // Simulated seconds per wall second so far predict the rest.
  const double sim_rate = elapsed_s > 0 ? now_s / elapsed_s : 0.0;
  const std::string eta = sim_rate > 0 ? "ETA " + duration_text((end_s - now_s) / sim_rate) : "ETA --";
  char buf[200];
  std::snprintf(buf, sizeof buf, "run: simulated %.6g s of %.6g s (%.1f %%), %.3g M events/s, %s", now_s, end_s,
                100.0 * fraction, events_per_s / 1e6, eta.c_str());
  return buf;
}

void SimulationProgress::update(const run::RunProgress& progress) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!forced_ && now - start_ < kQuietStart) return;
  if (drawn_ && now - last_draw_ < kRedrawInterval) return;
  last_draw_ = now;
  drawn_ = true;
  const double elapsed_s = std::chrono::duration<double>(now - start_).count();
  // Redrawn in place on a terminal; one line per report in a log.
  std::fprintf(stderr, terminal_ ? "\r%s\033[K" : "%s\n", line(progress, elapsed_s).c_str());
  std::fflush(stderr);
}

void SimulationProgress::finish() {
  if (!drawn_ || !terminal_) return;
  drawn_ = false;
  // On a terminal the line makes way for what follows.
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
}

}  // namespace latsim::sweep
