#include "child_process.hpp"

#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>  // environ (with _GNU_SOURCE, which g++ defines)

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

namespace latsim::app {

namespace fs = std::filesystem;

ChildResult run_child(const std::vector<std::string>& argv) {
  if (argv.empty()) throw std::runtime_error("run_child: no program given");
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int rc = ::posix_spawnp(&pid, args[0], nullptr, nullptr, args.data(), environ);
  if (rc != 0) throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(rc));
  int status = 0;
  struct rusage usage {};
  // wait4, unlike getrusage(RUSAGE_CHILDREN), gives this child's own peak, not
  // the largest of every child waited for so far.
  while (::wait4(pid, &status, 0, &usage) < 0) {
    if (errno != EINTR) throw std::runtime_error("waiting for " + argv[0] + ": " + std::strerror(errno));
  }
  ChildResult result;
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.peak_rss_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  else if (WIFSIGNALED(status)) result.exit_code = 128 + WTERMSIG(status);
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
