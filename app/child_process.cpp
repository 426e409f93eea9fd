#include "child_process.hpp"

#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>  // environ (with _GNU_SOURCE, which g++ defines)

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "stop_signals.hpp"

namespace latsim::app {

namespace fs = std::filesystem;

namespace {

// argv[0] as a path: itself when it has a slash, else the first match on PATH.
std::string resolve_program(const std::string& program) {
  if (program.find('/') != std::string::npos) return program;
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  size_t start = 0;
  while (start <= dirs.size()) {
    const size_t end = std::min(dirs.find(':', start), dirs.size());
    const fs::path candidate = fs::path(end > start ? dirs.substr(start, end - start) : ".") / program;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    start = end + 1;
  }
  throw std::runtime_error("cannot start " + program + ": not found on PATH");
}

// The environment of a child: ours, with the shorter stop deadline of a child.
std::vector<std::string> child_environment() {
  std::vector<std::string> env;
  for (char** e = environ; *e != nullptr; ++e)
    if (std::strncmp(*e, "LATSIM_STOP_DEADLINE_MS=", 24) != 0) env.emplace_back(*e);
  // Half its parent's: a stopped child ends on its own, temporaries removed,
  // before the parent's watchdog would have to kill it.
  env.push_back("LATSIM_STOP_DEADLINE_MS=" + std::to_string(std::max<long>(1, StopSignals::deadline().count() / 2)));
  return env;
}

std::vector<char*> pointers(std::vector<std::string>& strings) {
  std::vector<char*> out;
  for (auto& s : strings) out.push_back(s.data());
  out.push_back(nullptr);
  return out;
}

}  // namespace

ChildResult run_child(const std::vector<std::string>& argv) {
  if (argv.empty()) throw std::runtime_error("run_child: no program given");
  const std::string program = resolve_program(argv[0]);
  std::vector<std::string> arg_strings = argv, env_strings = child_environment();
  const std::vector<char*> args = pointers(arg_strings), env = pointers(env_strings);
  const pid_t parent = ::getpid();
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(errno));
  if (pid == 0) {
    // Only async-signal-safe calls here. The child ends with its parent,
    // even one killed outright, and takes a terminal's Ctrl-C from it only
    // (its own process group): one request, passed on once.
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) ::_exit(128 + SIGTERM);
    ::setpgid(0, 0);
    ::execve(program.c_str(), args.data(), env.data());
    ::_exit(127);
  }
  StopSignals::add_child(pid);
  int status = 0;
  struct rusage usage {};
  // wait4, unlike getrusage(RUSAGE_CHILDREN), gives this child's own peak, not
  // the largest of every child waited for so far.
  while (::wait4(pid, &status, 0, &usage) < 0) {
    if (errno != EINTR) {
      StopSignals::remove_child();
      throw std::runtime_error("waiting for " + argv[0] + ": " + std::strerror(errno));
    }
  }
  StopSignals::remove_child();
  ChildResult result;
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.peak_rss_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  else if (WIFSIGNALED(status)) result.exit_code = 128 + WTERMSIG(status);
  if (result.exit_code == 127) throw std::runtime_error("cannot start " + argv[0]);
  return result;
}

fs::path self_executable() { return fs::read_symlink("/proc/self/exe"); }

std::string python_interpreter() {
  std::error_code ec;
  return fs::exists("/usr/bin/python3", ec) ? "/usr/bin/python3" : "python3";
}

fs::path analysis_script(const std::string& script) {
  std::vector<fs::path> candidates{fs::path(LATSIM_SOURCE_DIR) / "analysis" / script};
  std::error_code ec;
  const fs::path exe_dir = self_executable().parent_path();
  candidates.push_back(exe_dir / ".." / "analysis" / script);
  candidates.push_back(exe_dir / "analysis" / script);
  for (const auto& c : candidates)
    if (fs::exists(c, ec)) return c;
  throw std::runtime_error("cannot find analysis/" + script + " (looked in " + candidates.front().parent_path().string() +
                           " and beside " + exe_dir.string() + ")");
}

}  // namespace latsim::app
