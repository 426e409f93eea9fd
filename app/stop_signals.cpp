#include "stop_signals.hpp"

#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#include "latsim/io/temporaries.hpp"

namespace latsim::app {

namespace {

// Only lock-free atomics, sig_atomic_t and write() may be touched from a handler.
std::atomic<bool> g_stop{false};
volatile sig_atomic_t g_signal = 0;
std::atomic<pid_t> g_child{0};
std::atomic<bool> g_closing{false};
std::atomic<bool> g_spoken{false};
int g_wake[2] = {-1, -1};  // the handler's word to the watchdog
struct sigaction g_previous_int {}, g_previous_term {};
StopSignals* g_installed = nullptr;
std::string g_command;
std::thread g_watchdog;

static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<pid_t>::is_always_lock_free,
              "a signal handler may only touch lock-free atomics");

void on_signal(int sig) {
  const int saved = errno;
  if (g_signal == 0) {
    g_signal = sig;
    g_stop.store(true, std::memory_order_relaxed);
  }
  const pid_t child = g_child.load(std::memory_order_relaxed);
  if (child > 0) ::kill(child, sig);
  // Every signal wakes the watchdog: the first starts its deadline, a second ends the program now.
  const char byte = 1;
  [[maybe_unused]] const ssize_t n = ::write(g_wake[1], &byte, 1);
  errno = saved;
}

// Ends the program that did not stop in time: its child, its temporaries, one line.
[[noreturn]] void end_now(const char* why) {
  const pid_t child = g_child.load();
  if (child > 0) ::kill(child, SIGKILL);
  io::remove_registered_temporaries();
  const char* name = g_signal == SIGINT ? "SIGINT" : "SIGTERM";
  if (!g_spoken.exchange(true)) {
    std::fprintf(stderr, "%s: stopped by %s (%s); nothing written\n", g_command.c_str(), name, why);
    std::fflush(stderr);
  }
  ::_exit(128 + static_cast<int>(g_signal));
}

// Waits for a byte on the wake pipe for at most `timeout` (-1: without end); false on timeout.
bool woken(int timeout_ms) {
  pollfd p{g_wake[0], POLLIN, 0};
  int rc = 0;
  while ((rc = ::poll(&p, 1, timeout_ms)) < 0 && errno == EINTR) {
  }
  if (rc <= 0) return false;
  char byte = 0;
  [[maybe_unused]] const ssize_t n = ::read(g_wake[0], &byte, 1);
  return true;
}

void watch() {
  woken(-1);
  if (g_closing.load()) return;
  const auto deadline = std::chrono::steady_clock::now() + StopSignals::deadline();
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) end_now("it had not stopped by its deadline");
    if (woken(static_cast<int>(left.count()) + 1)) {
      if (g_closing.load()) return;
      end_now("asked twice");
    }
  }
}

}  // namespace

StopSignals::StopSignals(std::string command) {
  if (g_installed != nullptr) throw std::logic_error("StopSignals: one per process");
  if (::pipe2(g_wake, O_CLOEXEC | O_NONBLOCK) != 0) throw std::runtime_error("StopSignals: no pipe");
  g_command = std::move(command);
  g_stop.store(false);
  g_signal = 0;
  g_closing.store(false);
  g_spoken.store(false);
  // The watchdog never takes the signals itself: a blocking call of the
  // main thread is what they must interrupt.
  sigset_t block, before;
  sigemptyset(&block);
  sigaddset(&block, SIGINT);
  sigaddset(&block, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &block, &before);
  g_watchdog = std::thread(watch);
  pthread_sigmask(SIG_SETMASK, &before, nullptr);
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  // Restart interrupted reads and writes: the flag, not EINTR, ends the work.
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
  g_installed = this;
}

StopSignals::~StopSignals() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
  g_closing.store(true);
  const char byte = 0;
  [[maybe_unused]] const ssize_t n = ::write(g_wake[1], &byte, 1);
  g_watchdog.join();
  ::close(g_wake[0]);
  ::close(g_wake[1]);
  g_installed = nullptr;
}

StopSignals& StopSignals::installed() {
  if (g_installed == nullptr) throw std::logic_error("StopSignals: none installed");
  return *g_installed;
}

const std::atomic<bool>& StopSignals::flag() const { return g_stop; }

const char* StopSignals::name() const {
  if (g_signal == SIGINT) return "SIGINT";
  if (g_signal == SIGTERM) return "SIGTERM";
  return "";
}

int StopSignals::exit_code() const { return 128 + static_cast<int>(g_signal); }

void StopSignals::add_child(pid_t pid) {
  g_child.store(pid);
  // A signal between the child's start and this line was not passed on.
  if (g_signal != 0) ::kill(pid, g_signal);
}

void StopSignals::remove_child() { g_child.store(0); }

bool StopSignals::first_word() { return !g_spoken.exchange(true); }

std::chrono::milliseconds StopSignals::deadline() {
  if (const char* text = std::getenv("LATSIM_STOP_DEADLINE_MS")) {
    const long ms = std::strtol(text, nullptr, 10);
    if (ms > 0 && ms <= 60000) return std::chrono::milliseconds(ms);
  }
  return std::chrono::milliseconds(800);
}

}  // namespace latsim::app
