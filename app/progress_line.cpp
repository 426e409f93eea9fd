#include "progress_line.hpp"

#include <unistd.h>

#include <cstdio>

namespace latsim::app {

namespace {

// Redrawing more often than this only costs terminal bandwidth.
constexpr auto kRedrawInterval = std::chrono::milliseconds(200);

}  // namespace

ProgressLine::ProgressLine(std::string label, size_t total, size_t already_done)
    : label_(std::move(label)),
      total_(total),
      resumed_(already_done),
      done_(already_done),
      enabled_(::isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {
  if (enabled_) draw(false);
}

void ProgressLine::advance() {
  std::lock_guard lock(mutex_);
  ++done_;
  const auto now = std::chrono::steady_clock::now();
  if (enabled_ && now - last_draw_ >= kRedrawInterval) draw(false);
}

void ProgressLine::finish() {
  std::lock_guard lock(mutex_);
  if (enabled_) draw(true);
}

void ProgressLine::draw(bool final_line) {
  last_draw_ = std::chrono::steady_clock::now();
  const double elapsed_s = std::chrono::duration<double>(last_draw_ - start_).count();
  // The rate counts only runs done by this process; resumed ones cost nothing.
  const size_t fresh = done_ - resumed_;
  const double rate_per_s = elapsed_s > 0.0 ? static_cast<double>(fresh) / elapsed_s : 0.0;
  char eta[32] = "ETA --";
  if (rate_per_s > 0.0) std::snprintf(eta, sizeof eta, "ETA %.0f s", static_cast<double>(total_ - done_) / rate_per_s);
  std::fprintf(stderr, "\r%s: %zu/%zu runs (%zu resumed), %.1f runs/s, %s, %.0f s elapsed\033[K%s", label_.c_str(),
               done_, total_, resumed_, rate_per_s, final_line ? "done" : eta, elapsed_s, final_line ? "\n" : "");
  std::fflush(stderr);
}

}  // namespace latsim::app
