// Temporaries a program that must end at once removes first: the staging
// directories and temporary files of work in progress.
#pragma once

#include <filesystem>
#include <functional>

namespace latsim::io {

/// Adds `path` (a staging directory, a temporary file) to the process's list
/// of temporaries; the owner removes it from the list once it is committed or
/// removed. A program told to stop that cannot wait for its work to notice
/// (StopSignals' deadline) removes every listed path before it exits.
void register_temporary(const std::filesystem::path& path);
/// Lists `path` and runs `make` (which creates it) while holding the list:
/// a program stopped at once then either removes what `make` made or ends
/// before `make` runs, never between the two.
void register_temporary(const std::filesystem::path& path, const std::function<void()>& make);
void unregister_temporary(const std::filesystem::path& path);

/// Removes every listed path and its contents, again while another thread
/// removes or fills it (for about 100 ms at most; errors ignored); for the
/// exit of a stopped program: the list stays locked, so no temporary is
/// listed after it. Does not wait long for a thread that holds the list.
void remove_registered_temporaries() noexcept;

}  // namespace latsim::io
