#include "latsim/io/temporaries.hpp"

#include <algorithm>
#include <chrono>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace latsim::io {

namespace {

std::timed_mutex& list_mutex() {
  static std::timed_mutex m;
  return m;
}

// Never destroyed: a program may end while another thread still registers.
std::vector<std::string>& listed() {
  static auto* paths = new std::vector<std::string>();
  return *paths;
}

}  // namespace

void register_temporary(const std::filesystem::path& path) {
  const std::lock_guard lock(list_mutex());
  listed().push_back(path.string());
}

void unregister_temporary(const std::filesystem::path& path) {
  const std::lock_guard lock(list_mutex());
  auto& paths = listed();
  const auto it = std::find(paths.begin(), paths.end(), path.string());
  if (it != paths.end()) paths.erase(it);
}

void remove_registered_temporaries() noexcept {
  // A thread that holds the list does so for a push or an erase: a moment.
  std::unique_lock lock(list_mutex(), std::defer_lock);
  if (!lock.try_lock_for(std::chrono::milliseconds(100))) return;
  for (const std::string& p : listed()) {
    std::error_code ec;
    std::filesystem::remove_all(p, ec);
  }
}

}  // namespace latsim::io
