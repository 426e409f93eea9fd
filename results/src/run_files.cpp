#include "latsim/results/run_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

#include "latsim/io/temporaries.hpp"
#include "latsim/renderer/png_writer.hpp"

namespace latsim::results {

namespace fs = std::filesystem;

WriteError::WriteError(fs::path file, int error_number)
    : std::runtime_error("cannot write " + file.string() + ": " + std::strerror(error_number)),
      file_(std::move(file)),
      errno_(error_number) {}

bool WriteError::storage_unusable() const {
  return errno_ == ENOSPC || errno_ == EDQUOT || errno_ == EROFS || errno_ == EFBIG || errno_ == EIO ||
         errno_ == EACCES || errno_ == EPERM;
}

namespace {

// Throws WriteError for `file` unless the call succeeded, after removing `temp`.
void check(bool ok, const fs::path& file, const fs::path& temp = {}) {
  if (ok) return;
  const int e = errno;
  if (!temp.empty()) ::unlink(temp.c_str());
  throw WriteError(file, e);
}

void make_directories(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw WriteError(dir, ec.value());
}

// Makes the folders of `name` inside the staging directory, never the
// staging directory itself: once a program stopped at once has removed it, a
// write fails rather than make it again behind the removal.
void make_parents_inside(const fs::path& staging, const std::string& name) {
  fs::path dir = staging;
  for (const fs::path& part : fs::path(name).parent_path()) {
    dir /= part;
    std::error_code ec;
    fs::create_directory(dir, ec);  // one that exists is no error
    if (ec) throw WriteError(dir, ec.value());
  }
}

}  // namespace

void write_file_atomically(const fs::path& file, std::string_view bytes) {
  const fs::path temp = file.string() + ".tmp." + std::to_string(::getpid());
  // Listed while it exists: a program stopped at once removes it.
  int fd = -1;
  struct Unlist {
    const fs::path& path;
    ~Unlist() { io::unregister_temporary(path); }
  } const unlist{temp};
  io::register_temporary(temp, [&] { fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644); });
  check(fd >= 0, file);
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int e = errno;
      ::close(fd);
      errno = e;
      check(false, file, temp);
    }
    done += static_cast<size_t>(n);
  }
  // close() reports what a network file system could not store.
  check(::close(fd) == 0, file, temp);
  check(::rename(temp.c_str(), file.c_str()) == 0, file, temp);
}

fs::path staging_dir_of(const fs::path& dir, long pid) {
  fs::path absolute = fs::absolute(dir).lexically_normal();
  if (!absolute.has_filename() && absolute.has_relative_path()) absolute = absolute.parent_path();  // "out/" is "out"
  const std::string suffix = ".tmp." + std::to_string(pid);
  if (!absolute.has_filename()) return absolute / suffix;  // the root itself
  return absolute.parent_path() / (absolute.filename().string() + suffix);
}

RunFiles::RunFiles(fs::path dir, fs::path staging) : dir_(std::move(dir)), staging_(std::move(staging)) {
  if (enabled() && staging_.empty()) staging_ = staging_dir_of(dir_, static_cast<long>(::getpid()));
}

RunFiles::~RunFiles() { discard(); }

RunFiles::RunFiles(RunFiles&& other) noexcept { *this = std::move(other); }

RunFiles& RunFiles::operator=(RunFiles&& other) noexcept {
  if (this == &other) return *this;
  discard();
  dir_ = std::move(other.dir_);
  staging_ = std::move(other.staging_);
  staged_ = other.staged_;
  write_images_ = other.write_images_;
  written_ = std::move(other.written_);
  other.dir_.clear();
  other.staging_.clear();
  other.staged_ = false;
  return *this;
}

