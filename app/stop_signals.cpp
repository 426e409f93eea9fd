#include "stop_signals.hpp"

#include <signal.h>

namespace latsim::app {

namespace {

// Only lock-free atomics and sig_atomic_t may be touched from a handler.
std::atomic<bool> g_stop{false};
volatile sig_atomic_t g_signal = 0;
struct sigaction g_previous_int {}, g_previous_term {};

void on_signal(int sig) {
  if (g_signal != 0) {
    // Asked twice: stop now, as the signal would have without us.
    ::signal(sig, SIG_DFL);
    ::raise(sig);
    return;
  }
  g_signal = sig;
  g_stop.store(true, std::memory_order_relaxed);
}

}  // namespace

static_assert(std::atomic<bool>::is_always_lock_free, "a signal handler may only set a lock-free flag");

StopSignals::StopSignals() {
  g_stop.store(false);
  g_signal = 0;
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  // Restart interrupted reads and writes: the flag, not EINTR, ends the work.
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
}

StopSignals::~StopSignals() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

const std::atomic<bool>& StopSignals::flag() const { return g_stop; }

const char* StopSignals::name() const {
  if (g_signal == SIGINT) return "SIGINT";
  if (g_signal == SIGTERM) return "SIGTERM";
  return "";
}

int StopSignals::exit_code() const { return 128 + static_cast<int>(g_signal); }

}  // namespace latsim::app
