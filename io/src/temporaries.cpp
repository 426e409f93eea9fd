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

void register_temporary(const std::filesystem::path& path, const std::function<void()>& make) {
  const std::lock_guard lock(list_mutex());
  listed().push_back(path.string());
  make();
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
  // The list stays locked until the program ends, which it does next: no
  // other thread lists, and so makes, a new temporary meanwhile.
  lock.release();
  for (const std::string& p : listed()) {
    // Another thread may be removing the same directory (its own stop) or
    // still writing into it: remove_all gives up at an entry that vanished
    // or a directory that filled meanwhile, so it is repeated until the path
    // is gone, for at most about 100 ms.
    for (int attempt = 0; attempt < 100; ++attempt) {
      std::error_code ec;
      std::filesystem::remove_all(p, ec);
      if (!std::filesystem::exists(std::filesystem::symlink_status(p, ec))) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
}

}  // namespace latsim::io