void RunFiles::discard() noexcept {
  if (!staged_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
  staged_ = false;
  io::unregister_temporary(staging_);
}

void RunFiles::prepare() {
  if (!enabled() || staged_) return;
  // A staging directory of the same name is a leftover of this pid's
  // predecessor (pids are reused): nothing of ours is in it.
  std::error_code ec;
  fs::remove_all(staging_, ec);
  // Listed as it is made: a program stopped at once removes it.
  io::register_temporary(staging_, [&] { make_directories(staging_); });
  staged_ = true;
}

StreamedFile::StreamedFile(fs::path staged, fs::path shown_as)
    : staged_(std::move(staged)), shown_as_(std::move(shown_as)) {
  out_ = std::fopen(staged_.c_str(), "wb");
  if (out_ == nullptr) throw WriteError(shown_as_, errno);
  buffer_ = std::make_unique_for_overwrite<char[]>(kBufferBytes);
  std::setvbuf(out_, buffer_.get(), _IOFBF, kBufferBytes);  // before any output, as setvbuf requires
}

StreamedFile::StreamedFile(StreamedFile&& o) noexcept
    : staged_(std::move(o.staged_)),
      shown_as_(std::move(o.shown_as_)),
      out_(std::exchange(o.out_, nullptr)),
      buffer_(std::move(o.buffer_)) {}

StreamedFile& StreamedFile::operator=(StreamedFile&& o) noexcept {
  if (this != &o) {
    discard();
    staged_ = std::move(o.staged_);
    shown_as_ = std::move(o.shown_as_);
    out_ = std::exchange(o.out_, nullptr);
    buffer_ = std::move(o.buffer_);  // after discard() closed the stream that used the old one
  }
  return *this;
}

StreamedFile::~StreamedFile() { discard(); }

void StreamedFile::write(std::string_view bytes) {
  if (out_ == nullptr) return;
  // Unlocked: a StreamedFile belongs to one run on one thread.
  if (fwrite_unlocked(bytes.data(), 1, bytes.size(), out_) != bytes.size()) {
    const int e = errno;
    discard();
    throw WriteError(shown_as_, e);
  }
}

void StreamedFile::close() {
  if (out_ == nullptr) return;
  const bool flushed = std::fflush(out_) == 0;
  const int e = errno;
  // fclose() reports what a network file system could not store.
  const bool closed = std::fclose(std::exchange(out_, nullptr)) == 0;
  if (!flushed || !closed) throw WriteError(shown_as_, flushed ? errno : e);
}

void StreamedFile::discard() noexcept {
  if (out_ == nullptr) return;
  std::fclose(std::exchange(out_, nullptr));
  ::unlink(staged_.c_str());
}

StreamedFile RunFiles::stream(const std::string& name) {
  if (!enabled()) return StreamedFile{};
  prepare();
  const fs::path file = staging_ / name;
  make_parents_inside(staging_, name);
  return StreamedFile(file, dir_ / name);
}

void RunFiles::commit(StreamedFile& file, const std::string& name) {
  if (!file.is_open()) return;
  file.close();
  written_.push_back(name);
}

void RunFiles::write_text(const std::string& name, std::string_view text) {
  if (!enabled()) return;
  prepare();
  const fs::path file = staging_ / name;
  make_parents_inside(staging_, name);
  try {
    write_file_atomically(file, text);
  } catch (const WriteError& e) {
    // Name the file as the user will look for it, not its staging place.
    throw WriteError(dir_ / name, e.error_number());
  }
  written_.push_back(name);
}

void RunFiles::write_png(const std::string& name, const renderer::ImageRGB& image) {
  if (!writes_images()) return;
  const std::vector<uint8_t> bytes = renderer::encode_png(image);
  write_text(name, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

void RunFiles::commit(const std::string& last) {
  if (!enabled()) return;
  prepare();
  std::error_code ec;
  if (!fs::exists(dir_, ec)) {
    if (::rename(staging_.c_str(), dir_.c_str()) == 0) {
      staged_ = false;
      io::unregister_temporary(staging_);
      return;
    }
    if (errno != EEXIST && errno != ENOTEMPTY) check(false, dir_);
    // Made meanwhile by someone else: merge like an existing directory.
  }
  // The old completion marker goes first: a reader never takes a half-updated directory for a whole one.
  if (::unlink((dir_ / last).c_str()) != 0 && errno != ENOENT) check(false, dir_ / last);
  std::set<std::string> moved{last};
  for (const std::string& name : written_) {
    if (!moved.insert(name).second) continue;
    make_directories((dir_ / name).parent_path());
    check(::rename((staging_ / name).c_str(), (dir_ / name).c_str()) == 0, dir_ / name);
  }
  if (fs::exists(staging_ / last, ec)) check(::rename((staging_ / last).c_str(), (dir_ / last).c_str()) == 0, dir_ / last);
  discard();
}

}  // namespace latsim::results

namespace latsim::results {

std::optional<nlohmann::json> read_summary(const fs::path& file, const std::string& remedy) {
  std::ifstream in(file);
  if (!in) return std::nullopt;
  std::stringstream buf;
  buf << in.rdbuf();
  try {
    return nlohmann::json::parse(buf.str());
  } catch (const nlohmann::json::parse_error& e) {
    // Written atomically, so this is damage from outside latsim; say so rather than guess.
    throw std::runtime_error(file.string() + ": unreadable summary (" + e.what() + "); " + remedy);
  }
}

}  // namespace latsim::results
