#include "line_source.hpp"

#include "latsim/capture/capture.hpp"
#include "latsim/des/stop_token.hpp"

namespace latsim::capture {

namespace {

constexpr size_t kChunkBytes = size_t{1} << 20;
constexpr size_t kMaxLineBytes = size_t{1} << 20;

io::InputFile open(const std::filesystem::path& file) {
  try {
    return io::InputFile(file, kMaxCaptureBytes);
  } catch (const io::InputFileError& e) {
    throw CaptureError(file, 0, std::string("cannot read the capture file: ") + e.what());
  }
}

}  // namespace

LineSource::LineSource(const std::filesystem::path& file) : file_(file), in_(open(file)) { buffer_.reserve(kChunkBytes); }

bool LineSource::next(std::string_view& line) {
  for (;;) {
    const size_t nl = buffer_.find('\n', pos_);
    if (nl != std::string::npos) {
      line = std::string_view(buffer_).substr(pos_, nl - pos_);
      pos_ = nl + 1;
      return finish(line);
    }
    if (buffer_.size() - pos_ > kMaxLineBytes)
      throw CaptureError(file_, number_ + 1, "a line longer than " + std::to_string(kMaxLineBytes) + " bytes");
    // A stop request is answered between pieces (a 256 MB capture takes
    // seconds to read), where a command has set the thread's stop flag.
    des::check_stop();
    buffer_.erase(0, pos_);
    pos_ = 0;
    const size_t had = buffer_.size();
    buffer_.resize(had + kChunkBytes);
    size_t got = 0;
    try {
      got = in_.read(buffer_.data() + had, kChunkBytes);
    } catch (const io::InputFileError& e) {
      throw CaptureError(file_, 0, std::string("cannot read the capture file: ") + e.what());
    }
    buffer_.resize(had + got);
    if (got == 0) {
      if (buffer_.empty()) return false;
      line = buffer_;  // a last line without a line end
      pos_ = buffer_.size();
      return finish(line);
    }
  }
}

bool LineSource::finish(std::string_view& line) {
  ++number_;
  // No text capture holds a NUL: a cell holding one was read up to it, or a
  // message quoting it was cut there (every reader of captures reads here).
  if (const size_t nul = line.find('\0'); nul != std::string_view::npos)
    throw CaptureError(file_, number_, "a NUL byte at column " + std::to_string(nul + 1) +
                                           ": not a text file, or a damaged one");
  if (number_ == 1 && line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return true;
}

}  // namespace latsim::capture
